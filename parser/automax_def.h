// AutoMax symbol definitions (IODEF, RIODEF, MEMDEF) and the layout of the AutoMax Remote I/O
// master's dual-port image in its M0 file.
//
// The AutoMax manual's configuration task names physical points of the Remote I/O network
// (AutoMax Remote I/O manual, section 4.7.1.1):
//   IODEF   RIO_D02@[SLOT=8,REGISTER=4,BIT=2]                           a master register (drop 0)
//   RIODEF  START@[MASTER_SLOT=8,DROP=2,SLOT=11,REGISTER=0,BIT=5]        a point in a slave drop
//   MEMDEF  RIONET_OK@                                                   an internal variable
// A trailing '@' names a bit, '%' a 16-bit register. softslc reads these statements in the
// program text and turns each into a symbol whose address is a word of the master module's M0
// file (so every access goes through the VM's M-file path and is charged by the timing model),
// or, for MEMDEF, a bit of B255 / a word of N254. docs/automax.md explains the decisions.
//
// The dual-port image is "divided into 8 image areas, one for each drop and the master"
// (section 4.2), and drop 0 has registers 0-511 (figure 4.1), so each area is 512 words and the
// whole image is the 4096-word M0 file: area d starts at word 512 d. Within a slave drop's area
// each rack slot has 32 registers (slot s, register r at 512 d + 32 s + r), enough for every
// register section 4.3 names (Shark 0-31, 57C328 head 0-31).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace softslc {

// The master module's catalog: the Reliance Remote I/O module (M/N 57C416).
inline constexpr const char* kAutomaxMasterCatalog = "57C416";

inline constexpr int kAutomaxAreaWords = 512;      // registers per image area (figure 4.1: 0-511)
inline constexpr int kAutomaxAreas = 8;            // drop 0 and drops 1-7
inline constexpr int kAutomaxImageWords = kAutomaxAreaWords * kAutomaxAreas;  // the M0 file
inline constexpr int kAutomaxSlotRegisters = 32;   // registers per rack slot in a drop's area
inline constexpr int kAutomaxSlots = kAutomaxAreaWords / kAutomaxSlotRegisters;  // rack slots 0-15

// MEMDEF variables live in these data files (bits in program order, then words).
inline constexpr int kMemdefBitFile = 255;
inline constexpr int kMemdefWordFile = 254;

// The image area of a drop number: 1-7 as set, and an all-digital Shark rack's 9-F (rotary
// switch) uses area number - 8 (its status bit too): the manual's figure 4.4 rack set to "C"
// is DROP=4 in the configuration task and RIO_D04 in drop 0 register 4.
constexpr int automax_image_area(int drop) { return drop >= 9 ? drop - 8 : drop; }

// M0 word of a drop 0 register, and of a slave drop point.
constexpr int automax_master_word(int reg) { return reg; }
constexpr int automax_drop_word(int area, int slot, int reg) {
  return area * kAutomaxAreaWords + slot * kAutomaxSlotRegisters + reg;
}

// One `KEY=value` of an IODEF/RIODEF, as written.
struct AutomaxField {
  std::string key;
  std::int64_t value = 0;
  std::string spelling;  // the value as written ("04", "C", "20H"), kept by fmt
  std::uint32_t line = 0;
  std::uint32_t column = 0;  // of the key
  std::uint32_t value_column = 0;
  bool operator==(const AutomaxField& o) const { return key == o.key && value == o.value; }
};

struct AutomaxDef {
  enum class Kind : std::uint8_t { IoDef, RioDef, MemDef };
  Kind kind = Kind::IoDef;
  char suffix = '@';  // '@' bit, '%' register
  std::vector<AutomaxField> fields;
  int memdef_index = 0;  // MEMDEF: position among the MEMDEFs of its suffix (program order)

  const AutomaxField* field(std::string_view key) const {
    for (const auto& f : fields)
      if (f.key == key) return &f;
    return nullptr;
  }
  bool operator==(const AutomaxDef& o) const {
    return kind == o.kind && suffix == o.suffix && fields == o.fields && memdef_index == o.memdef_index;
  }
};

constexpr std::string_view keyword_of(AutomaxDef::Kind k) {
  return k == AutomaxDef::Kind::IoDef ? "IODEF" : k == AutomaxDef::Kind::RioDef ? "RIODEF" : "MEMDEF";
}

}  // namespace softslc
