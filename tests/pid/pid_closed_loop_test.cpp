// The PID instruction closed-loop against a simulated first-order-plus-dead-time plant (the bench
// `process` node, modules/process/plant.h), in virtual time through the Runtime exactly as
// `softslc run --bench` and `softslc test` build it.
//
// Expected values come from control theory, not from the code: the open-loop step of a first-order
// lag (63.2 % at one time constant), the proportional-only offset PV = Kc K / (1 + Kc K) x SP, the
// integral action removing that offset, and the overshoot and settling of a PI loop tuned by the
// SIMC rules (Skogestad 2003: Kc = tau / (K (tau_c + theta)), Ti = min(tau, 4 (tau_c + theta)),
// tau_c = theta), which for a setpoint step give a response with little overshoot that settles in
// a few (tau_c + theta).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "modules/module_setup.h"
#include "parser/loader.h"
#include "vm/runtime.h"

namespace softslc::test {
namespace {

constexpr const char* kProgram =
    "START 1747-L532\n"
    "LADDER 2\n"
    "SOR PID N10:0 N7:0 N7:1 EOR\n";

std::unique_ptr<Runtime> build(const std::string& program, const std::string& bench, std::string* errors = nullptr) {
  LoadResult lr = load_program(program, "loop.slc");
  if (!lr.ok()) {
    if (errors) *errors = lr.render_diagnostics();
    return nullptr;
  }
  ModuleSetup s = load_module_setup_text(*lr.program, bench, "loop.bench");
  if (!s.ok()) {
    if (errors) *errors = s.render("loop.slc", lr.source);
    return nullptr;
  }
  RuntimeResult rr = Runtime::create(*lr.program, s.options);
  if (!rr.ok()) {
    if (errors) *errors = rr.render_errors();
    return nullptr;
  }
  return std::move(rr.runtime);
}

struct Loop {
  std::unique_ptr<Runtime> rt;
  explicit Loop(const std::string& bench, const std::string& program = kProgram) {
    std::string errors;
    rt = build(program, bench, &errors);  // cppcheck-suppress useInitializationList ; the build reports into the local errors
    if (!rt) throw std::runtime_error(errors);
  }
  void set(const char* a, std::int64_t v) {
    if (!rt->set(a, Value::of_int(v))) throw std::runtime_error(a);
  }
  std::int64_t get(const char* a) const { return rt->value(a).as_int(); }
  // Runs `seconds` of virtual time, sampling the PV (N7:0) and CV (N7:1) every 100 ms. The
  // runtime runs whole scans, so each sample is taken at the end of the first scan that reaches
  // the next multiple of 100 ms (the samples do not drift by a scan per call).
  void run(double seconds) {
    const int steps = static_cast<int>(std::lround(seconds * 10));
    for (int k = 0; k < steps; ++k) {
      next += milliseconds(100);
      if (next > rt->now()) rt->run_for(next - rt->now());
      pv.push_back(get("N7:0"));
      cv.push_back(get("N7:1"));
    }
  }
  VirtualTime next = 0;
  std::vector<std::int64_t> pv, cv;
};

// A PID control block in timed mode with output limits 0-100 %.
void configure(Loop& l, int sp, int kc, int ti, bool rg, int loop_update = 10) {
  l.set("N10:0", 1 | (rg ? 16 : 0));  // TM, RG
  l.set("N10:2", sp);
  l.set("N10:3", kc);
  l.set("N10:4", ti);
  l.set("N10:11", 100);
  l.set("N10:13", loop_update);
}

const char* kTank = "process TANK cv=N7:1 pv=N7:0 gain=1.0 tau=5s dead_time=500ms period=10ms\n";

TEST(PidPlant, OpenLoopFirstOrderStepReaches63PercentAtOneTimeConstant) {
  // The plant alone: CV held at 10000 by the program (manual mode, no limiting), gain 1, tau 5 s,
  // dead time 0.5 s. The PV is 10000 (1 - e^(-(t - 0.5)/5)): 6321 at 5.5 s, 8647 at 10.5 s.
  Loop l(kTank);
  configure(l, 0, 10, 0, false);
  l.set("N10:0", 1 | 2);  // TM, AM (manual)
  l.set("N7:1", 10000);
  ASSERT_TRUE(l.rt->set_mode(Mode::Run));
  l.run(0.5);
  EXPECT_EQ(l.pv.back(), 0) << "nothing arrives before the dead time";
  l.run(5.0);
  EXPECT_NEAR(l.pv.back(), 6321, 2);
  l.run(5.0);
  EXPECT_NEAR(l.pv.back(), 8647, 2);
}

TEST(PidPlant, ProportionalOnlyLeavesTheTextbookOffset) {
  // Kc 1.0 (RM 9-6: word 3 = 10 x 0.1), plant gain 1, no reset: the loop settles where
  // PV = Kc K / (1 + Kc K) x SP = SP / 2, and CV = Kc (SP - PV) = SP / 2.
  Loop l(kTank);
  configure(l, 8000, 10, 0, false);
  ASSERT_TRUE(l.rt->set_mode(Mode::Run));
  l.run(60);
  EXPECT_NEAR(l.pv.back(), 4000, 2);
  EXPECT_NEAR(l.cv.back(), 4000, 2);
}

TEST(PidPlant, IntegralActionRemovesTheOffsetWithBoundedOvershoot) {
  // SIMC PI for K = 1, tau = 5 s, theta = 0.5 s, tau_c = theta: Kc = 5 / (1 x 1.0) = 5.0 and
  // Ti = min(5, 4 x 1.0) = 4 s. With RG (RM 9-10): Kc 500 x 0.01, Ti 7 x 0.01 min = 4.2 s.
  // The 0 -> 8000 step saturates the CV at 100 % first (P alone asks 40000 counts), which is
  // where anti-reset windup matters: the PV must still not overshoot by more than 10 % of the
  // step, and must settle within 1 % of the setpoint in 20 s (4 time constants) and stay.
  Loop l(kTank);
  configure(l, 8000, 500, 7, true);
  ASSERT_TRUE(l.rt->set_mode(Mode::Run));
  l.run(60);
  ASSERT_FALSE(l.rt->fault().has_value()) << l.rt->fault()->to_string();
  const auto peak = *std::max_element(l.pv.begin(), l.pv.end());
  EXPECT_LE(peak, 8800) << "overshoot within 10 % of the step";
  EXPECT_GT(peak, 7920) << "it does reach the setpoint";
  for (std::size_t k = 200; k < l.pv.size(); ++k) EXPECT_NEAR(l.pv[k], 8000, 80) << "at " << k / 10.0 << " s";
  EXPECT_NEAR(l.pv.back(), 8000, 1) << "no offset once settled";
  EXPECT_NEAR(l.cv.back(), 8000, 2) << "gain 1: the CV that holds PV 8000";
  EXPECT_EQ(*std::max_element(l.cv.begin(), l.cv.end()), 16383) << "the CV saturated during the step";
}

TEST(PidPlant, ALoadDisturbanceIsRejected) {
  // A load of -2000 CV counts (a leak) injected at steady state: the PI loop brings the PV back to
  // the setpoint and the CV rises by the 2000 counts the load takes away.
  Loop l(kTank);
  configure(l, 8000, 500, 7, true);
  ASSERT_TRUE(l.rt->set_mode(Mode::Run));
  l.run(40);
  ASSERT_TRUE(l.rt->inject("TANK", "load", {"-2000"}));
  l.run(5);
  EXPECT_LT(l.pv.back(), 7900) << "the disturbance shows";
  l.run(40);
  EXPECT_NEAR(l.pv.back(), 8000, 1);
  EXPECT_NEAR(l.cv.back(), 10000, 2);
  EXPECT_FALSE(l.rt->inject("TANK", "load", {"lots"}));
  EXPECT_EQ(l.rt->observe("TANK", "pv").value().at(0), l.get("N7:0"));
}

TEST(PidPlant, TheStepResponseIsDeterministic) {
  // Same program, same bench, same calls: the same PV and CV at every sample, bit for bit.
  auto run = [] {
    Loop l(kTank);
    configure(l, 8000, 500, 7, true);
    EXPECT_TRUE(l.rt->set_mode(Mode::Run));
    l.run(30);
    return std::make_pair(l.pv, l.cv);
  };
  const auto a = run();
  const auto b = run();
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

TEST(PidPlant, SecondOrderPlantWithTheDerivativeSettles) {
  // Two 3 s lags and 0.2 s dead time, PID with derivative on the PV (RM 9-12): Kc 2.0, Ti 0.1 min
  // (6 s), Td 0.02 min (1.2 s). It settles to the setpoint without a sustained oscillation.
  Loop l("process OVEN cv=N7:1 pv=N7:0 gain=1 tau=3s tau2=3s dead_time=200ms period=10ms\n");
  configure(l, 6000, 20, 1, false);
  l.set("N10:5", 2);
  ASSERT_TRUE(l.rt->set_mode(Mode::Run));
  l.run(80);
  EXPECT_NEAR(l.pv.back(), 6000, 2);
  const auto peak = *std::max_element(l.pv.begin(), l.pv.end());
  EXPECT_LE(peak, 6000 * 1.25);
}

TEST(PidPlant, BenchErrorsArePositioned) {
  std::string errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=N7:0\n", &errors), nullptr);
  EXPECT_NE(errors.find("needs tau=TIME"), std::string::npos) << errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=I:1.0 tau=1s\n", &errors), nullptr);
  EXPECT_NE(errors.find("overwritten by the input scan"), std::string::npos) << errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=N7:0 tau=1s dead_time=15ms period=10ms\n", &errors), nullptr);
  EXPECT_NE(errors.find("whole number of periods"), std::string::npos) << errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=N7:0 tau=1s gain=x\n", &errors), nullptr);
  EXPECT_NE(errors.find("gain=x: expected a number"), std::string::npos) << errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=N7:0 tau=1s colour=red\n", &errors), nullptr);
  EXPECT_NE(errors.find("colour"), std::string::npos) << errors;
  EXPECT_EQ(build(kProgram, "process P cv=N7:1 pv=N7:90 tau=1s\n", &errors), nullptr);
  EXPECT_NE(errors.find("pv=N7:90 is not a word of the program's data table"), std::string::npos) << errors;
}

}  // namespace
}  // namespace softslc::test
