// The 1747-SDN scanner against the manual: the example application's mapping (chapters 2, 4 and 6),
// Run/Idle and the command register (appendix D, p.135-140), the status tables of M1 206...223
// (p.136-137), the chapter 7 numeric codes in M1:210 (p.90-91), and every failure injection.
#include <gtest/gtest.h>

#include "tests/devicenet/devicenet_test_util.h"

namespace softslc::devicenet::test {
namespace {

constexpr std::uint16_t kRun = 1u << 0;
constexpr std::uint16_t kFault = 1u << 1;
constexpr std::uint16_t kFlush = 1u << 2;
constexpr std::uint16_t kDisable = 1u << 4;
constexpr std::uint16_t kHalt = 1u << 6;
constexpr std::uint16_t kReboot = 1u << 7;

constexpr std::uint16_t kStatusDeviceFailure = 1u << 6;
constexpr std::uint16_t kStatusAutoverify = 1u << 8;
constexpr std::uint16_t kStatusCommFailure = 1u << 10;
constexpr std::uint16_t kStatusDuplicate = 1u << 12;

// M1:210 "high byte is the node address and the low byte is the status" (p.136).
std::uint16_t status_word(int node, int code) { return static_cast<std::uint16_t>(node << 8 | code); }

// ---- the example application -------------------------------------------------------------------

// Chapter 4, p.58-61: START is M1:2.0/1, STOP is M1:2.0/0; the photoeye's input bit is M1:2.0/8.
// Chapter 2, p.29-30: the photoeye's data bit appears at bit 8 and its status bit at bit 9.
TEST(ExampleApplication, InputsMapToM1WordZero) {
  ExampleNetwork x;
  x.run();
  x.start();
  EXPECT_EQ(x.m1(0), 0);
  x.redi->set_input("start", true);
  x.advance_ms(50);
  EXPECT_EQ(x.m1(0), 1u << 1);
  x.redi->set_input("start", false);
  x.redi->set_input("stop", true);
  x.eye->set_input("data", true);
  x.advance_ms(50);
  EXPECT_EQ(x.m1(0), (1u << 0) | (1u << 8));
  x.eye->set_input("status", true);
  x.redi->set_input("bulb_missing", true);  // bit 4 of the RediSTATION byte (p.27)
  x.advance_ms(50);
  EXPECT_EQ(x.m1(0), (1u << 0) | (1u << 4) | (1u << 8) | (1u << 9));
}

// Chapter 4, p.61: the indicator light is M0:2.0/0; chapter 6: pressing START lights it in Run.
TEST(ExampleApplication, LightFollowsM0InRun) {
  ExampleNetwork x;
  x.run();
  x.start();
  EXPECT_EQ(x.redi->output("light"), false);
  x.m0(0, 1);
  x.advance_ms(50);
  EXPECT_EQ(x.redi->output("light"), true);
  EXPECT_EQ(x.redi->output_state(), OutputState::Run);
  x.m0(0, 0);
  x.advance_ms(50);
  EXPECT_EQ(x.redi->output("light"), false);
}

// The devices of the example become active: M1 206...209 bit n for node n (p.136).
TEST(StatusTables, ActiveTableAfterConnecting) {
  ExampleNetwork x;
  x.run();
  x.start();
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kPhotoeyeNode));
  EXPECT_EQ(x.m1(layout::kActiveTable), (1u << 7) | (1u << 9));
  EXPECT_EQ(x.m1(layout::kActiveTable + 1), 0);
  EXPECT_EQ(x.m1(layout::kFailureTable), 0);
  EXPECT_EQ(x.m1(layout::kIdleTable), 0);
  EXPECT_EQ(x.m1(layout::kAutoverifyTable), 0);
  // Normal operation in Run: the display (and M1:210) shows the scanner's own address (p.90).
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, kScannerNode));
  EXPECT_EQ(x.sdn->input_image()[0] & 0x1FF, kRun);
}

// ---- Run and Idle (appendix D, p.135 and p.138) ------------------------------------------------

// Idle: "The scanner does not map output data to the devices, but keeps network connections to
// devices open ... Input data is returned from devices, and mapped ... Outputs on the network ...
// will be in their configured Idle state" (p.138). The RediSTATION's idle state is off.
TEST(RunIdle, IdleKeepsConnectionsAndInputsButNotOutputs) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.m0(0, 1);
  x.advance_ms(50);
  ASSERT_EQ(x.redi->output("light"), true);
  x.idle();
  x.advance_ms(50);
  EXPECT_EQ(x.redi->output("light"), false);
  EXPECT_EQ(x.redi->output_state(), OutputState::Idle);
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  x.redi->set_input("start", true);
  x.advance_ms(50);
  EXPECT_EQ(x.m1(0) & 0x2, 0x2);
  // Idle shows code 80 "Module is in Idle mode" (p.91) and status bit 0 = 0 (p.135).
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 80));
  EXPECT_EQ(x.sdn->status_register() & kRun, 0);
  x.run();
  x.advance_ms(50);
  EXPECT_EQ(x.redi->output("light"), true);
}

// Status bits 0, 1 and 4 echo the command register (p.135).
TEST(CommandRegister, StatusEchoesRunFaultDisable) {
  ExampleNetwork x;
  x.start();
  for (std::uint16_t cmd : {std::uint16_t{0}, kRun, kFault, std::uint16_t(kRun | kFault), kDisable,
                            std::uint16_t(kRun | kDisable)}) {
    x.command(cmd);
    EXPECT_EQ(x.sdn->status_register() & 0x13, cmd) << cmd;
  }
}

// Fault network: "The scanner has stopped communicating ... No outputs or inputs are mapped ... If
// scanner was in Run mode, devices will go to their fault state" (p.135); code 81 (p.91).
TEST(CommandRegister, FaultNetworkStopsCommunication) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.m0(0, 1);
  x.advance_ms(50);
  ASSERT_EQ(x.redi->output("light"), true);
  x.command(kRun | kFault);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 81));
  EXPECT_FALSE(x.sdn->port_running());
  const std::uint16_t before = x.m1(0);
  x.redi->set_input("start", true);
  x.advance_ms(400);  // past the device's 4 x 75 ms watchdog
  EXPECT_EQ(x.m1(0), before);  // no inputs mapped
  EXPECT_EQ(x.redi->output_state(), OutputState::Fault);
  EXPECT_EQ(x.redi->output("light"), false);  // fault action: outputs off (p.43)
  EXPECT_EQ(x.m1(layout::kActiveTable), 0);
  // Clearing the bit restarts the port: duplicate MAC check, then connections again.
  x.command(kRun);
  x.advance_ms(2200);
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  EXPECT_EQ(x.m1(0) & 0x2, 0x2);
}

// Disable network: code 90 "User has disabled communication port" (p.91).
TEST(CommandRegister, DisableNetwork) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.command(kRun | kDisable);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 90));
  EXPECT_FALSE(x.sdn->port_running());
  x.advance_ms(400);
  EXPECT_EQ(x.redi->output_state(), OutputState::Fault);
}

// Halt: code 97 "Module operation halted by user command" (p.91); all operations stop (p.139).
TEST(CommandRegister, Halt) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.command(kRun | kHalt);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 97));
  EXPECT_FALSE(x.sdn->port_running());
  const std::uint16_t counter = x.m1(layout::kScanCounter);
  x.advance_ms(100);
  EXPECT_EQ(x.m1(layout::kScanCounter), counter);
}

// Reserved bits "must be set to zero" (p.139): the module refuses the word, stops communicating and
// reports the Fault mode code 81; no command bit is echoed.
TEST(CommandRegister, ReservedBitIsAnError) {
  ExampleNetwork x;
  x.run();
  x.start();
  for (int b : {3, 5, 8, 9, 10, 11, 12, 13, 14, 15}) {
    x.command(static_cast<std::uint16_t>(kRun | (1u << b)));
    EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 81)) << b;
    EXPECT_EQ(x.sdn->status_register() & 0xFF, 0) << b;
    EXPECT_FALSE(x.sdn->port_running()) << b;
  }
  x.command(kRun);
  x.advance_ms(2200);
  EXPECT_TRUE(x.sdn->port_running());
}

// Flush: bit 2 alone restores the factory defaults, node 63, 125 Kbps, no scanlist, and shows E9
// until power is cycled (p.139-140); with other bits set "the module will generate an error".
TEST(CommandRegister, FlushToFactoryDefaults) {
  ExampleNetwork x;
  x.start();
  x.command(kFlush | kRun);
  EXPECT_EQ(x.m1(layout::kNodeStatus) & 0xFF, 81);
  EXPECT_EQ(x.sdn->config().node_address, kScannerNode);
  x.command(kFlush);
  EXPECT_EQ(x.sdn->config().node_address, 63);
  EXPECT_EQ(x.sdn->config().baud, Baud::k125);
  EXPECT_TRUE(x.sdn->config().scanlist.empty());
  EXPECT_FALSE(x.sdn->config().autoscan);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(63, 0xE9));
  x.command(0);
  x.advance_ms(3000);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(63, 0xE9));  // until power is cycled
  x.sdn->power_cycle();
  x.advance_ms(3000);
  // 125K on a 500K network: the scanner's port goes bus-off (91), see docs.
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(63, 91));
}

// Reboot: "the scanner to reset as though power had been cycled ... all scanner communication stops
// for the duration of the scanner's initialization sequence" (p.139).
TEST(CommandRegister, RebootRestartsTheModule) {
  ExampleNetwork x;
  x.run();
  x.start();
  ASSERT_GT(x.m1(layout::kScanCounter), 0);
  x.command(kRun | kReboot);
  EXPECT_FALSE(x.sdn->port_running());
  EXPECT_EQ(x.m1(layout::kScanCounter), 0);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 84));
  x.advance_ms(100);
  x.command(kRun | kReboot);  // still set: no second reboot
  x.advance_ms(timing::kRebootTime / kNsPerMs + 2200);
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, kScannerNode));
}

// ---- status codes and failure injections ---------------------------------------------------------

// 84 "Module is initializing the DeviceNet network" until every slave has been attempted (p.91).
TEST(StatusCodes, InitializingDuringDuplicateMacCheck) {
  ExampleNetwork x;
  x.run();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 84));
  x.advance_ms(1999);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 84));
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, kScannerNode));
}

// Offline device: 72 "Slave device stopped communicating (node number alternately flashes)"
// (p.91), its device failure bit (M1 216...219, p.137), status bit 6 (p.135), active bit cleared
// (p.136); its inputs are cleared. It comes back by itself when it returns.
TEST(Failures, DeviceOfflineThenBack) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.eye->set_input("data", true);
  x.advance_ms(50);
  ASSERT_EQ(x.m1(0) & 0xFF00, 0x0100);
  x.eye->set_online(false);
  x.advance_ms(200);
  EXPECT_FALSE(table_bit(x, layout::kFailureTable, kPhotoeyeNode));  // 4 x 75 ms not yet over
  x.advance_ms(150);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kPhotoeyeNode, 72));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kPhotoeyeNode));
  EXPECT_FALSE(table_bit(x, layout::kActiveTable, kPhotoeyeNode));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
  EXPECT_EQ(x.sdn->status_register() & kStatusDeviceFailure, kStatusDeviceFailure);
  EXPECT_EQ(x.m1(0) & 0xFF00, 0);
  x.eye->set_online(true);
  x.advance_ms(1500);
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kPhotoeyeNode));
  EXPECT_FALSE(table_bit(x, layout::kFailureTable, kPhotoeyeNode));
  EXPECT_EQ(x.sdn->status_register() & kStatusDeviceFailure, 0);
  EXPECT_EQ(x.m1(0) & 0xFF00, 0x0100);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, kScannerNode));
}

// A scanlist node with no device: 78 "Slave device in scanlist table does not exist" (p.91).
TEST(Failures, MissingDevice) {
  ExampleNetwork x;
  x.net.detach(kPhotoeyeNode);
  x.run();
  x.start();
  // The unanswered connection request times out after 500 ms (timing::kExplicitTimeout): until then
  // the module is still initializing (84).
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 84));
  x.advance_ms(400);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kPhotoeyeNode, 78));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kPhotoeyeNode));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
}

// Wrong data size at connection: 77 "Data size expected by the device does not match scanlist
// entry" (p.91), the autoverify failure table (M1 220...223, p.137) and status bits 6 and 8
// ("Bits 6 and 8 indicate that you should read the device failure table", p.134).
TEST(Failures, AutoverifyAtConnection) {
  ExampleNetwork x;
  x.redi->set_produced_size_override(2);
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 77));
  EXPECT_TRUE(table_bit(x, layout::kAutoverifyTable, kRediStationNode));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kRediStationNode));
  EXPECT_EQ(x.sdn->status_register() & (kStatusDeviceFailure | kStatusAutoverify),
            kStatusDeviceFailure | kStatusAutoverify);
  x.redi->set_produced_size_override(std::nullopt);
  x.advance_ms(1100);
  EXPECT_FALSE(table_bit(x, layout::kAutoverifyTable, kRediStationNode));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
  EXPECT_EQ(x.sdn->status_register() & (kStatusDeviceFailure | kStatusAutoverify), 0);
}

// Wrong data size while running: 85 "Data size was incorrect for this device at runtime" (p.91);
// the reconnection then fails autoverify (77).
TEST(Failures, WrongSizeAtRuntime) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.redi->set_produced_size_override(3);
  x.advance_ms(30);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 85));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kRediStationNode));
  EXPECT_FALSE(table_bit(x, layout::kAutoverifyTable, kRediStationNode));
  x.advance_ms(1100);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 77));
  EXPECT_TRUE(table_bit(x, layout::kAutoverifyTable, kRediStationNode));
}

// A device producing zero-length data: the device idle table (M1 212...215, p.136), and code 86
// "Device is producing zero length data (idle state) while module is in Run mode" only in Run.
TEST(Failures, IdleDevice) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.redi->set_input("start", true);
  x.advance_ms(30);
  x.redi->set_producing_idle(true);
  x.advance_ms(30);
  EXPECT_TRUE(table_bit(x, layout::kIdleTable, kRediStationNode));
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 86));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
  EXPECT_FALSE(table_bit(x, layout::kFailureTable, kRediStationNode));
  EXPECT_EQ(x.m1(0) & 0x2, 0x2);  // idle: inputs hold
  x.idle();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 80));
  x.redi->set_producing_idle(false);
  x.advance_ms(30);
  EXPECT_FALSE(table_bit(x, layout::kIdleTable, kRediStationNode));
}

// Identity mismatch: 73 "Device's identity information does not match electronic key" (p.91).
TEST(Failures, KeyingMismatch) {
  ScannerConfig c = example_config();
  c.scanlist[0].key.vendor = 1;
  c.scanlist[0].key.product_code = 2705;
  c.scanlist[0].key.major = 2;
  c.scanlist[0].key.minor = 3;
  ExampleNetwork x(false, c);
  x.run();
  x.start();
  ASSERT_TRUE(x.sdn->connected(kRediStationNode));
  Identity other = x.redi->identity();
  other.product_code = 2706;
  x.redi->set_identity_override(other);
  x.redi->set_online(false);  // replaced by another device: it reconnects with the other identity
  x.advance_ms(350);
  x.redi->set_online(true);
  x.advance_ms(1100);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 73));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kRediStationNode));
  EXPECT_FALSE(table_bit(x, layout::kAutoverifyTable, kRediStationNode));
  // "Minor revision or higher": a newer minor revision is accepted.
  other = x.redi->model().identity;
  other.minor = 9;
  x.redi->set_identity_override(other);
  x.advance_ms(1100);
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  other.minor = 2;
  x.redi->set_identity_override(other);
  x.redi->set_online(false);
  x.advance_ms(350);
  x.redi->set_online(true);
  x.advance_ms(1100);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 73));
}

// Error responses at connection: 83 (p.91), here because another master owns the slave.
TEST(Failures, OwnedByAnotherMaster) {
  ExampleNetwork x;
  x.redi->set_owned_elsewhere(true);
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 83));
  EXPECT_TRUE(table_bit(x, layout::kFailureTable, kRediStationNode));
}

// A configured connection the device does not support is refused with an error response: 83.
TEST(Failures, UnsupportedConnectionType) {
  ScannerConfig c = example_config();
  c.scanlist[1].conn(IoType::Poll) = ConnectionConfig{true, 1, 0, default_epr(IoType::Poll), false};
  ExampleNetwork x(false, c);
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kPhotoeyeNode, 83));
}

// Another node at the scanner's address: 70 "Module failed Duplicate Node Address check" (p.91)
// and status bit 12 (p.135). It stays until the port is restarted.
TEST(Failures, DuplicateNodeAddress) {
  ExampleNetwork x;
  x.net.set_duplicate_claim(kScannerNode, true);
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 70));
  EXPECT_EQ(x.sdn->status_register() & kStatusDuplicate, kStatusDuplicate);
  EXPECT_FALSE(x.sdn->port_running());
  x.net.set_duplicate_claim(kScannerNode, false);
  x.advance_ms(3000);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 70));
  x.command(kRun | kDisable);
  x.command(kRun);
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, kScannerNode));
  EXPECT_EQ(x.sdn->status_register() & kStatusDuplicate, 0);
}

// Bus-off: 91 (p.91) and status bit 10 "communication failure" (p.135); every connected device
// fails. The port restarts when the fault clears.
TEST(Failures, BusOff) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.net.set_bus_fault(true);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 91));
  EXPECT_EQ(x.sdn->status_register() & kStatusCommFailure, kStatusCommFailure);
  EXPECT_EQ(x.m1(layout::kFailureTable), (1u << 7) | (1u << 9));
  EXPECT_EQ(x.m1(layout::kActiveTable), 0);
  x.net.set_bus_fault(false);
  x.start();
  EXPECT_EQ(x.m1(layout::kActiveTable), (1u << 7) | (1u << 9));
  EXPECT_EQ(x.m1(layout::kFailureTable), 0);
  EXPECT_EQ(x.sdn->status_register() & kStatusCommFailure, 0);
}

// No network power: 92 (p.91) and status bit 10.
TEST(Failures, NoNetworkPower) {
  ExampleNetwork x;
  x.run();
  x.start();
  x.net.set_network_power(false);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 92));
  EXPECT_EQ(x.sdn->status_register() & kStatusCommFailure, kStatusCommFailure);
}

// A scanner alone on the cable: 79 "Module has failed to transmit a message" (p.91), bit 10.
TEST(Failures, AloneOnTheNetwork) {
  Network net(Baud::k500);
  Scanner sdn(net, example_config());
  net.advance_to(seconds(3));
  std::uint16_t w = 0;
  sdn.read_m(MFile::M1, layout::kNodeStatus, w);
  EXPECT_EQ(w, status_word(kScannerNode, 79));
  EXPECT_EQ(sdn.status_register() & kStatusCommFailure, kStatusCommFailure);
  net.attach(kRediStationNode, builtin_device_model("redistation"));
  net.advance_to(seconds(5));
  EXPECT_TRUE(sdn.port_running());
}

// Devices present but an empty scanlist: 75 "No traffic ... (Scanlist may be empty)" (p.91).
TEST(StatusCodes, EmptyScanlist) {
  ScannerConfig c = example_config();
  c.scanlist.clear();
  ExampleNetwork x(false, c);
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 75));
}

// Illegal scanlist data: 71 with the node (p.91); the entry is not scanned, the others are.
TEST(StatusCodes, IllegalScanlistEntry) {
  ScannerConfig c = example_config();
  c.scanlist[1].inputs[0].table.word = 149;  // 8 bits from M1:149/8 fit; from 149/9 they do not
  c.scanlist[1].inputs[0].table.bit = 9;
  ExampleNetwork x(false, c);
  ASSERT_EQ(x.sdn->scanlist_issues().size(), 1u);
  EXPECT_EQ(x.sdn->scanlist_issues()[0].path, "scanlist[1].inputs[0].to");
  x.run();
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kPhotoeyeNode, 71));
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  EXPECT_FALSE(x.sdn->connected(kPhotoeyeNode));
}

// The data rate must match the network's: a 125K scanner on a 500K cable sees bus errors (91).
TEST(StatusCodes, WrongBaudRate) {
  ScannerConfig c = example_config();
  c.baud = Baud::k125;
  ExampleNetwork x(false, c);
  x.start();
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kScannerNode, 91));
}

// Two failing nodes: the lowest address is shown (our rule; the display alternates, p.90).
TEST(StatusCodes, LowestFailingNodeShown) {
  ExampleNetwork x;
  x.net.detach(kPhotoeyeNode);
  x.redi->set_owned_elsewhere(true);
  x.run();
  x.advance_ms(2600);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 83));
  x.redi->set_owned_elsewhere(false);
  x.advance_ms(1100);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kPhotoeyeNode, 78));
}

// Every code the model can produce has a row in the chapter 7 table, and vice versa for the
// modelled flag (status_codes.def).
TEST(StatusCodes, TableHasTheManualsRows) {
  for (int code : {65, 70, 71, 72, 73, 74, 75, 76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87, 88, 89, 90, 91, 92, 95,
                   97, 98, 99, 0xE2, 0xE4, 0xE5, 0xE9})
    EXPECT_FALSE(sdn_code_text(code).empty()) << code;
  EXPECT_TRUE(sdn_code_text(64).empty());
  EXPECT_TRUE(sdn_code_text(93).empty());
  EXPECT_EQ(sdn_code_text(80), "Module is in Idle mode");
  EXPECT_TRUE(sdn_code_is_node_code(72));
  EXPECT_FALSE(sdn_code_is_node_code(80));
}

// ---- the scan counter and timing -------------------------------------------------------------------

// M1:211 "increments this counter whenever a scan of the DeviceNet devices is completed. The counter
// rolls over when it reaches a maximum value of 65,535" (p.136).
TEST(ScanCounter, RollsOverAfter65535) {
  ScannerConfig c = example_config();
  c.scanlist.clear();
  c.interscan_delay = milliseconds(1);
  ExampleNetwork x(false, c);
  x.advance_ms(2000);  // the first scan ends at 2 s exactly
  EXPECT_EQ(x.m1(layout::kScanCounter), 1);
  // With no devices each cycle is the 1 ms interscan delay: scan k ends at 2 s + (k - 1) ms.
  x.net.advance_to(seconds(2) + milliseconds(65534));
  EXPECT_EQ(x.m1(layout::kScanCounter), 65535);
  x.net.advance_to(seconds(2) + milliseconds(65535));
  EXPECT_EQ(x.m1(layout::kScanCounter), 0);
  x.net.advance_to(seconds(2) + milliseconds(65536));
  EXPECT_EQ(x.m1(layout::kScanCounter), 1);
}

// The cycle: the poll command (1 byte, 65 bits), the interscan delay counted from the end of the
// last poll request (glossary, "Interscan Delay"). At 500K a bit is 2 us, so the RediSTATION-only
// network cycles every 10 ms + 130 us, and the scan ends 130 + 100 (response time) + 130 us after
// the cycle starts.
TEST(ScanTiming, PeriodIsInterscanDelayAfterLastPollRequest) {
  ScannerConfig c = example_config();
  c.scanlist.pop_back();
  ExampleNetwork x(false, c);
  x.run();
  x.start();
  std::vector<VirtualTime> ends;
  std::uint16_t counter = x.m1(layout::kScanCounter);
  while (ends.size() < 4) {
    x.net.advance_to(*x.net.next_event_time());
    if (x.m1(layout::kScanCounter) != counter) {
      counter = x.m1(layout::kScanCounter);
      ends.push_back(x.net.now());
    }
  }
  EXPECT_EQ(ends[1] - ends[0], milliseconds(10) + microseconds(130));
  EXPECT_EQ(ends[2] - ends[1], milliseconds(10) + microseconds(130));
  EXPECT_EQ(ends[3] - ends[2], milliseconds(10) + microseconds(130));
}

// The background poll ratio: "if the ratio is set at 10, that device will be polled once every 10
// scans" (glossary, "Background Poll Ratio").
TEST(ScanTiming, BackgroundPollRatio) {
  ScannerConfig c = example_config(true);
  c.background_poll_ratio = 10;
  c.scanlist[2].conn(IoType::Poll).background = true;
  c.scanlist[2].conn(IoType::Poll).epr = milliseconds(1000);
  ExampleNetwork x(true, c);
  x.run();
  x.start();
  const auto redi0 = x.redi->messages_consumed(IoType::Poll);
  const auto drive0 = x.drive->messages_consumed(IoType::Poll);
  x.advance_ms(1000);
  const auto redi = x.redi->messages_consumed(IoType::Poll) - redi0;
  const auto drive = x.drive->messages_consumed(IoType::Poll) - drive0;
  EXPECT_GE(redi, 90u);
  EXPECT_LE(drive * 10, redi + 10);
  EXPECT_GE(drive * 10 + 10, redi);
}

// ---- appendix A: the discrete mapping example -------------------------------------------------------

// Data bits of nodes 1...62 in I:s.1...4 and status bits in I:s.5...8, bit n of the group for node n
// ("the data bit for node #11 is mapped to bit 11, word 1 ... Its status bit is mapped to bit 11,
// word 5", p.116); node n's output bit from bit n of the discrete output table into bit n of the
// strobe message (p.118-119).
TEST(AppendixA, DiscreteStrobeMapping) {
  const std::string model_text = R"({
    "name": "strobed-sensor",
    "identity": {"vendor": 1, "device_type": 6, "product_code": 1, "major": 1, "minor": 1, "product_name": "sensor"},
    "io": {"strobe": {"produce": 1, "consume": 1}},
    "inputs": [{"name": "data", "byte": 0, "bit": 0}, {"name": "status", "byte": 0, "bit": 1}],
    "outputs": [{"name": "out", "byte": 0, "bit": 0}]
  })";
  const std::vector<int> nodes = {1, 11, 17, 33, 62};
  ScannerConfig c;
  c.node_address = 0;  // "Address 0 must be used for the scanner" (p.116)
  c.baud = Baud::k500;
  Network net(Baud::k500);
  for (int n : nodes) {
    net.attach(n, parse_device_model_text(model_text));
    ScanlistEntry e;
    e.node = n;
    e.conn(IoType::Strobe) = ConnectionConfig{true, 1, 1, default_epr(IoType::Strobe), false};
    e.inputs.push_back(segment(IoType::Strobe, 0, 0, 1, TableRef::Area::Discrete, 1 + n / 16, n % 16));
    e.inputs.push_back(segment(IoType::Strobe, 0, 1, 1, TableRef::Area::Discrete, 5 + n / 16, n % 16));
    e.outputs.push_back(segment(IoType::Strobe, 0, 0, 1, TableRef::Area::Discrete, 1 + n / 16, n % 16));
    c.scanlist.push_back(e);
  }
  Scanner sdn(net, c);
  std::array<std::uint16_t, 32> out{};
  out[0] = kRun;
  out[1] = 1u << 11;  // node 11's output
  out[4] = 1u << 14;  // node 62's output (word 1 + 62/16 = 4, bit 14)
  sdn.write_output_image(out);
  net.advance_to(milliseconds(2200));
  net.set_input(11, "data", true);
  net.set_input(17, "status", true);
  net.set_input(62, "data", true);
  net.set_input(62, "status", true);
  net.advance_to(milliseconds(2300));
  const auto in = sdn.input_image();
  EXPECT_EQ(in[1], 1u << 11);
  EXPECT_EQ(in[2], 0);
  EXPECT_EQ(in[4], 1u << 14);
  EXPECT_EQ(in[5], 0);
  EXPECT_EQ(in[6], 1u << 1);  // node 17: word 5 + 1, bit 1
  EXPECT_EQ(in[8], 1u << 14);
  EXPECT_EQ(net.device(11)->output("out"), true);
  EXPECT_EQ(net.device(62)->output("out"), true);
  EXPECT_EQ(net.device(1)->output("out"), false);
  EXPECT_EQ(net.device(33)->output("out"), false);
}

// A map segment moves `bits` bits from a device bit position to a table bit position (the input and
// output tables of p.60-61, where RSNetWorx maps bytes and single bits anywhere in a word): here
// segments that start mid-byte and cross a device byte and a table word (issue 20: map_inputs and
// sample_outputs move them in runs, not bit by bit). Bits of the table words outside the segment
// keep what the ladder wrote; device bits outside it are not sent.
TEST(Mapping, SegmentsCrossingBytesAndWordsMoveBitForBit) {
  std::string points_in, points_out;
  for (int b = 0; b < 16; ++b) {
    const std::string pos = "\"byte\": " + std::to_string(b / 8) + ", \"bit\": " + std::to_string(b % 8) + "}";
    points_in += std::string(b ? ", " : "") + "{\"name\": \"i" + std::to_string(b) + "\", " + pos;
    points_out += std::string(b ? ", " : "") + "{\"name\": \"o" + std::to_string(b) + "\", " + pos;
  }
  const std::string model_text = R"({"name": "two-byte", "identity": {"vendor": 1, "device_type": 7, "product_code": 1,
    "major": 1, "minor": 1, "product_name": "two bytes"}, "io": {"poll": {"produce": 2, "consume": 2}},
    "inputs": [)" + points_in + R"(], "outputs": [)" + points_out + "]}";
  ScannerConfig c;
  c.node_address = 0;
  c.baud = Baud::k500;
  Network net(Baud::k500);
  net.attach(5, parse_device_model_text(model_text));
  ScanlistEntry e;
  e.node = 5;
  e.conn(IoType::Poll) = ConnectionConfig{true, 2, 2, default_epr(IoType::Poll), false};
  e.inputs.push_back(segment(IoType::Poll, 0, 3, 10, TableRef::Area::MFile, 2, 12));   // device bits 3-12 -> M1:2/12-3/5
  e.outputs.push_back(segment(IoType::Poll, 0, 6, 7, TableRef::Area::MFile, 4, 13));   // M0:4/13-5/3 -> device bits 6-12
  c.scanlist.push_back(e);
  Scanner sdn(net, c);
  std::array<std::uint16_t, 1> run{kRun};
  sdn.write_output_image(run);
  sdn.write_m(MFile::M1, 2, 0x0ABC);
  sdn.write_m(MFile::M1, 3, 0xFF00);
  sdn.write_m(MFile::M0, 4, 0xA000);  // bits 13 and 15: device bits 6 and 8
  sdn.write_m(MFile::M0, 5, 0x0019);  // bits 0 and 3: device bits 9 and 12; bit 4 is past the segment
  net.advance_to(milliseconds(2200));
  for (const char* p : {"i2", "i3", "i7", "i8", "i12", "i13"}) net.set_input(5, p, true);  // i2, i13 outside
  net.advance_to(milliseconds(2300));
  std::uint16_t w2 = 0, w3 = 0;
  sdn.read_m(MFile::M1, 2, w2);
  sdn.read_m(MFile::M1, 3, w3);
  EXPECT_EQ(w2, 0x0ABC | 1u << 12);                       // device bit 3 -> M1:2/12
  EXPECT_EQ(w3, 0xFF00 | 1u << 0 | 1u << 1 | 1u << 5);    // bits 7, 8, 12 -> M1:3/0, 3/1, 3/5
  EXPECT_EQ(net.device(5)->outputs(), (Bytes{0x40, 0x13}));  // bits 6 | 8, 9, 12
}

// ---- change of state and cyclic (chapter 1, p.16; glossary) ---------------------------------------

ScannerConfig cos_config() {
  ScannerConfig c = example_config();
  c.scanlist.pop_back();
  c.scanlist[0].conn(IoType::Poll).enabled = false;
  c.scanlist[0].conn(IoType::Cos) = ConnectionConfig{true, 1, 1, milliseconds(250), false};
  for (auto& seg : c.scanlist[0].inputs) seg.connection = IoType::Cos;
  for (auto& seg : c.scanlist[0].outputs) seg.connection = IoType::Cos;
  return c;
}

// "Data is sent whenever a data change occurs" (glossary, Change of State): a button press reaches
// M1 after the device's 100 us response time and one 1-byte frame (65 bits x 2 us = 130 us).
TEST(ChangeOfState, InputChangeArrivesAtOnce) {
  ExampleNetwork x(false, cos_config());
  x.run();
  x.start();
  ASSERT_TRUE(x.sdn->connected(kRediStationNode));
  const VirtualTime t = x.net.now();
  x.redi->set_input("start", true);
  x.net.advance_to(t + microseconds(229));
  EXPECT_EQ(x.m1(0) & 0x2, 0);
  x.net.advance_to(t + microseconds(230));
  EXPECT_EQ(x.m1(0) & 0x2, 0x2);
  // Outputs go out when they change.
  x.m0(0, 1);
  x.advance_ms(20);
  EXPECT_EQ(x.redi->output("light"), true);
  EXPECT_EQ(x.redi->output_state(), OutputState::Run);
}

// "Devices that are configured for change of state data can also send a heartbeat signal" (glossary,
// Heartbeat Rate): a silent COS device times out after 4 x its 250 ms heartbeat.
TEST(ChangeOfState, HeartbeatKeepsTheConnection) {
  ExampleNetwork x(false, cos_config());
  x.run();
  x.start();
  x.advance_ms(5000);  // no input change at all: heartbeats only
  EXPECT_TRUE(x.sdn->connected(kRediStationNode));
  EXPECT_TRUE(table_bit(x, layout::kActiveTable, kRediStationNode));
  x.redi->set_online(false);
  x.advance_ms(700);
  EXPECT_FALSE(table_bit(x, layout::kFailureTable, kRediStationNode));
  x.advance_ms(400);
  EXPECT_EQ(x.m1(layout::kNodeStatus), status_word(kRediStationNode, 72));
}

// "Data is sent only at a user-configurable rate" (glossary, Cyclic): an input change waits for the
// next production, 100 ms apart here.
TEST(Cyclic, DataAtTheConfiguredRate) {
  const std::string model_text = R"({
    "name": "cyclic-sensor",
    "identity": {"vendor": 1, "device_type": 7, "product_code": 3, "major": 1, "minor": 1, "product_name": "cyc"},
    "io": {"cyclic": {"produce": 2, "consume": 0}}
  })";
  Network net(Baud::k500);
  SimDevice& d = net.attach(12, parse_device_model_text(model_text));
  ScannerConfig c;
  c.node_address = 0;
  c.baud = Baud::k500;
  ScanlistEntry e;
  e.node = 12;
  e.conn(IoType::Cyclic) = ConnectionConfig{true, 2, 0, milliseconds(100), false};
  e.inputs.push_back(segment(IoType::Cyclic, 0, 0, 16, TableRef::Area::MFile, 5, 0));
  c.scanlist.push_back(e);
  Scanner sdn(net, c);
  net.advance_to(milliseconds(2500));
  ASSERT_TRUE(sdn.connected(12));
  std::uint16_t w = 0;
  d.set_input_byte(0, 0x34);
  d.set_input_byte(1, 0x12);
  std::vector<VirtualTime> updates;
  while (net.now() < milliseconds(2800)) {
    net.advance_to(*net.next_event_time());
    sdn.read_m(MFile::M1, 5, w);
    if (w == 0x1234) break;
  }
  const VirtualTime first = net.now();
  EXPECT_EQ(w, 0x1234);
  EXPECT_LE(first - milliseconds(2500), milliseconds(100) + microseconds(500));
  d.set_input_byte(1, 0x56);
  net.advance_to(first + milliseconds(99));
  sdn.read_m(MFile::M1, 5, w);
  EXPECT_EQ(w, 0x1234);  // not before the next production
  net.advance_to(first + milliseconds(100));
  sdn.read_m(MFile::M1, 5, w);
  EXPECT_EQ(w, 0x5634);
}

// A configuration download replaces the scanlist and restarts the port (chapter 4, p.62).
TEST(Configuration, DownloadRestartsThePort) {
  ExampleNetwork x;
  x.run();
  x.start();
  ScannerConfig c = example_config();
  c.scanlist.erase(c.scanlist.begin());
  x.sdn->download(c);
  EXPECT_FALSE(x.sdn->port_running());
  x.start();
  EXPECT_FALSE(x.sdn->connected(kRediStationNode));
  EXPECT_TRUE(x.sdn->connected(kPhotoeyeNode));
  x.advance_ms(400);
  EXPECT_EQ(x.redi->output_state(), OutputState::Fault);  // its master went away in Run
}

}  // namespace
}  // namespace softslc::devicenet::test
