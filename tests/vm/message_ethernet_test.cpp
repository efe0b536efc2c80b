// MSG on the SLC 5/05's channel 1: Ethernet, stations named by IP address (docs/semantics.md "MSG on
// Ethernet").
//
// Expected values come from 1747-RM001G (page and table in each test): p. 12-34 table 12.14 (the
// 51-word control block: word 11 the data length in bytes, 12/15 AO, 14-34 the IP address string with
// its first character in the high byte of word 14, 35 the Ethernet message type), p. D-21 table D.5
// (message lengths), p. 12-41 table 12.17 (error codes), from the SLC 500 user manual 1747-UM011G
// p. 242 (the channel's MSG Connection Timeout, 15,000 ms by default), and from 1762-RM001C p. 21-21/22
// (the Ethernet codes D0h-DAh; the D0h-D6h texts are [U]). Frame times are the 10 Mbit/s rate and
// 106 framing bytes of instructions/message_link.h (EST).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "vm/message_network.h"
#include "vm/profile_scan_time_model.h"
#include "vm/timing_profile.h"
#include "vm_test_util.h"

namespace softslc::test {
namespace {

constexpr std::string_view k505 = "START 1747-L552\n";
constexpr std::uint32_t kIpA = (192u << 24) | (168u << 16) | (1u << 8) | 10u;  // 192.168.1.10
constexpr std::uint32_t kIpB = (192u << 24) | (168u << 16) | (1u << 8) | 20u;  // 192.168.1.20

std::shared_ptr<const Program> load(std::string_view body, std::string_view header = k505) {
  LoadResult lr = load_program(program_text(body, header), "peer.slc");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  return std::make_shared<const Program>(std::move(*lr.program));
}

// The words of a NULL-terminated ASCII string as table 12.14 stores it: "the first byte in the array
// is the left most character in the string as written", in the high byte of the first word.
std::vector<std::uint16_t> ip_words(std::string_view text) {
  std::vector<std::uint16_t> words((text.size() + 2) / 2, 0);
  for (std::size_t i = 0; i < text.size(); ++i)
    words[i / 2] = static_cast<std::uint16_t>(words[i / 2] | (static_cast<unsigned char>(text[i]) << (i % 2 ? 0 : 8)));
  return words;
}

// A leader "A" (192.168.1.10 unless told) and a peer "B" (192.168.1.20), both SLC 5/05s on Ethernet.
struct Ethernet {
  std::unique_ptr<Runtime> a;
  Runtime* b = nullptr;

  Ethernet(std::string_view a_body, std::string_view b_body, std::uint32_t a_ip = kIpA, RuntimeOptions b_opts = {}) {
    PeerController peer;
    peer.name = "B";
    peer.ip = kIpB;
    peer.program = load(b_body);
    peer.options = std::make_shared<const RuntimeOptions>(std::move(b_opts));
    RuntimeOptions opts;
    opts.ip = a_ip;
    opts.peers.push_back(std::move(peer));
    std::string errors;
    a = try_build(program_text(a_body, k505), errors, std::move(opts));
    if (!a) throw std::runtime_error("network did not build:\n" + errors);
    b = a->peer("B");
    if (!b) throw std::runtime_error("no peer B");
  }
  std::int64_t ai(std::string_view addr) const { return a->value(addr).as_int(); }
  bool abit(std::string_view addr) const { return a->value(addr).as_bool(); }
  // Puts `text` into A's control block at N9:first+14 (the block's IP address string).
  void target(std::string_view text, int first = 0) {
    const std::vector<std::uint16_t> w = ip_words(text);
    for (std::size_t i = 0; i < w.size(); ++i)
      ASSERT_TRUE(a->set("N9:" + std::to_string(first + 14 + static_cast<int>(i)), Value::of_int(static_cast<std::int16_t>(w[i]))));
  }
  void run() { ASSERT_TRUE(a->set_mode(Mode::Run)); }
  bool until(std::string_view bit, Nanoseconds limit = kNsPerS) {
    return a->run_until([&](const Runtime& r) { return r.value(bit).as_bool(); }, limit);
  }
};

// B's N7:0-9 exist; A's MSGs use N9 (blocks) and N10 (data).
constexpr std::string_view kTarget = "SOR XIC B3:0/15 CLR N7:9 EOR";
constexpr std::string_view kReadFive = "SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 5 0 N7:0 5 EOR";
constexpr std::string_view kWriteThree = "SOR XIC B3:0/0 MSG WRITE 500CPU LOCAL N9:0 51 1 N10:0 3 0 N7:4 5 EOR";

// A frame of `data_bytes` on Ethernet: 10 Mbit/s, 8 bits a byte, 106 bytes of framing (EST).
constexpr Nanoseconds ethernet(int data_bytes) { return (Nanoseconds{106 + data_bytes} * 8 * kNsPerS + 9'999'999) / 10'000'000; }

TEST(MessageEthernet, TheIpStringIsStoredHighByteFirst) {
  // RM 12-34 table 12.14, note 1: the first byte is the left-most character, in the high-byte column.
  const std::vector<std::uint16_t> w = ip_words("192.168.1.20");
  ASSERT_EQ(w.size(), 7u);
  EXPECT_EQ(w[0], 0x3139);  // '1' '9'
  EXPECT_EQ(w[5], 0x3230);  // '2' '0'
  EXPECT_EQ(w[6], 0x0000);  // the NULL
  EXPECT_EQ(parse_ipv4("192.168.1.20"), kIpB);
  EXPECT_EQ(parse_ipv4("192.168.001.020"), kIpB);  // leading zeros: the manual's own example is 423.156.78.012
  EXPECT_EQ(parse_ipv4("423.156.78.012"), std::nullopt);  // ... whose first part is not an octet
  for (const char* bad : {"", "192.168.1", "192.168.1.20.", "192.168.1.2000", "client", "192.168.1.-1"})
    EXPECT_EQ(parse_ipv4(bad), std::nullopt) << bad;
  EXPECT_EQ(format_ipv4(kIpB), "192.168.1.20");
}

TEST(MessageEthernet, AReadBetweenTwo505sGoesThroughEnEwStDn) {
  Ethernet net(kReadFive, kTarget);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(net.b->set("N7:" + std::to_string(i), Value::of_int(200 + i)));
  net.target("192.168.1.20");
  // The setup in the block (table 12.14): word 1 reserved (0), 2 elements, 3 file, 4 type (N: 89h),
  // 5 element, 8 the timer preset.
  EXPECT_EQ(net.ai("N9:1"), 0);
  EXPECT_EQ(net.ai("N9:2"), 5);
  EXPECT_EQ(net.ai("N9:3"), 7);
  EXPECT_EQ(net.ai("N9:4"), 0x89);
  EXPECT_EQ(net.ai("N9:8"), 5);
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  net.a->scan(1);
  EXPECT_TRUE(net.abit("N9:0/15"));  // EN
  EXPECT_TRUE(net.abit("N9:0/10"));  // EW: in a buffer, waiting (RM 12-29 table 12.10)
  // Word 11, the data length in bytes, "written ... by the processor at run time" (RM D-21): 5 words.
  EXPECT_EQ(net.ai("N9:11"), 10);
  const VirtualTime sent = net.a->now();
  // The acknowledgement (ST) and the reply (DN, which clears ST, RM 12-29) are 85 us and 93.6 us frames:
  // both may reach A by its next servicing point, so ST need not be seen on its own.
  ASSERT_TRUE(net.until("N9:0/13"));  // DN
  EXPECT_FALSE(net.abit("N9:0/10"));
  EXPECT_FALSE(net.abit("N9:0/12"));
  EXPECT_FALSE(net.abit("N9:0/14"));
  EXPECT_EQ(net.ai("N9:0") & 0xFF, 0);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(net.ai("N10:" + std::to_string(i)), 200 + i);
  EXPECT_GE(net.a->now() - sent, ethernet(0) + ethernet(10));
}

TEST(MessageEthernet, AWriteLandsInTheTargetsFile) {
  Ethernet net(kWriteThree, kTarget);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(net.a->set("N10:" + std::to_string(i), Value::of_int(-7 - i)));
  net.target("192.168.1.20");
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("N9:0/13"));
  EXPECT_FALSE(net.abit("N9:0/12"));
  EXPECT_EQ(net.ai("N9:11"), 6);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(net.b->value("N7:" + std::to_string(4 + i)).as_int(), -7 - i);
  EXPECT_EQ(net.b->value("N7:3").as_int(), 0);
  EXPECT_EQ(net.b->value("N7:7").as_int(), 0);
}

TEST(MessageEthernet, TheIpAddressCanComeFromADataBlock) {
  // A program's own DATA block gives the block its IP address string, as RSLogix stores the one typed
  // in the setup screen: "192.168.1.20" is 3139h 322Eh 3136h 382Eh 312Eh 3230h 0 (12601 12846 ...).
  const std::string body = std::string(kReadFive) + "\nDATA N9:14\n% N9:14 % 12601 12846 12598 14382 12590 12848 0\n";
  Ethernet net(body, kTarget);
  ASSERT_TRUE(net.b->set("N7:0", Value::of_int(77)));
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("N9:0/13"));
  EXPECT_EQ(net.ai("N10:0"), 77);
}

TEST(MessageEthernet, OneMessageCarriesUpTo256ElementsOnEthernet) {
  // RM D-21 table D.5: 256 N elements (512 bytes) per 500CPU read on the 5/05, where DH-485 and DH+
  // carry 103 words.
  Ethernet net("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 200 0 N7:0 0 EOR",
               "SOR XIC B3:0/15 CLR N7:199 EOR");
  ASSERT_TRUE(net.b->set("N7:199", Value::of_int(4321)));
  net.target("192.168.1.20");
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("N9:0/13"));
  EXPECT_EQ(net.ai("N9:11"), 400);
  EXPECT_EQ(net.ai("N10:199"), 4321);
}

TEST(MessageEthernet, AnAddressNobodyHasEndsWithD5hAfterTheConnectionTimeout) {
  // No station answers at 192.168.1.99: the connection is not completed before the channel's MSG
  // Connection Timeout, 15,000 ms by default (1747-UM011G p. 242): ER with D5h. The message timeout
  // is 0 here ("no timer", RM 12-14), so nothing else ends it first.
  Ethernet net("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 5 0 N7:0 0 EOR", kTarget);
  net.target("192.168.1.99");
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  net.a->scan(1);
  const VirtualTime sent = net.a->now();
  ASSERT_TRUE(net.until("N9:0/12", 20 * kNsPerS));
  EXPECT_GE(net.a->now() - sent, 15 * kNsPerS);
  EXPECT_LT(net.a->now() - sent, 15 * kNsPerS + 10'000'000);
  EXPECT_EQ(net.ai("N9:0") & 0xFF, 0xD5);
  EXPECT_FALSE(net.abit("N9:0/13"));
  EXPECT_FALSE(net.abit("N9:0/14"));  // never acknowledged
  EXPECT_FALSE(net.abit("N9:0/8"));   // not the message timer's TO
}

TEST(MessageEthernet, AShorterMessageTimeoutEndsItFirstWith37h) {
  // The message timer (5 s) expires before the connection timeout: ER, TO and 37h (RM 12-41).
  Ethernet net(kReadFive, kTarget);
  net.target("192.168.1.99");
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  net.a->scan(1);
  const VirtualTime started = net.a->now();
  ASSERT_TRUE(net.until("N9:0/12", 20 * kNsPerS));
  EXPECT_GE(net.a->now() - started, 4 * kNsPerS);
  EXPECT_LT(net.a->now() - started, 6 * kNsPerS);
  EXPECT_EQ(net.ai("N9:0") & 0xFF, 0x37);
  EXPECT_TRUE(net.abit("N9:0/8"));
}

TEST(MessageEthernet, ATargetThatAcknowledgesButDoesNotReplyEndsWithD9h) {
  // B's scans take 5 s (its housekeeping; the watchdog faults it, and a faulted processor still answers):
  // it acknowledges A's request at once but replies only at its end of scan. A waits the channel's MSG
  // Reply Timeout, 3,000 ms by default (1747-UM011G p. 242), then "D9H Reply not received before
  // user-specified timeout" (1762-RM001C p. 21-22). The message timer is off (0).
  RuntimeOptions slow;
  slow.time_model = std::make_shared<SlowModel>(make_scan_time_model(*resolve_processor("1747-L552")), 5 * kNsPerS);
  Ethernet net("SOR XIC B3:0/0 MSG READ 500CPU LOCAL N9:0 51 1 N10:0 5 0 N7:0 0 EOR", kTarget, kIpA, slow);
  net.target("192.168.1.20");
  net.run();
  ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
  ASSERT_TRUE(net.until("N9:0/14", 10 * kNsPerS));
  const VirtualTime acked = net.a->now();
  ASSERT_TRUE(net.until("N9:0/12", 10 * kNsPerS));
  EXPECT_GE(net.a->now() - acked, 3 * kNsPerS - 2'000'000);  // from the acknowledgement's arrival, seen a scan later
  EXPECT_LT(net.a->now() - acked, 3 * kNsPerS + 10'000'000);
  EXPECT_EQ(net.ai("N9:0") & 0xFF, 0xD9);
  EXPECT_FALSE(net.abit("N9:0/8"));
  EXPECT_EQ(net.ai("N10:0"), 0);
}

TEST(MessageEthernet, ABlockTheProcessorCannotSendEndsAtOnce) {
  struct Case {
    std::string ip;            // the block's string
    std::uint32_t own_ip;      // A's address
    std::int16_t type;         // word 35
    std::uint8_t code;
  };
  const Case cases[] = {
      {"192.168.1", kIpA, 0, 0xD2},       // not an IP address: "Invalid internet address or host name" [U]
      {"client", kIpA, 0, 0xD2},          // a host name: names are not resolved (docs)
      {"", kIpA, 0, 0xD2},                // no address at all
      {"192.168.1.20", 0, 0, 0xD0},       // A has no IP address: "No IP address configured" [U]
      {"192.168.1.20", kIpA, 0x10, 0x17}, // MultiHop: not simulated ("Local service is not supported")
      {"192.168.1.20", kIpA, 0x11, 0x17},
      {"192.168.1.20", kIpA, 0x05, 0x04}, // a type table 12.14 does not have: the block was modified
  };
  for (const Case& c : cases) {
    Ethernet net(kReadFive, kTarget, c.own_ip);
    net.target(c.ip);
    ASSERT_TRUE(net.a->set("N9:35", Value::of_int(c.type)));
    net.run();
    ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
    net.a->scan(1);
    EXPECT_TRUE(net.abit("N9:0/12")) << c.ip << " " << c.own_ip << " " << c.type;
    EXPECT_EQ(net.ai("N9:0") & 0xFF, c.code) << c.ip << " " << c.own_ip << " " << c.type;
  }
}

TEST(MessageEthernet, AoSelectsLogicalAsciiOnlyForPlc5) {
  // AO (word 12 bit 15) "has no meaning for 485CIF and 500CPU types of reads and writes" (1747-10.4
  // p. 4-3): a 500CPU read with AO set completes; a PLC5 one would use logical ASCII addressing,
  // which softslc does not simulate: 17h.
  for (const char* device : {"500CPU", "PLC5"}) {
    Ethernet net(std::string("SOR XIC B3:0/0 MSG READ ") + device + " LOCAL N9:0 51 1 N10:0 5 0 N7:0 5 EOR", kTarget);
    net.target("192.168.1.20");
    ASSERT_TRUE(net.a->set("N9:12/15", Value::bit(true)));
    net.run();
    ASSERT_TRUE(net.a->set("B3:0/0", Value::bit(true)));
    ASSERT_TRUE(net.a->run_until([](const Runtime& r) { return r.value("N9:0").as_int() & 0x3000; }, kNsPerS));
    if (std::string(device) == "500CPU") EXPECT_TRUE(net.abit("N9:0/13"));
    else EXPECT_EQ(net.ai("N9:0") & 0xFF, 0x17);
  }
}

TEST(MessageEthernet, TwoRunsAreByteIdentical) {
  auto run_once = [] {
    Ethernet net(std::string(kReadFive) + "\nSOR XIC N9:0/13 ADD N11:0 1 N11:0 EOR\nSOR XIC N9:0/13 OTU B3:0/0 EOR\n"
                                          "SOR XIO N9:0/15 OTL B3:0/0 EOR",
                 "SOR ADD N7:0 1 N7:0 EOR\nSOR XIC B3:0/15 CLR N7:9 EOR");
    net.target("192.168.1.20");
    net.run();
    std::string trace;
    for (int i = 0; i < 400; ++i) {
      net.a->scan(1);
      trace += std::to_string(net.a->now()) + ":" + std::to_string(net.ai("N9:0")) + ":" +
               std::to_string(net.ai("N10:0")) + ":" + std::to_string(net.ai("N11:0")) + "\n";
    }
    return trace;
  };
  const std::string first = run_once();
  EXPECT_EQ(first, run_once());
  EXPECT_GT(std::stoi(first.substr(first.rfind(':') + 1)), 10);  // N11:0: it polled, DN after DN
}

TEST(MessageEthernet, TheNetworkNamesStationsByIpAddress) {
  std::string errors;
  PeerController b;
  b.name = "B";
  b.program = load(kTarget);
  RuntimeOptions opts;
  opts.ip = kIpA;
  opts.peers.push_back(b);
  // A 5/05 peer without an IP address.
  EXPECT_EQ(try_build(program_text(kTarget, k505), errors, opts), nullptr);
  EXPECT_NE(errors.find("peer B: an SLC 5/05 on Ethernet is named by its IP address"), std::string::npos) << errors;
  opts.peers[0].ip = kIpA;
  EXPECT_EQ(try_build(program_text(kTarget, k505), errors, opts), nullptr);
  EXPECT_NE(errors.find("IP address 192.168.1.10 is already this controller's"), std::string::npos) << errors;
  // A 5/03 (DH-485) on a 5/05's Ethernet, and an IP address on DH-485.
  opts.peers[0].ip = kIpB;
  opts.peers[0].program = load(kTarget, "START 1747-L532\n");
  EXPECT_EQ(try_build(program_text(kTarget, k505), errors, opts), nullptr);
  EXPECT_NE(errors.find("is on DH-485, this network is Ethernet"), std::string::npos) << errors;
  EXPECT_EQ(try_build(program_text(kTarget), errors, opts), nullptr);
  EXPECT_NE(errors.find("names stations by node number"), std::string::npos) << errors;
  opts.peers[0].program = load(kTarget);
  EXPECT_NE(try_build(program_text(kTarget, k505), errors, opts), nullptr) << errors;
}

TEST(MessageEthernet, ScantimePricesTheEthernetForm) {
  // The 5/05's MSG row prices both of its forms (channel 1 Ethernet and the 14-word one); no SLC 5/05
  // execution time for MSG is in the sources, so it is marked EST.
  auto p = builtin_timing_profile("5/05");
  ASSERT_TRUE(p);
  const auto& row = p->instructions[static_cast<std::size_t>(Opcode::MSG)];
  EXPECT_GT(row.true_ns, 0);
  EXPECT_TRUE(p->is_estimate(row.source));
  EXPECT_EQ(row.source, "EST_MSG_ETHERNET");
}

// ---- check ----------------------------------------------------------------------------------------------

std::string check(std::string_view body, std::string_view header = k505) {
  return load_program(program_text(body, header), "t.slc").render_diagnostics();
}

TEST(MessageEthernetCheck, The51WordBlockOnChannel1) {
  EXPECT_EQ(check(kReadFive), "");
  EXPECT_EQ(check("SOR MSG WRITE PLC5 LOCAL N9:0 51 1 N10:0 5 0 N7:0 5 EOR"), "");
  EXPECT_EQ(check("SOR MSG WRITE 485CIF LOCAL N9:0 51 1 N10:0 5 0 10 5 EOR"), "");
  // 51 words must fit the N file (RM 12-34): N9:206 + 51 runs past element 255.
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:206 51 1 N10:0 5 0 N7:0 5 EOR")
                .find("t.slc:3:27: error: the 51-word MSG control block starting at N9:206 does not fit its file"),
            std::string::npos)
      << check("SOR MSG READ 500CPU LOCAL N9:206 51 1 N10:0 5 0 N7:0 5 EOR");
  EXPECT_EQ(check("SOR MSG READ 500CPU LOCAL N9:205 51 1 N10:0 5 0 N7:0 5 EOR"), "");  // N9:205-255 fits
  // The 14-word block is not the Ethernet channel's, and 51 words is not DH-485's.
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:0 14 1 N10:0 5 0 N7:0 5 EOR").find("takes a 51-word control block, not 14"),
            std::string::npos);
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:0 51 1 N10:0 5 2 N7:0 5 EOR", kHeader).find("51 words is the SLC 5/05's Ethernet block"),
            std::string::npos);
  // The 93-word logical ASCII form, a node on Ethernet, the Ethernet message lengths (RM D-21).
  EXPECT_NE(check("SOR MSG READ PLC5 LOCAL N9:0 93 1 N10:0 5 0 N7:0 5 EOR").find("logical ASCII addressing"), std::string::npos);
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:0 51 1 N10:0 5 2 N7:0 5 EOR").find("MSG on Ethernet has no target node"),
            std::string::npos);
  EXPECT_EQ(check("SOR MSG READ 500CPU LOCAL N9:0 51 1 N10:0 256 0 N7:0 5 EOR"), "");
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:0 51 1 S:0 84 0 S:0 5 EOR").find("carries at most 83 (1747-RM001G p. D-21"),
            std::string::npos);
  EXPECT_NE(check("SOR MSG WRITE 500CPU LOCAL N9:0 51 1 ST10:0 25 0 ST10:0 5 EOR").find("carries at most 24"), std::string::npos);
  // Channel 0 is DF1 full-duplex when a test configures it (tests/vm/df1_test.cpp): the 14-word block there,
  // not the 51-word Ethernet one.
  EXPECT_EQ(check("SOR MSG READ 500CPU LOCAL N9:0 14 0 N10:0 5 2 N7:0 5 EOR"), "");
  EXPECT_NE(check("SOR MSG READ 500CPU LOCAL N9:0 51 0 N10:0 5 2 N7:0 5 EOR").find("takes a 14-word control block"),
            std::string::npos);
}

TEST(MessageEthernetCheck, MultiHopAndLogicalAsciiFromADataBlockAreRefusedByName) {
  // Word 35 = 10h (table 12.14: MultiHop) set by the program's DATA block.
  const std::string multihop = check(std::string(kReadFive) + "\nDATA N9:30\n% N9:30 % 0 0 0 0 0 16\n");
  EXPECT_NE(multihop.find("makes it a MultiHop message"), std::string::npos) << multihop;
  EXPECT_EQ(check(std::string(kReadFive) + "\nDATA N9:30\n% N9:30 % 0 0 0 0 0 0\n"), "");
  // AO (word 12 bit 15) with PLC5.
  const std::string ao = check("SOR MSG READ PLC5 LOCAL N9:0 51 1 N10:0 5 0 N7:0 5 EOR\nDATA N9:12\n% N9:12 % -32768\n");
  EXPECT_NE(ao.find("selects PLC5 logical ASCII addressing"), std::string::npos) << ao;
  EXPECT_EQ(check(std::string(kReadFive) + "\nDATA N9:12\n% N9:12 % -32768\n"), "");
}

}  // namespace
}  // namespace softslc::test
