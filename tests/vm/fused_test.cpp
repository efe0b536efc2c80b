// Fused rungs (vm/fused.h) must give exactly what the general path gives: the same data table,
// scan time, instruction count, last rung and faults. The main test generates random programs
// of bit-logic rungs (nested branches, coils inside legs, contacts that read a coil of the same
// rung, more contacts than a fused rung holds) mixed with rungs the general path must run (TON,
// CTU, MOV, OSR, MCR zones, JSR into a subroutine, JMP/LBL), and scans each with fusion on and off
// under a cost model whose every op has distinct true and false charges. The smaller tests pin
// values computed by hand from docs/bytecode.md ("Rung logic") and the default cost model's
// documented constants (vm/scan_time_model.h).
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

#include "parser/loader.h"
#include "vm/compiler.h"
#include "vm/fused.h"
#include "vm/interpreter.h"
#include "vm/scan_time_model.h"

namespace softslc {
namespace {

// Every op costs something different, true or false, so a wrong rung-in anywhere shows up in
// the scan time.
class DistinctCosts final : public ScanTimeModel {
 public:
  std::string_view name() const override { return "distinct"; }
  Nanoseconds instruction_cost(Opcode op, bool rung_in) const override {
    return 100 + 17 * static_cast<Nanoseconds>(op) + (rung_in ? 1000 : 0);
  }
  Nanoseconds input_scan_cost(const Module&) const override { return 0; }
  Nanoseconds output_scan_cost(const Module&) const override { return 0; }
  Nanoseconds housekeeping_cost() const override { return 0; }
};

struct NoChassis final : ChassisAccess {
  MAccess read_m(int, MFile, int, std::uint16_t&) override { return MAccess::NoSuchWord; }
  MAccess write_m(int, MFile, int, std::uint16_t) override { return MAccess::NoSuchWord; }
  void immediate_input(int, int, int, std::uint16_t) override {}
  void immediate_output(int, int, int, std::uint16_t) override {}
};

CompiledProgram build(const std::string& text) {
  LoadResult lr = load_program(text, "fused.slc");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics() + "\n" + text);
  CompileResult cr = compile(*lr.program);
  if (!cr.ok()) throw std::runtime_error(cr.render() + "\n" + text);
  return std::move(*cr.program);
}

// The rung structure comes from `shape`; bit addresses come from `bits` when `split` is set, so
// a saved `shape` state replays one rung structure with new operands (one fused shape repeated:
// a segment). Unsplit, both come from `shape`.
struct Rng {
  explicit Rng(unsigned seed) : shape(seed), bits(seed * 7919u + 1) {}
  std::uint32_t operator()() { return shape(); }
  std::uint32_t bit() { return split ? bits() : shape(); }
  std::mt19937 shape, bits;
  bool split = false;
  unsigned words = 4;
  int file = 3;  // the bit file
};

// A small pool of bits (four words by default), so contacts often read what coils of the same
// rung write, and contacts of one rung often share a word.
std::string random_bit(Rng& rng) {
  const std::uint32_t word = rng.bit() % rng.words;
  return "B" + std::to_string(rng.file) + ":" + std::to_string(word) + "/" + std::to_string(rng.bit() % 16);
}

// A random condition: contacts and (nested) input branches.
std::string random_condition(Rng& rng, int depth, int& budget) {
  std::string s;
  const int n = 1 + static_cast<int>(rng() % 4);
  for (int i = 0; i < n && budget > 0; ++i, --budget) {
    const unsigned pick = rng() % 10;
    if (pick < 5) {
      s += "XIC " + random_bit(rng) + " ";
    } else if (pick < 8 || depth >= 3) {
      s += "XIO " + random_bit(rng) + " ";
    } else {
      const int legs = 2 + static_cast<int>(rng() % 2);
      s += "BST ";
      for (int l = 0; l < legs; ++l) s += std::string(l > 0 ? "NXB " : "") + random_condition(rng, depth + 1, budget);
      s += "BND ";
    }
  }
  return s;
}

std::string random_coil(Rng& rng) {
  static const char* const kCoils[] = {"OTE ", "OTE ", "OTL ", "OTU "};
  return kCoils[rng() % 4] + random_bit(rng) + " ";
}

// A random rung body of contact logic: a condition, then one coil or an output branch whose legs
// have their own conditions and coils (a later leg's contact may read an earlier leg's coil).
std::string random_elements(Rng& rng, int& budget) {
  std::string s = random_condition(rng, 0, budget);
  if (rng() % 3 != 0) return s + random_coil(rng);
  const int legs = 2 + static_cast<int>(rng() % 3);
  s += "BST ";
  for (int l = 0; l < legs; ++l) {
    if (l > 0) s += "NXB ";
    if (rng() % 2) s += random_condition(rng, 1, budget);
    s += random_coil(rng);
    if (rng() % 4 == 0) s += random_coil(rng);
  }
  return s + "BND ";
}

std::string random_program(Rng& rng) {
  std::string s = "START 1747-L532\nLADDER 2\n";
  const int rungs = 40 + static_cast<int>(rng() % 40);
  for (int r = 0; r < rungs; ++r) {
    const unsigned kind = rng() % 20;
    if (kind == 0) {
      s += "SOR XIC " + random_bit(rng) + " TON T4:" + std::to_string(rng() % 4) + " 0.01 5 0 EOR\n";
    } else if (kind == 1) {
      s += "SOR XIC " + random_bit(rng) + " CTU C5:" + std::to_string(rng() % 4) + " 3 0 EOR\n";
    } else if (kind == 2) {
      s += "SOR XIC " + random_bit(rng) + " MOV B3:" + std::to_string(rng() % 4) + " B3:" + std::to_string(rng() % 4) +
           " EOR\n";
    } else if (kind == 3) {
      s += "SOR XIC " + random_bit(rng) + " OSR B3:4/" + std::to_string(rng() % 16) + " OTE " + random_bit(rng) + " EOR\n";
    } else if (kind == 4) {
      // An MCR zone: the rungs inside it run with rung-in false while the opening MCR is false.
      s += "SOR XIC " + random_bit(rng) + " MCR EOR\n";
      int budget = 12;
      s += "SOR " + random_elements(rng, budget) + "EOR\n";
      s += "SOR MCR EOR\n";
    } else if (kind == 5) {
      s += "SOR XIC " + random_bit(rng) + " JSR 3 EOR\n";
    } else if (kind == 6) {
      // A JMP over the next fused rung to a label rung.
      const std::string label = std::to_string(r);
      int budget = 6;
      s += "SOR XIO " + random_bit(rng) + " JMP " + label + " EOR\n";
      s += "SOR " + random_elements(rng, budget) + "EOR\n";
      s += "SOR LBL " + label + " XIC " + random_bit(rng) + " OTE " + random_bit(rng) + " EOR\n";
    } else {
      int budget = 4 + static_cast<int>(rng() % 10);
      s += "SOR " + random_elements(rng, budget) + "EOR\n";
    }
  }
  s += "LADDER 3\nSOR SBR OTE B3:5/0 EOR\n";
  for (int r = 0; r < 5; ++r) {
    int budget = 8;
    s += "SOR " + random_elements(rng, budget) + "EOR\n";
  }
  s += "SOR RET EOR\n";
  return s;
}

struct Machine {
  DataTable table;
  NoChassis chassis;
  Interpreter interp;
  Machine(const CompiledProgram& p, const ScanTimeModel& m, bool fusion)
      : table(p.layout, p.initial_words), interp(p, table, chassis, m) {
    interp.set_fusion(fusion);
  }
};

FusedProgram fused_program(const CompiledProgram& p, const Machine& m) {
  return FusedProgram(p, m.interp.costs(), m.interp.per_word_costs());
}

void expect_same(const ProgramScanResult& a, const ProgramScanResult& b, const std::string& where) {
  EXPECT_EQ(a.faulted, b.faulted) << where;
  EXPECT_EQ(a.fault.code, b.fault.code) << where;
  EXPECT_EQ(a.fault.rung, b.fault.rung) << where;
  EXPECT_EQ(a.elapsed, b.elapsed) << where;
  EXPECT_EQ(a.instructions, b.instructions) << where;
  EXPECT_EQ(a.last_file, b.last_file) << where;
  EXPECT_EQ(a.last_rung, b.last_rung) << where;
}

// Scans `p` 30 times with fusion on and off, setting the first words of the bit file to random
// values before every other scan, and requires the same results and data table after every scan.
void expect_fusion_changes_nothing(const CompiledProgram& p, const std::string& text, unsigned seed,
                                   Nanoseconds watchdog, Rng& rng) {
  const DistinctCosts model;
  Machine fused(p, model, true), general(p, model, false);
  for (int scan = 0; scan < 30; ++scan) {
    for (std::uint32_t w = 0; w < rng.words; ++w) {
      const auto v = static_cast<std::uint16_t>(rng());
      const std::uint32_t at = p.layout->files[static_cast<std::size_t>(rng.file)].base + w;
      // Half the scans keep what the program wrote, so latches and feedback carry over.
      if (scan % 2 == 0) {
        fused.table.set_word(at, v);
        general.table.set_word(at, v);
      }
    }
    const auto a = fused.interp.program_scan(scan * 10'000'000LL, 0, scan == 0, watchdog);
    const auto b = general.interp.program_scan(scan * 10'000'000LL, 0, scan == 0, watchdog);
    const std::string where = "seed " + std::to_string(seed) + " scan " + std::to_string(scan) + "\n" + text;
    expect_same(a, b, where);
    for (std::uint32_t w = 0; w < p.layout->total_words; ++w)
      ASSERT_EQ(fused.table.word(w), general.table.word(w)) << "word " << p.layout->describe(w) << ", " << where;
  }
}

TEST(Fused, RandomProgramsMatchTheGeneralPath) {
  const DistinctCosts model;
  std::size_t fused_total = 0, rungs_total = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    Rng rng(seed);
    const std::string text = random_program(rng);
    const CompiledProgram p = build(text);
    const FusedProgram fp = fused_program(p, Machine(p, model, true));
    fused_total += fp.fused_rungs();
    for (const auto& f : p.files) rungs_total += f.rungs.size();
    // A watchdog that some seeds reach mid-scan, so the fused path's watchdog exit is compared too.
    const Nanoseconds watchdog = seed % 3 == 0 ? 40'000 : INT64_MAX;
    expect_fusion_changes_nothing(p, text, seed, watchdog, rng);
  }
  // The comparison means something only if many rungs were fused and many were not.
  EXPECT_GT(fused_total, rungs_total / 3);
  EXPECT_LT(fused_total, rungs_total);
}

// Groups of consecutive rungs with one structure and fresh operands, as generated ladder and
// copied rungs are: each group is one fused shape repeated, which a single kernel call runs as a
// segment (vm/fused.h). Series contacts with one coil (0 to 8 contacts, each coil kind), one
// parallel branch, and random networks; two words of bits, so contacts of a rung often share a
// word and a contact often reads the bit its rung's coil writes (a seal-in: it must see the
// value before the coil). Some seeds' watchdog stops a scan inside a segment.
std::string random_segmented_program(Rng& rng, bool big_data_table) {
  std::string s = "START 1747-L532\nLADDER 2\n";
  // Sizes nine string files (9 x 256 x 42 words) so the data table passes 65,536 words; the
  // ACN never runs (B9:0/0 is never set).
  if (big_data_table)
    s += "SOR XIC B9:0/0 ACN ST10:255 ST11:255 ST12:255 ACN ST13:255 ST14:255 ST15:255 "
         "ACN ST16:255 ST17:255 ST18:255 EOR\n";
  rng.split = true;
  const int groups = 8 + static_cast<int>(rng() % 10);
  for (int g = 0; g < groups; ++g) {
    const int repeat = 1 + static_cast<int>(rng() % 12);
    const unsigned kind = rng() % 5;
    const int contacts = static_cast<int>(rng() % 9);
    const int budget0 = 2 + static_cast<int>(rng() % 8);
    const std::mt19937 saved = rng.shape;
    for (int i = 0; i < repeat; ++i) {
      rng.shape = saved;
      std::string rung;
      if (kind <= 1) {
        for (int c = 0; c < contacts; ++c) rung += (rng() % 2 ? "XIC " : "XIO ") + random_bit(rng) + " ";
        rung += random_coil(rng);
      } else if (kind == 2) {
        rung = "XIC " + random_bit(rng) + " BST XIC " + random_bit(rng) + " NXB XIO " + random_bit(rng) + " BND " +
               random_coil(rng);
      } else {
        int budget = budget0;
        rung = random_elements(rng, budget);
      }
      s += "SOR " + rung + "EOR\n";
    }
    // Now and then a rung the general path runs ends the run of fused rungs.
    if (rng() % 4 == 0) s += "SOR XIC " + random_bit(rng) + " TON T4:0 0.01 5 0 EOR\n";
  }
  rng.split = false;
  return s;
}

TEST(Fused, RepeatedRungShapesMatchTheGeneralPath) {
  const DistinctCosts model;
  std::size_t fused_total = 0, segments_total = 0, watchdog_scans = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    Rng rng(seed);
    rng.words = 2;
    const std::string text = random_segmented_program(rng, false);
    const CompiledProgram p = build(text);
    const FusedProgram fp = fused_program(p, Machine(p, model, true));
    EXPECT_FALSE(fp.wide_indices());
    fused_total += fp.fused_rungs();
    segments_total += fp.segments();
    Nanoseconds watchdog = INT64_MAX;
    if (seed % 2 == 0) {
      watchdog = 20'000 + static_cast<Nanoseconds>(seed) * 7'919;
      ++watchdog_scans;
    }
    expect_fusion_changes_nothing(p, text, seed, watchdog, rng);
  }
  // Most rungs share a segment with the rung before.
  EXPECT_LT(segments_total * 2, fused_total);
  EXPECT_GT(watchdog_scans, 0u);
}

// The same with a data table of more than 65,536 words: the records hold 32-bit word indices,
// and the bits (B20, after the string files) are past word 65,535.
TEST(Fused, WideWordIndicesMatchTheGeneralPath) {
  const DistinctCosts model;
  for (unsigned seed = 101; seed <= 110; ++seed) {
    Rng rng(seed);
    rng.words = 2;
    rng.file = 20;
    const std::string text = random_segmented_program(rng, true);
    const CompiledProgram p = build(text);
    ASSERT_GT(p.layout->files[20].base, 0xFFFFu);
    const FusedProgram fp = fused_program(p, Machine(p, model, true));
    EXPECT_TRUE(fp.wide_indices());
    EXPECT_GT(fp.fused_rungs(), 0u);
    expect_fusion_changes_nothing(p, text, seed, seed % 2 ? INT64_MAX : 60'000, rng);
  }
}

// ---- Word rungs: contacts and compares, then TON/TOF/RTO, CTU/CTD, RES, MOV, ADD or SUB ----

// Slow enough that a scan spans several 10 ms ticks, so timers read the tick count at their own
// virtual time inside the scan and a tick boundary falls between rungs; still distinct per op
// and per rung-in, so a wrong charge anywhere shows up in the scan time and the timer stamps.
class SlowDistinctCosts final : public ScanTimeModel {
 public:
  std::string_view name() const override { return "slow distinct"; }
  Nanoseconds instruction_cost(Opcode op, bool rung_in) const override {
    return 40'000 + 1'700 * static_cast<Nanoseconds>(op) + (rung_in ? 90'000 : 0);
  }
  // COP and the other file instructions charge per word too (a fused COP adds it with its rung).
  Nanoseconds per_word_cost(Opcode op) const override { return 300 + static_cast<Nanoseconds>(op); }
  Nanoseconds input_scan_cost(const Module&) const override { return 0; }
  Nanoseconds output_scan_cost(const Module&) const override { return 0; }
  Nanoseconds housekeeping_cost() const override { return 0; }
};

// A word operand read by a compare, MOV, ADD or SUB: a few N7 words (so rungs read what others
// write, and an ADD's destination is often its own source), a timer's or counter's ACC or PRE
// (aliasing the elements the timers and counters write), a B3 word the coils write, S:0, and
// immediates at the 16-bit edges and past them (MOV 40000 saturates and sets V).
std::string random_source(Rng& rng) {
  static const char* const kImmediates[] = {"0", "1", "-1", "5", "32767", "-32768", "30000", "-30000", "40000"};
  const unsigned pick = rng() % 13;
  if (pick < 5) return "N7:" + std::to_string(rng() % 4);
  if (pick < 9) return kImmediates[rng() % 9];
  if (pick == 9) return "T4:" + std::to_string(rng() % 3) + (rng() % 2 ? ".ACC" : ".PRE");
  if (pick == 10) return "C5:" + std::to_string(rng() % 3) + ".ACC";
  if (pick == 11) return "B3:" + std::to_string(rng() % 2);  // the words the coils write
  return "S:0";
}
std::string random_dest(Rng& rng) {
  const unsigned pick = rng() % 16;
  if (pick < 13) return "N7:" + std::to_string(rng() % 4);
  if (pick < 15) return "C5:" + std::to_string(rng() % 3) + ".ACC";
  return "T4:" + std::to_string(rng() % 3) + ".ACC";
}

// A contact on a B3 bit or on a timer's or counter's status bit.
std::string random_word_contact(Rng& rng) {
  static const char* const kStatus[] = {"/DN", "/EN", "/TT"};
  const std::string kind = rng() % 2 ? "XIC " : "XIO ";
  switch (rng() % 4) {
    case 0: return kind + "T4:" + std::to_string(rng() % 3) + kStatus[rng() % 3] + " ";
    case 1: return kind + "C5:" + std::to_string(rng() % 3) + "/DN ";
    default: return kind + random_bit(rng) + " ";
  }
}

std::string random_word_rung(Rng& rng) {
  static const char* const kCompares[] = {"EQU", "NEQ", "LES", "LEQ", "GRT", "GEQ"};
  std::string s;
  // 0-3 contacts and 0-2 compares, sometimes a parallel branch, sometimes a coil.
  const int contacts = static_cast<int>(rng() % 4);
  const int compares = static_cast<int>(rng() % 3);
  for (int i = 0; i < contacts; ++i) s += random_word_contact(rng);
  // An output branch whose second leg compares after the first leg's coil: a compare reading
  // the word that coil writes must see the new value (such a rung stays general).
  if (rng() % 5 == 0)
    return s + "BST " + random_coil(rng) + "NXB " + kCompares[rng() % 6] + " " + random_source(rng) + " " +
           random_source(rng) + " " + random_coil(rng) + "BND";
  for (int i = 0; i < compares; ++i)
    s += std::string(kCompares[rng() % 6]) + " " + random_source(rng) + " " + random_source(rng) + " ";
  if (rng() % 5 == 0) s += "BST " + random_word_contact(rng) + "NXB " + random_word_contact(rng) + "BND ";
  if (rng() % 6 == 0) s += random_coil(rng);
  const std::string e = std::to_string(rng() % 3);
  switch (rng() % 11) {
    case 0: return s + "TON T4:" + e + (rng() % 4 ? " 0.01 " : " 1.0 ") + std::to_string(rng() % 12) + " 0";
    case 1: return s + "TOF T4:" + e + " 0.01 " + std::to_string(rng() % 12) + " 0";
    case 2: return s + "RTO T4:" + e + " 0.01 " + std::to_string(rng() % 12) + " 0";
    case 3: return s + "CTU C5:" + e + " " + std::to_string(rng() % 5) + " 0";
    case 4: return s + "CTD C5:" + e + " " + std::to_string(-static_cast<int>(rng() % 5)) + " 0";
    case 5: return s + "RES " + (rng() % 2 ? "T4:" : rng() % 2 ? "C5:" : "R6:") + e;
    case 6:
    case 7: return s + "MOV " + random_source(rng) + " " + random_dest(rng);
    case 8:
    case 9: return s + "ADD " + random_source(rng) + " " + random_source(rng) + " " + random_dest(rng);
    default: return s + "SUB " + random_source(rng) + " " + random_source(rng) + " " + random_dest(rng);
  }
}

std::string random_word_program(Rng& rng) {
  // Presets (and accumulators) made negative below are restored first thing on half the scans (a branch of MOVs: the
  // general path runs it).
  std::string s = "START 1747-L532\nLADDER 2\n"
                  "SOR XIO B3:1/15 BST MOV 7 T4:0.PRE NXB MOV 7 T4:1.PRE NXB MOV 7 T4:2.PRE NXB LES T4:0.ACC 0 "
                  "MOV 0 T4:0.ACC NXB LES T4:1.ACC 0 MOV 0 T4:1.ACC NXB LES T4:2.ACC 0 MOV 0 T4:2.ACC BND EOR\n";
  const int rungs = 30 + static_cast<int>(rng() % 30);
  for (int r = 0; r < rungs; ++r) {
    const unsigned kind = rng() % 24;
    if (kind == 0) {
      s += "SOR XIC " + random_bit(rng) + " JSR 3 EOR\n";
    } else if (kind == 1 && rng() % 2) {
      // A negative preset now and then: TON/TOF/RTO on it is fault 0034h (the fused run hands
      // the rung back to the general path, which raises it).
      s += "SOR XIC B3:0/" + std::to_string(rng() % 16) + " XIC B3:1/" + std::to_string(rng() % 16) + " XIC B3:0/" +
           std::to_string(rng() % 16) + " MOV " + (rng() % 2 ? "-1" : "7") + " T4:" + std::to_string(rng() % 3) +
           ".PRE EOR\n";
    } else if (kind == 2) {
      // An MCR zone around a word rung: inside a false zone it runs (false) on the general path.
      s += "SOR XIC " + random_bit(rng) + " MCR EOR\nSOR " + random_word_rung(rng) + " EOR\nSOR MCR EOR\n";
    } else if (kind == 3 || kind == 4) {
      // A contact network (branches, one or more coils) between word rungs: built as a word rung
      // and run in the word-rung loop (FusedProgram::word_form_rungs).
      int budget = 6;
      s += "SOR " + random_elements(rng, budget) + "EOR\n";
    } else {
      s += "SOR " + random_word_rung(rng) + " EOR\n";
    }
  }
  // Clears the overflow trap on some scans only, so an overflow is sometimes fault 0020h at END.
  s += "SOR XIC B3:0/0 OTU S:5/0 EOR\n";
  s += "LADDER 3\nSOR SBR " + random_word_rung(rng) + " EOR\n";
  for (int r = 0; r < 3; ++r) s += "SOR " + random_word_rung(rng) + " EOR\n";
  s += "SOR RET EOR\n";
  return s;
}

TEST(Fused, WordRungShapesMatchTheGeneralPath) {
  const SlowDistinctCosts model;
  std::size_t word_total = 0, word_form_total = 0, rungs_total = 0, faults = 0, tick_crossings = 0;
  for (unsigned seed = 1; seed <= 80; ++seed) {
    Rng rng(seed);
    rng.words = 2;
    const std::string text = random_word_program(rng);
    const CompiledProgram p = build(text);
    Machine fused(p, model, true), general(p, model, false);
    const FusedProgram fp = fused_program(p, fused);
    word_total += fp.word_rungs();
    word_form_total += fp.word_form_rungs();
    for (const auto& f : p.files) rungs_total += f.rungs.size();
    const auto& L = *p.layout;
    // Counters near +32767 and -32768 (CTU/CTD wrap, OV and UN), S:2/14 on for some seeds
    // (ADD/SUB keep the low bits instead of clamping).
    for (std::uint32_t e = 0; e < 3; ++e) {
      const auto acc = static_cast<std::uint16_t>(rng() % 2 ? 32766 : -32767);
      fused.table.set_word(L.files[5].base + 3 * e + 2, acc);
      general.table.set_word(L.files[5].base + 3 * e + 2, acc);
    }
    if (seed % 3 == 0) {
      const std::uint32_t s2 = L.status_word(status::kControl);
      fused.table.set_word(s2, fused.table.word(s2) | status::kOverflowSelect);
      general.table.set_word(s2, general.table.word(s2) | status::kOverflowSelect);
    }
    const Nanoseconds watchdog = seed % 4 == 0 ? 9'000'000 + static_cast<Nanoseconds>(seed) * 77'777 : INT64_MAX;
    VirtualTime start = static_cast<VirtualTime>(rng() % 10'000'000);
    for (int scan = 0; scan < 30; ++scan) {
      for (std::uint32_t w = 0; w < 2; ++w) {
        const auto v = static_cast<std::uint16_t>(rng());
        if (scan % 2 == 0) {
          fused.table.set_word(L.files[3].base + w, v);
          general.table.set_word(L.files[3].base + w, v);
        }
      }
      const auto a = fused.interp.program_scan(start, 0, scan == 0, watchdog);
      const auto b = general.interp.program_scan(start, 0, scan == 0, watchdog);
      const std::string where = "seed " + std::to_string(seed) + " scan " + std::to_string(scan) + "\n" + text;
      expect_same(a, b, where);
      if (a.faulted) ++faults;
      if ((start + a.elapsed) / kTick != start / kTick) ++tick_crossings;
      for (std::uint32_t w = 0; w < L.total_words; ++w)
        ASSERT_EQ(fused.table.word(w), general.table.word(w)) << "word " << L.describe(w) << ", " << where;
      start += a.elapsed + static_cast<VirtualTime>(rng() % 3'000'000);
    }
  }
  // The comparison means something only if most rungs were fused word rungs, some scans
  // faulted (overflow trap, negative preset, watchdog) and the scans crossed tick boundaries.
  EXPECT_GT(word_total * 2, rungs_total);
  EXPECT_GT(word_form_total, 80u);
  EXPECT_GT(faults, 50u);
  EXPECT_GT(tick_crossings, 500u);
}

// ---- Transfers and COP: JSR and RET ending a fused rung, COP on resolved spans ----

// A COP on N7 (twelve elements): overlapping ranges in either direction, lengths 1-6, and now and
// then an indirect source (not fused: resolved at run time) that N10:0 sometimes sends past the
// file's end (fault 002Ah), or a COP into the status file's S:24.
std::string random_copy(Rng& rng) {
  const unsigned pick = rng() % 10;
  const std::string len = std::to_string(1 + rng() % 6);
  if (pick == 0) return "COP #N7:[N10:0] #N7:" + std::to_string(rng() % 6) + " " + len;
  if (pick == 1) return "COP #N7:" + std::to_string(rng() % 6) + " #N9:" + std::to_string(rng() % 4) + " " + len;
  return "COP #N7:" + std::to_string(rng() % 6) + " #N7:" + std::to_string(rng() % 6) + " " + len;
}

// A rung ending in a JSR to `file` or in a RET, with conditions (contacts and compares from
// random_word_rung's pools) and, in a parallel leg before the transfer, a COP, an ADD, a MOV or a
// coil, or nothing (the transfer alone).
std::string random_transfer_rung(Rng& rng, const std::string& transfer) {
  static const char* const kCompares[] = {"EQU", "NEQ", "LES", "LEQ", "GRT", "GEQ"};
  std::string s;
  const int contacts = static_cast<int>(rng() % 3);
  for (int i = 0; i < contacts; ++i) s += random_word_contact(rng);
  if (rng() % 3 == 0) s += std::string(kCompares[rng() % 6]) + " " + random_source(rng) + " " + random_source(rng) + " ";
  switch (rng() % 6) {
    case 0:
    case 1: return s + "BST " + random_copy(rng) + " NXB " + transfer + " BND";
    case 2: return s + "BST ADD " + random_source(rng) + " " + random_source(rng) + " " + random_dest(rng) + " NXB " +
                   transfer + " BND";
    case 3:
      // A timer before the transfer keeps the rung general (it must see the rung's whole time).
      if (rng() % 4 == 0) return s + "BST TON T4:" + std::to_string(rng() % 3) + " 0.01 5 0 NXB " + transfer + " BND";
      return s + "BST " + random_coil(rng) + "NXB " + transfer + " BND";
    case 4: return s + "BST MOV " + random_source(rng) + " " + random_dest(rng) + " NXB XIC " + random_bit(rng) + " " + transfer + " BND";
    default: return s + transfer;
  }
}

// Word rungs with COPs, and JSR/RET rungs: file 2 calls 3 and 4, 3 and 4 call each other (so the
// nesting limit, fault 0030h, is reached when their conditions stay true), and conditional RETs
// part-way through each subroutine (`check` refuses a RET in file 2).
std::string random_transfer_program(Rng& rng) {
  std::string s = "START 1747-L532\nLADDER 2\n"
                  "SOR XIO B3:1/15 BST MOV 7 T4:0.PRE NXB MOV 7 T4:1.PRE NXB MOV 7 T4:2.PRE NXB LES T4:0.ACC 0 "
                  "MOV 0 T4:0.ACC NXB LES T4:1.ACC 0 MOV 0 T4:1.ACC NXB LES T4:2.ACC 0 MOV 0 T4:2.ACC BND EOR\n"
                  // Sizes N7 (twelve elements) and N9; N10:0 is the indirect COP's element.
                  "SOR XIC B3:1/14 EQU N7:11 N9:9 MOV N10:0 N10:1 EOR\n";
  // In the subroutines (`guard`) a call also needs B3:0/13, so not every scan nests to the limit.
  auto body = [&](int rungs, const std::string& calls, const std::string& guard = "") {
    std::string b;
    for (int r = 0; r < rungs; ++r) {
      const unsigned kind = rng() % 8;
      if (kind < 3)
        b += "SOR " + guard + random_transfer_rung(rng, calls[rng() % calls.size()] == '3' ? "JSR 3" : "JSR 4") + " EOR\n";
      else if (kind == 3) b += "SOR XIC " + random_bit(rng) + " " + random_copy(rng) + " EOR\n";
      else b += "SOR " + random_word_rung(rng) + " EOR\n";
    }
    return b;
  };
  s += body(20 + static_cast<int>(rng() % 20), "34");
  s += body(5, "3");
  s += "SOR XIC B3:0/0 OTU S:5/0 EOR\n";
  s += "LADDER 3\nSOR SBR " + random_word_contact(rng) + "OTE B3:1/3 EOR\n" + body(4, "4", "XIC B3:0/13 ") +
       "SOR " + random_transfer_rung(rng, "RET") + " EOR\n" + body(3, "4", "XIC B3:0/13 ") + "SOR RET EOR\n";
  s += "LADDER 4\nSOR SBR " + random_word_rung(rng) + " EOR\n" + body(3, "3", "XIC B3:0/13 ") + "SOR " +
       random_transfer_rung(rng, "RET") + " EOR\n" + body(2, "3", "XIC B3:0/13 ") + "SOR RET EOR\n";
  return s;
}

// Scans `text` 30 times fused and unfused from the same data (random N7 values, S:2/14 on for a
// third of the seeds, the watchdog for a quarter) and requires the same data table, scan time,
// instruction count, last rung and fault after every scan; counts each fault code in `faults`.
void compare_transfer_scans(const std::string& text, unsigned seed, Rng& rng, std::map<std::uint16_t, std::size_t>& faults) {
  const SlowDistinctCosts model;
  const CompiledProgram p = build(text);
  Machine fused(p, model, true), general(p, model, false);
  const auto& L = *p.layout;
  auto set_both = [&](std::uint32_t at, std::uint16_t v) {
    fused.table.set_word(at, v);
    general.table.set_word(at, v);
  };
  for (std::uint32_t e = 0; e < 12; ++e) set_both(L.files[7].base + e, static_cast<std::uint16_t>(rng() % 64 - 8));
  // S:2/14 on for some seeds (ADD keeps the low bits instead of clamping).
  if (seed % 3 == 0) {
    const std::uint32_t s2 = L.status_word(status::kControl);
    set_both(s2, static_cast<std::uint16_t>(fused.table.word(s2) | status::kOverflowSelect));
  }
  // Without a near watchdog, a far one (1,000 s of virtual time) still ends a scan that a broken
  // fused path sends round in a loop, so such a change fails here instead of hanging.
  const Nanoseconds watchdog =
      seed % 4 == 0 ? 9'000'000 + static_cast<Nanoseconds>(seed) * 77'777 : Nanoseconds{1'000'000'000'000};
  VirtualTime start = static_cast<VirtualTime>(rng() % 10'000'000);
  for (int scan = 0; scan < 30; ++scan) {
    if (scan % 2 == 0) {
      for (std::uint32_t w = 0; w < 2; ++w) set_both(L.files[3].base + w, static_cast<std::uint16_t>(rng()));
      // The indirect COP's source element: past N7's end (002Ah) now and then.
      set_both(L.files[10].base, static_cast<std::uint16_t>(rng() % 4 == 0 ? 9 + rng() % 3 : rng() % 6));
    }
    const auto a = fused.interp.program_scan(start, 0, scan == 0, watchdog);
    const auto b = general.interp.program_scan(start, 0, scan == 0, watchdog);
    const std::string where = "seed " + std::to_string(seed) + " scan " + std::to_string(scan) + "\n" + text;
    expect_same(a, b, where);
    EXPECT_EQ(a.fault.file, b.fault.file) << where;
    EXPECT_EQ(a.fault.message, b.fault.message) << where;
    if (a.faulted) ++faults[a.fault.code];
    for (std::uint32_t w = 0; w < L.total_words; ++w)
      ASSERT_EQ(fused.table.word(w), general.table.word(w)) << "word " << L.describe(w) << ", " << where;
    start += a.elapsed + static_cast<VirtualTime>(rng() % 3'000'000);
  }
}

// Scans the programs `make` writes for 80 seeds fused and unfused (compare_transfer_scans), passing
// each one's FusedProgram to `count`; returns how often each fault occurred.
template <class Make, class Count>
std::map<std::uint16_t, std::size_t> compare_random_programs(Make make, Count count) {
  const SlowDistinctCosts model;
  std::map<std::uint16_t, std::size_t> faults;
  for (unsigned seed = 1; seed <= 80; ++seed) {
    Rng rng(seed);
    rng.words = 2;
    const std::string text = make(rng, seed);
    const CompiledProgram p = build(text);
    count(fused_program(p, Machine(p, model, true)));
    compare_transfer_scans(text, seed, rng, faults);
  }
  return faults;
}

TEST(Fused, TransferAndCopyRungsMatchTheGeneralPath) {
  const SlowDistinctCosts model;
  std::size_t transfer_total = 0, word_total = 0, rungs_total = 0;
  std::map<std::uint16_t, std::size_t> faults;
  for (unsigned seed = 1; seed <= 80; ++seed) {
    Rng rng(seed);
    rng.words = 2;
    const std::string text = random_transfer_program(rng);
    const CompiledProgram p = build(text);
    const FusedProgram fp = fused_program(p, Machine(p, model, true));
    transfer_total += fp.transfer_rungs();
    word_total += fp.word_rungs();
    for (const auto& f : p.files) rungs_total += f.rungs.size();
    compare_transfer_scans(text, seed, rng, faults);
  }
  // Many transfer rungs were fused, and the scans met each fault the brief names: the nesting
  // limit (0030h), a COP past its file (002Ah), the watchdog (0022h), the overflow trap (0020h).
  EXPECT_GT(transfer_total, 80u * 10);
  EXPECT_GT(word_total * 2, rungs_total);
  for (std::uint16_t code : {std::uint16_t{0x0030}, std::uint16_t{0x002A}, std::uint16_t{0x0022}, std::uint16_t{0x0020}})
    EXPECT_GT(faults[code], 5u) << std::hex << code;
}

// Calls a run takes itself (vm/fused.h, "Calls"): files 2, 3, 4 and 5 call one another (3 calls
// itself too) through fused JSR rungs, so a run enters subroutines and returns from them several
// deep and up to the nesting limit (0030h). Around them, what makes a call leave the run: a
// subroutine whose first rung stays general (an OSR), a general rung right after a JSR (the
// return lands on it), a JSR as its file's last rung (the return is the EOF), a subroutine with
// no RET (it returns at its EOF), a RET part-way through, a subroutine whose first rung is a
// timer with a negative preset for some seeds (handed back: 0034h), and the watchdog (0022h)
// reached inside subroutines.
std::string random_call_program(Rng& rng, unsigned seed) {
  std::string s = "START 1747-L532\nLADDER 2\n"
                  "SOR XIO B3:1/15 BST MOV 7 T4:0.PRE NXB MOV 7 T4:1.PRE NXB MOV 7 T4:2.PRE NXB MOV 7 T4:3.PRE BND EOR\n"
                  "SOR XIC B3:1/14 EQU N7:11 N9:9 MOV N10:0 N10:1 EOR\n";
  if (seed % 5 == 0) s += "SOR XIC B3:0/9 MOV -1 T4:3.PRE EOR\n";
  const std::string guard = "XIC B3:0/13 ";
  auto body = [&](int rungs, const std::string& calls, const std::string& g) {
    std::string b;
    for (int r = 0; r < rungs; ++r) {
      const unsigned kind = rng() % 10;
      const std::string jsr = std::string("JSR ") + calls[rng() % calls.size()];
      if (kind < 4) {
        b += "SOR " + g + random_transfer_rung(rng, jsr) + " EOR\n";
        // The return lands on a general rung.
        if (rng() % 3 == 0) b += "SOR XIC " + random_bit(rng) + " OSR B3:2/" + std::to_string(r % 8) + " OTE B3:2/" + std::to_string(8 + r % 8) + " EOR\n";
      } else if (kind == 4) {
        b += "SOR XIC " + random_bit(rng) + " " + random_copy(rng) + " EOR\n";
      } else {
        b += "SOR " + random_word_rung(rng) + " EOR\n";
      }
    }
    return b;
  };
  s += body(15 + static_cast<int>(rng() % 15), "345", "");
  // File 2 ends in a JSR for some seeds: the return is its EOF.
  s += rng() % 2 ? "SOR XIC B3:0/0 OTU S:5/0 EOR\n" : "SOR XIC B3:0/0 OTU S:5/0 EOR\nSOR XIC B3:0/7 JSR 5 EOR\n";
  s += "LADDER 3\nSOR SBR " + random_word_contact(rng) + "OTE B3:1/3 EOR\n" + body(4, "345", guard) + "SOR " +
       random_transfer_rung(rng, "RET") + " EOR\n" + body(2, "45", guard) + "SOR RET EOR\n";
  // File 4's first rung is general for half the seeds; it has no RET (it returns at its EOF).
  s += std::string("LADDER 4\n") + (rng() % 2 ? "SOR SBR XIC B3:0/5 OSR B3:2/0 OTE B3:2/1 EOR\n" : "SOR SBR XIC B3:0/5 OTE B3:2/1 EOR\n") +
       body(3, "35", guard);
  s += "LADDER 5\nSOR SBR XIC B3:0/6 TON T4:3 0.01 5 0 EOR\n" + body(3, "34", guard) + "SOR " +
       random_transfer_rung(rng, "RET") + " EOR\n" + body(2, "3", guard);
  return s;
}

TEST(Fused, CallsTakenInsideARunMatchTheGeneralPath) {
  std::size_t linked = 0, word_form = 0;
  auto faults = compare_random_programs(random_call_program, [&](const FusedProgram& fp) {
    linked += fp.linked_calls();
    // File 3's first rung (SBR, a contact, OTE) is a contact network built as a word rung when
    // a word rung follows it, so calls into file 3 continue in the word-rung loop.
    word_form += fp.word_form_rungs();
  });
  EXPECT_GT(linked, 80u * 8);
  EXPECT_GT(word_form, 40u);
  for (std::uint16_t code : {std::uint16_t{0x0030}, std::uint16_t{0x0034}, std::uint16_t{0x0022}})
    EXPECT_GT(faults[code], 5u) << std::hex << code;
}

// ---- Several actions in one rung (vm/fused.h, "Several actions"), and CLR ----

// One action of a rung of several: MOV, ADD, SUB, CLR, CTU, CTD, RES or COP on the word-rung
// pools (so an action often reads what an earlier action of its rung writes, an ADD overflows, a
// counter wraps), now and then a timer (the rung then stays general).
std::string random_step(Rng& rng) {
  const std::string e = std::to_string(rng() % 3);
  switch (rng() % 17) {
    case 0:
    case 1:
    case 2: return "MOV " + random_source(rng) + " " + random_dest(rng);
    case 3:
    case 4: return "ADD " + random_source(rng) + " " + random_source(rng) + " " + random_dest(rng);
    case 5: return "SUB " + random_source(rng) + " " + random_source(rng) + " " + random_dest(rng);
    case 6:
    case 7: return "CLR " + random_dest(rng);
    case 8: return "CTU C5:" + e + " " + std::to_string(rng() % 5) + " 0";
    case 9: return "CTD C5:" + e + " " + std::to_string(-static_cast<int>(rng() % 5)) + " 0";
    case 10: return std::string("RES ") + (rng() % 2 ? "T4:" : rng() % 2 ? "C5:" : "R6:") + e;
    case 11:
    case 12: return random_copy(rng);
    case 13: return "TON T4:" + e + " 0.01 " + std::to_string(rng() % 12) + " 0";
    default: return "MOV " + random_source(rng) + " N7:" + std::to_string(rng() % 4);
  }
}

// A rung of several actions: contacts and compares, a coil now and then, then two to five actions
// in parallel legs (the first leg may have conditions of its own, so the actions' rung-ins
// differ) or in series, sometimes with a JSR or RET in the last leg. A fifth of the branched ones
// put a condition after an action (general).
std::string random_several_action_rung(Rng& rng, const std::string& transfer) {
  static const char* const kCompares[] = {"EQU", "NEQ", "LES", "LEQ", "GRT", "GEQ"};
  std::string s;
  const int contacts = static_cast<int>(rng() % 3);
  for (int i = 0; i < contacts; ++i) s += random_word_contact(rng);
  if (rng() % 3 == 0) s += std::string(kCompares[rng() % 6]) + " " + random_source(rng) + " " + random_source(rng) + " ";
  if (rng() % 5 == 0) s += random_coil(rng);
  const int actions = 2 + static_cast<int>(rng() % 4);
  const bool late_condition = rng() % 5 == 0;
  if (rng() % 4 == 0) {
    for (int i = 0; i < actions; ++i) s += random_step(rng) + " ";
    return transfer.empty() ? s : s + transfer;
  }
  s += "BST ";
  if (rng() % 2) s += random_word_contact(rng);
  if (rng() % 3 == 0) s += random_coil(rng) + "NXB " + random_word_contact(rng);
  for (int i = 0; i < actions; ++i) {
    if (i > 0) s += "NXB ";
    if (late_condition && i == actions - 1) s += random_word_contact(rng);
    s += random_step(rng) + " ";
  }
  if (!transfer.empty()) s += "NXB " + transfer + " ";
  return s + "BND";
}

// File 2: rungs of several actions among word rungs (a bare CLR among them) and the DII's own
// configuration rung (five unconditional MOVs in parallel legs, into N7 here); files 3 and 4: a
// subroutine each, called from rungs of several actions ending in a JSR, with RETs after actions.
std::string random_several_action_program(Rng& rng) {
  std::string s = "START 1747-L532\nLADDER 2\n"
                  "SOR BST MOV 3 N7:4 NXB MOV 1 N7:5 NXB MOV 1 N7:6 NXB MOV 1 N7:7 NXB MOV 5 N7:8 BND EOR\n"
                  // Sizes N7 (twelve elements) and N9; N10:0 is the indirect COP's element.
                  "SOR XIC B3:1/14 EQU N7:11 N9:9 MOV N10:0 N10:1 EOR\n";
  const int rungs = 20 + static_cast<int>(rng() % 20);
  for (int r = 0; r < rungs; ++r) {
    const unsigned kind = rng() % 10;
    if (kind < 5) s += "SOR " + random_several_action_rung(rng, "") + " EOR\n";
    else if (kind == 5) s += "SOR " + random_several_action_rung(rng, rng() % 2 ? "JSR 3" : "JSR 4") + " EOR\n";
    else if (kind == 6) s += "SOR " + random_word_contact(rng) + "CLR " + random_dest(rng) + " EOR\n";
    else s += "SOR " + random_word_rung(rng) + " EOR\n";
  }
  s += "SOR XIC B3:0/0 OTU S:5/0 EOR\n";
  for (const char* file : {"3", "4"}) {
    s += std::string("LADDER ") + file + "\nSOR SBR " + random_several_action_rung(rng, "") + " EOR\n";
    for (int r = 0; r < 3; ++r) s += "SOR XIC B3:0/13 " + random_several_action_rung(rng, "") + " EOR\n";
    s += "SOR " + random_several_action_rung(rng, "RET") + " EOR\n";
    s += "SOR " + random_word_rung(rng) + " EOR\nSOR RET EOR\n";
  }
  return s;
}

TEST(Fused, SeveralActionRungsMatchTheGeneralPath) {
  std::size_t several = 0, transfers = 0;
  auto faults = compare_random_programs(
      [](Rng& rng, unsigned) { return random_several_action_program(rng); },
      [&](const FusedProgram& fp) {
        several += fp.several_action_rungs();
        transfers += fp.transfer_rungs();
      });
  // Most programs' rungs of several actions were fused (a fifth of them have a late condition or a
  // timer: general), some with a transfer, and the scans met the overflow trap (0020h), a COP past
  // its file (002Ah) and the watchdog (0022h).
  EXPECT_GT(several, 80u * 10);
  EXPECT_GT(transfers, 80u * 2);
  for (std::uint16_t code : {std::uint16_t{0x0020}, std::uint16_t{0x002A}, std::uint16_t{0x0022}})
    EXPECT_GT(faults[code], 5u) << std::hex << code;
}

// The DII's configuration rung of examples/ladder/dii/dii_batch.slc, fused: each MOV writes its
// word and leaves S:0 as MOV does (docs/semantics.md: MOV sets Z and S from the value, clears C
// and V; CLR sets Z only), and the scan time is every instruction's true charge under the default
// model (vm/scan_time_model.h: an output instruction 2 us true), with the branch structure free.
TEST(Fused, ConfigurationRungOfFiveMovsWritesEachWord) {
  const DefaultScanTimeModel model;
  const CompiledProgram p = build(
      "START 1747-L532\nLADDER 2\nSOR BST MOV 3 N7:0 NXB MOV 1 N7:1 NXB MOV 1 N7:2 NXB MOV 1 N7:3 NXB MOV 0 N7:4 BND EOR\n"
      "SOR CLR N7:5 EOR\n");
  Machine m(p, model, true);
  const FusedProgram fp = fused_program(p, m);
  ASSERT_EQ(fp.several_action_rungs(), 1u);
  ASSERT_EQ(fp.fused_rungs(), 2u);
  const std::uint32_t n7 = p.layout->files[7].base, s0 = p.layout->status_word(status::kArith);
  m.table.set_word(n7 + 5, 9);
  m.table.set_word(s0, status::kCarry | status::kSign);
  const auto r = m.interp.program_scan(0, 0, false, INT64_MAX);
  EXPECT_EQ(m.table.word(n7 + 0), 3);
  EXPECT_EQ(m.table.word(n7 + 1), 1);
  EXPECT_EQ(m.table.word(n7 + 4), 0);
  EXPECT_EQ(m.table.word(n7 + 5), 0);
  EXPECT_EQ(m.table.word(s0) & 0xF, status::kZero);  // CLR last: Z only
  EXPECT_EQ(r.instructions, 6u);
  EXPECT_EQ(r.elapsed, 6 * 2'000);
}

// docs/bytecode.md "Rung logic": each leg starts from the condition at BST, and an output acts on
// the rung condition where it stands, so the second leg's XIC sees the bit the first leg's OTE
// has just written. Fused rungs gather contacts first, so this rung must not be fused.
TEST(Fused, ContactReadingACoilOfTheSameRungSeesTheNewValue) {
  const DefaultScanTimeModel model;
  const CompiledProgram p = build("START 1747-L532\nLADDER 2\nSOR BST OTE B3:0/1 NXB XIC B3:0/1 OTE B3:0/2 BND EOR\n");
  Machine m(p, model, true);
  EXPECT_EQ(fused_program(p, m).fused_rungs(), 0u);
  m.interp.program_scan(0, 0, false, INT64_MAX);
  EXPECT_EQ(m.table.word(p.layout->files[3].base), 0b110);
}

// The default model (vm/scan_time_model.h): inputs 1 us true or false, outputs 2 us true and
// 1 us false. XIC B3:0/0 OTE B3:0/1: 1 + 1 = 2 us with B3:0/0 off, 1 + 2 = 3 us with it on; a
// second rung XIO B3:0/0 OTL B3:0/2 is the mirror image.
TEST(Fused, ScanTimeIsEachInstructionsTrueOrFalseCharge) {
  const DefaultScanTimeModel model;
  const CompiledProgram p =
      build("START 1747-L532\nLADDER 2\nSOR XIC B3:0/0 OTE B3:0/1 EOR\nSOR XIO B3:0/0 OTL B3:0/2 EOR\n");
  Machine m(p, model, true);
  ASSERT_EQ(fused_program(p, m).fused_rungs(), 2u);
  const std::uint32_t b3 = p.layout->files[3].base;
  auto r = m.interp.program_scan(0, 0, false, INT64_MAX);
  EXPECT_EQ(r.elapsed, 2'000 + 3'000);
  EXPECT_EQ(r.instructions, 4u);
  EXPECT_EQ(m.table.word(b3), 0b100);
  m.table.set_word(b3, 0b001);
  r = m.interp.program_scan(0, 0, false, INT64_MAX);
  EXPECT_EQ(r.elapsed, 3'000 + 2'000);
  EXPECT_EQ(m.table.word(b3), 0b011);  // B3:0/2 was cleared by the set_word; XIO is now false
}

}  // namespace
}  // namespace softslc
