// AutoScan (chapter 9, p.103-113): the allocation arithmetic and the scanlist entries it creates,
// as pure functions; Scanner runs the probing.
//
// With AutoScan enabled and the scanner in Idle, the scanner probes unmapped nodes 0...61 round
// robin. For a device it finds it reads the produced and consumed sizes of the first connection
// the device supports in the order COS, poll, strobe, cyclic (p.110) and maps the device at a
// fixed place given by its address:
//     M file input (output) byte offset = node address x allocation size          (p.110)
// byte b being the low byte of word b/2 when b is even and the high byte when odd ("with the
// non-integer result the offset starts at the upper byte of the word"). A device is rejected when
// either size exceeds the allocation size, or when its allocation would not fit in the 150-word
// (300-byte) data table (p.112: "Devices outside of the scanner's allowable I/O image space will
// be rejected").
//
// The enable flag and the allocation size are reached by explicit messages to the scanner's own
// address (p.104-106). The manual's figures with the class/instance/attribute values are missing
// from our copy; we use the vendor-specific scanner configuration class 0x90, instance 1,
// attribute 1 (enable, USINT 0/1) and attribute 2 (allocation size, USINT 1...32). These three
// constants are the only place the assumption lives.
#pragma once

#include <cstdint>
#include <optional>

#include "modules/devicenet/device_model.h"
#include "modules/devicenet/scanlist.h"

namespace softslc::devicenet::autoscan {

inline constexpr std::uint8_t kClass = 0x90;
inline constexpr std::uint16_t kInstance = 1;
inline constexpr std::uint8_t kEnableAttribute = 1;
inline constexpr std::uint8_t kAllocationAttribute = 2;

inline constexpr int kFirstNode = 0;
inline constexpr int kLastNode = 61;     // "only checks for devices with node addresses between 0...61"
inline constexpr int kTableBytes = 300;  // 150 words
inline constexpr int kMinAllocation = 1;
inline constexpr int kMaxAllocation = 32;
inline constexpr int kDefaultAllocation = 4;
inline constexpr Nanoseconds kInterscanDelay = 4 * kNsPerMs;  // "changes ... ISD from 10 ms to 4 ms" (p.113)

// The connection types in the order AutoScan tries them (p.110).
inline constexpr IoType kPreference[] = {IoType::Cos, IoType::Poll, IoType::Strobe, IoType::Cyclic};

constexpr int byte_offset(int node, int allocation) { return node * allocation; }
// Whether node's whole allocation lies inside the 300-byte table.
constexpr bool fits(int node, int allocation) { return byte_offset(node, allocation) + allocation <= kTableBytes; }
// The highest node whose allocation fits, capped at 61 (the manual's "Max Node" column, p.112).
constexpr int max_node(int allocation) {
  const int n = kTableBytes / allocation - 1;
  return n < kLastNode ? n : kLastNode;
}

enum class Verdict : std::uint8_t { Accepted, NoConnection, TooLarge, OutsideTable };

// Decides on a found device and, when accepted, gives the scanlist entry to add.
struct Decision {
  Verdict verdict = Verdict::NoConnection;
  std::optional<ScanlistEntry> entry;
};
Decision decide(int node, int allocation, const Identity& id, const std::array<IoSupport, 4>& reported);

}  // namespace softslc::devicenet::autoscan
