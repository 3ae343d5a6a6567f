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
      case Ip247Error::pg_job_list_full:
        return "PG job list full (Auftragsliste PG ist voll)";
      case Ip247Error::job_not_allowed:
        return "job not allowed (Nicht erlaubter Auftrag)";
      case Ip247Error::block_stored:
        return "block stored (Satz abgespeichert)";
      case Ip247Error::axis_running:
        return "axis running, input impossible (Achse in Betrieb)";
      case Ip247Error::ag_job_list_full:
        return "AG job list full (Auftragsliste AG ist voll)";
      case Ip247Error::waits_for_external_start:
        return "motor waits for external start (Motor wartet auf externen Start)";
      case Ip247Error::state_after_power_failure:
        return "state after power failure (Zustand nach Spannungsausfall)";
      case Ip247Error::module_number_locked:
        return "module number cannot be changed with correct MD (Baugruppennummer nicht aenderbar)";
      case Ip247Error::db_not_present:
        return "data block not present (Datenbaustein nicht vorhanden)";
      case Ip247Error::max_programs:
        return "maximum number of programs reached (Max. Programmzahl erreicht)";
      case Ip247Error::teach_in_exclusive:
        return "multiple traversing-program processing forbidden (Multi Verfahrprogramm-Verarbeitung verboten)";
      case Ip247Error::program_memory_full:
        return "not enough room for the traversing program (Zu wenig Platz fuer Verfahrprogramm)";
      case Ip247Error::mode_not_allowed_in_teach_in:
        return "operating mode not allowed in teach-in (Unzulaessige Betriebsart im Teach-In)";
      case Ip247Error::block_start:
        return "error at block start (Fehler am Satzanfang)";
      case Ip247Error::subprogram_number:
        return "subprogram DB number too large (Unterprogramm-DB-Nummer zu gross)";
      case Ip247Error::g_not_allowed:
        return "G function not allowed (G-Funktion nicht erlaubt)";
      case Ip247Error::endless_loop_not_outer:
        return "endless loop only as the outer loop (Endlosschleife nur als aeussere Schleife)";
      case Ip247Error::nesting_too_deep:
        return "nesting depth exceeded (Schachtelungstiefe ueberschritten)";
      case Ip247Error::x_wrong:
        return "X function wrong (X-Funktion falsch)";
      case Ip247Error::f_wrong:
        return "F function wrong (F-Funktion falsch)";
      case Ip247Error::path_too_long:
        return "path too long (Verfahrweg zu lang)";
      case Ip247Error::speed_too_high:
        return "traversing speed too high (Verfahrgeschwindigkeit zu gross)";
      case Ip247Error::block_end:
        return "error at block end (Fehler am Satzende)";
      case Ip247Error::program_end_before_loop_end:
        return "program end before loop end (Programmende vor Schleifenende)";
      case Ip247Error::mode_not_allowed_on_axis:
        return "operating mode not allowed on this axis (Unzulaessige Betriebsart auf dieser Achse)";
      case Ip247Error::no_direction_change_in_flying_change:
        return "no direction change in flying change (Keine Richtungsaenderung bei fliegendem Wechsel)";
      case Ip247Error::program_faulty:
        return "traversing program faulty (Verfahrprogramm fehlerhaft)";
      case Ip247Error::program_exists:
        return "traversing program already present (Verfahrprogramm bereits vorhanden)";
      case Ip247Error::program_active:
        return "traversing program is active (Verfahrprogramm ist aktiv)";
      case Ip247Error::flying_change_failed:
        return "flying change could not be executed (Fliegender Wechsel konnte nicht ausgefuehrt werden)";
      case Ip247Error::plc_failed:
        return "PLC has failed (AG ist ausgefallen)";
      case Ip247Error::ramp_table_access:
        return "faulty ramp table access (Fehlerhafter Zugriff auf Rampentabelle)";
      case Ip247Error::block_not_interpreted:
        return "block not yet fully interpreted (Satz ist noch nicht fertig interpretiert)";
      case Ip247Error::speed_too_low:
        return "traversing speed too low (Verfahrgeschwindigkeit zu klein)";
      case Ip247Error::deleted_from_directory_only:
        return "program only deleted from the directory (Verfahrprogramm ist nur aus dem Directory geloescht)";
      case Ip247Error::illegal_path:
        return "illegal path specification (Unzulaessige Wegangabe)";
      case Ip247Error::illegal_tool_offset:
        return "illegal tool offset (Unzulaessige Werkzeugkorrektur)";
      case Ip247Error::program_waits_for_continuation:
        return "program waits for continuation (Verfahrprogramm wartet auf Fortsetzung)";
      case Ip247Error::path_not_bcd:
        return "path not BCD-coded (Wegangabe nicht BCD-codiert)";
      case Ip247Error::speed_not_bcd:
        return "speed not BCD-coded (Geschwindigkeit nicht BCD-codiert)";
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
