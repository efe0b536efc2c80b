// RPC, Read Program Checksum, on the MicroLogix 1400 (issue 16), and the instructions of the same
// chapter softslc leaves refused on the MicroLogix (RHC, TDF: pages not reached; LCD).
//
// Manual facts used: 1766-RM001A p. 239: "Proc/Mmod is an immediate value with a range from 0…1"
// (PROC-MEM / MEM-MOD), the destination "integer file location", "Execution Time for the RPC
// Instruction": MicroLogix 1400 true 4.2844 us, false 0.2028 us (the table names the 1400 only).
// 1747-RM001G p. 7-23: the checksum is "a 16-bit value that is calculated for the entire ladder logic
// image, excluding the data table values. The checksum changes any time program edits are made."
//
// The algorithm is softslc's (docs/semantics.md "RPC"): CRC-32 (IEEE 802.3) of the ladder image, the
// program files in number order, each "LADDER n\n" then its rungs' canonical text one per line,
// folded to 16 bits as (crc >> 16) XOR (crc & FFFFh). Each expected value below was computed by hand
// from that definition with Python's zlib.crc32, outside softslc:
//   python3 -c 'import zlib; c = zlib.crc32(IMAGE); print(hex((c >> 16) ^ (c & 0xffff)))'
#include <gtest/gtest.h>

#include <string>

#include "load_errors.h"
#include "parser/loader.h"
#include "tools/controller/controller.h"
#include "vm/scantime.h"
#include "vm/timing_profile.h"

namespace softslc {
namespace {

using test::load_errors;

// N7:0 as the unsigned 16-bit word RPC wrote.
unsigned checksum_read(Controller& plc, const char* address = "N7:0") {
  return static_cast<unsigned>(plc.get_int(address)) & 0xFFFFu;
}

// N7:0 after one scan of a MicroLogix 1400 running `ladder` (program files from LADDER 2 on).
unsigned checksum_of(const std::string& ladder) {
  Controller plc = Controller::from_text("START Bul.1766\nLADDER 2\n" + ladder);
  plc.scan(1);
  return checksum_read(plc);
}

TEST(MicroLogixRpc, ProcMemReadsTheChecksumOfTheLadderImage) {
  // Image "LADDER 2\nSOR RPC 0 N7:0 EOR\n": CRC-32 ED3E73D3h, folded ED3Eh ^ 73D3h = 9EEDh.
  EXPECT_EQ(checksum_of("SOR RPC 0 N7:0 EOR\n"), 0x9EEDu);
}

TEST(MicroLogixRpc, TheChecksumChangesWithARungAndNotWithDataOrComments) {
  // A second rung: image "LADDER 2\nSOR RPC 0 N7:0 EOR\nSOR RPC 1 N7:1 EOR\n" gives DB73h; the
  // MEM-MOD read of the same program is 0 (no memory module in softslc, docs/semantics.md "RPC").
  Controller two = Controller::from_text("START Bul.1766\nLADDER 2\nSOR RPC 0 N7:0 EOR\nSOR RPC 1 N7:1 EOR\n");
  two.set("N7:1", 1234);
  two.scan(1);
  EXPECT_EQ(checksum_read(two), 0xDB73u);
  EXPECT_EQ(two.get_int("N7:1"), 0);

  // Data values ("excluding the data table values", RM001G p. 7-23) and a rung comment are not ladder
  // logic: the one-rung program with initial data and a comment reads the one-rung figure, 9EEDh.
  Controller with_data = Controller::from_text(
      "START Bul.1766\nLADDER 2\n% Rung: 0 %\n% the checksum rung %\nSOR RPC 0 N7:0 EOR\n"
      "DATA N7:0\n% N7:0 %  0 77 -5 12\n");
  EXPECT_EQ(with_data.get_int("N7:1"), 77);
  with_data.scan(1);
  EXPECT_EQ(checksum_read(with_data), 0x9EEDu);
  // Nor does data the program or a client writes at run time.
  with_data.set("N7:2", 999);
  with_data.scan(1);
  EXPECT_EQ(checksum_read(with_data), 0x9EEDu);
}

TEST(MicroLogixRpc, ARungInASubroutineFileCountsToo) {
  // Files 2 and 3: "LADDER 2\nSOR RPC 0 N7:0 EOR\nSOR JSR 3 EOR\nLADDER 3\nSOR MOV 5 N7:1 EOR\n" gives
  // 44F2h; the same with MOV 6 gives BB11h.
  EXPECT_EQ(checksum_of("SOR RPC 0 N7:0 EOR\nSOR JSR 3 EOR\nLADDER 3\nSOR MOV 5 N7:1 EOR\n"), 0x44F2u);
  EXPECT_EQ(checksum_of("SOR RPC 0 N7:0 EOR\nSOR JSR 3 EOR\nLADDER 3\nSOR MOV 6 N7:1 EOR\n"), 0xBB11u);
}

TEST(MicroLogixRpc, AFalseRungLeavesTheDestination) {
  Controller plc = Controller::from_text("START Bul.1766\nLADDER 2\nSOR XIC B3:0/0 RPC 0 N7:0 EOR\n");
  plc.set("N7:0", 42);
  plc.scan(1);
  EXPECT_EQ(plc.get_int("N7:0"), 42);
  plc.set("B3:0/0", 1);
  plc.scan(1);
  // "LADDER 2\nSOR XIC B3:0/0 RPC 0 N7:0 EOR\n" gives B38Eh.
  EXPECT_EQ(checksum_read(plc), 0xB38Eu);
}

TEST(MicroLogixRpc, CheckTakesItWhereAPageSaysSo) {
  EXPECT_EQ(load_errors("START Bul.1766\nLADDER 2\nSOR RPC 0 N7:0 EOR\nSOR RPC 1 N10:3 EOR\n"), "");
  // p. 239: Proc/Mmod 0…1; the destination an integer file location.
  EXPECT_NE(load_errors("START Bul.1766\nLADDER 2\nSOR RPC 2 N7:0 EOR\n").find("out of range"), std::string::npos);
  const std::string f = load_errors("START Bul.1766\nLADDER 2\nSOR RPC 0 F8:0 EOR\n");
  EXPECT_NE(f.find("t.slc:3:11: error: RPC writes its checksum to an N word"), std::string::npos) << f;
  EXPECT_NE(load_errors("START Bul.1766\nLADDER 2\nSOR RPC 0 L9:0 EOR\n").find("N word"), std::string::npos);
  // The 1100, 1200 and 1500 pages were not reached: refused, naming where RPC is.
  for (const char* p : {"Bul.1763", "Bul.1762", "1764-LRP", "Bul.1761"}) {
    const std::string e = load_errors(std::string("START ") + p + "\nLADDER 2\nSOR RPC 0 N7:0 EOR\n");
    EXPECT_NE(e.find("RPC is not available on the MicroLogix"), std::string::npos) << p << ": " << e;
    EXPECT_NE(e.find("MicroLogix 1400"), std::string::npos) << p << ": " << e;
  }
}

TEST(MicroLogixRpc, ScantimeAndVirtualTimeUseThePagesExecutionTime) {
  LoadResult r = load_program("START Bul.1766\nLADDER 2\nSOR RPC 0 N7:0 EOR\n", "t.slc");
  ASSERT_TRUE(r.ok()) << r.render_diagnostics();
  auto profile = builtin_timing_profile(r.program->processor.timing_key());
  ASSERT_TRUE(profile.has_value());
  const ScanTimePrediction t = predict_scan_time(*r.program, r.program->processor, *profile);
  ASSERT_EQ(t.rungs.size(), 1u);
  EXPECT_EQ(t.rungs[0].worst, 4'284);  // 4.2844 us to the nanosecond
  EXPECT_EQ(t.rungs[0].best, 203);     // 0.2028 us
  EXPECT_FALSE(profile->is_estimate(profile->instruction(Opcode::RPC).source));

  // In virtual time: a rung with one RPC against the same rung with two in series differs by one RPC.
  auto scan = [](const std::string& rung, bool on) {
    Controller plc = Controller::from_text("START Bul.1766\nLADDER 2\n" + rung);
    plc.set("B3:0/0", on ? 1 : 0);
    plc.scan(2);
    return plc.runtime().stats().last;
  };
  for (bool on : {true, false}) {
    const Nanoseconds one = scan("SOR XIC B3:0/0 RPC 0 N7:0 EOR\n", on);
    const Nanoseconds two = scan("SOR XIC B3:0/0 RPC 0 N7:0 RPC 0 N7:1 EOR\n", on);
    EXPECT_EQ(two - one, on ? 4'284 : 203) << (on ? "true" : "false");
  }
}

// RHC and TDF: the MicroLogix pages (their clock's width and tick, the operand files) were not
// reached; the SLC form is not taken as the MicroLogix one (docs/semantics.md "Free-running clock").
TEST(MicroLogixRpc, RhcTdfAndLcdStayRefusedByName) {
  for (const char* p : {"Bul.1763", "Bul.1766", "Bul.1762", "1764-LRP"}) {
    const std::string e = load_errors(std::string("START ") + p + "\nLADDER 2\nSOR RHC N7:0 EOR\n");
    EXPECT_NE(e.find("RHC is supported in its SLC 5/03-5/05 form only"), std::string::npos) << p << ": " << e;
    EXPECT_NE(e.find("reference pages"), std::string::npos) << p << ": " << e;
  }
  // LCD: the instruction's page was not reached (docs/micrologix-function-files-sources.md).
  const std::string lcd = load_errors("START Bul.1766\nLADDER 2\nSOR LCD N7:0 EOR\n");
  EXPECT_NE(lcd.find("instruction LCD is not supported by softslc yet"), std::string::npos) << lcd;
}

}  // namespace
}  // namespace softslc
