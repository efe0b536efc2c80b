// Modbus TCP as a MicroLogix 1100/1400 answers it when its channel is configured as a Modbus slave:
// a pure decoder and executor, without sockets, like server/pccc.h.
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
//
// A frame is the 7-byte MBAP header (transaction u16, protocol u16 = 0, length u16 = unit id +
// PDU bytes, unit id u8, all big-endian) and the PDU. A protocol id other than 0 or a length
// outside 2-254 (a PDU is at most 253 bytes) is not a Modbus frame: the connection closes. The
// unit id is echoed and not checked (a Modbus TCP server addressed directly is the unit).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "server/pccc.h"

namespace softslc::modbus {

inline constexpr std::uint16_t kPort = 502;
inline constexpr std::size_t kHeaderSize = 7;  // MBAP
inline constexpr std::size_t kMaxPdu = 253;

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
// The address and counters are the Modbus RTU slave's (server/modbus_rtu.h); without one they
// read 0, and Modbus TCP requests are not counted.
inline constexpr std::uint16_t kCommParameterBase = 500;
inline constexpr std::uint32_t kCommParameterCount = 32;
using CommParameters = std::array<std::uint16_t, kCommParameterCount>;
// The parameters of a map without a serial link: the four file numbers, the rest 0.
CommParameters comm_parameters(const Map& map);

// Checks a map against the program's files: empty when usable, else what is wrong.
std::string check_map(const Map& map, const pccc::Target& target);

struct Header {
  std::uint16_t transaction = 0;
  std::uint16_t protocol = 0;
  std::uint16_t length = 0;  // unit id + PDU
  std::uint8_t unit = 0;
};
// The MBAP header of the first 7 bytes; nullopt when fewer, or when it is not a Modbus TCP header
// (protocol id not 0, length outside 2-254) — `error` says which.
std::optional<Header> decode_header(std::span<const std::uint8_t> bytes, std::string* error = nullptr);

// Executes one request PDU (function code and data) and returns the reply PDU: the function and
// its data, or function | 80h and one exception code. Modbus TCP (handle below) and Modbus RTU
// (server/modbus_rtu.h) both answer through it, so the map, the exception codes and the writes
// (through `target`, journaled by the live controller) are the same on both. An empty PDU gets an
// empty reply. `refusal`, when given, receives why an exception was answered (for the log).
// `comm`: the communication parameters to answer at 30501-30532; nullptr: comm_parameters(map).
std::vector<std::uint8_t> handle_pdu(std::span<const std::uint8_t> pdu, const Map& map, pccc::Target& target,
                                     std::string* refusal = nullptr, const CommParameters* comm = nullptr);

// Handles one whole frame (header and exactly length-1 PDU bytes) and returns the reply frame.
// nullopt: the frame is malformed (the connection closes, `error` says why). `refusal`, when
// given, receives why an exception was answered (for the log).
std::optional<std::vector<std::uint8_t>> handle(std::span<const std::uint8_t> frame, const Map& map,
                                                pccc::Target& target, std::string* error = nullptr,
                                                std::string* refusal = nullptr, const CommParameters* comm = nullptr);

}  // namespace softslc::modbus
