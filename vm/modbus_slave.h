// The MicroLogix 1100/1400 as a Modbus slave: its memory map and the execution of one request PDU, pure,
// without framing or I/O. One implementation for every slave softslc simulates: `softslc serve` answers
// Modbus TCP (server/modbus.h) and Modbus RTU (server/modbus_rtu.h) through it with the live controller as
// the target, and a simulated MicroLogix whose channel 0 is a Modbus RTU slave on another controller's line
// answers that controller's MSGs through it with its own data table as the target (vm/message_network.h,
// docs/semantics.md "A MicroLogix as a Modbus RTU slave").
//
// The map is the controller's (1763-RM001C p. 530 / 1766-RM001A p. 617, "Modbus to MicroLogix
// Memory Map - Summary", and the "Detail" table on the next page for the function codes). The
// channel configuration names four data files, each a B or N file numbered 3-255:
//   coils 00001-04096            bits 0-4095 of the coil file             FC 1 read, 5, 15 write
//   contacts 10001-14096         bits 0-4095 of the contact file          FC 2 read
//   input registers 30001-30256  words 0-255 of the input register file   FC 4 read
//   input registers 31501-31566  words 0-65 of the status file S2         FC 4 read
//   holding registers 40001-40256  words 0-255 of the holding register file  FC 3 read, 6, 16 write
//   holding registers 41501-41566  words 0-65 of the status file S2       FC 3 read, 6, 16 write
//   FC 8 subfunction 0           echo (the manual's "Echo Command Data")
// Coil n is bit n%16 of word n/16 (bit 0 of word 0 is coil 00001). Protocol addresses are the
// 0-based ones on the wire: holding register 40001 is address 0, 41501 is 1500. Input registers
// 30501-30532 are the "Modbus Communication Parameters" (CommParameters below). Not simulated: the
// expanded holding-register files 40257-41280 and 41793-42048, which the manual says are active
// only when "specially configured"; they answer exception 02.
//
// Replies (Modbus Application Protocol v1.1b3 §7 for the exception codes):
//   01 illegal function       a function code not in the table above, or FC 8 with another
//                             subfunction (contacts and input registers have no write function)
//   02 illegal data address   an address range not wholly inside a mapped space and its file
//   03 illegal data value     a quantity outside the function's limits, a byte count that
//                             disagrees with the quantity, FC 5 with a value other than FF00h/0000h
//   04 server device failure  a write the controller refused (--read-only, a forced input bit)
// Decision (the manuals do not say what a MicroLogix answers for a write it cannot perform): 04.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/pccc_target.h"

namespace softslc::modbus {

inline constexpr std::size_t kMaxPdu = 253;  // a PDU is at most 253 bytes (Modbus application protocol §4.1)

inline constexpr std::uint8_t kReadCoils = 1;
inline constexpr std::uint8_t kReadDiscreteInputs = 2;
inline constexpr std::uint8_t kReadHoldingRegisters = 3;
inline constexpr std::uint8_t kReadInputRegisters = 4;
inline constexpr std::uint8_t kWriteSingleCoil = 5;
inline constexpr std::uint8_t kWriteSingleRegister = 6;
inline constexpr std::uint8_t kDiagnostics = 8;
inline constexpr std::uint8_t kWriteMultipleCoils = 15;
inline constexpr std::uint8_t kWriteMultipleRegisters = 16;

inline constexpr std::uint8_t kIllegalFunction = 0x01;
inline constexpr std::uint8_t kIllegalDataAddress = 0x02;
inline constexpr std::uint8_t kIllegalDataValue = 0x03;
inline constexpr std::uint8_t kServerDeviceFailure = 0x04;

// The channel configuration: the data file of each Modbus space (each a B or N file, 3-255).
struct Map {
  int coils = 0;
  int contacts = 0;
  int input_registers = 0;
  int holding_registers = 0;
};
// The status file number, mapped at 31501 and 41501.
inline constexpr int kStatusFile = 2;
inline constexpr std::uint16_t kStatusRegisterBase = 1500;  // 31501 / 41501
inline constexpr std::uint32_t kStatusRegisters = 66;       // words 0-65
inline constexpr std::uint32_t kCoilSpace = 4096;
inline constexpr std::uint32_t kRegisterSpace = 256;

// Input registers 30501-30532 (FC 4, protocol addresses 500-531): the "Modbus Communication
// Parameters" of the channel (1766-RM001A p. 618 / AG-UM008C p. 3-52, "Modbus Slave to MicroLogix
// Memory Map - Detail", which names each word and says no more). Index i is register 30501 + i:
//   0-3   the coil, contact, input register and holding register file numbers (30501-30504)
//   6     the Modbus slave address (30507)
//   17-25 messages to this slave with function code 1, 2, 3, 4, 5, 6, 8, 15, 16 (30518-30526)
//   27    total messages responded to by this slave (30528)
//   28    total messages to this slave (30529)
//   29    total messages seen (30530)
//   30    link layer error count (30531)
// and 0 for the rest: 30505 (not in the table), the pre-send, RTS send and RTS off delays and the
// inter-character timeout (30506, 30508-30510: not simulated; 0 is the channel's default, p. 3-49,
// 0 = 3.5 character times), and the words whose coding the page does not give: parity (30511),
// the error codes and error request (30512-30517), modem status (30527), link layer error (30532).
// The address and counters are the Modbus RTU slave's (server/modbus_rtu.h; a peer controller's on a master's
// line, vm/message_network.h; SlaveCounters below); without one they read 0, and Modbus TCP requests are not
// counted.
inline constexpr std::uint16_t kCommParameterBase = 500;
inline constexpr std::uint32_t kCommParameterCount = 32;
using CommParameters = std::array<std::uint16_t, kCommParameterCount>;
// The parameters of a map without a serial link: the four file numbers, the rest 0.
CommParameters comm_parameters(const Map& map);

// The message counters a slave keeps in its communication parameters (1766-RM001A p. 618 "Modbus Slave to
// MicroLogix Memory Map - Detail", 30518-30531): serve's Modbus RTU slave (server/modbus_rtu.h) and a peer whose
// channel 0 is a slave on another controller's line (vm/message_network.h) count alike. 16-bit registers.
struct SlaveCounters {
  std::uint16_t seen = 0;         // frames on the line, whatever their address ("Total Messages Seen")
  std::uint16_t to_slave = 0;     // of them, to this slave or broadcast ("Total messages to this Slave")
  std::uint16_t responded = 0;    // replies sent ("Total messages responded to by this slave")
  std::uint16_t link_errors = 0;  // frames dropped: bad CRC, too long, cut short ("Link Layer Error Count")
  // Requests to this slave per function code 1, 2, 3, 4, 5, 6, 8, 15, 16 (30518-30526).
  std::uint16_t function[9] = {};
  // A request to this slave (or broadcast) with function code `fc`: to_slave and its function's counter.
  void count_request(std::uint8_t fc);
  // Writes the counters into their registers of `p` (indices 17-25 and 27-30).
  void write(CommParameters& p) const;
};
// The parameters a Modbus RTU slave answers: the map's file numbers, its address (30507) and its counters.
CommParameters comm_parameters(const Map& map, int address, const SlaveCounters& counters);

// The baud rates of a MicroLogix channel configured for Modbus RTU (AG-UM008C p. 3-49): serve's --modbus-baud,
// a test's `peer ... modbus baud=`.
inline constexpr int kSlaveBauds[] = {300, 600, 1200, 2400, 4800, 9600, 19200, 38400};
inline constexpr int kMinSlaveAddress = 1;
inline constexpr int kMaxSlaveAddress = 247;  // Modbus over serial line §2.2: 248-255 are reserved

// A simulated MicroLogix 1100/1400 whose channel 0 is configured as a Modbus RTU slave (a test's `peer NAME PATH
// modbus SETTING...`, docs/testing.md): its slave address, baud rate and map; unset settings as serve's defaults.
struct SlaveOptions {
  int address = 1;
  std::int64_t baud = 19200;
  Map map{3, 3, 7, 7};  // B3,B3,N7,N7
};
// One setting, `address=N` (1-247), `baud=N` (kSlaveBauds) or `map=C,D,I,H`: "" or why it is refused.
std::string parse_slave_option(std::string_view text, SlaveOptions& options);

// "B3,B3,N7,N7" (or "3,3,7,7"): the four file numbers of a map, coils, contacts, input registers, holding
// registers (serve's --modbus-map, a test's `peer ... modbus map=`); nullopt when the text is not four files.
std::optional<Map> parse_map(const std::string& text);

// Checks a map against the program's files: empty when usable, else what is wrong.
std::string check_map(const Map& map, const pccc::Target& target);

// Modbus puts 16-bit fields high byte first (Modbus Application Protocol V1.1b3, 4.2); the TCP
// framing (server/modbus.cpp) and the PDUs share these.
inline std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] << 8 | b[at + 1]);
}

inline void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
}

// Executes one request PDU (function code and data) and returns the reply PDU: the function and
// its data, or function | 80h and one exception code. Modbus TCP (handle below) and Modbus RTU
// (server/modbus_rtu.h) both answer through it, and so does a simulated slave controller (vm/message_network.h), so the map, the exception codes and the writes
// (through `target`, journaled by the live controller) are the same on both. An empty PDU gets an
// empty reply. `refusal`, when given, receives why an exception was answered (for the log).
// `comm`: the communication parameters to answer at 30501-30532; nullptr: comm_parameters(map).
std::vector<std::uint8_t> handle_pdu(std::span<const std::uint8_t> pdu, const Map& map, pccc::Target& target,
                                     std::string* refusal = nullptr, const CommParameters* comm = nullptr);

}  // namespace softslc::modbus
