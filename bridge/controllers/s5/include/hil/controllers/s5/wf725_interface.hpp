// SPDX-License-Identifier: MIT
#pragma once
// The DB axis of a WF 725/726 axis (digest wf725-726.md §6.3): the data words through which the
// S5 PLC commands the axis and reads its status. The manual names D 1.1/1.3 (direction), D 2.0
// (drive enable), D 2.1 (cam), DL 2 (block number), D 3.0 PEH, D 3.3, D 3.4, D 3.5, D 3.6, DW 3/4
// (M output), DR 4 (error number), DL 4 (speed level) and DW 40 (program-I/O error); the other
// positions are our decision (docs/wf725.md, "DB axis"), kept in one place here.
// Words are plain data of the controller (S5InterfaceDb over the image's data area).

#include <cstdint>

namespace hil::controllers::s5::wf_db {

inline constexpr std::uint16_t words = 48;  ///< DW 0..47
inline constexpr double um = 1e-3;          ///< mm per µm, the unit of the position double words

// ---- PLC -> WF -----------------------------------------------------------------------------
inline constexpr std::uint16_t dw_mode = 0;                ///< DL 0: mode bits, DR 0: submode number
inline constexpr std::uint8_t bit_mode_traversing = 8;     ///< D 0.8
inline constexpr std::uint8_t bit_mode_program_io = 9;     ///< D 0.9
inline constexpr std::uint8_t bit_mode_machine_data = 10;  ///< D 0.10
inline constexpr std::uint16_t dw_control = 1;
inline constexpr std::uint8_t bit_start = 0;          ///< D 1.0 start (rising edge)
inline constexpr std::uint8_t bit_plus = 1;           ///< D 1.1 direction + (manual)
inline constexpr std::uint8_t bit_stop = 2;           ///< D 1.2 stop (level: the job is aborted by a ramp stop)
inline constexpr std::uint8_t bit_minus = 3;          ///< D 1.3 direction - (manual)
inline constexpr std::uint8_t bit_reset = 4;          ///< D 1.4 RESET (rising edge)
inline constexpr std::uint8_t bit_skip = 5;           ///< D 1.5 skip block
inline constexpr std::uint8_t bit_ram = 7;            ///< D 1.7 memory selection: 1 RAM, 0 EEPROM (teach-in)
inline constexpr std::uint16_t dw_enable = 2;         ///< DL 2: block number (single step)
inline constexpr std::uint8_t bit_drive_enable = 0;   ///< D 2.0 (manual)
inline constexpr std::uint8_t bit_cam = 1;            ///< D 2.1 deceleration cam, MD 15 = 1 (manual)
inline constexpr std::uint8_t bit_m_ack = 2;          ///< D 2.2 M-function acknowledgement
inline constexpr std::uint16_t dw_program = 5;        ///< program number
inline constexpr std::uint16_t dw_data_code = 11;     ///< data code (hex, 800C = acknowledge)
inline constexpr std::uint16_t dw_data_execute = 12;  ///< D 12.0 execute the data code (rising edge)
inline constexpr std::uint16_t dd_data_param1 = 13;   ///< DD 13 (DW 13/14): first parameter
inline constexpr std::uint16_t dd_data_param2 = 15;   ///< DD 15 (DW 15/16): second parameter

// ---- WF -> PLC -----------------------------------------------------------------------------
inline constexpr std::uint16_t dw_status = 3;        ///< DR 3 status bits, DL 3 M function (binary)
inline constexpr std::uint8_t bit_peh = 0;           ///< D 3.0 position reached and stopped (manual)
inline constexpr std::uint8_t bit_moving_plus = 1;   ///< D 3.1
inline constexpr std::uint8_t bit_moving_minus = 2;  ///< D 3.2
inline constexpr std::uint8_t bit_pre_limit = 3;     ///< D 3.3 (manual)
inline constexpr std::uint8_t bit_limit = 4;         ///< D 3.4 (manual)
inline constexpr std::uint8_t bit_error = 5;         ///< D 3.5 error strobe (manual)
inline constexpr std::uint8_t bit_syn = 6;           ///< D 3.6 synchronized (manual)
inline constexpr std::uint8_t bit_m_strobe = 7;      ///< D 3.7 M function output valid
inline constexpr std::uint16_t dw_error = 4;         ///< DR 4 traversing error (hex byte), DL 4 speed level
inline constexpr std::uint16_t dw_data_status = 17;  ///< D 17.0 data code done, D 17.1 refused (DW 40)
inline constexpr std::uint16_t dd_data_result = 18;  ///< DD 18: value a data code returns
inline constexpr std::uint16_t dd_actual = 20;       ///< DD 20: actual value, µm (10^-3 degree)
inline constexpr std::uint16_t dw_block = 22;        ///< DL 22 running program, DR 22 running block
inline constexpr std::uint16_t dw_state = 23;        ///< DL 23 active mode bits (as DL 0), DR 23 active submode
inline constexpr std::uint16_t dw_flags = 24;        ///< D 24.0 waits for start, D 24.1 program active,
                                                     ///< D 24.2 waits for read-in enable
inline constexpr std::uint16_t dw_list = 30;         ///< DW 30 entries on the listed page, DW 31..38 the numbers
inline constexpr std::uint16_t list_page = 8;        ///< numbers per page of a listing (data codes 47/4A)
inline constexpr std::uint16_t dw_io_error = 40;     ///< program-I/O error as the manual writes it (KH: 0123)

/// Operating submodes (DR 0).
enum class Submode : std::uint8_t {
  none = 0,              ///< submode "0"
  set_up = 1,            ///< jog with D 1.1 / D 1.3
  reference = 2,         ///< reference point approach
  set_actual = 3,        ///< setting actual value (MD 28)
  mdi = 4,               ///< manual data input (data codes 19h position, 1Ah feed)
  single_step = 5,       ///< one block (DL 2) of the program (DW 5)
  automatic = 6,         ///< automatic cycle
  automatic_step = 7,    ///< automatic single step: one block per start
  clamping = 8,          ///< clamping (MD 32)
  automatic_buffer = 9,  ///< automatic buffer: buffer DW 5 (this axis' pair), M11/M12 change buffers
  control = 10,          ///< control: the voltage of data code 1D with the polarity of D 1.1 / D 1.3
  run = 11,              ///< RUN: the axis holds under position control; data code 10 compensates the drift
};

/// Data codes (DW 11), hex as the manual writes them; ours marked (decision).
namespace code {
inline constexpr std::uint16_t encoder_speed = 0x03;     ///< encoder speed in 1/min (incremental, MD 34)
inline constexpr std::uint16_t pulse_difference = 0x04;  ///< pulse-check difference (missing pulses < 0)
inline constexpr std::uint16_t ref_rapid = 0x08;         ///< reference speed V_rapid, 10^-2 mm/min
inline constexpr std::uint16_t ref_reduced = 0x09;       ///< V_reduced
inline constexpr std::uint16_t ref_slow = 0x0A;          ///< V_slow
inline constexpr std::uint16_t drift = 0x10;             ///< submode RUN: standstill following error -> MD 35
inline constexpr std::uint16_t mdi_position = 0x19;      ///< (decision) MDI position µm; param2 bit 0 = G91
inline constexpr std::uint16_t mdi_feed = 0x1A;          ///< MDI feed, 10^-2 mm/min (0 -> 145)
inline constexpr std::uint16_t jog_feed = 0x1C;          ///< (decision) set-up speed, 10^-2 mm/min
inline constexpr std::uint16_t control_voltage = 0x1D;   ///< (decision) submode control: voltage in mV
inline constexpr std::uint16_t measured = 0x32;          ///< actual value latched at the flying-measurement edge
inline constexpr std::uint16_t teach_in = 0x40;          ///< (decision) param1 program, param2 block
inline constexpr std::uint16_t tool_offset = 0x42;       ///< (decision) param1 number 1..20, param2 µm
inline constexpr std::uint16_t delete_program = 0x43;    ///< (decision) param1 program
inline constexpr std::uint16_t program_in = 0x44;        ///< (decision) param1 user DB: read in the program text there
inline constexpr std::uint16_t program_out = 0x45;       ///< (decision) param1 program, param2 user DB to write
inline constexpr std::uint16_t delete_block = 0x46;      ///< (decision) param1 program, param2 block
inline constexpr std::uint16_t list_programs = 0x47;     ///< (decision) param1 page 1.. -> DW 30..38, result: count
inline constexpr std::uint16_t list_blocks = 0x4A;       ///< (decision) param1 program, param2 page -> DW 30..38
inline constexpr std::uint16_t buffer_length = 0x48;     ///< (decision) param1 buffer 1..6, param2 length 1..50
inline constexpr std::uint16_t buffer_reload = 0x49;     ///< (decision) param1 buffer, param2 user DB with blocks
inline constexpr std::uint16_t write_md = 0x50;          ///< (decision) param1 MD number, param2 value (MD I/O mode)
inline constexpr std::uint16_t read_md = 0x51;           ///< (decision) param1 MD number -> result
inline constexpr std::uint16_t acknowledge = 0x800C;
}  // namespace code

}  // namespace hil::controllers::s5::wf_db
