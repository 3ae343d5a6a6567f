// SPDX-License-Identifier: MIT
#include "hil/stepdir/ip247_error.hpp"

#include <string>

namespace hil::stepdir {
namespace {

class Ip247Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "ip247"; }
  std::string message(int v) const override {
    switch (static_cast<Ip247Error>(v)) {
      case Ip247Error::none:
        return "no error (fehlerfrei)";
      case Ip247Error::speed_out_of_range:
        return "speed out of range, frequency clamped (Geschwindigkeit ausserhalb des zulaessigen Bereichs)";
      case Ip247Error::reference_missing:
        return "reference point missing (Referenzpunkt fehlt)";
      case Ip247Error::no_machine_data:
        return "no or wrong machine data (Keine oder falsche Maschinendaten)";
      case Ip247Error::faulty_machine_data:
        return "faulty machine data (Fehlerhafte Maschinendaten)";
      case Ip247Error::traversing_range_exceeded:
        return "traversing range exceeded (Verfahrbereichsueberschreitung)";
      case Ip247Error::limit_start_overrun:
        return "limit switch start overrun (Endschalter Anfang ueberfahren)";
      case Ip247Error::limit_end_overrun:
        return "limit switch end overrun (Endschalter Ende ueberfahren)";
      case Ip247Error::external_stop:
        return "external stop (externer STOP aufgetreten)";
      case Ip247Error::sw_limit_start_overrun:
        return "software limit start overrun (Software-Endschalter Anfang ueberfahren)";
      case Ip247Error::sw_limit_end_overrun:
        return "software limit end overrun (Software-Endschalter Ende ueberfahren)";
      case Ip247Error::pulse_generator_defective:
        return "pulse generator defective (Impulsgenerator defekt)";
      case Ip247Error::power_section_off:
        return "switch power section on (Leistungsteil einschalten)";
      case Ip247Error::ramp_table_generation:
        return "faulty ramp table generation (Fehlerhafte Generierung der Rampentabelle)";
      case Ip247Error::reference_cam_defective:
        return "reference cam defective (Der Referenznocken ist defekt)";
    }
    return "IP247 error " + std::to_string(v);
  }
};

class Ip247MdCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "ip247-md"; }
  std::string message(int v) const override {
    switch (static_cast<Ip247MdError>(v)) {
      case Ip247MdError::none:
        return "machine data OK";
      case Ip247MdError::pulse_duration:
        return "wrong pulse duration (Falsche Impulsdauer): 1..31 us and at most half the period of fmax";
      case Ip247MdError::max_frequency:
        return "wrong maximum frequency (Falsche Maximalfrequenz): 12 Hz..100 kHz";
      case Ip247MdError::speed:
        return "wrong speed (Falsche Tipp-/Schrittmass-Geschwindigkeit): 1 Hz..fmax";
      case Ip247MdError::frequency_increase:
        return "wrong frequency increase (Falsche Frequenzzunahme): 20..2599999 Hz/s and tau 5..2600 ms";
      case Ip247MdError::reference_direction:
        return "wrong reference direction or synchronisation";
      case Ip247MdError::ramp_generation:
        return "ramp table generated wrongly (Rampentabelle falsch generiert)";
      case Ip247MdError::reference_speed:
        return "wrong reference speed (Falsche Referenzgeschwindigkeit): fss < f_ref <= fmax";
      case Ip247MdError::edge_polarity:
        return "wrong edge polarity (Falsche Flankenbewertung)";
      case Ip247MdError::limit_polarity:
        return "wrong limit switch polarity (Falsche Polaritaet der Endschalter): switches read as actuated";
      case Ip247MdError::backlash:
        return "wrong backlash value (Falscher Losekompensationswert): 0..64999";
      case Ip247MdError::start_stop_frequency:
        return "wrong start-stop frequency (Falsche Start-Stopp-Frequenz): 1 Hz..10 kHz";
      case Ip247MdError::patterns:
        return "wrong number of energisation patterns (Falsche Anzahl Bestromungsmuster): 4..40";
    }
    return "IP247 MD error " + std::to_string(v);
  }
};

}  // namespace

const std::error_category& ip247_category() noexcept {
  static const Ip247Category c;
  return c;
}
const std::error_category& ip247_md_category() noexcept {
  static const Ip247MdCategory c;
  return c;
}

}  // namespace hil::stepdir
