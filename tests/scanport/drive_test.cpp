// The drive model: scaling formulas (page B-13), non-volatile storage semantics, the speed
// response over virtual time, logic command/status, drive-written parameters, datalinks.
#include "tests/scanport/scanport_test_util.h"

namespace softslc::scanport::test {
namespace {

constexpr std::uint16_t kStop = 1u << 0, kStart = 1u << 1, kClearFaults = 1u << 3, kForward = 1u << 4,
                        kReverse = 1u << 5;
constexpr std::uint16_t kEnabled = 1u << 0, kRunning = 1u << 1, kCommandForward = 1u << 2, kRotatingForward = 1u << 3,
                        kAccelerating = 1u << 4, kDecelerating = 1u << 5, kFaulted = 1u << 7, kAtSpeed = 1u << 8;

Rational q(std::int64_t n, std::int64_t d = 1) { return *make_rational(n, d); }

// ---------------------------------------------------------------------------------------------
// Scaling

TEST(Scaling, AccelTime1OfFigureB8) {
  // Multiplier 1, divisor 10, base 1, offset 0, precision 1; descriptor bit 6 (extended).
  const ScalingFactors f{1, 10, 1, 0, 1};
  // Formula 1: (100 + 0) x 1 x 1 / (10 x 10^1) = 1 -> "1.0" Secs.
  EXPECT_EQ(engineering_value(f, 0x64, true), q(1));
  EXPECT_EQ(display_text(f, 0x64, true), "1.0");
  EXPECT_EQ(display_text(f, 0x03E8, true), "10.0");   // the default
  EXPECT_EQ(display_text(f, 0xEA60, true), "600.0");  // the maximum
  // Formula 2 inverts it.
  EXPECT_EQ(internal_value(f, q(1), true), 0x64);
  EXPECT_EQ(internal_value(f, q(6), true), 600);  // the 0x0258 of the scattered write
  // Formulas 3 and 4 on the same factors: the engineering value counts tenths, and the display
  // places the decimal point one digit from the right, so the text is the same.
  EXPECT_EQ(engineering_value(f, 0x64, false), q(10));
  EXPECT_EQ(display_text(f, 0x64, false), "1.0");
  EXPECT_EQ(internal_value(f, q(10), false), 0x64);
  // Through the drive, with the descriptor's choice of formula.
  Drive d = drive_1305();
  EXPECT_EQ(d.display_text(7), "1.0");
  EXPECT_EQ(d.display_value(7), q(1));
}

TEST(Scaling, AllFourFormulasWithOffsetAndBase) {
  const ScalingFactors f{2, 3, 5, -10, 2};
  // 1: (40 - 10) x 2 x 5 / (3 x 100) = 1.     3: (40 - 10) x 2 x 5 / 3 = 100.
  EXPECT_EQ(engineering_value(f, 40, true), q(1));
  EXPECT_EQ(engineering_value(f, 40, false), q(100));
  EXPECT_EQ(display_text(f, 40, true), "1.00");
  EXPECT_EQ(display_text(f, 40, false), "1.00");
  // 2: 1 x 3 x 100 / (2 x 5) - (-10) = 40.    4: 100 x 3 / (2 x 5) + 10 = 40.
  EXPECT_EQ(internal_value(f, q(1), true), 40);
  EXPECT_EQ(internal_value(f, q(100), false), 40);
  // Fractions stay exact: internal 41 -> 31 x 10 / 300 = 31/30.
  EXPECT_EQ(engineering_value(f, 41, true), q(31, 30));
  EXPECT_EQ(display_text(f, 41, true), "1.03");
  // Round trip over a range of values.
  for (std::int64_t v = -500; v <= 500; ++v) {
    EXPECT_EQ(internal_value(f, *engineering_value(f, v, true), true), v);
    EXPECT_EQ(internal_value(f, *engineering_value(f, v, false), false), v);
    EXPECT_EQ(internal_from_display(f, *display_value(f, v, false), false), v);
  }
}

TEST(Scaling, RoundingAndFormatting) {
  const ScalingFactors one{};
  EXPECT_EQ(internal_value(one, q(2, 3), false), 1);
  EXPECT_EQ(internal_value(one, q(1, 2), false), 1);  // half away from zero
  EXPECT_EQ(internal_value(one, q(-1, 2), false), -1);
  EXPECT_EQ(internal_value(one, q(-1, 3), false), 0);
  EXPECT_EQ(format_fixed(q(1, 3), 2), "0.33");
  EXPECT_EQ(format_fixed(q(-5, 2), 0), "-3");
  EXPECT_EQ(format_fixed(q(1, 20), 1), "0.1");
  EXPECT_EQ(format_fixed(q(-1, 20), 1), "-0.1");
  EXPECT_EQ(format_fixed(q(-1, 1000), 2), "0.00");  // no "-0.00"
  EXPECT_EQ(format_fixed(q(12345), 0), "12345");
  EXPECT_EQ(format_fixed(q(7, 1000), 3), "0.007");
  EXPECT_EQ(format_fixed(q(1), 19), std::nullopt);
}

TEST(Scaling, NoResultRatherThanAWrongOne) {
  EXPECT_EQ(make_rational(1, 0), std::nullopt);
  const ScalingFactors zero_div{1, 0, 1, 0, 0};
  EXPECT_EQ(engineering_value(zero_div, 5, false), std::nullopt);
  const ScalingFactors zero_mul{0, 1, 1, 0, 0};
  EXPECT_EQ(internal_value(zero_mul, q(5), false), std::nullopt);
  const ScalingFactors big{65535, 1, 65535, 0, 0};
  EXPECT_EQ(engineering_value(big, std::numeric_limits<std::int64_t>::max(), false), std::nullopt);
  const ScalingFactors deep{1, 1, 1, 0, 40};
  EXPECT_EQ(engineering_value(deep, 1, true), std::nullopt);
}

TEST(Scaling, ScalingLinksReplaceFactorsWithParameterValues) {
  // Descriptor bit 3: Decel Time 1 takes its multiplier from User Data 1 and its divisor from
  // User Data 2 (attributes 17 and 18 name them).
  DriveDescription desc = builtin_drive("1305");
  auto& p = desc.parameters[7];
  p.descriptor |= descriptor::kScalingLinks;
  p.scaling.multiplier_link = 151;
  p.scaling.divisor_link = 152;
  Drive d(desc);
  ASSERT_EQ(d.write_value(151, 3), ErrorCode::kNone);
  ASSERT_EQ(d.write_value(152, 10), ErrorCode::kNone);
  EXPECT_EQ(d.scaling_factors(8).multiplier, 3);
  EXPECT_EQ(d.display_text(8), "3.0");  // 100 x 3 / (10 x 10)
  // The links appear in Read Full Parameter at N11:27 and N11:28.
  const Words w = encode_response(transact(&d, make_request(0x01, 0x0F, 8, 0)));
  EXPECT_EQ(w[27], 151);
  EXPECT_EQ(w[28], 152);
  // A linked divisor of 0 has no engineering value.
  ASSERT_EQ(d.write_value(152, 0), ErrorCode::kNone);
  EXPECT_EQ(d.display_value(8), std::nullopt);
  // Without bit 3 the links are ignored.
  desc.parameters[7].descriptor &= static_cast<std::uint16_t>(~descriptor::kScalingLinks);
  Drive plain(desc);
  EXPECT_EQ(plain.scaling_factors(8).multiplier, 1);
}

// ---------------------------------------------------------------------------------------------
// Non-volatile storage

TEST(Storage, SaveRestoreResetPowerCycle) {
  Drive d = drive_1305();
  ASSERT_EQ(d.write_value(8, 500), ErrorCode::kNone);
  EXPECT_EQ(d.value(8), 500);
  EXPECT_EQ(d.stored_value(8), 100);  // a write changes RAM only
  ASSERT_EQ(d.restore(), ErrorCode::kNone);
  EXPECT_EQ(d.value(8), 100);

  ASSERT_EQ(d.write_value(8, 500), ErrorCode::kNone);
  ASSERT_EQ(d.save(), ErrorCode::kNone);
  EXPECT_EQ(d.stored_value(8), 500);
  ASSERT_EQ(d.write_value(8, 700), ErrorCode::kNone);
  d.power_cycle();
  EXPECT_EQ(d.value(8), 500);  // power-up loads storage

  ASSERT_EQ(d.reset_to_defaults(), ErrorCode::kNone);
  EXPECT_EQ(d.value(8), 1000);
  EXPECT_EQ(d.stored_value(8), 1000);  // "EEPROM and RAM"
  EXPECT_EQ(d.value(5), 1);            // Freq Select 1's default
  d.power_cycle();
  EXPECT_EQ(d.value(8), 1000);
}

TEST(Storage, LinksAreStoredLikeValues) {
  Drive d = drive_1305();
  ASSERT_EQ(d.write_link(5, 9), ErrorCode::kNone);
  ASSERT_EQ(d.save(), ErrorCode::kNone);
  ASSERT_EQ(d.write_link(5, 10), ErrorCode::kNone);
  ASSERT_EQ(d.restore(), ErrorCode::kNone);
  EXPECT_EQ(d.link(5), 9);
  ASSERT_EQ(d.write_link(5, 0), ErrorCode::kNone);  // 0 removes it
  EXPECT_EQ(d.link(5), 0);
  ASSERT_EQ(d.reset_to_defaults(), ErrorCode::kNone);
  EXPECT_EQ(d.link(5), 0);
  EXPECT_EQ(d.stored_link(5), 0);
}

TEST(Storage, ReadOnlyParametersAreNeverStoredOrReset) {
  DriveDescription desc = builtin_drive("1305");
  desc.parameters[44].value = 7;  // Drive Type, read-only, default 3
  Drive d(desc);
  ASSERT_EQ(d.reset_to_defaults(), ErrorCode::kNone);
  EXPECT_EQ(d.value(45), 7);
  EXPECT_EQ(d.write_value(45, 3), ErrorCode::kServiceFailed);
}

// ---------------------------------------------------------------------------------------------
// Speed response and logic

TEST(Speed, FirstOrderResponseToTheReference) {
  Drive d = drive_1305();
  EXPECT_EQ(d.logic_status(), kEnabled | kCommandForward | kRotatingForward);
  d.set_reference(32767);
  d.set_logic_command(kStart);
  EXPECT_EQ(d.logic_status(), kEnabled | kRunning | kCommandForward | kRotatingForward | kAccelerating);
  EXPECT_EQ(d.feedback(), 0);
  // One time constant (500 ms): 1 - (1 - 1/500)^500 = 63.2 % of full scale.
  d.advance_to(milliseconds(500));
  EXPECT_GE(d.feedback(), 20'600);
  EXPECT_LE(d.feedback(), 20'800);
  EXPECT_TRUE(d.logic_status() & kAccelerating);
  EXPECT_FALSE(d.logic_status() & kAtSpeed);
  // Within the 0.5 % band after ln(200) = 5.3 time constants.
  d.advance_to(milliseconds(2700));
  EXPECT_TRUE(d.logic_status() & kAtSpeed);
  // Exactly on the reference once the step rounds to nothing.
  d.advance_to(seconds(10));
  EXPECT_EQ(d.feedback(), 32767);
  EXPECT_EQ(d.logic_status(), kEnabled | kRunning | kCommandForward | kRotatingForward | kAtSpeed);
  // The drive keeps its parameters current: Output Freq 120.00 Hz, Freq Command 120.00 Hz.
  EXPECT_EQ(d.value(2), 12000);
  EXPECT_EQ(d.display_text(2), "120.00");
  EXPECT_EQ(d.value(3), 12000);
  EXPECT_EQ(d.value(4), d.logic_status());
  // A new reference: half speed.
  d.set_reference(16384);
  EXPECT_EQ(d.value(3), 6000);  // 16384 / 32767 x 120 Hz = 60.0018 Hz
  EXPECT_TRUE(d.logic_status() & kDecelerating);
  d.advance_to(seconds(20));
  EXPECT_EQ(d.feedback(), 16384);
  // Stop: the speed decays to 0 and the drive counts as running until it gets there.
  d.set_logic_command(kStop);
  EXPECT_TRUE(d.running());
  EXPECT_EQ(d.logic_status() & (kRunning | kDecelerating), kRunning | kDecelerating);
  d.advance_to(seconds(30));
  EXPECT_EQ(d.feedback(), 0);
  EXPECT_FALSE(d.running());
  EXPECT_EQ(d.value(2), 0);
}

// The frequency parameters are kept from the reference (and feedback) and the Maximum Freq
// parameter: a new Maximum Freq with the same reference, a reset to defaults and a restore each
// give the frequency the new maximum stands for, and the same inputs give the same value again.
TEST(Speed, FrequencyParametersFollowMaximumFreqChangesAtAnUnchangedReference) {
  Drive d = drive_1305();
  d.set_reference(16384);
  EXPECT_EQ(d.value(3), 6000);  // 16384 / 32767 x 120 Hz
  EXPECT_EQ(d.write_value(1, 60), ErrorCode::kNone);  // stopped: Maximum Freq may change
  EXPECT_EQ(d.value(3), 3000);  // the same reference now stands for 30.00 Hz
  d.set_reference(16384);
  EXPECT_EQ(d.value(3), 3000);
  EXPECT_EQ(d.save(), ErrorCode::kNone);
  EXPECT_EQ(d.write_value(1, 240), ErrorCode::kNone);
  EXPECT_EQ(d.value(3), 12000);
  EXPECT_EQ(d.restore(), ErrorCode::kNone);  // back to the stored 60 Hz
  EXPECT_EQ(d.value(1), 60);
  EXPECT_EQ(d.value(3), 3000);
  EXPECT_EQ(d.reset_to_defaults(), ErrorCode::kNone);  // default Maximum Freq: 60 Hz
  EXPECT_EQ(d.value(3), 3000);
  EXPECT_EQ(d.write_value(1, 120), ErrorCode::kNone);
  EXPECT_EQ(d.value(3), 6000);
}

TEST(Speed, StateDoesNotDependOnHowTimeIsAdvanced) {
  auto make = [] {
    Drive d = drive_1305();
    d.set_reference(30000);
    d.set_logic_command(kStart);
    return d;
  };
  Drive coarse = make(), fine = make();
  const VirtualTime checkpoints[] = {milliseconds(1), milliseconds(250) + 3, milliseconds(777), seconds(2), seconds(9)};
  VirtualTime t = 0;
  for (VirtualTime c : checkpoints) {
    coarse.advance_to(c);
    while (t < c) {
      t = std::min(c, t + 1 + (t * 7919) % 3'000'000);  // irregular steps
      fine.advance_to(t);
    }
    EXPECT_EQ(coarse.feedback(), fine.feedback()) << c;
    EXPECT_EQ(coarse.logic_status(), fine.logic_status()) << c;
  }
}

TEST(Speed, UpdatesHappenAtFixedInstants) {
  Drive d = drive_1305();
  d.set_reference(32767);
  d.set_logic_command(kStart);
  d.advance_to(999'999);  // before the first update at 1 ms
  EXPECT_EQ(d.feedback(), 0);
  d.advance_to(milliseconds(1));
  EXPECT_EQ(d.feedback(), 66);  // 32767 / 500, rounded
  EXPECT_THROW(d.advance_to(5), TimeWentBackwards);
}

TEST(Logic, StartIsAnEdgeStopIsALevel) {
  Drive d = drive_1305();
  d.set_reference(1000);
  d.set_logic_command(kStart);
  EXPECT_TRUE(d.logic_status() & kRunning);
  d.set_logic_command(kStart | kStop);  // stop wins
  d.advance_to(seconds(5));
  EXPECT_FALSE(d.running());
  d.set_logic_command(kStart);  // start still held: no new edge
  EXPECT_FALSE(d.running());
  d.set_logic_command(0);
  d.set_logic_command(kStart);
  EXPECT_TRUE(d.running());
}

TEST(Logic, DirectionAndReverseRotation) {
  Drive d = drive_1305();
  d.set_reference(20000);
  d.set_logic_command(kStart | kReverse);
  EXPECT_FALSE(d.logic_status() & kCommandForward);
  d.advance_to(seconds(10));
  EXPECT_EQ(d.feedback(), 20000);  // feedback is the magnitude
  EXPECT_EQ(d.logic_status() & (kCommandForward | kRotatingForward | kAtSpeed), kAtSpeed);
  // Forward while turning in reverse: decelerate through zero, then accelerate forward.
  d.set_logic_command(kForward);
  EXPECT_TRUE(d.logic_status() & kDecelerating);
  d.advance_to(seconds(20));
  EXPECT_EQ(d.logic_status() & (kCommandForward | kRotatingForward | kAtSpeed),
            kCommandForward | kRotatingForward | kAtSpeed);
  // Both direction bits keep the direction.
  d.set_logic_command(kForward | kReverse);
  EXPECT_TRUE(d.logic_status() & kCommandForward);
}

TEST(Logic, FaultStopsAndNeedsAClearAndANewStart) {
  Drive d = drive_1305();
  d.set_reference(32767);
  d.set_logic_command(kStart);
  d.advance_to(seconds(1));
  d.fault(42);
  EXPECT_EQ(d.logic_status() & (kEnabled | kFaulted), kFaulted);
  EXPECT_EQ(d.value(40), 42);  // Last Fault
  d.set_logic_command(0);
  d.set_logic_command(kStart);  // ignored while faulted
  d.advance_to(seconds(10));
  EXPECT_FALSE(d.running());
  d.set_logic_command(kClearFaults);
  EXPECT_EQ(d.logic_status() & (kEnabled | kFaulted), kEnabled);
  d.set_logic_command(kStart);
  EXPECT_TRUE(d.running());
  // A power cycle clears everything but storage.
  d.power_cycle();
  EXPECT_FALSE(d.running());
  EXPECT_EQ(d.logic_command(), 0);
  EXPECT_EQ(d.reference(), 0);
  EXPECT_EQ(d.feedback(), 0);
}

TEST(Logic, ReferenceAboveFullScaleIsFullSpeed) {
  Drive d = drive_1305();
  d.set_reference(0xFFFF);
  d.set_logic_command(kStart);
  d.advance_to(seconds(10));
  EXPECT_EQ(d.feedback(), 32767);
  EXPECT_EQ(d.value(3), 12000);
}

// ---------------------------------------------------------------------------------------------
// Datalinks

TEST(Datalinks, DataInWritesAndDataOutReadsTheSelectedParameters) {
  Drive d = drive_1305();
  // Chapter 4: "set parameter 111 (Data In A1) to 27" - here A1 carries Decel Time 1 (8).
  ASSERT_EQ(d.write_value(111, 8), ErrorCode::kNone);
  EXPECT_EQ(d.write_datalink(0, 250), ErrorCode::kNone);
  EXPECT_EQ(d.value(8), 250);
  // Out of range and read-only targets are refused and keep their value.
  ASSERT_EQ(d.write_value(111, 7), ErrorCode::kNone);
  EXPECT_EQ(d.write_datalink(0, 60001), ErrorCode::kValueOutOfRange);
  EXPECT_EQ(d.value(7), 0x64);
  ASSERT_EQ(d.write_value(111, 2), ErrorCode::kNone);
  EXPECT_EQ(d.write_datalink(0, 5), ErrorCode::kServiceFailed);
  // A datalink word whose Data In parameter is 0 goes nowhere.
  EXPECT_EQ(d.write_datalink(1, 1234), ErrorCode::kNone);
  // Data Out A1 (119) = Output Freq (2).
  ASSERT_EQ(d.write_value(119, 2), ErrorCode::kNone);
  d.set_reference(32767);
  d.set_logic_command(kStart);
  d.advance_to(seconds(10));
  EXPECT_EQ(d.read_datalink(0), 12000);
  EXPECT_EQ(d.read_datalink(1), 0);  // Data Out A2 = 0
  // Signed parameters travel as two's complement words.
  ASSERT_EQ(d.write_value(112, 151), ErrorCode::kNone);
  ASSERT_EQ(d.write_value(120, 151), ErrorCode::kNone);
  EXPECT_EQ(d.write_datalink(1, 0xFFFF), ErrorCode::kNone);
  EXPECT_EQ(d.value(151), -1);
  EXPECT_EQ(d.read_datalink(1), 0xFFFF);
  // Datalink parameters can also be set by message, as a HIM would.
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 113, 1, bytes_of({9}))).error(), ErrorCode::kNone);
  EXPECT_EQ(d.write_datalink(2, 77), ErrorCode::kNone);
  EXPECT_EQ(d.value(9), 77);
}

TEST(Datalinks, DriveWithoutDatalinks) {
  DriveDescription desc = builtin_drive("1305");
  desc.data_in.fill(0);
  desc.data_out.fill(0);
  Drive d(desc);
  EXPECT_EQ(d.write_datalink(0, 1), ErrorCode::kServiceNotSupported);
  EXPECT_EQ(d.read_datalink(0), 0);
  EXPECT_EQ(d.write_datalink(-1, 1), ErrorCode::kServiceNotSupported);
  EXPECT_EQ(d.write_datalink(8, 1), ErrorCode::kServiceNotSupported);
}

// ---------------------------------------------------------------------------------------------
// The shipped database

TEST(Database1305, ShapeAndManualValues) {
  Drive d = drive_1305();
  EXPECT_EQ(d.parameter_count(), 216);
  EXPECT_EQ(d.parameter(5)->name, "Freq Select 1");
  EXPECT_EQ(d.enum_string(5, 1), "Remote Pot  ");
  EXPECT_EQ(d.parameter(7)->name, "Accel Time 1");
  EXPECT_EQ(d.parameter(7)->units, "Secs");
  EXPECT_EQ(d.parameter(7)->descriptor, 0x0064);
  EXPECT_EQ(d.parameter(111)->name, "Data In A1");
  EXPECT_EQ(d.parameter(119)->name, "Data Out A1");
  EXPECT_EQ(d.product().number, 3);
  EXPECT_EQ(d.product().series, 1);
  EXPECT_EQ(d.product().software_versions, std::vector<std::uint16_t>{0x00CA});
  EXPECT_EQ(builtin_drive_names(), std::vector<std::string>{"1305"});
  // Every parameter the manual shows says where it comes from.
  for (int n : {1, 2, 3, 5, 6, 7}) EXPECT_NE(d.parameter(n)->source.find("Figure B."), std::string::npos) << n;
}

}  // namespace
}  // namespace softslc::scanport::test
