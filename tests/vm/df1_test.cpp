// MSG over DF1 full-duplex on channel 0 (issue 16; docs/semantics.md "DF1 full-duplex on channel 0"): the
// link's frames, ACK/NAK/ENQ and retries in virtual time (vm/df1_link.h), and the SLC and MicroLogix MSG on a
// channel 0 joined point to point to a peer's.
//
// Manual facts used (the expected values are worked out by hand from them):
// - 1770-6.5.16 p. 2-8 table 2.D: a frame is DLE STX ... DLE ETX BCC/CRC, "A data 10h is sent as 10 10 (DLE
//   DLE)"; DLE ACK, DLE NAK, DLE ENQ are two characters. p. 2-7/2-8: BCC is the two's complement of the sum
//   of the data bytes, CRC-16 (x^16 + x^15 + x^2 + 1) over the data and the ETX.
// - 1770-6.5.16 ch. 7: the protected typed logical read with three address fields, CMD 0Fh FNC A2h
//   (write AAh): DST SRC CMD STS TNS(2) FNC SIZE FILE TYPE ELEMENT SUB-ELEMENT.
// - AG-UM008C p. 1-16 Figure 1.8: ACK timer after the command packet; "NAK received and retries > 'NAK
//   retries' or ACK timeout received and tries > 'ENQ retries' return error indication"; otherwise "send
//   enquiry" / resend.
// - 1770-6.5.16 p. 4-13: a destroyed ACK, the receiver answering the ENQ with NAK, the retransmission, "the
//   receiver discards the duplicate message (if duplicate message detection is enabled)".
// - 1747-RM001G p. 12-14: "Message Timeout for a channel 0 DF1 Full-duplex MSG instruction should be
//   configured greater than the channel 0 [ACK Timeout x (ENQ Retries + 1)]"; p. 12-29: ST is set at the
//   ACK; p. 12-41 table 12.17: 07h "Target node does not respond", 12h "Local channel configuration
//   protocol error exists", 37h "Message timed out in local processor"; p. 13-49: full-duplex "the
//   processor ignores the destination and source addresses".
// - 1766-RM001A p. 592: DF1 full-duplex defaults 19.2K, no parity, CRC, duplicate detect enabled, ACK
//   timeout 50 (x20 ms), NAK retries 3, ENQ retries 3; ranges ACK timeout 1-65535, retries 0-255; stop
//   bits always 1. AG-UM008C p. 6-14 table 6.2 (MicroLogix 1000): 9600 baud, 6 retries, 1 s, only the baud
//   rate configurable.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "vm/df1_link.h"
#include "message_line.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

// n characters of (start + 8 data + stop) bits at `baud`, rounded up to a whole ns as the link does.
constexpr Nanoseconds chars(std::int64_t n, std::int64_t baud, std::int64_t bits = 10) {
  return (n * bits * kNsPerS + baud - 1) / baud;
}

std::string slc(std::string_view rungs) { return program_text(std::string(rungs) + "\nSOR XIC B3:0/15 CLR N10:9 EOR"); }
std::string ml(std::string_view catalog, std::string_view rungs) {
  return "START " + std::string(catalog) + "\nLADDER 2\n" + std::string(rungs) + "\nSOR XIC B3:0/15 CLR N7:9 EOR\n";
}

// A leader "A" (node 1) with channel 0 DF1 full-duplex, and, unless `b_text` is empty, a peer "B" at the
// cable's other end.
struct Df1Line {
  std::unique_ptr<Runtime> a;
  Runtime* b = nullptr;
  std::string errors;
  Df1Line(std::string_view a_text, std::string_view b_text, Df1Options a_df1 = {}, Df1Options b_df1 = {}) {
    RuntimeOptions ao;
    ao.node = 1;
    ao.channel0_df1 = a_df1;
    if (!b_text.empty()) {
      PeerController p;
      p.name = "B";
      p.node = 2;
      p.df1 = true;
      p.program = load_peer_program(b_text);
      RuntimeOptions bo;
      bo.channel0_df1 = b_df1;
      p.options = std::make_shared<const RuntimeOptions>(std::move(bo));
      ao.peers.push_back(std::move(p));
    }
    a = try_build(a_text, errors, std::move(ao));
    if (!a) throw std::runtime_error("did not build:\n" + errors);
    b = a->peer("B");
    EXPECT_TRUE(a->set_mode(Mode::Run));
  }
  std::int64_t ai(std::string_view addr) const { return a->value(addr).as_int(); }
  std::int64_t bi(std::string_view addr) const { return b->value(addr).as_int(); }
  std::int64_t counter(Runtime& rt, std::string_view what) const {
    const auto v = rt.observe(kDf1DeviceName, what);
    return v && v->size() == 1 ? (*v)[0] : -1;
  }
  bool until(std::string_view bit, Nanoseconds limit) {
    return a->run_until([&](const Runtime& r) { return r.value(bit).as_bool(); }, limit);
  }
  // Starts A's MSG (its rung is XIC B3:0/0) and returns the time of the servicing that sent it.
  VirtualTime start() {
    EXPECT_TRUE(a->set("B3:0/0", Value::bit(true)));
    a->scan(1);
    return a->now();
  }
};

constexpr VirtualTime kForever = std::numeric_limits<VirtualTime>::max();

constexpr std::string_view kRead = "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR";

// ---- The link, computed ---------------------------------------------------------------------------------

TEST(Df1Link, TheReadPacketAndItsFrame) {
  // A 500CPU read of 5 N words from N7:0 at node 2, from node 1, transaction 1: DST 02 SRC 01 CMD 0F STS 00
  // TNS 01 00, FNC A2, 10 bytes, file 7, type 89h (N), element 0, sub-element 0 (ch. 7).
  Df1Command c;
  c.dst = 2;
  c.src = 1;
  c.tns = 1;
  c.file = 7;
  c.type_code = 0x89;
  c.words = 5;
  const std::vector<std::uint8_t> packet = df1_command_packet(c);
  EXPECT_EQ(packet, (std::vector<std::uint8_t>{0x02, 0x01, 0x0F, 0x00, 0x01, 0x00, 0xA2, 0x0A, 0x07, 0x89, 0x00, 0x00}));
  // BCC: the sum is 2+1+15+1+162+10+7+137 = 335 = 14Fh; two's complement of 4Fh is B1h (p. 2-7).
  EXPECT_EQ(df1_bcc(packet), 0xB1);
  // DLE STX, 12 bytes, DLE ETX and a BCC: 17 characters; with the CRC 18.
  EXPECT_EQ(df1_frame(packet, Df1ErrorCheck::Bcc).size(), 17u);
  EXPECT_EQ(df1_frame(packet, Df1ErrorCheck::Crc).size(), 18u);
  // Eight words are 16 = 10h bytes: the size byte is a DLE and is sent twice (p. 2-8 table 2.D).
  c.words = 8;
  const std::vector<std::uint8_t> eight = df1_frame(df1_command_packet(c), Df1ErrorCheck::Crc);
  EXPECT_EQ(eight.size(), 19u);
  EXPECT_EQ(eight[9], 0x10);
  EXPECT_EQ(eight[10], 0x10);
  EXPECT_EQ(eight[0], kDle);
  EXPECT_EQ(eight[1], kStx);
  EXPECT_EQ(eight[eight.size() - 4], kDle);
  EXPECT_EQ(eight[eight.size() - 3], kEtx);
}

TEST(Df1Link, TheCrcIsCrc16OverTheDataAndTheEtx) {
  // x^16 + x^15 + x^2 + 1, reflected, initial 0: the catalogue check value of "123456789" is BB3Dh.
  EXPECT_EQ(crc16({'1', '2', '3', '4', '5', '6', '7', '8', '9'}), 0xBB3D);
  const std::vector<std::uint8_t> packet{0x02, 0x01, 0x0F};
  EXPECT_EQ(df1_crc(packet), crc16({0x02, 0x01, 0x0F, kEtx}));
  EXPECT_NE(df1_crc(packet), crc16(packet));
  // The frame carries it low byte first after DLE ETX.
  const auto f = df1_frame(packet, Df1ErrorCheck::Crc);
  EXPECT_EQ(f[f.size() - 2] | (f[f.size() - 1] << 8), df1_crc(packet));
}

TEST(Df1Link, AnAckedFrameTakesItsCharactersAndTheAckAtTheBaudRate) {
  for (const int baud : {19200, 1200}) {
    Df1Port from, to;
    from.config.baud = to.config.baud = baud;
    const Df1Outcome o = df1_transfer(from, &to, true, 0, 18, 1);
    ASSERT_TRUE(o.acked);
    // 18 characters of 10 bits, then DLE ACK's 2: at 19,200 baud 9.375 ms + 1.0417 ms; at 1200, 150 + 16.67 ms.
    EXPECT_EQ(o.done, chars(18, baud) + chars(2, baud)) << baud;
    EXPECT_EQ(o.done, baud == 19200 ? 9'375'000 + 1'041'667 : 150'000'000 + 16'666'667);
    ASSERT_EQ(o.deliveries.size(), 1u);
    EXPECT_EQ(o.deliveries[0], chars(18, baud));
    EXPECT_EQ(from.counters.at(Df1Count::Sent, kForever), 1);
    EXPECT_EQ(to.counters.at(Df1Count::Received, kForever), 1);
    // Even parity adds a bit to each character.
    Df1Port even_from, even_to;
    even_from.config.parity_even = even_to.config.parity_even = true;
    even_from.config.baud = even_to.config.baud = baud;
    EXPECT_EQ(df1_transfer(even_from, &even_to, true, 0, 18, 1).done, chars(20, baud, 11));
  }
}

TEST(Df1Link, NobodyAnsweringEndsAfterTheEnqRetries) {
  // Figure 1.8: ACK timeout, ENQ, ... "tries > ENQ retries": the frame, then 4 ACK timeouts of 1 s with
  // 3 ENQs of 2 characters between them (RM 12-14: ACK Timeout x (ENQ Retries + 1)).
  Df1Port from;
  const Df1Outcome o = df1_transfer(from, nullptr, false, 0, 18, 1);
  EXPECT_FALSE(o.acked);
  EXPECT_EQ(o.done, chars(18, 19200) + 4 * kNsPerS + 3 * chars(2, 19200));
  EXPECT_EQ(from.counters.at(Df1Count::EnqsSent, kForever), 3);
  // The counters count what has happened by the observer's time: the first ENQ goes at the first timeout.
  EXPECT_EQ(from.counters.at(Df1Count::EnqsSent, chars(18, 19200) + kNsPerS - 1), 0);
  EXPECT_EQ(from.counters.at(Df1Count::EnqsSent, chars(18, 19200) + kNsPerS), 1);
  EXPECT_EQ(from.counters.at(Df1Count::Undelivered, kForever), 1);
  EXPECT_TRUE(o.deliveries.empty());
  // Breakage: ENQ retries 0 gives up at the first timeout.
  Df1Port none;
  none.config.enq_retries = 0;
  EXPECT_EQ(df1_transfer(none, nullptr, false, 0, 18, 1).done, chars(18, 19200) + kNsPerS);
  // The transmitter holds one packet at a time: the next starts when this one has given up.
  EXPECT_EQ(df1_transfer(from, nullptr, false, 0, 18, 2).done, 2 * o.done);
}

TEST(Df1Link, NaksResendUntilTheNakRetriesAreUsed) {
  // A receiver checking BCC NAKs every CRC frame: "NAK received and retries > 'NAK retries'" ends it after
  // the first frame and 3 retries, each frame followed by DLE NAK.
  Df1Port from, to;
  to.config.error_check = Df1ErrorCheck::Bcc;
  const Df1Outcome o = df1_transfer(from, &to, true, 0, 18, 1);
  EXPECT_FALSE(o.acked);
  EXPECT_EQ(o.frames, 4);
  EXPECT_EQ(o.done, 4 * (chars(18, 19200) + chars(2, 19200)));
  EXPECT_EQ(from.counters.at(Df1Count::NaksReceived, kForever), 4);
  EXPECT_EQ(to.counters.at(Df1Count::BadPackets, kForever), 4);
  EXPECT_TRUE(o.deliveries.empty());
  // Noise on two frames only: the third gets through.
  Df1Port noisy, far;
  noisy.corrupt_frames = 2;
  const Df1Outcome n = df1_transfer(noisy, &far, true, 0, 18, 1);
  EXPECT_TRUE(n.acked);
  EXPECT_EQ(n.frames, 3);
  EXPECT_EQ(n.done, 3 * (chars(18, 19200) + chars(2, 19200)));
}

TEST(Df1Link, ALostAckMakesADuplicateThatTheReceiverDiscards) {
  // p. 4-13: ACK destroyed, the ENQ after the ACK timeout answered with NAK, the frame sent again and
  // acknowledged; the receiver's sink takes the packet once.
  for (const bool detect : {true, false}) {
    Df1Port from, to;
    to.config.duplicate_detect = detect;
    from.lose_ack = true;
    const Df1Outcome o = df1_transfer(from, &to, true, 0, 18, 7);
    ASSERT_TRUE(o.acked);
    const Nanoseconds f = chars(18, 19200), s = chars(2, 19200);
    EXPECT_EQ(o.done, f + kNsPerS + s + s + f + s);
    EXPECT_EQ(o.deliveries.size(), detect ? 1u : 2u) << "duplicate detection " << detect;
    EXPECT_EQ(to.counters.at(Df1Count::Duplicates, kForever), detect ? 1 : 0);
    EXPECT_EQ(from.counters.at(Df1Count::EnqsSent, kForever), 1);
  }
}

TEST(Df1Link, ConfigurationDefaultsAndRanges) {
  Df1Config c;
  // 1766-RM001A p. 592.
  ASSERT_EQ(df1_configure(*resolve_processor("Bul.1766"), {}, c), "");
  EXPECT_EQ(c.baud, 19200);
  EXPECT_EQ(c.ack_timeout_ns(), kNsPerS);
  EXPECT_EQ(c.nak_retries, 3);
  EXPECT_EQ(c.enq_retries, 3);
  EXPECT_TRUE(c.duplicate_detect);
  EXPECT_EQ(c.error_check, Df1ErrorCheck::Crc);
  EXPECT_EQ(c.bits_per_character(), 10);
  // AG-UM008C p. 6-14 table 6.2.
  ASSERT_EQ(df1_configure(*resolve_processor("Bul.1761"), {}, c), "");
  EXPECT_EQ(c.baud, 9600);
  EXPECT_EQ(c.nak_retries, 6);
  EXPECT_EQ(c.enq_retries, 6);
  Df1Options o;
  o.ack_timeout = 0;
  EXPECT_NE(df1_configure(*resolve_processor("1747-L532"), o, c).find("ack_timeout 0 is out of range 1-65535"), std::string::npos);
  o.ack_timeout = 10;
  EXPECT_EQ(df1_configure(*resolve_processor("Bul.1761"), o, c),
            "channel 0: the MicroLogix 1000's DF1 full-duplex ACK timeout is not configurable (AG-UM008C p. 6-14 "
            "table 6.2: only the baud rate and the node address have options)");
  Df1Options parse;
  EXPECT_EQ(df1_parse_option("baud=1200", parse), "");
  EXPECT_EQ(parse.baud, 1200);
  EXPECT_EQ(df1_parse_option("bcc", parse), "");
  EXPECT_NE(df1_parse_option("baud=fast", parse).find("baud takes a whole number"), std::string::npos);
  EXPECT_NE(df1_parse_option("parity=odd", parse).find("parity is none or even"), std::string::npos);
  EXPECT_NE(df1_parse_option("speed=3", parse).find("'speed' is not a DF1 setting"), std::string::npos);
}

// ---- MSG on it ----------------------------------------------------------------------------------------

TEST(Df1Msg, AnSlcReadsAMicroLogixAndTheMicroLogixWritesTheSlc) {
  // B, a MicroLogix 1400, writes its N7:0-1 into A's N11:0-1 with its own MG element on channel 0.
  Df1Line line(slc(std::string(kRead) + "\nSOR XIC B3:0/15 CLR N11:9 EOR"),
               ml("Bul.1766", "SOR XIC B3:0/0 MSG MG11:0 WRITE 500CPU LOCAL 0 N7:0 2 1 N11:0 5 EOR"));
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(line.b->set("N7:" + std::to_string(i), Value::of_int(300 + i)));
  const VirtualTime sent = line.start();
  // ST at the ACK (RM 12-29): the 18-character command and DLE ACK at 19,200 baud.
  ASSERT_TRUE(line.until("N9:0/14", kNsPerS));
  EXPECT_GE(line.a->now() - sent, chars(18, 19200) + chars(2, 19200));
  EXPECT_LE(line.a->now() - sent, chars(18, 19200) + chars(2, 19200) + line.a->stats().max);
  ASSERT_TRUE(line.until("N9:0/13", kNsPerS));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(line.ai("N10:" + std::to_string(i)), 300 + i);
  // The reply (6 header bytes + 10 data bytes, 22 characters) came back after B's servicing; each packet is
  // taken when its last character has arrived (its ACK follows).
  EXPECT_GE(line.a->now() - sent, chars(18 + 22, 19200));
  // The other direction.
  ASSERT_TRUE(line.b->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(line.a->run_until([&](const Runtime&) { return line.b->value("MG11:0/DN").as_bool(); }, kNsPerS));
  EXPECT_EQ(line.ai("N11:0"), 300);
  EXPECT_EQ(line.ai("N11:1"), 301);
  EXPECT_EQ(line.ai("N11:2"), 0);
  EXPECT_EQ(line.counter(*line.a, "sent"), 2);      // A's command, A's reply to B's command
  EXPECT_EQ(line.counter(*line.a, "received"), 2);  // B's reply, B's command
  EXPECT_EQ(line.counter(*line.b, "sent"), 2);
}

TEST(Df1Msg, AMicroLogix1100ReadsAnSlcWithItsMgElement) {
  // The MG form on channel 0 (1763-RM001B), target node 0: a full-duplex receiver ignores it (RM 13-49). Two
  // words from N10:0 of file 10: the packet is again 12 bytes, 18 characters.
  Df1Line line(ml("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 2 0 N10:0 5 EOR"), slc(""));
  ASSERT_TRUE(line.b->set("N10:0", Value::of_int(5)));
  ASSERT_TRUE(line.b->set("N10:1", Value::of_int(-6)));
  const VirtualTime sent = line.start();
  ASSERT_TRUE(line.until("MG11:0/ST", kNsPerS));
  EXPECT_GE(line.a->now() - sent, chars(20, 19200));
  EXPECT_LE(line.a->now() - sent, chars(20, 19200) + line.a->stats().max);
  ASSERT_TRUE(line.until("MG11:0/DN", kNsPerS));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0);
  EXPECT_EQ(line.ai("N7:0"), 5);
  EXPECT_EQ(line.ai("N7:1"), -6);
}

TEST(Df1Msg, StComesLaterAtALowerBaudRate) {
  // Both ends at 1200 baud: the command's 18 characters and the ACK take 166.67 ms.
  Df1Options slow;
  slow.baud = 1200;
  Df1Line line(slc(kRead), ml("Bul.1762", ""), slow, slow);
  const VirtualTime sent = line.start();
  ASSERT_TRUE(line.until("N9:0/14", kNsPerS));
  EXPECT_GE(line.a->now() - sent, chars(20, 1200));
  EXPECT_LE(line.a->now() - sent, chars(20, 1200) + line.a->stats().max);
  ASSERT_TRUE(line.until("N9:0/13", kNsPerS));
}

TEST(Df1Msg, AnAbsentPeerEndsWith07AfterAckTimeoutTimesEnqRetriesPlusOne) {
  // No peer on the cable (RM 12-14): 07h after the frame, 4 x 1 s and 3 ENQs; a 5 s MSG timeout is longer.
  Df1Line line(slc(kRead), "");
  const VirtualTime sent = line.start();
  ASSERT_TRUE(line.until("N9:0/12", 5 * kNsPerS));
  const Nanoseconds expected = chars(18, 19200) + 4 * kNsPerS + 3 * chars(2, 19200);
  EXPECT_GE(line.a->now() - sent, expected);
  EXPECT_LE(line.a->now() - sent, expected + line.a->stats().max);
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x07);
  EXPECT_FALSE(line.a->value("N9:0/14").as_bool());
  EXPECT_EQ(line.counter(*line.a, "enqs sent"), 3);
  // A 2 s MSG timeout is shorter than the link's retries: 37h and TO first (RM 12-41).
  Df1Line short_timer(slc("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 2 N7:0 2 EOR"), "");
  short_timer.start();
  ASSERT_TRUE(short_timer.until("N9:0/12", 5 * kNsPerS));
  EXPECT_EQ(short_timer.ai("N9:0") & 0xFF, 0x37);
}

TEST(Df1Msg, ABaudMismatchOrAnOpenCableIsNoAnswer) {
  Df1Options slow;
  slow.baud = 9600;
  Df1Line line(slc(kRead), ml("Bul.1762", ""), {}, slow);
  line.start();
  ASSERT_TRUE(line.until("N9:0/12", 5 * kNsPerS));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x07);
  // The cable (`device DF1 cable removed`), then connected again.
  Df1Line cable(slc(kRead), ml("Bul.1762", ""));
  ASSERT_TRUE(cable.a->inject(kDf1DeviceName, "cable removed"));
  cable.start();
  ASSERT_TRUE(cable.until("N9:0/12", 5 * kNsPerS));
  EXPECT_EQ(cable.ai("N9:0") & 0xFF, 0x07);
  ASSERT_TRUE(cable.a->inject(kDf1DeviceName, "cable connected"));
  ASSERT_TRUE(cable.a->set("B3:0/0", Value::bit(false)));
  cable.a->scan(1);
  cable.start();
  ASSERT_TRUE(cable.until("N9:0/13", kNsPerS));
}

TEST(Df1Msg, AnErrorCheckMismatchUsesTheNakRetries) {
  Df1Options bcc;
  bcc.error_check = Df1ErrorCheck::Bcc;
  Df1Line line(slc(kRead), ml("Bul.1762", ""), {}, bcc);
  const VirtualTime sent = line.start();
  ASSERT_TRUE(line.until("N9:0/12", kNsPerS));
  EXPECT_EQ(line.ai("N9:0") & 0xFF, 0x07);
  EXPECT_LE(line.a->now() - sent, 4 * (chars(18, 19200) + chars(2, 19200)) + line.a->stats().max);
  EXPECT_EQ(line.counter(*line.a, "sent"), 4);
  EXPECT_EQ(line.counter(*line.a, "naks received"), 4);
  EXPECT_EQ(line.counter(*line.b, "bad packets"), 4);
  // Breakage: NAK retries 5 sends 6 frames.
  Df1Options more;
  more.nak_retries = 5;
  Df1Line six(slc(kRead), ml("Bul.1762", ""), more, bcc);
  six.start();
  ASSERT_TRUE(six.until("N9:0/12", kNsPerS));
  EXPECT_EQ(six.counter(*six.a, "sent"), 6);
}

TEST(Df1Msg, ADuplicateWriteIsNotExecutedTwice) {
  // B counts each write that puts a non-zero value into its N7:0 and clears it: a write executed twice
  // (the retransmission after the lost ACK, 1 s later) counts 2.
  constexpr std::string_view kCounter = "SOR NEQ N7:0 0 ADD N7:1 1 N7:1 MOV 0 N7:0 EOR";
  for (const bool detect : {true, false}) {
    Df1Options b;
    b.duplicate_detect = detect;
    Df1Line line(slc("SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 14 0 N10:0 1 2 N7:0 5 EOR"), ml("Bul.1762", kCounter),
                 {}, b);
    ASSERT_TRUE(line.a->set("N10:0", Value::of_int(42)));
    ASSERT_TRUE(line.a->inject(kDf1DeviceName, "lose ack"));
    line.start();
    ASSERT_TRUE(line.until("N9:0/13", 3 * kNsPerS));
    line.a->run_for(2 * kNsPerS);
    EXPECT_EQ(line.bi("N7:1"), detect ? 1 : 2) << "duplicate detection " << detect;
    EXPECT_EQ(line.counter(*line.b, "duplicates"), detect ? 1 : 0);
    EXPECT_EQ(line.counter(*line.a, "enqs sent"), 1);
  }
}

TEST(Df1Msg, AnUnconfiguredChannel0IsDf1FullDuplexAtItsDefaults) {
  // An SLC 5/03's channel 0 that no test line or option configures is at its factory configuration, DF1
  // full-duplex ("You can use channel 0 as a programming port, or as a peer-to-peer port using the MSG
  // instruction", RM 13-49; docs/semantics.md "Channel 0"). With no cable partner the MSG goes out and ends
  // as an absent peer's does: 07h after the frame, (ENQ retries + 1) ACK timeouts and the ENQs (RM 12-14),
  // not at once with 12h.
  std::string errors;
  auto a = try_build(slc(kRead), errors);
  ASSERT_TRUE(a) << errors;
  ASSERT_TRUE(a->set_mode(Mode::Run));
  ASSERT_TRUE(a->set("B3:0/0", Value::bit(true)));
  a->scan(1);
  const VirtualTime sent = a->now();
  a->scan(1);
  EXPECT_FALSE(a->value("N9:0/12").as_bool());  // no 12h at once
  EXPECT_TRUE(a->value("N9:0/15").as_bool());   // EN: the message is out
  while (!a->value("N9:0/12").as_bool() && a->now() < sent + 6 * kNsPerS) a->scan(1);
  ASSERT_TRUE(a->value("N9:0/12").as_bool());
  EXPECT_EQ(a->value("N9:0").as_int() & 0xFF, 0x07);
  // The defaults of the 1400's table (1766-RM001A p. 592, taken for the SLC [U]): 19.2K, ACK timeout 1 s,
  // 3 ENQ retries: the frame of 18 characters, four ACK timeouts and three 2-character ENQs.
  const Nanoseconds expected = chars(18, 19200) + 4 * kNsPerS + 3 * chars(2, 19200);
  EXPECT_GE(a->now() - sent, expected);
  EXPECT_LE(a->now() - sent, expected + a->stats().max);
}

// The test's `device DF1` line reaches a factory-configured channel 0 before any MSG has used it: the port is the one
// the MSG then uses (its counters count the MSG's ENQs), not an unknown device.
TEST(Df1Msg, TheDf1DeviceOfAnUnconfiguredChannel0IsThereBeforeAnyMsg) {
  std::string errors;
  auto a = try_build(slc(kRead), errors);
  ASSERT_TRUE(a) << errors;
  const auto enqs = [&] { return a->observe("DF1", "enqs sent"); };
  ASSERT_TRUE(enqs());
  EXPECT_EQ(*enqs(), std::vector<std::int64_t>{0});
  EXPECT_TRUE(a->inject("DF1", "cable removed"));
  const RuntimeStatus bad = a->inject("DF1", "unplugged");
  EXPECT_FALSE(bad);
  EXPECT_NE(bad.message.find("the DF1 link takes"), std::string::npos) << bad.message;
  ASSERT_TRUE(a->set_mode(Mode::Run));
  ASSERT_TRUE(a->set("B3:0/0", Value::bit(true)));
  const VirtualTime start = a->now();
  while (!a->value("N9:0/12").as_bool() && a->now() < start + 6 * kNsPerS) a->scan(1);
  ASSERT_TRUE(a->value("N9:0/12").as_bool());
  EXPECT_EQ(a->value("N9:0").as_int() & 0xFF, 0x07);
  // Three ENQ retries, the defaults (1766-RM001A p. 592, taken for the SLC [U]).
  EXPECT_EQ(*enqs(), std::vector<std::int64_t>{3});
}

TEST(Df1Msg, TheMicroLogix1000OnDf1UsesItsOwnDefaults) {
  // The 1000 defaults to 9600 baud (table 6.2), the SLC to 19,200: no answer until the SLC is set to 9600.
  const std::string ml1000 = ml("Bul.1761", "SOR XIC B3:0/0 MSG READ 500CPU N7:50 7 N7:0 5 2 N10:0 EOR");
  const std::string target = slc("");
  Df1Options slc9600;
  slc9600.baud = 9600;
  Df1Line ok(ml1000, target, {}, slc9600);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(ok.b->set("N10:" + std::to_string(i), Value::of_int(10 + i)));
  ok.start();
  ASSERT_TRUE(ok.until("N7:50/13", kNsPerS));
  EXPECT_EQ(ok.ai("N7:4"), 14);
  Df1Line mismatch(ml1000, target);
  mismatch.start();
  // 6 ENQ retries: 7 ACK timeouts of 1 s.
  ASSERT_TRUE(mismatch.until("N7:50/12", 8 * kNsPerS));
  EXPECT_GE(mismatch.a->now(), 7 * kNsPerS);
  EXPECT_EQ(mismatch.ai("N7:50") & 0xFF, 0x07);
}

TEST(Df1Msg, BadConfigurationsAreRefusedByName) {
  auto build = [](std::string_view a_text, std::optional<Df1Options> a_df1, std::vector<PeerController> peers) {
    RuntimeOptions o;
    o.channel0_df1 = a_df1;
    o.peers = std::move(peers);
    std::string errors;
    auto rt = try_build(a_text, errors, std::move(o));
    return rt ? std::string("built") : errors;
  };
  auto df1_peer = [](std::string name, std::string_view text) {
    PeerController p;
    p.name = std::move(name);
    p.df1 = true;
    p.program = load_peer_program(text);
    return p;
  };
  const std::string a = slc(kRead), b = ml("Bul.1762", "");
  EXPECT_EQ(build(a, Df1Options{}, {df1_peer("B", b)}), "built");
  Df1Options bad;
  bad.nak_retries = 256;
  EXPECT_NE(build(a, bad, {}).find("channel 0: nak_retries 256 is out of range 0-255"), std::string::npos);
  Df1Options rate;
  rate.baud = 1234;
  EXPECT_NE(build(a, rate, {}).find("baud 1234 is not a rate the SLC 5/03"), std::string::npos);
  EXPECT_NE(build(program_text("SOR XIC B3:0/15 CLR N7:9 EOR", "START 1747-L524\n"), Df1Options{}, {}).find("has no RS-232 channel"),
            std::string::npos);
  EXPECT_NE(build(a, Df1Options{}, {df1_peer("B", b), df1_peer("C", b)}).find("peer C: DF1 full-duplex is point to point"),
            std::string::npos);
  EXPECT_NE(build(a, std::nullopt, {df1_peer("B", b)}).find("this controller's channel 0 is not DF1 full-duplex"),
            std::string::npos);
  // A MicroLogix whose channel 0 is DF1 is on no DH-485 network.
  PeerController dh485;
  dh485.name = "D";
  dh485.node = 2;
  dh485.program = load_peer_program(b);
  EXPECT_NE(build(ml("Bul.1763", ""), Df1Options{}, {dh485}).find("peer D: this controller's channel 0 is DF1 full-duplex"),
            std::string::npos);
}

TEST(Df1Msg, AMicroLogixOnDh485EndsANodeAbove31With16h) {
  // `check` takes a MicroLogix channel 0 node 0-254 (the DF1 addresses); on DH-485, where responders are 1-31
  // (RM 13-4), "16H Target or Local Bridge address is higher than the maximum node address" (RM 12-41).
  MessageLine line(ml("Bul.1763", "SOR XIC B3:0/0 MSG MG11:0 READ 500CPU LOCAL 0 N7:0 1 32 N10:0 5 EOR"),
                   ml("Bul.1762", ""));
  line.run();
  line.set("B3:0/0", 1);
  line.a->scan(2);
  EXPECT_TRUE(line.abit("MG11:0/ER"));
  EXPECT_EQ(line.ai("MG11:0.ERR"), 0x16);
}

TEST(Df1Msg, CheckTakesTheSlcChannel0FormAndNamesWhatItDoesNot) {
  std::string errors;
  // Channel 0 with a 14-word block and node 0-254 loads (the receiver ignores the destination, RM 13-49).
  EXPECT_TRUE(try_build(slc("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 0 N7:0 5 EOR"), errors)) << errors;
  errors.clear();
  EXPECT_FALSE(try_build(slc("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 255 N7:0 5 EOR"), errors));
  EXPECT_NE(errors.find("target node 255 is out of range 0-254"), std::string::npos) << errors;
  errors.clear();
  EXPECT_FALSE(try_build(slc("SOR XIC B3:0/0 MSG READ PLC5 LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR"), errors));
  EXPECT_NE(errors.find("MSG PLC5 on channel 0 (DF1 full-duplex)"), std::string::npos) << errors;
  errors.clear();
  EXPECT_FALSE(try_build(slc("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 0 N10:0 5 2 N7:0 5 EOR"), errors));
  EXPECT_NE(errors.find("takes a 14-word control block"), std::string::npos) << errors;
}

}  // namespace
}  // namespace softslc::test
