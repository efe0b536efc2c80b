#include "instructions/instruction_table.h"

#include <algorithm>
#include <array>

namespace softslc {

namespace {
constexpr bool table_is_in_opcode_order() {
  for (std::size_t i = 0; i < kInstructionCount; ++i)
    if (static_cast<std::size_t>(kInstructionTable[i].opcode) != i) return false;
  return true;
}
static_assert(table_is_in_opcode_order(), "kInstructionTable must be indexed by Opcode");
}  // namespace

namespace {
// find_instruction runs for every instruction of a program, and comparing each row's mnemonic in
// turn was 5% of loading a 1M-rung program (docs/performance.md "Load time"). The rows are grouped
// by their mnemonic's length and first letter (every mnemonic starts with a capital, checked
// below), in table order within a group, so a lookup compares only the few rows of its group and
// still finds the first row of a mnemonic with several forms.
constexpr std::size_t mnemonic_group(std::size_t length, char first) {
  return length * 26 + static_cast<std::size_t>(first - 'A');
}
constexpr std::size_t kLongestMnemonic = [] {
  std::size_t n = 0;
  for (const auto& s : kInstructionTable) n = std::max(n, s.mnemonic.size());
  return n;
}();
static_assert([] {
  for (const auto& s : kInstructionTable)
    if (s.mnemonic.empty() || s.mnemonic[0] < 'A' || s.mnemonic[0] > 'Z') return false;
  return true;
}(), "find_instruction groups mnemonics by a capital first letter");
constexpr std::size_t group_of_row(std::size_t row) {
  return mnemonic_group(kInstructionTable[row].mnemonic.size(), kInstructionTable[row].mnemonic[0]);
}
// Row numbers ordered by group, table order kept within a group (an insertion sort: stable).
constexpr auto kRowsByGroup = [] {
  std::array<std::uint16_t, kInstructionCount> rows{};
  for (std::size_t i = 0; i < kInstructionCount; ++i) {
    std::size_t j = i;
    while (j > 0 && group_of_row(rows[j - 1]) > group_of_row(i)) {
      rows[j] = rows[j - 1];
      --j;
    }
    rows[j] = static_cast<std::uint16_t>(i);
  }
  return rows;
}();
// Where each group starts in kRowsByGroup (group g is kGroupStart[g] to kGroupStart[g + 1]).
constexpr auto kGroupStart = [] {
  std::array<std::uint16_t, mnemonic_group(kLongestMnemonic + 1, 'A') + 1> start{};
  std::size_t i = 0;
  // `!=`, not `<`: cppcheck 2.10 takes `g < start.size()` in this lambda for a template argument
  // list and stops at a syntax error.
  for (std::size_t g = 0; g != start.size(); ++g) {
    while (i < kInstructionCount && group_of_row(kRowsByGroup[i]) < g) ++i;
    start[g] = static_cast<std::uint16_t>(i);
  }
  return start;
}();
}  // namespace

const InstructionSpec* find_instruction(std::string_view mnemonic) {
  if (mnemonic.empty() || mnemonic.size() > kLongestMnemonic || mnemonic[0] < 'A' || mnemonic[0] > 'Z') return nullptr;
  const std::size_t g = mnemonic_group(mnemonic.size(), mnemonic[0]);
  for (std::size_t i = kGroupStart[g]; i < kGroupStart[g + 1]; ++i)
    if (kInstructionTable[kRowsByGroup[i]].mnemonic == mnemonic) return &kInstructionTable[kRowsByGroup[i]];
  return nullptr;
}

const InstructionSpec* find_instruction_form(std::string_view mnemonic, std::size_t operand_count) {
  for (const auto& s : kInstructionTable)
    if (s.mnemonic == mnemonic && s.operand_count == operand_count) return &s;
  return find_instruction(mnemonic);
}

std::string_view to_string(OperandKind k) {
  switch (k) {
    case OperandKind::Bit: return "bit address";
    case OperandKind::Source: return "word address or constant";
    case OperandKind::Dest: return "word address";
    case OperandKind::File: return "file address (#)";
    case OperandKind::Timer: return "timer element (T)";
    case OperandKind::Counter: return "counter element (C)";
    case OperandKind::Control: return "control element (R)";
    case OperandKind::Resettable: return "timer, counter or control element";
    case OperandKind::TimeBase: return "time base (1.0 or 0.01)";
    case OperandKind::Literal: return "integer constant";
    case OperandKind::Label: return "label number";
    case OperandKind::ProgramFile: return "program file number";
    case OperandKind::SlotWord: return "I: or O: slot word";
    case OperandKind::Buffer: return "M-file buffer address (M0:e.x00 / M1:e.x00)";
    case OperandKind::ControlBlock3: return "integer control block (3 words)";
    case OperandKind::ControlBlock70: return "integer control block (70 words)";
    case OperandKind::ControlBlock23: return "integer control block (23 words)";
    case OperandKind::WordSource: return "integer word address or constant (no F)";
    case OperandKind::WordDest: return "integer word address (no F)";
    case OperandKind::Expression: return "CPT expression";
    case OperandKind::String: return "string element (STf:e)";
    case OperandKind::MessageCommand: return "READ or WRITE (a Modbus MSG: its command, 01-06, 15 or 16)";
    case OperandKind::MessageDevice: return "target device (500CPU, 485CIF, PLC5 or MODBUS)";
    case OperandKind::MessageRoute: return "LOCAL or REMOTE";
    case OperandKind::MessageBlock: return "integer control block (the control block length)";
    case OperandKind::MessageData: return "data table element address";
    case OperandKind::MessageElement: return "MG message file element (MG11:0)";
    case OperandKind::MessageTarget: return "target node (channel 0) or RI routing element (RI12:0, channel 1 Ethernet)";
    case OperandKind::RemoteAddress: return "the target's data table address (485CIF: word offset)";
  }
  return "?";
}

namespace {
constexpr std::string_view kCommandWords[] = {"READ", "WRITE"};
constexpr std::string_view kDeviceWords[] = {"500CPU", "485CIF", "PLC5", "MODBUS"};
constexpr std::string_view kRouteWords[] = {"LOCAL", "REMOTE"};
}  // namespace

std::span<const std::string_view> keyword_words(OperandKind k) {
  switch (k) {
    case OperandKind::MessageCommand: return kCommandWords;
    case OperandKind::MessageDevice: return kDeviceWords;
    case OperandKind::MessageRoute: return kRouteWords;
    default: return {};
  }
}

std::optional<int> keyword_code(OperandKind k, std::string_view word) {
  const auto words = keyword_words(k);
  for (std::size_t i = 0; i < words.size(); ++i)
    if (words[i] == word) return static_cast<int>(i);
  return std::nullopt;
}

std::string_view to_string(MFileAccess a) {
  switch (a) {
    case MFileAccess::NoM: return "no M-file access allowed";
    case MFileAccess::ExamineBit: return "XIC or XIO";
    case MFileAccess::OutputBit: return "OTU, OTE, or OTL";
    case MFileAccess::CopToM: return "COP to M file";
    case MFileAccess::CopFromM: return "COP from M file";
    case MFileAccess::FllToM: return "FLL";
    case MFileAccess::MvmToM: return "MVM to M file";
    case MFileAccess::OtherM: return "any source or destination M file address";
  }
  return "?";
}

}  // namespace softslc
