// The .RSS reader against real projects (../shared/fixtures/rss) and their RSLogix reports.
//
// The oracle is the "Project Report" PDF that RSLogix printed from the same project, turned into
// text by `pdftotext -layout` at test time: for every ladder file the report gives "LAD n - NAME
// --- Total Rungs in File = N" and prints every instruction box and operand address. The tests
// compare the reader's program files, rung counts, box mnemonics and operand addresses with it.
// Nothing here is derived from the reader's own output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "instructions/processor.h"
#include "parser/formatter.h"
#include "parser/loader.h"
#include "parser/rss/rss_reader.h"

namespace fs = std::filesystem;
using softslc::rss::read_project;

namespace {

const fs::path kFixtures = fs::path(SOFTSLC_SHARED_DIR) / "fixtures" / "rss";

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<fs::path> fixtures() {
  std::vector<fs::path> out;
  if (!fs::exists(kFixtures)) return out;
  for (const auto& e : fs::recursive_directory_iterator(kFixtures))
    if (e.path().extension() == ".RSS") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The report printed from the same project (SOURCES.md): X.RSS → X.pdf or X_live.pdf; the
// water-filtration ladder report is plclogic.pdf.
std::optional<fs::path> report_for(const fs::path& rss) {
  for (std::string suffix : {".pdf", "_live.pdf"}) {
    fs::path p = rss.parent_path() / (rss.stem().string() + suffix);
    if (fs::exists(p)) return p;
  }
  if (rss.stem() == "water_filtration_system") return rss.parent_path() / "plclogic.pdf";
  return std::nullopt;
}

std::string pdftotext(const fs::path& pdf) {
  std::string cmd = "pdftotext -layout '" + pdf.string() + "' - 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  if (!p) return out;
  std::array<char, 65536> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p.get())) > 0) out.append(buf.data(), n);
  return out;
}

// The report's ladder sections: file number → (rung count, all text printed for that file).
struct ReportFile {
  int rungs = -1;
  std::string text;
};
std::map<int, ReportFile> report_files(const std::string& report) {
  std::map<int, ReportFile> files;
  static const std::regex header(R"(LAD (\d+) - .*Total Rungs in File = (\d+))");
  std::istringstream in(report);
  std::string line;
  ReportFile* current = nullptr;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, header)) {
      current = &files[std::stoi(m[1])];
      current->rungs = std::stoi(m[2]);
      continue;
    }
    // The page title of another section ("Data File N7 (dec) -- INTEGER", "Data File List",
    // cross reference) ends the ladder text; rung comments may mention data files in passing.
    static const std::regex other_section(R"(^\s*(Data File [A-Z]+[0-9]*( \(\w+\))?\s+--|Data File List|Cross Reference))");
    if (std::regex_search(line, other_section)) current = nullptr;
    if (current) current->text += line + "\n";
  }
  return files;
}

// The reader's ladder files: file number → rungs, each the list of tokens between SOR and EOR.
std::map<int, std::vector<std::vector<std::string>>> our_files(const std::string& text) {
  std::map<int, std::vector<std::vector<std::string>>> files;
  std::istringstream in(text);
  std::string line;
  int current = -1;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "LADDER") {
      ls >> current;
      files[current];
    } else if (w == "SOR") {
      std::vector<std::string> toks;
      while (ls >> w && w != "EOR") toks.push_back(w);
      files[current].push_back(toks);
    }
  }
  return files;
}

bool is_mnemonic(const std::string& t) {
  if (t.size() < 2 || t.size() > 4) return false;
  for (char c : t)
    if (c < 'A' || c > 'Z') return false;
  return true;
}

// How the report prints an operand address: a bit's "/b" goes on the line below the word
// ("T4:0/DN" is "T4:0" over "DN", "B11:0/[N17:2]" is "B11:0" over "[N17:2]"), an I/O word 0 is printed without ".0" ("O:0.0/0" is "O:0"),
// and a file operand without its "#".
std::string report_form(std::string a) {
  if (!a.empty() && a[0] == '#') a.erase(0, 1);
  if (auto slash = a.find('/'); slash != std::string::npos) a.erase(slash);
  if ((a.rfind("I:", 0) == 0 || a.rfind("O:", 0) == 0) && a.size() > 2 && a.substr(a.size() - 2) == ".0") a.erase(a.size() - 2);
  return a;
}

}  // namespace

TEST(RssReader, EveryFixtureDecodes) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  EXPECT_EQ(all.size(), 15u) << "SOURCES.md lists 15 project files";
  for (const auto& f : all) {
    auto r = read_project(slurp(f), f.filename().string());
    EXPECT_TRUE(r.text.has_value()) << f << ": " << r.error;
  }
}

// Every ladder file of the report, with its rung count, every instruction box and every operand
// address, is what the reader decodes (and the reader has no ladder file the report lacks).
TEST(RssReader, RungsAgreeWithTheRslogixReports) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  int compared = 0;
  for (const auto& f : all) {
    auto pdf = report_for(f);
    if (!pdf) continue;
    SCOPED_TRACE(f.filename().string());
    std::string report = pdftotext(*pdf);
    ASSERT_FALSE(report.empty()) << "pdftotext (poppler-utils) could not read " << *pdf;
    auto r = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(r.text) << r.error;
    auto theirs = report_files(report);
    auto ours = our_files(*r.text);
    ASSERT_FALSE(theirs.empty());
    std::set<int> their_numbers, our_numbers;
    for (const auto& [n, _] : theirs) their_numbers.insert(n);
    for (const auto& [n, _] : ours) our_numbers.insert(n);
    EXPECT_EQ(our_numbers, their_numbers);
    for (const auto& [n, rf] : theirs) {
      auto it = ours.find(n);
      if (it == ours.end()) continue;
      SCOPED_TRACE("LAD " + std::to_string(n));
      EXPECT_EQ(static_cast<int>(it->second.size()), rf.rungs);
      for (std::size_t k = 0; k < it->second.size(); ++k) {
        for (const auto& tok : it->second[k]) {
          if (tok == "BST" || tok == "NXB" || tok == "BND") continue;
          // Bit instructions are drawn as contacts and coils, not named; every box is named.
          static const std::set<std::string> drawn = {"XIC", "XIO", "OTE", "OTL", "OTU", "END"};
          if (is_mnemonic(tok)) {
            if (!drawn.count(tok)) {
              EXPECT_NE(rf.text.find(tok), std::string::npos) << "rung " << k << ": box " << tok;
            }
            continue;
          }
          if (tok.find(':') == std::string::npos) continue;  // constants: printed with values
          EXPECT_NE(rf.text.find(report_form(tok)), std::string::npos) << "rung " << k << ": operand " << tok;
        }
      }
      ++compared;
    }
  }
  EXPECT_GE(compared, 20) << "ladder files compared with a report";
}

// single_timer_live.pdf, LAD 2 rung 0000: XIO T4:0/DN, then a branch of TON T4:0 (time base
// 0.001, preset 4000) over XIC T4:0/DN RES T4:0. The TON's accumulator (608 in the live report)
// is the data-table value; the instruction record holds 0.
TEST(RssReader, SingleTimerRungZeroIsTheReportsRung) {
  fs::path f = kFixtures / "drbitboy-PLC_2s_lamp_flash" / "single_timer.RSS";
  if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
  auto r = read_project(slurp(f), "single_timer.RSS");
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_NE(r.text->find("SOR XIO T4:0/DN BST TON T4:0 0.001 4000 0 NXB XIC T4:0/DN RES T4:0 BND EOR"), std::string::npos) << *r.text;
  EXPECT_NE(r.text->find("START Bul.1763 SERIES B"), std::string::npos);
}

// A truncated, a corrupted and a foreign file each end in one clean error and no program.
TEST(RssReader, DamagedFilesEndInCleanErrors) {
  fs::path f = kFixtures / "drbitboy-PLC_2s_lamp_flash" / "single_timer.RSS";
  if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
  std::string good = slurp(f);
  for (std::size_t cut : {std::size_t{8}, std::size_t{512}, good.size() / 4, good.size() / 2}) {
    auto r = softslc::load_program_bytes(good.substr(0, cut), "t.RSS");
    EXPECT_FALSE(r.ok()) << "cut at " << cut;
    ASSERT_EQ(r.diagnostics.items().size(), 1u) << "cut at " << cut << ": " << r.render_diagnostics();
  }
  // Flip every byte of the compressed PROGRAM FILES region in turn: each result is a clean
  // error or a program; never a crash (run under ASan/UBSan in CI).
  for (std::size_t i = 0; i < good.size(); i += 97) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x5A);
    auto r = softslc::load_program_bytes(bad, "t.RSS");
    if (!r.ok()) {
      EXPECT_FALSE(r.diagnostics.items().empty());
      for (const auto& d : r.diagnostics.items())
        for (char c : d.message) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7F)) << "binary in a diagnostic at flip " << i;
    }
  }
  auto foreign = softslc::load_program_bytes(std::string("\x7F" "ELF\x02\x01\x01\0\0\0", 10), "t.RSS");
  ASSERT_FALSE(foreign.ok());
  EXPECT_NE(foreign.render_diagnostics().find("binary content"), std::string::npos);
  std::string ole(good.substr(0, 8));
  ole += std::string(600, '\0');
  auto empty_ole = softslc::load_program_bytes(ole, "t.RSS");
  ASSERT_FALSE(empty_ole.ok());
  EXPECT_NE(empty_ole.render_diagnostics().find("not an RSLogix project file"), std::string::npos) << empty_ole.render_diagnostics();
}

// A header that counts more allocation-table sectors than the file holds is refused before
// libolecf sizes its tables from it: rss_fuzz found 16,777,215 master-allocation-table sectors in
// a 140 KB file making libolecf allocate and clear hundreds of MB (over 1 s under ASan).
TEST(RssReader, HeaderSectorCountsBeyondTheFileAreRefused) {
  fs::path f = kFixtures / "drbitboy-PLC_2s_lamp_flash" / "single_timer.RSS";
  if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
  const std::string good = slurp(f);
  ASSERT_TRUE(softslc::load_program_bytes(good, "t.RSS").ok());
  for (std::size_t at : {std::size_t{0x2C}, std::size_t{0x40}, std::size_t{0x48}}) {
    std::string bad = good;
    bad.replace(at, 4, std::string("\xff\xff\xff\x00", 4));
    auto r = softslc::load_program_bytes(bad, "t.RSS");
    ASSERT_FALSE(r.ok()) << std::hex << at;
    EXPECT_NE(r.render_diagnostics().find("its header names 16777215 "), std::string::npos) << r.render_diagnostics();
  }
}

// A known RSLogix mnemonic softslc lacks is named as not supported; a typo stays unknown.
TEST(RssReader, InstructionsSoftslcLacksAreNamedNotSupported) {
  auto r = softslc::load_program("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 RCP N7:0 EOR\n", "t.slc");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.render_diagnostics().find("instruction RCP is not supported by softslc yet"), std::string::npos) << r.render_diagnostics();
  auto typo = softslc::load_program("START Bul.1763\nLADDER 2\nSOR XIC B3:0/0 QQQ N7:0 EOR\n", "t.slc");
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.render_diagnostics().find("unknown instruction 'QQQ'"), std::string::npos) << typo.render_diagnostics();
}

// Diagnostics about a converted project name the program file and rung. Every fixture now loads,
// so the 2080-MOT-HSC driver's LAD 2 rung 1 (`XIC T4:0/DN PTO 0`) is given an instruction softslc
// does not have (HSD, same length: the lines stay where they were) in its converted text.
TEST(RssReader, DiagnosticsNameTheProgramFileAndRung) {
  fs::path f = kFixtures / "drbitboy-PLC_reject_timing" / "20230719_MicroLogix_1100_driver_of_Micro8xx_2080-MOT-HSC.RSS";
  if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
  auto rr = read_project(slurp(f), f.filename().string());
  ASSERT_TRUE(rr.text) << rr.error;
  const auto at = rr.text->find("XIC T4:0/DN PTO 0 EOR");
  ASSERT_NE(at, std::string::npos);
  rr.text->replace(at + 12, 3, "HSD");
  auto r = softslc::load_converted_project(std::move(*rr.text), rr.origins, f.filename().string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.render_diagnostics().find("program file 2 rung 1: instruction HSD is not supported by softslc yet"), std::string::npos)
      << r.render_diagnostics();
}

// The STI function file's configuration is carried from the project's DATA FILES stream (the
// function-file record of type 0x14: PFN ER bits SPM, docs/micrologix-function-files-sources.md
// section 6) as the DATA STI0:0 row an RSLogix export writes (59-BSGS.SLC: "0 0 0X0002 0").
// sti_1000ms_live.RSS: its STI file is LAD 3 (the only ladder file no JSR calls; the report's
// program file list), the time comes from its STS 2000. TVZ_1100_REV02.RSS: LAD 13 STI_SPEED,
// "executed at regular intervals (300ms) via Selectable Timed Interrupt" (the annotated report),
// with no STS, so auto start is set. Projects without an STI hold RSLogix's default row.
TEST(RssReader, StiFunctionFileConfigurationIsCarried) {
  const std::vector<std::pair<fs::path, std::string>> cases = {
      {kFixtures / "drbitboy-PLC_2s_lamp_flash" / "sti_1000ms_live.RSS", "\nDATA STI0:0\n% STI0:0 %\n3 0 0X0002 0\n"},
      {kFixtures / "drbitboy-PLC_reject_timing" / "TVZ_1100_REV02.RSS", "\nDATA STI0:0\n% STI0:0 %\n13 0 0X0032 300\n"},
      {kFixtures / "drbitboy-PLC_2s_lamp_flash" / "single_timer.RSS", "\nDATA STI0:0\n% STI0:0 %\n0 0 0X0002 0\n"},
  };
  for (const auto& [f, row] : cases) {
    SCOPED_TRACE(f.filename().string());
    if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
    auto r = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(r.text) << r.error;
    EXPECT_NE(r.text->find(row), std::string::npos) << *r.text;
  }
  // Loaded, the block is the STI's configuration.
  auto sti = softslc::load_program_file(cases[0].first);
  ASSERT_TRUE(sti.ok()) << sti.render_diagnostics();
  const softslc::DataBlock* block = nullptr;
  for (const auto& d : sti.program->data)
    if (d.file_name == "STI0:0") block = &d;
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(block->words, (std::vector<std::int64_t>{3, 0, 2, 0}));
}

// `import` then `check` of the .slc says exactly what `check` of the .RSS says (only the program
// file/rung prefix differs); where a project loads, both give the same program, and the
// formatter's text of it loads back to the same program (the fmt round trip).
TEST(RssReader, ConvertedTextChecksAndLoadsLikeTheProject) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  fs::path dir = fs::temp_directory_path() / ("softslc_rss_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const auto& f : all) {
    SCOPED_TRACE(f.filename().string());
    auto rr = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(rr.text) << rr.error;
    fs::path slc = dir / (f.stem().string() + ".slc");
    std::ofstream(slc, std::ios::binary) << *rr.text;
    auto from_rss = softslc::load_program_file(f);
    auto from_slc = softslc::load_program_file(slc);
    std::vector<std::string> a, b;
    static const std::regex prefix(R"(^program file \d+ rung \d+: )");
    for (const auto& d : from_rss.diagnostics.items()) a.push_back(std::regex_replace(d.message, prefix, ""));
    for (const auto& d : from_slc.diagnostics.items()) b.push_back(d.message);
    EXPECT_EQ(a, b);
    EXPECT_EQ(from_rss.ok(), from_slc.ok());
    if (from_rss.ok() && from_slc.ok()) {
      std::string diff;
      EXPECT_TRUE(softslc::same_program(*from_rss.program, *from_slc.program, &diff)) << diff;
      auto again = softslc::load_program(softslc::format_program(*from_rss.program), "fmt.slc");
      ASSERT_TRUE(again.ok()) << again.render_diagnostics();
      EXPECT_TRUE(softslc::same_program(*from_rss.program, *again.program, &diff)) << diff;
    }
  }
  fs::remove_all(dir);
}

namespace {

// Collapses every run of blanks to one space, so text the report lays out in columns compares
// with the reader's single-spaced text.
std::string squeeze(const std::string& s) {
  std::string out;
  for (char c : s) {
    bool blank = c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
    if (blank) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

// The reader's rung comments: file number → comment lines (the `% ... %` lines directly above
// each SOR), and its SYMBOL lines: address → name.
struct OurAnnotations {
  std::map<int, std::vector<std::string>> comment_lines;
  std::map<std::string, std::string> symbols;
  int comments = 0;
};
OurAnnotations our_annotations(const std::string& text) {
  OurAnnotations out;
  std::istringstream in(text);
  std::string line;
  int file = -1;
  std::vector<std::string> pending;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "LADDER") {
      ls >> file;
      pending.clear();
    } else if (w == "%" && file >= 0 && line.size() >= 4) {
      pending.push_back(line.substr(2, line.size() - 4));
    } else if (w == "SOR") {
      if (!pending.empty()) ++out.comments;
      for (auto& p : pending) out.comment_lines[file].push_back(p);
      pending.clear();
    } else if (w == "SYMBOL") {
      std::string address, name;
      ls >> address >> name;
      out.symbols[address] = name;
    } else {
      pending.clear();
    }
  }
  return out;
}

}  // namespace

// Rung comments and symbols (MEM DATABASE) against the reports: every line of every rung comment
// is printed in that ladder file's pages, and every operand that has a symbol is printed with
// it (the report shows "LAMP_FLASH_TON" above T4:0). lecky_demo.pdf, LAD 2 rung 0001 starts
// "Detect the rising edge (start) of a new failed can event"; single_timer_live.pdf LAD 2 rung
// 0000 shows T4:0 as LAMP_FLASH_TON.
TEST(RssReader, SymbolsAndRungCommentsAgreeWithTheRslogixReports) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  int comments = 0, symbols_compared = 0;
  for (const auto& f : all) {
    auto pdf = report_for(f);
    if (!pdf) continue;
    SCOPED_TRACE(f.filename().string());
    auto r = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(r.text) << r.error;
    auto theirs = report_files(pdftotext(*pdf));
    auto ours = our_files(*r.text);
    auto notes = our_annotations(*r.text);
    comments += notes.comments;
    for (const auto& [n, lines] : notes.comment_lines) {
      auto it = theirs.find(n);
      ASSERT_NE(it, theirs.end()) << "LAD " << n;
      std::string report = squeeze(it->second.text);
      for (const auto& line : lines) {
        std::string want = squeeze(line);
        if (want.empty() || want == " ") continue;
        // The report wraps long comment lines; the first 40 characters stay on one line.
        if (want.size() > 40) want = squeeze(want.substr(0, 40));
        while (!want.empty() && want.back() == ' ') want.pop_back();
        if (!want.empty() && want.front() == ' ') want.erase(0, 1);
        EXPECT_NE(report.find(want), std::string::npos) << "LAD " << n << ": comment line '" << want << "'";
      }
    }
    for (const auto& [n, rungs] : ours) {
      auto it = theirs.find(n);
      if (it == theirs.end()) continue;
      // A contact or coil is always printed under its operand's symbol, a timer or counter box
      // under its timer's; the other boxes' operands are printed with a symbol only where the
      // column has room, so they are not compared.
      static const std::set<std::string> labelled = {"XIC", "XIO", "OTE", "OTL", "OTU", "TON", "TOF", "RTO", "CTU", "CTD"};
      for (const auto& rung : rungs)
        for (std::size_t k = 0; k < rung.size(); ++k) {
          const std::string& tok = rung[k];
          if (k == 0 || !labelled.count(rung[k - 1])) continue;
          auto s = notes.symbols.find(tok);
          if (s == notes.symbols.end() && tok.find('/') != std::string::npos) s = notes.symbols.find(tok.substr(0, tok.find('/')));
          if (s == notes.symbols.end()) continue;
          EXPECT_NE(it->second.text.find(s->second), std::string::npos) << "LAD " << n << ": symbol " << s->second << " of " << tok;
          ++symbols_compared;
        }
    }
  }
  EXPECT_GE(comments, 100) << "rung comments compared with a report";
  EXPECT_GE(symbols_compared, 100) << "symbol uses compared with a report";
}

// A known rung comment and symbols, exactly (lecky_demo.pdf, LAD 2 rung 0001; its Data File
// T4 page: T4:0 500 preset).
TEST(RssReader, LeckyDemoCommentSymbolAndTimerPreset) {
  fs::path f = kFixtures / "drbitboy-PLC_reject_timing" / "lecky_demo.RSS";
  if (!fs::exists(f)) GTEST_SKIP() << "no fixture " << f;
  auto r = read_project(slurp(f), "lecky_demo.RSS");
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_NE(r.text->find("% Detect the rising edge (start) of a new failed can event %\nSOR "), std::string::npos);
  EXPECT_NE(r.text->find("SYMBOL B103:0/0 FAIL_OS"), std::string::npos);
  EXPECT_NE(r.text->find("SYMBOL T4:2 2560MS_TIMER"), std::string::npos) << "a symbol that starts with digits, as RSLogix allows";
  EXPECT_NE(r.text->find("0X0100 500 0 % T4:0 %"), std::string::npos);
  auto loaded = softslc::load_program_file(f);
  ASSERT_TRUE(loaded.ok()) << loaded.render_diagnostics();
  const auto* sym = loaded.program->find_symbol("FAIL_OS");
  ASSERT_NE(sym, nullptr);
}

namespace {

// The data values a report prints: "N7:0  v v v ..." rows (N, L, F files; B is printed in
// bits and skipped) and T/C rows "T4:0  EN TT DN BASE PRE ACC" → "T4:0.PRE", "T4:0.ACC".
std::map<std::string, std::string> report_values(const std::string& report) {
  std::map<std::string, std::string> out;
  std::istringstream in(report);
  std::string line;
  static const std::regex words(R"(^([NLF]\d+):(\d+)((\s+-?[0-9][0-9.e+-]*)+)\s*$)");
  static const std::regex tc(R"(^([TC]\d+:\d+)\s+[01]\s+[01]\s+[01]\s.*?\s(-?\d+)\s+(-?\d+)\s*(\(.*)?$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, words)) {
      std::istringstream vs(m[3].str());
      std::string v;
      for (int k = std::stoi(m[2]); vs >> v; ++k) out[m[1].str() + ":" + std::to_string(k)] = v;
    } else if (std::regex_match(line, m, tc)) {
      out[m[1].str() + ".PRE"] = m[2];
      out[m[1].str() + ".ACC"] = m[3];
    }
  }
  return out;
}

// The reader's DATA blocks in the same form.
std::map<std::string, std::string> our_values(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string line;
  static const std::regex row(R"(^% ([BNLF]\d+):(\d+) %(.*)$)");
  static const std::regex tcr(R"(^0X[0-9A-F]{4}\s+(-?\d+)\s+(-?\d+)\s+% ([TC]\d+:\d+) %$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, row)) {
      std::istringstream vs(m[3].str());
      std::string v;
      for (int k = std::stoi(m[2]); vs >> v; ++k) out[m[1].str() + ":" + std::to_string(k)] = v;
    } else if (std::regex_match(line, m, tcr)) {
      out[m[3].str() + ".PRE"] = m[1];
      out[m[3].str() + ".ACC"] = m[2];
    }
  }
  return out;
}

// Whether the report was printed from this very file: its page headers name the file in capitals
// ("SINGLE_TIMER_LIVE.RSS" is a later, online save of single_timer.RSS, not this one).
bool report_is_of_this_save(const std::string& report, const fs::path& rss) {
  std::string upper = rss.filename().string();
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return report.find(" " + upper + "\n") != std::string::npos || report.find(" " + upper + " ") != std::string::npos;
}

bool same_value(const std::string& key, const std::string& ours, const std::string& theirs) {
  if (ours == theirs) return true;
  if (key[0] != 'F') return false;
  double a = std::stod(ours), b = std::stod(theirs);  // the report prints 6 or 7 significant digits
  return std::abs(a - b) <= 1e-5 * std::max(1.0, std::abs(b));
}

}  // namespace

// Data files (DATA FILES) against the reports' data-file pages. Where the report was printed
// from this very file (its page header names the file), every N, L, F value and every timer and
// counter PRE and ACC it shows is the reader's. Four lamp-flash reports were printed from a
// later, online save ("SINGLE_TIMER_LIVE.RSS" for single_timer.RSS): there accumulators and
// logged values moved on, and only the presets are compared.
TEST(RssReader, DataValuesAgreeWithTheRslogixReports) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  int exact = 0, presets = 0;
  for (const auto& f : all) {
    auto pdf = report_for(f);
    if (!pdf) continue;
    SCOPED_TRACE(f.filename().string());
    std::string report = pdftotext(*pdf);
    auto r = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(r.text) << r.error;
    const bool same_save = report_is_of_this_save(report, f);
    auto theirs = report_values(report);
    auto ours = our_values(*r.text);
    for (const auto& [key, value] : theirs) {
      bool preset = key.size() > 4 && key.substr(key.size() - 4) == ".PRE";
      if (!same_save && !preset) continue;
      auto it = ours.find(key);
      ASSERT_NE(it, ours.end()) << key << " is in the report's data files";
      EXPECT_TRUE(same_value(key, it->second, value)) << key << ": ours " << it->second << ", report " << value;
      ++(same_save ? exact : presets);
    }
  }
  EXPECT_GE(exact, 2000) << "values compared where the report is of the same save";
  EXPECT_GE(presets, 8) << "presets compared where the report is of a later save";
}

namespace {

// Words the report prints bit by bit: "O:0.0  0 0 ... 1  Bul.1763 ..." (O, I) and "B3:0  0 ... 0"
// (B), bit 15 first. Key "O:0.0", "B3:0"; value the 16-bit word.
std::map<std::string, std::uint16_t> report_bit_words(const std::string& report) {
  std::map<std::string, std::uint16_t> out;
  std::istringstream in(report);
  std::string line;
  static const std::regex row(R"(^((?:O|I):\d+\.\d+|B\d+:\d+)((?:\s+[01]){16})(\s.*)?$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    std::istringstream bits(m[2].str());
    std::uint16_t w = 0;
    int b = 0;
    for (int k = 15; bits >> b; --k) w = static_cast<std::uint16_t>(w | b << k);
    out[m[1].str()] = w;
  }
  return out;
}

// The status-file page: "Free Running Clock S:4 = 0001-1011-0011-0001", "S:22 = 25",
// "S:3 (high byte) = 10", "S:2/14 = 1", "S:63 = 8108h", "S:1/5 = Yes". Key "S:4", "S:3H",
// "S:2/14"; values the report prints as text, a letter or "?" are left out.
std::map<std::string, int> report_status(const std::string& report) {
  std::map<std::string, int> out;
  // "S:14-S:13 = 280" (the math register as a pair) is not a field of one word: a field's "S:"
  // follows a blank or starts the line.
  static const std::regex field(R"((?:^|\s)(S:\d+)(/\d+)?( \((high|low) byte\))? = ([0-9A-Fa-f-]+h|[01]{4}(?:-[01]{4}){3}|\d+|Yes|No|True|False)(?=\s|$))");
  for (std::sregex_iterator it(report.begin(), report.end(), field), end; it != end; ++it) {
    const std::smatch& m = *it;
    std::string key = m[1].str() + m[2].str() + (m[4].matched ? (m[4] == "high" ? "H" : "L") : "");
    std::string v = m[5].str();
    int value = 0;
    if (v == "Yes" || v == "True") value = 1;
    else if (v == "No" || v == "False") value = 0;
    else if (v.back() == 'h') value = std::stoi(v.substr(0, v.size() - 1), nullptr, 16);
    else if (v.size() == 19 && v[4] == '-') {
      for (char c : v)
        if (c != '-') value = value * 2 + (c - '0');
    } else value = std::stoi(v);
    out[key] = value;
  }
  return out;
}

// The reader's DATA O:0 / I:0 (hex), B (decimal) and S:0 (decimal) rows as 16-bit words.
std::map<std::string, std::uint16_t> our_words(const std::string& text) {
  std::map<std::string, std::uint16_t> out;
  std::istringstream in(text);
  std::string line;
  static const std::regex io(R"(^% ([OI]):0\.0 %(.*)$)"), dec(R"(^% (B\d+|S):(\d+) %(.*)$)");
  while (std::getline(in, line)) {
    std::smatch m;
    std::istringstream vs;
    std::string v;
    if (std::regex_match(line, m, io)) {
      vs.str(m[2].str());
      for (int k = 0; vs >> v; ++k) out[m[1].str() + ":0." + std::to_string(k)] = static_cast<std::uint16_t>(std::stoul(v.substr(2), nullptr, 16));
    } else if (std::regex_match(line, m, dec)) {
      vs.str(m[3].str());
      for (int k = std::stoi(m[2]); vs >> v; ++k) out[m[1].str() + ":" + std::to_string(k)] = static_cast<std::uint16_t>(std::stoi(v));
    }
  }
  return out;
}

// A status field of the report, computed from our S words: "S:4", "S:3H", "S:2/14".
std::optional<int> our_status_field(const std::map<std::string, std::uint16_t>& words, const std::string& key) {
  static const std::regex k(R"(S:(\d+)(?:/(\d+))?([HL])?)");
  std::smatch m;
  if (!std::regex_match(key, m, k)) return std::nullopt;
  auto it = words.find("S:" + m[1].str());
  if (it == words.end()) return std::nullopt;
  int w = it->second;
  if (m[2].matched) return (w >> std::stoi(m[2])) & 1;
  if (m[3].matched) return m[3] == "H" ? w >> 8 : w & 0xFF;
  return w;
}

}  // namespace

// The image (O0, I1), status (S2) and bit (B) files against the reports' data-file pages, where
// the report was printed from this very save: every O/I/B word the report prints bit by bit, and
// every status field it prints as a number, bit or Yes/No (1763-RM001-style page: "Free Running
// Clock S:4", "Watchdog S:3 (high byte)", "Math Overflow Selected S:2/14", ...). This is the
// oracle for `DATA O:0`, `DATA I:0` and `DATA S:0`, which carry them into the program.
TEST(RssReader, ImageStatusAndBitFilesAgreeWithTheRslogixReports) {
  auto all = fixtures();
  if (all.empty()) GTEST_SKIP() << "no fixtures at " << kFixtures;
  int io = 0, bits = 0, status = 0, fixtures_compared = 0;
  for (const auto& f : all) {
    auto pdf = report_for(f);
    if (!pdf) continue;
    std::string report = pdftotext(*pdf);
    if (!report_is_of_this_save(report, f)) continue;
    SCOPED_TRACE(f.filename().string());
    auto r = read_project(slurp(f), f.filename().string());
    ASSERT_TRUE(r.text) << r.error;
    auto ours = our_words(*r.text);
    ++fixtures_compared;
    for (const auto& [key, word] : report_bit_words(report)) {
      auto it = ours.find(key);
      ASSERT_NE(it, ours.end()) << key << " is in the report's data files";
      EXPECT_EQ(it->second, word) << key;
      ++(key[0] == 'B' ? bits : io);
    }
    for (const auto& [key, value] : report_status(report)) {
      auto v = our_status_field(ours, key);
      ASSERT_TRUE(v) << key << " is on the report's status page";
      EXPECT_EQ(*v, value) << key;
      ++status;
    }
  }
  EXPECT_GE(fixtures_compared, 3);
  EXPECT_GE(io, 50) << "O and I words compared";
  EXPECT_GE(bits, 30) << "B words compared";
  EXPECT_GE(status, 200) << "status fields compared";
}

// A DATA FILES payload in the layout the reader documents (rss_reader.cpp, "DATA FILES"): a
// CDataHolder with one CDataFile record of `type` holding `words` one-word elements.
std::string data_holder(std::uint16_t type, std::uint16_t number, const std::vector<std::uint16_t>& words,
                        const std::vector<std::uint16_t>& forces) {
  std::string out;
  auto u16 = [&](std::uint16_t v) {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>(v >> 8);
  };
  auto cls = [&](const std::string& name) {
    u16(0xFFFF);
    u16(1);
    u16(static_cast<std::uint16_t>(name.size()));
    out += name;
  };
  cls("CDataHolder");
  u16(1);
  cls("CDataFile");
  u16(type);
  out += std::string(6, '\0');
  u16(static_cast<std::uint16_t>(words.size()));
  u16(1);
  u16(0);
  u16(0xFFFF);
  for (auto w : words) u16(w);
  for (auto w : forces) u16(w);
  u16(number);
  out += '\0';  // description
  out += '\0';  // name
  out += std::string(4, '\0');
  u16(0);  // no function files
  return out;
}

// The O and I files become the embedded slot's DATA and FORCE blocks; a file larger than the
// embedded image is expansion I/O, which the reader does not decode: a named error, not a project
// that silently loses its slots (MicroLogix 1100 embedded I/O: 4 output words).
TEST(RssReader, OutputFileAndForcesOfTheEmbeddedSlot) {
  auto ok = softslc::rss::decode_data_files_payload(
      data_holder(0, 0, {0x0001, 0, 0, 0x8000}, {0x0001, 0xFFFF, 0, 0xFFFF, 0, 0xFFFF, 0, 0x7FFF}));
  ASSERT_TRUE(ok.text) << ok.error;
  EXPECT_EQ(*ok.text,
            "\nDATA O:0\n% O:0.0 % 0X0001 0X0000 0X0000 0X8000\n"
            "\nFORCE O:00\n% ON     OFF  %\n0X0001 0XFFFF % FORCE O:0.0 %\n0X0000 0XFFFF % FORCE O:0.1 %\n"
            "0X0000 0XFFFF % FORCE O:0.2 %\n0X0000 0X7FFF % FORCE O:0.3 %\n");
  auto expansion = softslc::rss::decode_data_files_payload(data_holder(0, 0, {0, 0, 0, 0, 0}, std::vector<std::uint16_t>(10, 0)));
  ASSERT_FALSE(expansion.text);
  EXPECT_NE(expansion.error.find("OUTPUT file of 5 words; the Bul.1763's embedded I/O has 4: expansion I/O is not read"), std::string::npos)
      << expansion.error;
}

// `payload` (a data_holder) with its function-file count replaced by one record of `type`, as the
// projects store them after the data files: a reference to the CDataFile class (0x8003), then the
// CDataFile record.
std::string with_function_file(std::string payload, std::uint16_t type, std::uint16_t elements, std::uint16_t words_per_element,
                               const std::vector<std::uint16_t>& words) {
  payload.resize(payload.size() - 2);
  auto u16 = [&](std::uint16_t v) {
    payload += static_cast<char>(v & 0xFF);
    payload += static_cast<char>(v >> 8);
  };
  u16(1);
  u16(0x8003);
  u16(type);
  payload += std::string(6, '\0');
  u16(elements);
  u16(words_per_element);
  u16(0);
  u16(0xFFFF);
  for (auto w : words) u16(w);
  u16(0);
  payload += std::string(2, '\0');  // description, name
  payload += std::string(4, '\0');
  return payload;
}

// The STI record (type 0x14) becomes the export's DATA STI0:0 row, before the force tables; one of
// another shape is an error, not a guess.
TEST(RssReader, StiFunctionFileRecord) {
  const std::string output = data_holder(0, 0, {0, 0, 0, 0}, {0, 0xFFFF, 0, 0xFFFF, 0, 0xFFFF, 0, 0xFFFF});
  auto r = softslc::rss::decode_data_files_payload(with_function_file(output, 0x14, 1, 4, {13, 0, 0x32, 300}));
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_NE(r.text->find("\nDATA STI0:0\n% STI0:0 %\n13 0 0X0032 300\n\nFORCE O:00\n"), std::string::npos) << *r.text;
  auto other = softslc::rss::decode_data_files_payload(with_function_file(output, 0x17, 1, 8, std::vector<std::uint16_t>(8, 0)));
  ASSERT_TRUE(other.text) << other.error;
  EXPECT_EQ(other.text->find("STI"), std::string::npos) << "only the STI is carried";
  auto bad = softslc::rss::decode_data_files_payload(with_function_file(output, 0x14, 2, 4, std::vector<std::uint16_t>(8, 0)));
  ASSERT_FALSE(bad.text);
  EXPECT_NE(bad.error.find("the STI function file has 2 elements of 4 words"), std::string::npos) << bad.error;
}

// A forced output saved in the project is forced when the converted program runs: the FORCE
// block reaches the runtime like an export's (docs/program-format.md "FORCE blocks").
TEST(RssReader, SavedForcesLoadAsTheExportsForceBlocks) {
  auto r = softslc::rss::decode_data_files_payload(data_holder(0, 0, {0, 0, 0, 0}, {0x0004, 0xFFFF, 0, 0xFFFF, 0, 0xFFFF, 0, 0xFFFF}));
  ASSERT_TRUE(r.text) << r.error;
  auto program = softslc::load_program("START Bul.1763 SERIES B\nSLOT 0 Bul.1763 SCAN_IN 6 SCAN_OUT 4\nLADDER 2\nSOR XIC B3:0/0 OTE O:0/0 EOR\n" + *r.text,
                                       "forces.slc");
  ASSERT_TRUE(program.ok()) << program.render_diagnostics();
  ASSERT_EQ(program.program->forces.size(), 1u);
  EXPECT_EQ(program.program->forces[0].words[0].on, 0x0004);
}

// Pasted rungs (issue 14): bare SOR ... EOR lines are program file 2 of the processor named,
// with its default data files and a MicroLogix's embedded I/O; line numbers are the text's own.
TEST(PastedRungs, LoadAsProgramFileTwoOfTheNamedProcessor) {
  const std::string rungs = "SOR XIC I:0/0 BST OTE O:0/0 NXB TON T4:0 1.0 10 0 BND EOR\nSOR XIC T4:0/DN OTL B3:0/1 EOR\n";
  EXPECT_TRUE(softslc::is_pasted_rungs(rungs));
  EXPECT_TRUE(softslc::is_pasted_rungs("% copied from RSLogix %\n\n" + rungs));
  EXPECT_FALSE(softslc::is_pasted_rungs("START Bul.1766\nLADDER 2\n" + rungs));
  EXPECT_FALSE(softslc::is_pasted_rungs("LADDER 2\n" + rungs));
  EXPECT_FALSE(softslc::is_pasted_rungs(""));
  auto ml = softslc::resolve_processor("Bul.1766", std::nullopt);
  ASSERT_TRUE(ml);
  auto r = softslc::load_pasted_rungs(rungs, "pasted.txt", *ml);
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  ASSERT_EQ(r.program->files.size(), 1u);
  EXPECT_EQ(r.program->files[0].number, 2);
  EXPECT_EQ(r.program->files[0].rungs.size(), 2u);
  // The same program as with the header written out.
  auto full = softslc::load_program("START Bul.1766\nLADDER 2\n" + rungs, "full.slc");
  ASSERT_TRUE(full.ok()) << full.render_diagnostics();
  std::string diff;
  EXPECT_TRUE(softslc::same_program(*r.program, *full.program, &diff)) << diff;
  // A modular SLC 5/03 has no I/O in slot 0: the pasted text's own line 1 is named.
  auto slc = softslc::resolve_processor("1747-L532", std::nullopt);
  ASSERT_TRUE(slc);
  auto bad = softslc::load_pasted_rungs(rungs, "pasted.txt", *slc);
  ASSERT_FALSE(bad.ok());
  ASSERT_FALSE(bad.diagnostics.items().empty());
  EXPECT_EQ(bad.diagnostics.items()[0].line, 1u);
  EXPECT_NE(bad.render_diagnostics().find("slot 0 has no module"), std::string::npos) << bad.render_diagnostics();
}
