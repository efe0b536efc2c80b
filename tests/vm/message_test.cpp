// MSG and SVC between controllers on one simulated network (docs/semantics.md "MSG").
//
// Expected values come from the SLC 500 Instruction Set Reference, 1747-RM001G chapter 12 (page in
// each test), the DH-485 facts of chapter 13, and the data rates of instructions/message_link.h.
// Every test builds a leader (node 1, the program under test) and its peers through the public
// Runtime API, as the test runner does.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "vm/message_network.h"
#include "vm/profile_scan_time_model.h"
#include "vm/timing_profile.h"
#include "message_line.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

std::shared_ptr<const Program> load(std::string_view body, std::string_view header = kHeader) {
  return load_peer_program(program_text(body, header));
}

std::shared_ptr<const ScanTimeModel> slc503_model() {
  ProcessorModel p = *resolve_processor("1747-L532");
  return make_scan_time_model(p);
}

// A leader running `a_body` (node 1) and a peer "B" running `b_body` (node 2), both SLC 5/03s on DH-485.
struct Line : MessageLine {
  Line(std::string_view a_body, std::string_view b_body, RuntimeOptions a_opts = {}, RuntimeOptions b_opts = {})
      : MessageLine(program_text(a_body), program_text(b_body), std::move(a_opts), std::move(b_opts)) {}
};

// B's N7:0-9 exist (a rung that never runs names N7:9); A's N10 likewise.
constexpr std::string_view kTarget = "SOR XIC B3:0/15 CLR N7:9 EOR";
constexpr std::string_view kReadFive = "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR";

// The time a frame of `data_bytes` takes on DH-485: 19,200 baud, 11 bits a character, 16 bytes of
// framing (EST) — instructions/message_link.h.
constexpr Nanoseconds dh485(int data_bytes) { return (Nanoseconds{16 + data_bytes} * 11 * kNsPerS + 19199) / 19200; }

TEST(Message, TheSetupIsWrittenIntoTheControlBlock) {
  // RM 12-31, table 12.11: word 1 target node, 2 number of elements, 3 file number, 4 file type,
  // 5 element number, 8 the message timer preset. The file type is the PCCC code of N, 89h.
  Line line(kReadFive, kTarget);
  EXPECT_EQ(line.ai("N9:1"), 2);
  EXPECT_EQ(line.ai("N9:2"), 5);
  EXPECT_EQ(line.ai("N9:3"), 7);
  EXPECT_EQ(line.ai("N9:4"), 0x89);
  EXPECT_EQ(line.ai("N9:5"), 0);
  EXPECT_EQ(line.ai("N9:8"), 5);
}

TEST(Message, AReadGoesThroughEnEwStDnAndCopiesTheTargetsWords) {
  Line line(kReadFive, kTarget);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(line.b->set("N7:" + std::to_string(i), Value::of_int(100 + i)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  // RM 12-29 table 12.10: EN and EW set, "MSG and source data is buffered"; not yet acknowledged.
  EXPECT_TRUE(line.abit("N9:0/15"));
  EXPECT_TRUE(line.abit("N9:0/10"));
  EXPECT_FALSE(line.abit("N9:0/14"));
  EXPECT_FALSE(line.abit("N9:0/13"));
  const VirtualTime sent = line.a->now();  // the end-of-scan servicing sent it
  // ST "is set when the processor receives acknowledgment (ACK) from the target device" (RM 12-29):
  // one request frame later, seen at A's next servicing point. EW is cleared by the ACK.
  ASSERT_TRUE(line.until("N9:0/14"));
  const Nanoseconds to_ack = line.a->now() - sent;
  EXPECT_GE(to_ack, dh485(0));
  EXPECT_LE(to_ack, dh485(0) + line.a->stats().max);
  EXPECT_FALSE(line.abit("N9:0/10"));
  EXPECT_FALSE(line.abit("N9:0/13"));
  // DN once the reply is back; "The ST bit is reset when the DN, ER, or TO bit is set" (RM 12-29).
  ASSERT_TRUE(line.until("N9:0/13"));
  EXPECT_FALSE(line.abit("N9:0/14"));
  EXPECT_FALSE(line.abit("N9:0/12"));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(line.ai("N10:" + std::to_string(i)), 100 + i);
  // The reply carried 10 data bytes after B's servicing: the round trip is at least both frames.
  EXPECT_GE(line.a->now() - sent, dh485(0) + dh485(10));
}

TEST(Message, EnStaysSetUntilTheRungGoesFalseAfterDn) {
  // RM 12-29: EN "remains set until message transmission is completed and the rung goes false".
  Line line(kReadFive, kTarget);
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.until("N9:0/13"));
  line.a->scan(3);
  EXPECT_TRUE(line.abit("N9:0/15"));
  EXPECT_TRUE(line.abit("N9:0/13"));
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(false)));
  line.a->scan(1);
  EXPECT_FALSE(line.abit("N9:0/15"));
  EXPECT_TRUE(line.abit("N9:0/13")) << "DN is reset by the next false-to-true transition only (RM 12-28)";
  // The next false-to-true transition resets DN and sends again.
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  EXPECT_TRUE(line.abit("N9:0/15"));
  EXPECT_FALSE(line.abit("N9:0/13"));
}

TEST(Message, AWriteChangesOnlyTheTargetsWords) {
  Line line("SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 3 2 N7:4 5 EOR", kTarget);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(line.a->set("N10:" + std::to_string(i), Value::of_int(-7 - i)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.until("N9:0/13"));
  EXPECT_EQ(line.bi("N7:3"), 0);
  EXPECT_EQ(line.bi("N7:4"), -7);
  EXPECT_EQ(line.bi("N7:5"), -8);
  EXPECT_EQ(line.bi("N7:6"), -9);
  EXPECT_EQ(line.bi("N7:7"), 0);
}

// Runs one message of A's and returns the error code once ER is set (-1: it never was).
int error_of(std::string_view a_body, std::string_view b_body) {
  Line line(a_body, b_body);
  line.run();
  EXPECT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  if (!line.until("N9:0/12", 10 * kNsPerS)) return -1;
  EXPECT_FALSE(line.abit("N9:0/13"));
  EXPECT_FALSE(line.abit("N9:0/14"));
  return static_cast<int>(line.ai("N9:0") & 0xFF);
}

TEST(Message, ErrorCodesOfTheTarget) {
  // RM 12-41 table 12.17: "07H Target node does not respond" (no station at node 9).
  EXPECT_EQ(error_of("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 9 N7:0 5 EOR", kTarget), 0x07);
  // "10H ... or the data file specified does not exist" (B has no N12).
  EXPECT_EQ(error_of("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N12:0 5 EOR", kTarget), 0x10);
  // EAh "transaction size plus word address is too large" (1762-RM001C p. 21-22): N7:8 + 5 words
  // runs past B's N7:9.
  EXPECT_EQ(error_of("SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:8 5 EOR", kTarget), 0xEA);
  // E6h "address does not exist": the first element is past the file's end.
  EXPECT_EQ(error_of("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 1 2 N7:40 5 EOR", kTarget), 0xE6);
  // F1h "illegal target file type": B's file 8 is an F file, the message carries N data.
  EXPECT_EQ(error_of("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 1 2 N8:0 5 EOR",
                     "SOR XIC B3:0/15 CLR N7:9 CLR F8:3 EOR"),
            0xF1);
}

TEST(Message, AControlBlockTheProgramBrokeIsError04And16) {
  // RM 12-41: "04H ... OR the control block may have been inadvertently modified": 0 elements.
  // "16H Target or Local Bridge address is higher than the maximum node address": node 40 on DH-485.
  Line line("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR", kTarget);
  ASSERT_TRUE(line.a->set("N9:2", Value::of_int(0)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  EXPECT_TRUE(line.abit("N9:0/12"));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x04);
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(false)));
  line.a->scan(1);
  ASSERT_TRUE(line.a->set("N9:2", Value::of_int(5)));
  ASSERT_TRUE(line.a->set("N9:1", Value::of_int(40)));
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x16);
}

TEST(Message, WordOneRetargetsTheMessage) {
  // The processor reads the target from the control block (RM 12-31), so a program that writes word 1
  // sends to another node: node 3 is peer C.
  PeerController c;
  c.name = "C";
  c.node = 3;
  c.program = load(kTarget);
  RuntimeOptions opts;
  opts.peers.push_back(c);
  Line line("SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 1 2 N7:0 5 EOR", kTarget, opts);
  Runtime* peer_c = line.a->peer("C");
  ASSERT_NE(peer_c, nullptr);
  ASSERT_TRUE(line.a->set("N10:0", Value::of_int(321)));
  ASSERT_TRUE(line.a->set("N9:1", Value::of_int(3)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.until("N9:0/13"));
  EXPECT_EQ(peer_c->value("N7:0").as_int(), 321);
  EXPECT_EQ(line.bi("N7:0"), 0);
}

std::string check_errors_of(std::string_view body, std::string_view header) {
  LoadResult lr = load_program(program_text(body, header), "t.slc");
  return lr.render_diagnostics();
}

// A target whose scans take 3 s (its housekeeping): it answers only at its end of scan. (The watchdog
// faults it after its first scan; a faulted processor still answers messages.)
RuntimeOptions slow_target() { return test::slow_target("1747-L532"); }

TEST(Message, TheMessageTimerErrorsWith37hAndTo) {
  // RM 12-14: "Specifies the length of the message timer in seconds"; RM 12-42 table 12.17 "37H
  // Message timed out in local processor". The timer starts with the rung (1762-RM001C p. 21-12).
  Line line("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 2 EOR", kTarget, {}, slow_target());
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  const VirtualTime started = line.a->now();
  ASSERT_TRUE(line.until("N9:0/12", 5 * kNsPerS));
  EXPECT_GE(line.a->now() - started, 2 * kNsPerS - line.a->stats().max);
  EXPECT_LE(line.a->now() - started, 2 * kNsPerS + line.a->stats().max);
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x37);
  EXPECT_TRUE(line.abit("N9:0/8")) << "TO with ER (decision, docs/semantics.md \"MSG\")";
  EXPECT_FALSE(line.abit("N9:0/13"));
  EXPECT_EQ(line.ai("N9:10"), 2) << "the accumulator (whole seconds) reached the preset";
  // The late reply changes nothing (the message is gone).
  line.a->run_for(4 * kNsPerS);
  EXPECT_FALSE(line.abit("N9:0/13"));
  EXPECT_EQ(line.ai("N10:0"), 0);
}

TEST(Message, ATimeoutOfOneSecondIsTwo) {
  // RM 12-53: "Like the Message Timeout in a standard MSG instruction, a value of 0 disables the Message
  // Timeout and a value of 1 second gets bumped to 2 seconds upon instruction execution."
  Line line("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 1 EOR", kTarget, {}, slow_target());
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  line.a->run_for(kNsPerS + kNsPerS / 2);
  EXPECT_FALSE(line.abit("N9:0/12")) << "not timed out at 1.5 s";
  ASSERT_TRUE(line.until("N9:0/12", kNsPerS));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x37);
}

TEST(Message, ATimeoutOfZeroWaitsForTheReply) {
  // RM 12-14: "A timeout of 0 seconds means that there is no timer and a message that has been
  // acknowledged waits indefinitely for a reply."
  Line line("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 0 EOR", kTarget, {}, slow_target());
  ASSERT_TRUE(line.b->set("N7:0", Value::of_int(55)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.until("N9:0/13", 10 * kNsPerS));
  EXPECT_FALSE(line.abit("N9:0/12"));
  EXPECT_EQ(line.ai("N10:0"), 55);
}

TEST(Message, SettingToAbortsTheMessage) {
  // RM 12-30: "when a MSG is in progress and the ladder program wishes to terminate it ... enabling the
  // time-out bit (TO = bit 8). The next time the processor scans the MSG instruction with the TO bit
  // set, it will error the MSG (ER = 1)."
  Line line("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 0 EOR", kTarget, {}, slow_target());
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(2);
  ASSERT_FALSE(line.abit("N9:0/12"));
  ASSERT_TRUE(line.a->set("N9:0/8", Value::bit(true)));
  line.a->scan(1);
  EXPECT_TRUE(line.abit("N9:0/12"));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x37);
}

TEST(Message, FourBuffersTenQueuePositionsThenWq) {
  // RM 12-7: four channel buffers (EN and EW); "from the fifth instruction to the fourteenth" the
  // overflow queue (EN only); beyond 14 "only control block status bit WQ is set" (word 7 bit 0, RM 12-29).
  std::string body;
  for (int i = 0; i < 15; ++i)
    body += "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N20:" + std::to_string(14 * i) + " 14 1 N10:" + std::to_string(i) +
            " 1 2 N7:0 0 EOR\n";
  Line line(body, kTarget, {}, slow_target());
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  for (int i = 0; i < 15; ++i) {
    const std::string w0 = "N20:" + std::to_string(14 * i), w7 = "N20:" + std::to_string(14 * i + 7);
    const std::int64_t bits = line.ai(w0);
    SCOPED_TRACE("MSG " + std::to_string(i + 1));
    EXPECT_EQ((bits & msg::kEN) != 0, i < 14);
    EXPECT_EQ((bits & msg::kEW) != 0, i < 4);
    EXPECT_EQ((line.ai(w7) & msg::kWQ) != 0, i == 14);
  }
  // The 15th gets in once a place is free, the rung still true; all 15 complete in the end.
  ASSERT_TRUE(line.a->run_until(
      [](const Runtime& r) {
        for (int i = 0; i < 15; ++i)
          if (!r.value("N20:" + std::to_string(14 * i) + "/13").as_bool()) return false;
        return true;
      },
      60 * kNsPerS));
  EXPECT_EQ(line.ai("N20:203") & msg::kWQ, 0);
}

TEST(Message, TheSlc502FormServesOneMessageAtATime) {
  // RM 12-5: "The SLC 5/02 processor can service one message instruction at any given time", holding
  // others "enabled and waiting (control block status bits EN and EW set)"; a 7-word block.
  constexpr std::string_view k502 = "START 1747-L524\nSLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\nSLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n";
  LoadResult peer_lr = load_program(program_text(kTarget, k502), "b.slc");
  ASSERT_TRUE(peer_lr.ok()) << peer_lr.render_diagnostics();
  PeerController b;
  b.name = "B";
  b.node = 2;
  b.program = std::make_shared<const Program>(std::move(*peer_lr.program));
  b.options = std::make_shared<const RuntimeOptions>(slow_target());
  RuntimeOptions opts;
  opts.peers.push_back(b);
  std::string errors;
  auto a = try_build(program_text("SOR XIC B3:0/0 BST MSG READ 500CPU N9:0 7 N10:0 1 2 N7:0 NXB MSG READ 500CPU N9:7 7 N10:1 1 2 N7:1 BND EOR", k502),
                     errors, opts);
  ASSERT_TRUE(a) << errors;
  ASSERT_TRUE(a->peer("B")->set("N7:0", Value::of_int(11)));
  ASSERT_TRUE(a->peer("B")->set("N7:1", Value::of_int(12)));
  ASSERT_TRUE(a->set_mode(Mode::Run));
  ASSERT_TRUE(a->set("B3:0/0", Value::bit(true)));
  a->scan(1);
  EXPECT_EQ(a->value("N9:0").as_int() & (msg::kEN | msg::kEW), msg::kEN | msg::kEW);
  EXPECT_EQ(a->value("N9:7").as_int() & (msg::kEN | msg::kEW), msg::kEN | msg::kEW);
  // The first is answered at the slow target's end of scan (3 s); the second goes out only then.
  ASSERT_TRUE(a->run_until([](const Runtime& r) { return r.value("N9:0/13").as_bool(); }, 10 * kNsPerS));
  EXPECT_FALSE(a->value("N9:7/13").as_bool());
  ASSERT_TRUE(a->run_until([](const Runtime& r) { return r.value("N9:7/13").as_bool(); }, 10 * kNsPerS));
  EXPECT_EQ(a->value("N10:0").as_int(), 11);
  EXPECT_EQ(a->value("N10:1").as_int(), 12);
}

TEST(Message, TheTargetAnswersAtItsEndOfScan) {
  // A request is acted on at the target's communication servicing (RM 12-41: "at end of scan or SVC"):
  // with B's scans 3 s long the write lands in B at B's end of scan, not when the frame arrives.
  Line line("SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 1 2 N7:0 0 EOR", kTarget, {}, slow_target());
  ASSERT_TRUE(line.a->set("N10:0", Value::of_int(9)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  line.a->scan(1);
  line.a->run_for(100 * kNsPerMs);
  EXPECT_EQ(line.bi("N7:0"), 0) << "the request reached B after 10.3 ms, but B has not serviced yet";
  ASSERT_TRUE(line.a->run_until([&](const Runtime&) { return line.bi("N7:0") == 9; }, 10 * kNsPerS));
  EXPECT_GE(line.a->now(), 3 * kNsPerS);
}

// B writes 77 into A's N7:0 once; A copies N7:0 to N7:1, runs `middle` (a rung, or nothing), copies N7:0 to
// N7:2, each MOV 4.5 ms long. B sends at its first end of scan (about 0.95 ms after the test sets its trigger)
// and the frame takes 10.31 ms (18 bytes at 19,200 baud, 11 bits each): it arrives in A's second scan (9.5-19
// ms) before that scan's middle rung (14 ms). What A's N7:1 and N7:2 hold after each of its first three scans.
using Copies = std::vector<std::pair<std::int64_t, std::int64_t>>;
Copies copies_around(const std::string& middle) {
  const std::string b_body = "SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 1 1 N7:0 5 EOR\n";
  const std::string a_body = "SOR MOV N7:0 N7:1 EOR\n" + middle + "SOR MOV N7:0 N7:2 EOR\nSOR XIC B3:0/15 CLR N7:9 EOR\n";
  RuntimeOptions a_opts;
  a_opts.time_model = std::make_shared<SlowModel>(slc503_model(), 500'000, 4'500'000);
  Line line(a_body, b_body, a_opts);
  line.run();
  EXPECT_TRUE(line.b->set("N10:0", Value::of_int(77)));
  EXPECT_TRUE(line.b->set("B3:0/0", Value::bit(true)));
  Copies seen;
  for (int i = 0; i < 3; ++i) {
    line.a->scan(1);
    seen.emplace_back(line.ai("N7:1"), line.ai("N7:2"));
  }
  return seen;
}

TEST(Message, SvcServicesTheChannelAtItsPlaceInTheScan) {
  // RM 12-41: messages are serviced "at end of scan or SVC". With the SVC, the second scan's N7:2 has the
  // value and its N7:1 not; without, A takes it at the scan's end and both copies see it in the next scan.
  EXPECT_EQ(copies_around("SOR SVC EOR\n"), (Copies{{0, 0}, {0, 77}, {77, 77}}));
  EXPECT_EQ(copies_around(""), (Copies{{0, 0}, {0, 0}, {77, 77}}));
}

TEST(Message, RefServicesEveryChannelLikeSvc) {
  // A REF services communications between its output and input scans, as an SVC does: "at the next execution
  // of a Service Communications (SVC) instruction, I/O Refresh (REF) instruction, or when it performs
  // Communications Servicing" (1766-RM001A p. 410-411; on the SLC a decision, docs/semantics.md "REF"). A
  // false REF does nothing.
  EXPECT_EQ(copies_around("SOR REF EOR\n"), (Copies{{0, 0}, {0, 77}, {77, 77}}));
  EXPECT_EQ(copies_around("SOR XIC B3:0/1 REF EOR\n"), (Copies{{0, 0}, {0, 0}, {77, 77}}));
}

TEST(Message, Cif485WritesIntoTheTargetsN9AtTheOffset) {
  // 485CIF: "a word offset into the target's Common Interface File" (1763-RM001 "Data Table
  // Address/Offset"; SLC processors use a word offset); an SLC's CIF is N9 (docs/semantics.md).
  Line line("SOR XIC B3:0/0 MSG WRITE 485CIF LOCAL N9:0 14 1 N10:0 2 2 3 5 EOR",
            "SOR XIC B3:0/15 CLR N9:9 EOR");
  EXPECT_EQ(line.ai("N9:3"), 9) << "word 3: the CIF, N9";
  EXPECT_EQ(line.ai("N9:5"), 3) << "word 5: the offset";
  ASSERT_TRUE(line.a->set("N10:0", Value::of_int(-1)));
  ASSERT_TRUE(line.a->set("N10:1", Value::of_int(2)));
  line.run();
  ASSERT_TRUE(line.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.until("N9:0/13"));
  EXPECT_EQ(line.bi("N9:2"), 0);
  EXPECT_EQ(line.bi("N9:3"), -1);
  EXPECT_EQ(line.bi("N9:4"), 2);
}

TEST(Message, Plc5TypedOnDhPlusBetweenTwoSlc504s) {
  // The SLC 5/04's channel 1 is DH+ (RM 12-14), 57,600 baud (1747-SG001 p. 64), 8 bits a byte: a
  // one-word PLC5 read is a (16 + 0)-byte request and a (16 + 2)-byte reply, 2.22 ms and 2.5 ms.
  constexpr std::string_view k504 = "START 1747-L542\n";
  PeerController b;
  b.name = "B";
  b.node = 9;  // 11 octal; DH+ has nodes 0-63
  b.program = load("SOR XIC B3:0/15 CLR N7:9 EOR", k504);
  RuntimeOptions opts;
  opts.node = 1;
  opts.peers.push_back(b);
  std::string errors;
  auto a = try_build(program_text("SOR XIC B3:0/0 MSG READ PLC5 LOCAL N9:0 14 1 N10:0 1 9 N7:4 5 EOR", k504), errors, opts);
  ASSERT_TRUE(a) << errors;
  ASSERT_TRUE(a->peer("B")->set("N7:4", Value::of_int(4242)));
  ASSERT_TRUE(a->set_mode(Mode::Run));
  ASSERT_TRUE(a->set("B3:0/0", Value::bit(true)));
  a->scan(1);
  const VirtualTime sent = a->now();
  ASSERT_TRUE(a->run_until([](const Runtime& r) { return r.value("N9:0/13").as_bool(); }, kNsPerS));
  EXPECT_EQ(a->value("N10:0").as_int(), 4242);
  constexpr Nanoseconds request = (Nanoseconds{16} * 8 * kNsPerS + 57599) / 57600, reply = (Nanoseconds{18} * 8 * kNsPerS + 57599) / 57600;
  EXPECT_GE(a->now() - sent, request + reply);
  EXPECT_LT(a->now() - sent, request + reply + 4 * a->stats().max) << "DH+ is three times DH-485's rate";
  // DH+ nodes go to 63, DH-485's to 31.
  EXPECT_EQ(check_errors_of("SOR MSG READ PLC5 LOCAL N9:0 14 1 N10:0 1 63 N7:4 5 EOR", k504), "");
  EXPECT_NE(check_errors_of("SOR MSG READ PLC5 LOCAL N9:0 14 1 N10:0 1 64 N7:4 5 EOR", k504).find("out of range 0-63"),
            std::string::npos);
}

TEST(Message, TwoRunsAreByteIdentical) {
  // Determinism: the same network and inputs give the same data tables and times, word for word.
  auto run = [] {
    const std::string b_body =
        "SOR ADD N10:0 3 N10:0 EOR\n"
        "SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 1 N10:0 2 1 N7:0 5 EOR\n";
    Line line(std::string(kReadFive) + "\nSOR XIC N9:0/13 OTU B3:0/0 EOR\nSOR XIO B3:0/0 OTL B3:0/0 EOR\n" +
                  std::string(kTarget), b_body);
    line.run();
    EXPECT_TRUE(line.b->set("N9:0/11", Value::bit(true)));
    EXPECT_TRUE(line.b->set("B3:0/0", Value::bit(true)));
    line.a->run_for(2 * kNsPerS);
    std::vector<std::uint16_t> words(line.a->data().words(), line.a->data().words() + line.a->data().size());
    words.insert(words.end(), line.b->data().words(), line.b->data().words() + line.b->data().size());
    words.push_back(static_cast<std::uint16_t>(line.a->now() % 65536));
    words.push_back(static_cast<std::uint16_t>(line.b->now() % 65536));
    return words;
  };
  const auto first = run();
  EXPECT_EQ(first, run());
}

TEST(Message, TheNetworkRefusesABadSetup) {
  std::string errors;
  PeerController b;
  b.name = "B";
  b.node = 1;  // the leader's node
  b.program = load(kTarget);
  RuntimeOptions opts;
  opts.peers.push_back(b);
  EXPECT_EQ(try_build(program_text(kTarget), errors, opts), nullptr);
  EXPECT_NE(errors.find("node 1 is already this controller's"), std::string::npos) << errors;
  opts.peers[0].node = 32;
  EXPECT_EQ(try_build(program_text(kTarget), errors, opts), nullptr);
  EXPECT_NE(errors.find("out of range 1-31 on DH-485"), std::string::npos) << errors;
  // A 5/04 is on DH+, not on the 5/03's DH-485.
  opts.peers[0].node = 2;
  opts.peers[0].program = load(kTarget, "START 1747-L542\n");
  EXPECT_EQ(try_build(program_text(kTarget), errors, opts), nullptr);
  EXPECT_NE(errors.find("is on DH+, this network is DH-485"), std::string::npos) << errors;
}

TEST(Message, ScantimePricesMsgAndSvcAsEstimates) {
  // No SLC execution times for MSG or SVC are in the sources: every SLC profile has a row, marked EST
  // (SVC scaled from the MicroLogix 1200's documented 208 us, 1762-RM001C p. 21-26).
  for (const char* key : {"5/02B", "5/02C", "5/03", "5/04", "5/05"}) {
    auto p = builtin_timing_profile(key);
    ASSERT_TRUE(p) << key;
    for (Opcode op : {Opcode::MSG, Opcode::MSG_502, Opcode::SVC, Opcode::SVC_CH}) {
      const auto& row = p->instructions[static_cast<std::size_t>(op)];
      EXPECT_GT(row.true_ns, 0) << key;
      EXPECT_TRUE(p->is_estimate(row.source)) << key;
    }
  }
  EXPECT_EQ(builtin_timing_profile("5/03")->instructions[static_cast<std::size_t>(Opcode::SVC)].true_ns, 208'000);
}

// ---- check ----------------------------------------------------------------------------------------------

std::string check_errors(std::string_view body, std::string_view header = kHeader) {
  return check_errors_of(body, header);
}

TEST(MessageCheck, RefusesBadOperandsWithAPosition) {
  EXPECT_EQ(check_errors(kReadFive), "");
  // A control block that does not fit its file (RM 12-31: 14 words).
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:250 14 1 N10:0 5 2 N7:0 5 EOR").find("t.slc:5:27: error: the 14-word MSG control block"),
            std::string::npos)
      << check_errors("SOR MSG READ 500CPU LOCAL N9:250 14 1 N10:0 5 2 N7:0 5 EOR");
  // A target node out of range (RM 13-4: responders 1-31).
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 32 N7:0 5 EOR").find("target node 32 is out of range 1-31"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 0 N7:0 5 EOR").find("target node 0 is out of range"),
            std::string::npos);
  // A length beyond the file, and beyond one message.
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:250 10 2 N7:0 5 EOR").find("runs past the end of the file"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 T4:0 35 2 T4:0 5 EOR").find("is 105 words; one message carries at most 103"),
            std::string::npos);
  // A message type the channel cannot send.
  EXPECT_NE(check_errors("SOR MSG READ PLC5 LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR").find("MSG PLC5 on DH-485"),
            std::string::npos);
  // Channel 0 is DF1 full-duplex when a test configures it (tests/vm/df1_test.cpp): check takes its form; PLC5
  // there is not simulated.
  EXPECT_EQ(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR"), "");
  EXPECT_NE(check_errors("SOR MSG READ PLC5 LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR").find("MSG PLC5 on channel 0"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU REMOTE N9:0 14 1 N10:0 5 2 N7:0 5 EOR").find("MSG REMOTE"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR", "START 1747-L552\n").find("Ethernet"),
            std::string::npos);
  // Keywords, the block's file type, the target's, one block per MSG.
  EXPECT_NE(check_errors("SOR MSG FETCH 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR").find("expected READ, WRITE, found 'FETCH'"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL B9:0 14 1 N10:0 5 2 N7:0 5 EOR").find("an integer file element such as N9:0"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 F8:0 5 EOR").find("is not of the local data's file type"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 2 N7:0 5 EOR\nSOR MSG READ 500CPU LOCAL N9:10 14 1 N10:0 5 2 N7:0 5 EOR")
                .find("overlaps the one of the MSG at line 5"),
            std::string::npos);
  // The 5/02 form, and each processor refusing the other's.
  constexpr std::string_view k502 = "START 1747-L524\n";
  EXPECT_EQ(check_errors("SOR MSG WRITE 485CIF N9:0 7 N10:0 5 2 10 EOR", k502), "");
  EXPECT_NE(check_errors(kReadFive, k502).find("on the SLC 5/02 MSG takes 8 operands"), std::string::npos);
  EXPECT_NE(check_errors("SOR MSG WRITE 485CIF N9:0 7 N10:0 5 2 10 EOR").find("is the SLC 5/02 form"), std::string::npos);
  // The SLC form on a MicroLogix names the MicroLogix form; the box alone without the setup (an
  // operand count no form takes) is held to the MicroLogix form and lists its operands, with no word
  // of the SLC's (tests/micrologix/msg_test.cpp has the MicroLogix MSG itself).
  EXPECT_NE(check_errors(kReadFive, "START Bul.1766\n").find("MG message file element"), std::string::npos);
  const std::string ml = check_errors("SOR XIC B3:0/0 MSG MG11:0 EOR", "START Bul.1766\n");
  EXPECT_NE(ml.find("MSG takes 10 operands (message file, read/write, target device, local/remote, channel, data "
                    "table address, size in elements, target node or RI element, target address, message timeout), found 1"),
            std::string::npos)
      << ml;
  EXPECT_EQ(ml.find("SLC 500 form"), std::string::npos) << ml;
  EXPECT_EQ(check_errors("SOR XIC B3:0/0 MOV MG11:0.ERR N7:0 EOR", "START Bul.1766\n"), "");
  EXPECT_NE(check_errors("SOR XIC B3:0/0 MOV MG11:0.ERR N7:0 EOR").find("MG (message) files exist on the MicroLogix"),
            std::string::npos);
  EXPECT_NE(check_errors("SOR SVC EOR", "START 1747-L511\n").find("SVC is not available"), std::string::npos);
  EXPECT_EQ(check_errors("SOR SVC EOR\nSOR SVC 2 EOR"), "");
}

}  // namespace
}  // namespace softslc::test
