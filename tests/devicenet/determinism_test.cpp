// Determinism: the same inputs give byte-identical traces and tables (house style: "a test that two
// runs produce byte-identical traces").
#include <gtest/gtest.h>

#include "modules/devicenet/dem.h"
#include "tests/devicenet/devicenet_test_util.h"

namespace softslc::devicenet::test {
namespace {

struct Outcome {
  std::vector<std::string> trace;
  std::vector<std::uint16_t> m1;
  std::vector<std::uint8_t> outputs;
  VirtualTime end = 0;
};

// A busy scenario: the example network with the drive, field changes, a failure and recovery,
// explicit messages by M0 block and by DEM, Run/Idle changes and a bus fault.
Outcome scenario() {
  ExampleNetwork x(true);
  x.sdn->set_tracing(true);
  dem::DemPort port(*x.sdn);
  std::array<std::uint16_t, dem::kWords> cb{};
  dem::write_setup(cb, dem::Setup{0x10, kDriveNode, 0x0F, 39, 1, {0x2C, 0x01}, 5});
  x.run();
  x.start();
  for (int step = 0; step < 400; ++step) {
    x.redi->set_input("start", step % 7 == 0);
    x.eye->set_input("data", step % 3 == 0);
    x.m0(0, static_cast<std::uint16_t>(step % 2));
    if (step == 50) x.eye->set_online(false);
    if (step == 120) x.eye->set_online(true);
    if (step == 200) x.idle();
    if (step == 230) x.run();
    if (step == 300) x.net.set_bus_fault(true);
    if (step == 310) x.net.set_bus_fault(false);
    if (step % 25 == 0) {
      RequestBlock r;
      r.command = step % 50 == 0 ? 1 : 4;
      r.txid = static_cast<std::uint8_t>(1 + step / 50);
      r.size = 6;
      r.service = 0x0E;
      r.mac = kRediStationNode;
      r.class_id = 1;
      r.instance = 1;
      r.attribute = static_cast<std::uint8_t>(1 + step % 7);
      x.sdn->handle_request(r);
    }
    port.on_rung(1, cb, step % 40 < 20, x.net.now());
    x.advance_ms(13);
  }
  Outcome o;
  o.trace = x.sdn->trace();
  for (int w = 0; w < layout::kMFileWords; ++w) o.m1.push_back(x.m1(w));
  o.outputs = x.redi->outputs();
  o.end = x.net.now();
  return o;
}

TEST(Determinism, TwoRunsAreIdentical) {
  const Outcome a = scenario();
  const Outcome b = scenario();
  ASSERT_GT(a.trace.size(), 20u);
  EXPECT_EQ(a.trace, b.trace);
  EXPECT_EQ(a.m1, b.m1);
  EXPECT_EQ(a.outputs, b.outputs);
  EXPECT_EQ(a.end, b.end);
}

// The start of the example's trace as a golden listing, every time derived by hand from the model
// (docs/1747-sdn.md, "Timing"): 500K, 2 us a bit; CAN frame bits 47 + 8n + floor((33 + 8n) / 4).
//   2 s        the duplicate MAC ID check ends; the first cycle starts connections (no I/O yet)
//   photoeye   (explicit answer 800 us) allocate 230 + 800 + 170 = 1200 us; identity 190 + 800 +
//              2620 (35-byte reply in 6 acknowledged fragments: 5 x 220 + 210 bits) = 3610 us;
//              produced size 210 + 800 + 190 = 1200 us; set EPR 250 + 800 + 150 = 1200 us
//              -> 7210 us
//   RediSTATION (1000 us) allocate 1400; identity 190 + 1000 + 2600 = 3790; produced and consumed
//              size 1400 each; set EPR 1400 -> 9390 us
//   2.010 s    the second cycle (10 ms interscan delay, no requests in the first): the 8-byte strobe
//              (135 bits, 270 us), the photoeye's reply 50 us later (65 bits, 130 us) at +450 us;
//              the RediSTATION's poll (130 us), its 100 us answer and reply (130 us) at +810 us.
TEST(Determinism, GoldenStart) {
  ExampleNetwork x;
  x.sdn->set_tracing(true);
  x.run();
  x.start();
  EXPECT_EQ(x.sdn->trace(), (std::vector<std::string>{"0 command 1", "2000000000 port running",
                                                      "2007210000 node 9 connected", "2009390000 node 7 connected",
                                                      "2010450000 node 9 active", "2010810000 node 7 active"}));
}

}  // namespace
}  // namespace softslc::devicenet::test
