// The 1203-SM1 module in a running processor: the I/O image of chapters 3 and 4, the drives on a
// bench over virtual time, DIP switch fault/program states (chapter 2), G file datalinks and safe
// state (chapter 4), M0/M1 files and the READY/DONE/BUSY message handshake (chapter 4, appendix
// B). Manual: ../shared/seeds/001_0b60ddd8c475c2fb.txt.
#include <gtest/gtest.h>

#include <random>

#include "modules/scanport/messages.h"
#include "sm1_test_util.h"

namespace softslc::test {
namespace {

constexpr Nanoseconds ms(std::int64_t n) { return n * kNsPerMs; }

// Channel status byte bits (chapter 4, "Enhanced Mode Interface").
constexpr int kV = 3;
// Input word 1: DONE 8/10/12, READY 9/11/13, M0 STA 14.
bool ready(Bench& b, int c) { return (b.u("I:1.1") >> (9 + 2 * (c - 1))) & 1; }
bool done(Bench& b, int c) { return (b.u("I:1.1") >> (8 + 2 * (c - 1))) & 1; }
bool m0_sta(Bench& b) { return (b.u("I:1.1") >> 14) & 1; }

// A program that copies N10 into M0 buffer `buffer` while B3:0/0 is set; the test drives the
// channel command bits itself.
std::string copy_program(int buffer = 0) {
  return "SOR XIC B3:0/0 COP #N10:0 #M0:1." + std::to_string(buffer * 100) + " 10 EOR \n";
}

// Writes a request's words into N10, lets the program copy them into M0 and waits for M0 STA.
void load_request(Bench& b, std::initializer_list<int> words) {
  int k = 0;
  for (int w : words) b.set("N10:" + std::to_string(k++), w);
  b.set("B3:0/0", 1);
  b.rt->scan(1);
  b.set("B3:0/0", 0);
  ASSERT_TRUE(b.until([&] { return m0_sta(b); }, ms(10)));
}

// ---- Basic mode (chapter 3) ---------------------------------------------------------------------------------------

TEST(Sm1Basic, ChannelStatusShowsThePortAndValidOnlyAfterDataEnable) {
  Bench b(sm1_program(kBasic), "scanport SM1 slot=1 {\n  drive D1 channel=1 port=2\n  drive D3 channel=3 port=5\n}\n");
  b.run();
  b.rt->scan(1);
  // ID1 = 2, channel 2 has nothing: ID2 = 7 ("the channel is not connected"); ID3 = 5. No V yet.
  EXPECT_EQ(b.u("I:1.0"), 0x0702);
  EXPECT_EQ(b.u("I:1.1"), 0x0005);
  b.set("O:1.0/0", 1);  // DE1
  b.set("O:1.1/0", 1);  // DE3
  b.rt->scan(1);        // the module sees DE at this output scan
  EXPECT_EQ(b.u("I:1.0") & (1 << kV), 0);
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0"), 0x070A);
  EXPECT_EQ(b.u("I:1.1"), 0x000D);  // basic mode: no message status bits
  // Logic status of an enabled, stopped 1305: enabled + command forward + rotating forward.
  EXPECT_EQ(b.u("I:1.2"), 0x000D);
  EXPECT_EQ(b.u("I:1.3"), 0);
  // Basic mode has no M files.
  EXPECT_EQ(sm1(b).m_file_words(MFile::M0), 0);
  EXPECT_EQ(sm1(b).m_file_words(MFile::M1), 0);
}

TEST(Sm1Basic, BasicModeIgnoresMessageEnable) {
  Bench b(sm1_program(kBasic), kOneDrive);
  b.run();
  b.set("O:1.0", 0x0003);  // DE1 and what would be ME1
  b.rt->scan(3);
  EXPECT_EQ(sm1(b).message_state(1), Sm1Module::MessageState::Ready);
  EXPECT_EQ(b.u("I:1.1") & 0xFF00, 0);
}

TEST(Sm1Basic, Figures36To39StartStopAndReferenceForThreeDrives) {
  Bench b(sm1_example("ch3_basic_drives.slc"), sm1_example("drives.bench"));
  b.run();
  b.set("I:2/1", 1);  // stop push buttons not pressed (normally closed)
  b.set("I:2/3", 1);
  b.set("I:2/5", 1);
  b.set("N7:0", 16384);
  b.set("N7:1", 32767);
  b.set("I:2/0", 1);  // start drive 1
  b.rt->scan(3);
  b.set("I:2/0", 0);
  b.set("I:2/2", 1);  // start drive 2
  b.rt->scan(3);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 1);
  EXPECT_EQ(observed(b, "DRIVE2", "running"), 1);
  EXPECT_EQ(observed(b, "DRIVE3", "running"), 0);
  EXPECT_EQ(observed(b, "DRIVE1", "reference"), 16384);
  // First order, 500 ms time constant: 63 % of the step after 500 ms, at speed later.
  b.rt->run_for(ms(500));
  const auto f = b.i("I:1.3");
  EXPECT_GT(f, 16384 * 60 / 100);
  EXPECT_LT(f, 16384 * 66 / 100);
  b.rt->run_for(ms(4000));
  EXPECT_NEAR(static_cast<double>(b.i("I:1.3")), 16384.0, 164.0);
  EXPECT_EQ((b.u("I:1.2") >> 8) & 1, 1);  // at speed
  // Stop drive 1 (normally closed button pressed: input 0); the drive decelerates to 0.
  b.set("I:2/1", 0);
  b.rt->run_for(ms(8000));
  EXPECT_EQ(b.i("I:1.3"), 0);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 0);
  EXPECT_EQ(observed(b, "DRIVE2", "running"), 1);
}

TEST(Sm1Basic, ClearingDataEnableDisconnectsAndFaultsTheDrive) {
  Bench b(sm1_program(kBasic), kOneDrive);
  b.run();
  b.set("O:1.0/0", 1);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "faulted"), 0);
  b.set("O:1.0/0", 0);
  b.rt->scan(2);
  // "When reset to low (0), the channel disconnects ... This usually causes the connected
  // SCANport device to fault" (chapter 3).
  EXPECT_EQ(observed(b, "DRIVE1", "faulted"), 1);
  EXPECT_EQ(b.u("I:1.0") & (1 << kV), 0);
  EXPECT_EQ(b.u("I:1.2"), 0);  // not valid: no data
}

TEST(Sm1Basic, CableRemovedWhileEnabledFaultsTheDrive) {
  Bench b(sm1_program(kBasic), kOneDrive);
  b.run();
  b.set("O:1.0/0", 1);
  b.rt->scan(2);
  b.inject("DRIVE1", "cable removed");
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0") & 0x0F, 0x07);  // ID 7, V 0
  b.inject("DRIVE1", "cable restored");
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0") & 0x0F, 0x0A);
  EXPECT_EQ(observed(b, "DRIVE1", "faulted"), 1);  // "the connected SCANport device will fault" (chapter 2)
  // A cable pulled from a channel that is not enabled does not fault the drive.
  Bench c(sm1_program(kBasic), kOneDrive);
  c.run();
  c.inject("DRIVE1", "cable removed");
  c.inject("DRIVE1", "cable restored");
  EXPECT_EQ(observed(c, "DRIVE1", "faulted"), 0);
}

TEST(Sm1Basic, AnUnpoweredDriveIsNotConnectedAndPowersUpFromStorage) {
  Bench b(sm1_program(kBasic), "scanport SM1 slot=1 {\n  drive D channel=1 power=off\n}\n");
  b.run();
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0") & 0x07, 7);
  b.inject("D", "online");
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0") & 0x07, 2);  // default port 2
  EXPECT_FALSE(b.rt->inject("D", "warp speed").ok);
  EXPECT_FALSE(b.rt->inject("SM1", "offline").ok);
}

TEST(Sm1Basic, PowerLossStopsTheDriveWithoutAFault) {
  Bench b(sm1_program(kBasic), kOneDrive);
  b.run();
  b.set("O:1.0/0", 1);
  b.set("O:1.2", 0x0002);  // start
  b.set("O:1.3", 10000);
  b.rt->scan(3);
  ASSERT_EQ(observed(b, "DRIVE1", "running"), 1);
  b.inject("DRIVE1", "power off");
  b.rt->scan(1);
  EXPECT_EQ(b.u("I:1.0") & 0x0F, 0x07);
  b.inject("DRIVE1", "power on");
  EXPECT_EQ(observed(b, "DRIVE1", "faulted"), 0);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 0);  // powered up stopped, command memory 0
  // The program still holds the start bit: to the powered-up drive that is a new start edge.
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "reference"), 10000);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 1);
}

// ---- Fault/Program state DIP switches (chapter 2) --------------------------------------------------------------------

struct FaultStateCase {
  std::string option;
  bool enhanced;
  bool faults;            // the drive faults
  std::uint16_t command;  // what the drive then receives
  std::uint16_t reference;
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const FaultStateCase& c, std::ostream* os) {
  *os << c.option << (c.enhanced ? " enhanced" : " basic") << (c.faults ? " faults" : "");
}

class Sm1DipSwitch : public ::testing::TestWithParam<FaultStateCase> {};

TEST_P(Sm1DipSwitch, ProgramModeAndProcessorFaultApplyTheSwitch) {
  const auto& p = GetParam();
  for (Mode leave_run_for : {Mode::Program, Mode::Test, Mode::Faulted}) {
    SCOPED_TRACE(std::string(to_string(leave_run_for)));
    // G file: safe state channel 1 command 0x0002 (start), reference 1000 (Figure 4.8 words 2, 3).
    const std::string slot = p.enhanced ? "SCAN_IN 32 SCAN_OUT 32 ID_CODE 13616 G_FILE 4\n 0 0 2 1000 OPTION ch1=" + p.option
                                        : kBasic + " OPTION ch1=" + p.option;
    // B3:0/1 makes the program divide by zero: major fault 0020h (an overflow trap, S:5/0).
    Bench b(sm1_program(slot, "SOR XIC B3:0/1 DIV 1 0 N7:0 EOR \n"), kOneDrive);
    b.run();
    b.set("O:1.0/0", 1);
    b.set("O:1.2", 0x0002);  // start
    b.set("O:1.3", 5000);
    b.rt->scan(3);
    ASSERT_EQ(observed(b, "DRIVE1", "running"), 1);
    if (leave_run_for == Mode::Faulted) {
      b.set("B3:0/1", 1);
      b.rt->scan(1);
      ASSERT_TRUE(b.rt->fault().has_value());
    } else {
      // Test mode de-energises outputs like Program mode: the switch applies too (decision).
      ASSERT_TRUE(b.rt->set_mode(leave_run_for).ok);
    }
    b.rt->scan(2);
    EXPECT_EQ(observed(b, "DRIVE1", "faulted"), p.faults ? 1 : 0);
    if (!p.faults) {
      // "the channel enable bits ... will retain their last state values": still valid.
      EXPECT_EQ((b.u("I:1.0") >> kV) & 1, 1);
      EXPECT_EQ(observed(b, "DRIVE1", "command"), p.command);
      EXPECT_EQ(observed(b, "DRIVE1", "reference"), p.reference);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Chapter2, Sm1DipSwitch,
    ::testing::Values(FaultStateCase{"fault", true, true, 0, 0}, FaultStateCase{"zero", true, false, 0, 0},
                      FaultStateCase{"hold", true, false, 0x0002, 5000}, FaultStateCase{"safe", true, false, 0x0002, 1000},
                      FaultStateCase{"zero", false, false, 0, 0}, FaultStateCase{"hold", false, false, 0x0002, 5000},
                      // "Safe state data (enhanced mode only), Fault (basic mode only)".
                      FaultStateCase{"safe", false, true, 0, 0}),
    [](const auto& info) { return info.param.option + (info.param.enhanced ? "_enhanced" : "_basic"); });

TEST(Sm1DipSwitchReturn, BackInRunTheImageRulesAgain) {
  Bench b(sm1_program(kEnhanced + " G_FILE 4\n 0 0 2 1000 OPTION ch1=safe"), kOneDrive);
  b.run();
  b.set("O:1.0/0", 1);
  b.set("O:1.3", 5000);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "reference"), 5000);
  ASSERT_TRUE(b.rt->set_mode(Mode::Program).ok);
  b.rt->scan(1);
  EXPECT_EQ(observed(b, "DRIVE1", "reference"), 1000);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 1);  // the safe state starts the drive
  b.run();
  b.rt->scan(1);
  EXPECT_EQ(observed(b, "DRIVE1", "reference"), 5000);
}

// ---- Enhanced mode: M files, messaging (chapter 4, appendix B) ---------------------------------------------------

TEST(Sm1Messaging, M1EchoesTheDipSwitchesAndTheGFileAndIsReadOnly) {
  Bench b(sm1_program(kEnhanced + " G_FILE 4\n 0 1 2 1000 OPTION ch1=zero OPTION ch2=hold OPTION ch3=safe",
                      "SOR XIC B3:0/0 COP #M1:1.0 #N11:0 10 EOR \nSOR XIC B3:0/1 MOV 1 M1:1.100 EOR \n"),
          kOneDrive);
  b.run();
  b.set("B3:0/0", 1);
  b.rt->scan(1);
  EXPECT_EQ(b.u("N11:0"), 0b11'10'01);
  EXPECT_EQ(b.u("N11:1"), 0x0001);
  EXPECT_EQ(b.u("N11:2"), 0x0002);
  EXPECT_EQ(b.u("N11:3"), 1000);
  EXPECT_EQ(b.u("N11:4"), 0);  // beyond the 4-word G file
  EXPECT_EQ(sm1(b).m_file_words(MFile::M0), 800);
  EXPECT_EQ(sm1(b).m_file_words(MFile::M1), 400);
  // "the M1 file is a module input file (read-only)": a write faults the processor (xx55h).
  b.set("B3:0/1", 1);
  b.rt->scan(1);
  ASSERT_TRUE(b.rt->fault().has_value());
  EXPECT_EQ(b.fault_code() & 0x00FF, 0x55);
}

TEST(Sm1Messaging, M0StaIsLowUntilTheModuleHasReadTheBuffer) {
  Bench b(sm1_program(kEnhanced, copy_program()), kOneDrive);
  b.run();
  b.rt->scan(2);
  EXPECT_FALSE(m0_sta(b));  // "the SLC program has not loaded any M0 file data"
  b.set("B3:0/0", 1);
  b.rt->scan(1);
  b.set("B3:0/0", 0);
  ASSERT_TRUE(b.until([&] { return m0_sta(b); }, kM0ReadTime + ms(5)));
  // Any M0 write drops it again while the module reads the change.
  ASSERT_EQ(sm1(b).write_m(MFile::M0, 0, 5), MAccess::Ok);
  EXPECT_FALSE(sm1(b).m0_status());
  b.rt->run_for(kM0ReadTime);
  EXPECT_TRUE(sm1(b).m0_status());
  ASSERT_TRUE(b.until([&] { return m0_sta(b); }, kM0ReadTime + ms(5)));
}

// One message through buffer `buffer` on channel `c`, driving the command bits directly.
void send(Bench& b, int c, int buffer) {
  const std::string word = c == 3 ? "O:1.1" : "O:1.0";
  const int shift = c == 2 ? 8 : 0;
  b.set(word, (b.u(word) & ~(0xFF << shift)) | ((0x02 | (buffer << 2)) << shift));
}
void clear_me(Bench& b, int c) {
  const std::string word = c == 3 ? "O:1.1" : "O:1.0";
  const int shift = c == 2 ? 8 : 0;
  b.set(word, b.u(word) & ~(0x02 << shift));
}

TEST(Sm1Messaging, ReadyBusyDoneHandshakeTakesTheLinkTime) {
  Bench b(sm1_program(kEnhanced, copy_program(3)), kOneDrive);
  b.run();
  // Figure B.4's request in buffer 3.
  load_request(b, {0x000e, 0x000f, 0, 0x0002});
  EXPECT_TRUE(ready(b, 1));
  EXPECT_FALSE(done(b, 1));
  send(b, 1, 3);
  b.rt->scan(1);
  const VirtualTime sent = b.rt->now();
  b.rt->scan(1);
  // BUSY: READY and DONE both 0 ("These status bits should never be high at the same time").
  EXPECT_FALSE(ready(b, 1));
  EXPECT_FALSE(done(b, 1));
  bool both = false;
  ASSERT_TRUE(b.until([&] { both = both || (ready(b, 1) && done(b, 1)); return done(b, 1); }, ms(100)));
  EXPECT_FALSE(both);
  // Request 0 bytes (1 frame) + 2 ms processing + a 6-byte reply (2 frames), 888 us a frame:
  // 4.664 ms
  // after the output scan that sent it (docs/1203-sm1.md, "Timing"); DONE shows at the next
  // input scan.
  const auto t = scanport::link_timing(sm1(b).drive(1));
  EXPECT_EQ(scanport::frames_for(0, t) * scanport::frame_time(t) + t.device_processing + scanport::frames_for(6, t) * scanport::frame_time(t),
            4'664'000);
  EXPECT_GE(b.rt->now() - sent, 4'664'000 - ms(2));
  EXPECT_LE(b.rt->now() - sent, 4'664'000 + ms(2));
  std::uint16_t w = 0;
  ASSERT_EQ(sm1(b).read_m(MFile::M1, 104, w), MAccess::Ok);
  EXPECT_EQ(w, 6);
  ASSERT_EQ(sm1(b).read_m(MFile::M1, 105, w), MAccess::Ok);
  EXPECT_EQ(w, 216);
  // DONE holds while ME is held; clearing ME returns to READY.
  b.rt->scan(5);
  EXPECT_TRUE(done(b, 1));
  clear_me(b, 1);
  b.rt->scan(2);
  EXPECT_TRUE(ready(b, 1));
  EXPECT_FALSE(done(b, 1));
}

TEST(Sm1Messaging, ChannelsShareABufferAndAnswerInTheirOwnResponseBuffers) {
  Bench b(sm1_program(kEnhanced, copy_program(0)),
          "scanport SM1 slot=1 {\n  drive D1 channel=1\n  drive D2 channel=2 parameters=5:3\n}\n");
  b.run();
  load_request(b, {0x000e, 0x000f, 5, 1});
  send(b, 1, 0);
  send(b, 2, 0);
  send(b, 3, 0);  // channel 3 has no drive: 0xFE after the timeout
  ASSERT_TRUE(b.until([&] { return done(b, 1) && done(b, 2); }, ms(100)));
  std::uint16_t w = 0;
  sm1(b).read_m(MFile::M1, 105, w);
  EXPECT_EQ(w, 7);
  sm1(b).read_m(MFile::M1, 205, w);
  EXPECT_EQ(w, 3);
  EXPECT_FALSE(done(b, 3));
  ASSERT_TRUE(b.until([&] { return done(b, 3); }, ms(1100)));
  sm1(b).read_m(MFile::M1, 300, w);
  EXPECT_EQ(w, 0x0014);
  sm1(b).read_m(MFile::M1, 305, w);
  EXPECT_EQ(w, 0x00FE);
  EXPECT_EQ(observed(b, "SM1", "messages", 0), 1);
  EXPECT_EQ(observed(b, "SM1", "messages", 2), 1);
}

TEST(Sm1Messaging, ACablePulledDuringTheTransactionTimesOut) {
  Bench b(sm1_program(kEnhanced, copy_program(0)), kOneDrive);
  b.run();
  load_request(b, {0x000e, 0x000f, 5, 1});
  send(b, 1, 0);
  b.rt->scan(1);
  b.inject("DRIVE1", "cable removed");
  ASSERT_TRUE(b.until([&] { return done(b, 1); }, ms(1100)));
  EXPECT_GT(b.rt->now(), ms(1000));
  std::uint16_t w = 0;
  sm1(b).read_m(MFile::M1, 105, w);
  EXPECT_EQ(w, 0x00FE);
}

TEST(Sm1Messaging, ADeviceThatPadsEveryReplyToSixBytes) {
  // Figure B.2 footnote: "These products always return a length which is a multiple of six."
  // Figure B.5's Read Parameter Value answers 2 bytes from the 1305 model, 6 with pad=6.
  for (int pad : {1, 6}) {
    Bench b(sm1_program(kEnhanced, copy_program(0)),
            "scanport SM1 slot=1 {\n  drive DRIVE1 channel=1" + std::string(pad == 6 ? " pad=6" : "") + "\n}\n");
    b.run();
    load_request(b, {0x000e, 0x000f, 5, 1});
    send(b, 1, 0);
    ASSERT_TRUE(b.until([&] { return done(b, 1); }, ms(100)));
    std::uint16_t len = 0, value = 0;
    sm1(b).read_m(MFile::M1, 104, len);
    sm1(b).read_m(MFile::M1, 105, value);
    EXPECT_EQ(len, pad == 6 ? 6 : 2);
    EXPECT_EQ(value, 7);
  }
}

TEST(Sm1Messaging, MessagingIsIndependentOfDataEnable) {
  // "These functions are independent; you can use either function by itself" (chapter 4):
  // clearing DE during a message faults the drive but does not cut the message.
  Bench b(sm1_program(kEnhanced, copy_program(0)), kOneDrive);
  b.run();
  b.set("O:1.0/0", 1);
  b.rt->scan(2);
  load_request(b, {0x000e, 0x000f, 5, 1});
  send(b, 1, 0);
  b.rt->scan(1);
  b.set("O:1.0/0", 0);
  ASSERT_TRUE(b.until([&] { return done(b, 1); }, ms(100)));
  std::uint16_t w = 0;
  sm1(b).read_m(MFile::M1, 105, w);
  EXPECT_EQ(w, 7);
  EXPECT_EQ(observed(b, "DRIVE1", "faulted"), 1);
}

TEST(Sm1Messaging, ClearingMeWhileBusyEndsReady) {
  Bench b(sm1_program(kEnhanced, copy_program(0)), kOneDrive);
  b.run();
  load_request(b, {0x000e, 0x000f, 0, 2});
  send(b, 1, 0);
  b.rt->scan(1);
  clear_me(b, 1);
  b.rt->run_for(ms(20));
  EXPECT_TRUE(ready(b, 1));
  EXPECT_FALSE(done(b, 1));
  std::uint16_t w = 0;
  sm1(b).read_m(MFile::M1, 105, w);
  EXPECT_EQ(w, 216);  // the response still arrived
}

TEST(Sm1Messaging, SmallerMFilesHoldFewerBuffers) {
  // M0_SIZE 100 holds buffer 0 only: MSG ID 3 sends an empty request (all words 0), which the
  // drive refuses; M1_SIZE 200 has no room for channel 2's response, which is lost, but the
  // handshake still completes (decision).
  Bench b(sm1_program(kEnhanced + " M0_SIZE 100 M1_SIZE 200", copy_program(0)),
          "scanport SM1 slot=1 {\n  drive D1 channel=1\n  drive D2 channel=2\n}\n");
  b.run();
  load_request(b, {0x000e, 0x000f, 5, 1});
  send(b, 1, 3);
  send(b, 2, 0);
  ASSERT_TRUE(b.until([&] { return done(b, 1) && done(b, 2); }, ms(100)));
  std::uint16_t w = 0;
  sm1(b).read_m(MFile::M1, 100, w);
  EXPECT_EQ(w, 0x0014);
  EXPECT_EQ(sm1(b).read_m(MFile::M1, 200, w), MAccess::NoSuchWord);
}

// ---- Datalinks (chapter 4, "Datalinks") ------------------------------------------------------------------------------

TEST(Sm1Datalinks, DataInA1WritesAndDataOutA1ReadsParameter27) {
  // G file word 1 bit 0 = EA1; parameter 111 (Data In A1) and 119 (Data Out A1) = 27, as a HIM
  // would set them.
  Bench b(sm1_program(kEnhanced + " G_FILE 2\n 0 1"),
          "scanport SM1 slot=1 {\n  drive DRIVE1 channel=1 parameters=111:27,119:27\n}\n");
  b.run();
  b.set("O:1.8", 45);
  b.rt->scan(2);
  // "The datalink is only active while the channel's Data Enable bit is also set."
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 27), 0);
  EXPECT_EQ(b.u("I:1.0") & 0xF0, 0);
  b.set("O:1.0/0", 1);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 27), 45);
  EXPECT_EQ(b.u("I:1.8"), 45);
  EXPECT_EQ(b.u("I:1.0") & 0xF0, 0x10);  // A1 valid only: B-D are not enabled
  // A value the parameter cannot take (Preset Freq 7: 0-400) is refused and kept.
  b.set("O:1.8", 500);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 27), 45);
  EXPECT_EQ(observed(b, "DRIVE1", "datalink error"), 6);
}

TEST(Sm1Datalinks, AStoppedOnlyParameterRefusesDatalinkWritesWhileRunning) {
  // Data In A1 = parameter 1 (Maximum Freq, written only while stopped): error 7 while running.
  Bench b(sm1_program(kEnhanced + " G_FILE 2\n 0 1"),
          "scanport SM1 slot=1 {\n  drive DRIVE1 channel=1 parameters=111:1\n}\n");
  b.run();
  b.set("O:1.0/0", 1);
  b.set("O:1.8", 90);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 1), 90);
  b.set("O:1.2", 0x0002);  // start
  b.set("O:1.3", 1000);
  b.set("O:1.8", 100);
  b.rt->scan(2);
  EXPECT_EQ(observed(b, "DRIVE1", "running"), 1);
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 1), 90);
  EXPECT_EQ(observed(b, "DRIVE1", "datalink error"), 7);
}

TEST(Sm1Datalinks, DisabledDatalinksCarryNothing) {
  Bench b(sm1_program(kEnhanced + " G_FILE 2\n 0 0"),
          "scanport SM1 slot=1 {\n  drive DRIVE1 channel=1 parameters=111:27,119:27\n}\n");
  b.run();
  b.set("O:1.0/0", 1);
  b.set("O:1.8", 45);
  b.inject("DRIVE1", "parameter", {"27", "12"});
  b.rt->scan(3);
  EXPECT_EQ(observed(b, "DRIVE1", "parameters", 27), 12);
  EXPECT_EQ(b.u("I:1.8"), 0);
}

// ---- Robustness ----------------------------------------------------------------------------------------------------

TEST(Sm1Robustness, BasicModeHasNoMFilesAnAccessFaultsTheProcessor) {
  Bench b(sm1_program(kBasic, "SOR XIC B3:0/0 MOV 1 M0:1.0 EOR \n"), kOneDrive);
  b.run();
  b.set("B3:0/0", 1);
  b.rt->scan(1);
  EXPECT_EQ(b.fault_code(), 0x0155);  // xx55h with xx = the slot
}

TEST(Sm1Robustness, RandomCommandsAndBuffersNeverBreakTheHandshake) {
  // Arbitrary channel command words, M0 contents (any service, class, length, buffer), mode
  // changes and link faults: the module never crashes, READY and DONE are never both set, and
  // every message ends (DONE or READY) within the timeout.
  std::string slot = kEnhanced + " G_FILE 32\n 0 4095";  // every datalink enabled
  for (int k = 2; k < 32; ++k) slot += " 7";                // safe state data
  slot += " OPTION ch1=hold OPTION ch2=zero OPTION ch3=safe";
  Bench b(sm1_program(slot, "SOR XIC B3:0/0 COP #N10:0 #M0:1.0 10 EOR \nSOR XIC B3:0/1 COP #N10:0 #M0:1.700 10 EOR \n"),
          "scanport SM1 slot=1 {\n  drive D1 channel=1\n  drive D2 channel=2 pad=6\n  drive D3 channel=3 port=6\n}\n");
  b.run();
  std::mt19937 rng(1203);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  // Every draw is its own statement: two draws in one call's arguments come out in an order the
  // compiler chooses (GCC and clang differ), and the sequence must be the same under both.
  // The value is drawn before the address, the order GCC's right-to-left evaluation gave.
  for (int step = 0; step < 3000; ++step) {
    switch (pick(20)) {
      case 0: {
        const auto value = static_cast<std::int16_t>(rng());
        const int word = pick(10);
        b.set("N10:" + std::to_string(word), value);
        break;
      }
      case 1: {
        const int value = pick(0x100);
        const int word = pick(5);
        b.set("N10:" + std::to_string(word), value);
        break;
      }
      case 2: {
        const int value = pick(2);
        const int bit = pick(2);
        b.set("B3:0/" + std::to_string(bit), value);
        break;
      }
      case 3:
        if (!b.rt->fault()) (void)b.rt->set_mode(pick(3) == 0 ? Mode::Program : Mode::Run);
        break;
      case 4: {
        const char* faults[] = {"cable removed", "cable restored", "offline", "online", "message timeout", "normal"};
        const char* fault = faults[pick(6)];
        const int drive = 1 + pick(3);
        b.inject("D" + std::to_string(drive), fault);
        break;
      }
      default: {
        const auto value = static_cast<std::int16_t>(rng());
        const bool second = pick(2) != 0;
        b.set(second ? "O:1.0" : "O:1.1", value);
        break;
      }
    }
    b.rt->scan(1);
    const std::uint16_t w1 = b.u("I:1.1");
    for (int c = 1; c <= 3; ++c) ASSERT_FALSE(((w1 >> (8 + 2 * (c - 1))) & 3) == 3) << "step " << step;
  }
  // Everything settles: with ME cleared no channel stays BUSY past the timeout.
  if (b.rt->fault()) b.rt->clear_fault();
  ASSERT_TRUE(b.rt->set_mode(Mode::Run).ok);
  b.set("O:1.0", 0);
  b.set("O:1.1", 0);
  b.rt->run_for(ms(1200));
  for (int c = 1; c <= 3; ++c) {
    EXPECT_EQ(sm1(b).message_state(c), Sm1Module::MessageState::Ready) << c;
    EXPECT_GT(observed(b, "SM1", "messages", static_cast<std::size_t>(c - 1)), 20) << c;  // it did exercise messaging
  }
}

}  // namespace
}  // namespace softslc::test
