#include "instructions/mfile_access_time.h"

#include <array>

namespace softslc {

namespace {

using A = MFileAccess;

// 1747-SN manual appendix B p. B-4 / 1203-SM1 manual appendix A p. A-5, row by row.
constexpr std::array kRows{
    // SLC 5/02 Series B, "All Types": 1930 µs; 1580 µs plus 670 µs per word.
    MFileAccessRow{"5/02B", A::OtherM, 1930, 1580, 670},
    // SLC 5/02 Series C, "All Types": 1160 µs; 950 µs plus 400 µs per word.
    MFileAccessRow{"5/02C", A::OtherM, 1160, 950, 400},
    // SLC 5/03 (all series).
    MFileAccessRow{"5/03", A::ExamineBit, 782, 0, 0},
    MFileAccessRow{"5/03", A::OutputBit, 925, 0, 0},
    MFileAccessRow{"5/03", A::CopToM, 0, 772, 23},
    MFileAccessRow{"5/03", A::CopFromM, 0, 760, 22},
    MFileAccessRow{"5/03", A::FllToM, 0, 753, 30},
    MFileAccessRow{"5/03", A::MvmToM, 894, 0, 0},
    MFileAccessRow{"5/03", A::OtherM, 730, 0, 0},
    // SLC 5/04 OS400 (and, in the 1747-SN table, SLC 5/05).
    MFileAccessRow{"5/04", A::ExamineBit, 743, 0, 0},
    MFileAccessRow{"5/04", A::OutputBit, 879, 0, 0},
    MFileAccessRow{"5/04", A::CopToM, 0, 735, 23},
    MFileAccessRow{"5/04", A::CopFromM, 0, 722, 22},
    MFileAccessRow{"5/04", A::FllToM, 0, 716, 30},
    MFileAccessRow{"5/04", A::MvmToM, 850, 0, 0},
    MFileAccessRow{"5/04", A::OtherM, 694, 0, 0},
    MFileAccessRow{"5/05", A::ExamineBit, 743, 0, 0},
    MFileAccessRow{"5/05", A::OutputBit, 879, 0, 0},
    MFileAccessRow{"5/05", A::CopToM, 0, 735, 23},
    MFileAccessRow{"5/05", A::CopFromM, 0, 722, 22},
    MFileAccessRow{"5/05", A::FllToM, 0, 716, 30},
    MFileAccessRow{"5/05", A::MvmToM, 850, 0, 0},
    MFileAccessRow{"5/05", A::OtherM, 694, 0, 0},
};

}  // namespace

std::span<const MFileAccessRow> mfile_access_table() { return kRows; }

std::optional<std::int64_t> mfile_access_us(std::string_view timing_key, MFileAccess access, int words) {
  if (access == MFileAccess::NoM || words < 1) return std::nullopt;
  // The 5/02 rows are "All Types": one row serves every instruction type.
  bool all_types = timing_key == "5/02B" || timing_key == "5/02C";
  for (const auto& r : kRows) {
    if (r.processor != timing_key || (!all_types && r.access != access)) continue;
    if (is_multi_word(access)) return r.multi_base_us + r.multi_per_word_us * words;
    return r.per_access_us * words;
  }
  return std::nullopt;
}

}  // namespace softslc
