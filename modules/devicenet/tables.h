// The 1747-SDN's data tables as the SLC sees them (appendix D, "Data Organization", p.133-141).
//
//   input image  I:s.0        module status register           output image  O:s.0      command register
//                I:s.1...31   DeviceNet input data (31 words)                O:s.1...31 DeviceNet output data
//
//   M1 file  0...149   DeviceNet input data (150 words)        M0 file  0...149   DeviceNet output data
//            150...205 reserved (56 words)                               150...223 reserved (74 words)
//            206...209 device active table  (node n: word 206 + n/16, bit n%16)
//            210       high byte: node address, low byte: status code (chapter 7 numeric codes)
//            211       scan counter (increments per completed scan, 65535 rolls over to 0)
//            212...215 device idle table
//            216...219 device failure table
//            220...223 autoverify failure table
//            224...255 Explicit Message Program Control   (both files; appendix E, transaction.h)
//            256...394 pass-through (139 words)            (both files; not emulated: reads 0)
//
// Bit-per-node tables give node n bit n%16 of word base + n/16, "starting at node 0 at M1.S.206/0".
// Every table and bit number lives here, once; the scanner and the tests read these names.
#pragma once

#include <cstdint>
#include <string_view>

namespace softslc::devicenet {

enum class MFile : std::uint8_t { M0 = 0, M1 = 1 };

namespace layout {
inline constexpr int kImageWords = 32;        // I:s.0...31 and O:s.0...31
inline constexpr int kDataWords = 150;        // M0/M1 0...149
inline constexpr int kActiveTable = 206;
inline constexpr int kNodeStatus = 210;
inline constexpr int kScanCounter = 211;
inline constexpr int kIdleTable = 212;
inline constexpr int kFailureTable = 216;
inline constexpr int kAutoverifyTable = 220;
inline constexpr int kTransactionBlock = 224;  // 224...255
inline constexpr int kTransactionWords = 32;
inline constexpr int kPassThrough = 256;       // 256...394
inline constexpr int kMFileWords = 395;        // the largest M0/M1 length RSLogix configures (p.64)
inline constexpr int kNodeTableWords = 4;      // 64 nodes, one bit each
}  // namespace layout

enum class StatusBit : std::uint8_t {
#define STATUS_BIT(bit, name, text) name = bit,
#include "modules/devicenet/registers.def"
#undef STATUS_BIT
};
enum class CommandBit : std::uint8_t {
#define COMMAND_BIT(bit, name, text) name = bit,
#include "modules/devicenet/registers.def"
#undef COMMAND_BIT
};
constexpr std::uint16_t bit(StatusBit b) { return static_cast<std::uint16_t>(1u << static_cast<unsigned>(b)); }
constexpr std::uint16_t bit(CommandBit b) { return static_cast<std::uint16_t>(1u << static_cast<unsigned>(b)); }

// The command register bits that have a meaning; any other bit set is a command error.
inline constexpr std::uint16_t kDefinedCommandBits = 0
#define COMMAND_BIT(bit, name, text) | (1u << bit)
#include "modules/devicenet/registers.def"
#undef COMMAND_BIT
    ;
// The command bits the status register echoes (status bits 0, 1 and 4; p.135).
inline constexpr std::uint16_t kEchoedCommandBits = bit(CommandBit::Run) | bit(CommandBit::FaultNetwork) |
                                                    bit(CommandBit::DisableNetwork);

std::string_view status_bit_meaning(int bit);   // "" for a reserved bit
std::string_view command_bit_meaning(int bit);  // "" for a reserved bit

}  // namespace softslc::devicenet
