// Helpers for the VM tests: small ladder programs in the export text format, run through the
// public Runtime API exactly as a tool would.
//
// `Plc plc(R"(SOR XIC B3:0/0 OTE B3:0/1 EOR)")` loads a program whose header is a 5/03 with an
// input card in slot 1 (I:1, one word) and an output card in slot 2 (O:2, one word), then the
// given text after "LADDER 2" (more rungs, more LADDER files, DATA blocks). Load or compile
// errors fail the test with the rendered diagnostics.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "parser/loader.h"
#include "vm/disassembler.h"
#include "vm/discrete_io.h"
#include "vm/runtime.h"

namespace softslc::test {

inline constexpr std::string_view kHeader =
    "START 1747-L532\n"
    "SLOT 1 1746-IB16 SCAN_IN 1 SCAN_OUT 0\n"
    "SLOT 2 1746-OB16 SCAN_IN 0 SCAN_OUT 1\n";

inline std::string program_text(std::string_view body, std::string_view header = kHeader) {
  return std::string(header) + "LADDER 2\n" + std::string(body) + "\n";
}

// Loads and compiles; returns the errors as text (empty on success) and the runtime.
inline std::unique_ptr<Runtime> try_build(std::string_view full_text, std::string& errors, RuntimeOptions opts = {}) {
  LoadResult lr = load_program(std::string(full_text), "test.slc");
  if (!lr.ok()) {
    errors = lr.render_diagnostics();
    return nullptr;
  }
  RuntimeResult rr = Runtime::create(*lr.program, std::move(opts));
  if (!rr.ok()) {
    errors = rr.render_errors();
    return nullptr;
  }
  return std::move(rr.runtime);
}

// The scan-time model of a processor with some costs replaced, so a test can place a servicing point
// where it needs one: a slower housekeeping (a target that answers late), a slower MOV.
class SlowModel final : public ScanTimeModel {
 public:
  SlowModel(std::shared_ptr<const ScanTimeModel> base, Nanoseconds housekeeping, Nanoseconds mov = -1)
      : base_(std::move(base)), housekeeping_(housekeeping), mov_(mov) {}
  std::string_view name() const override { return "slow"; }
  Nanoseconds instruction_cost(Opcode op, bool rung_in) const override {
    return op == Opcode::MOV && mov_ >= 0 ? mov_ : base_->instruction_cost(op, rung_in);
  }
  Nanoseconds input_scan_cost(const Module& m) const override { return base_->input_scan_cost(m); }
  Nanoseconds output_scan_cost(const Module& m) const override { return base_->output_scan_cost(m); }
  Nanoseconds housekeeping_cost() const override { return housekeeping_; }
  Nanoseconds per_word_cost(Opcode op) const override { return base_->per_word_cost(op); }
  TransitionCost transition_cost(Opcode op, int variant) const override { return base_->transition_cost(op, variant); }

 private:
  std::shared_ptr<const ScanTimeModel> base_;
  Nanoseconds housekeeping_;
  Nanoseconds mov_;
};

struct Plc {
  std::unique_ptr<Runtime> rt;

  explicit Plc(std::string_view body, RuntimeOptions opts = {}, std::string_view header = kHeader) {
    std::string errors;
    rt = try_build(program_text(body, header), errors, std::move(opts));  // cppcheck-suppress useInitializationList ; the build reports into the local errors
    if (!rt) throw std::runtime_error("program did not build:\n" + errors);
  }

  Runtime* operator->() { return rt.get(); }
  Runtime& operator*() { return *rt; }

  // Shorthands for reading values.
  std::int64_t i(std::string_view a) { return rt->value(a).as_int(); }
  bool b(std::string_view a) { return rt->value(a).as_bool(); }
  double f(std::string_view a) { return rt->value(a).as_double(); }
  void set(std::string_view a, std::int64_t v) {
    auto st = rt->set(a, Value::of_int(v));
    if (!st) throw std::runtime_error(st.message);
  }
  void setf(std::string_view a, double v) {
    auto st = rt->set(a, Value::of_float(v));
    if (!st) throw std::runtime_error(st.message);
  }
  void run() {
    auto st = rt->set_mode(Mode::Run);
    if (!st) throw std::runtime_error(st.message);
  }
  // Enters Run and scans n times.
  void run_scans(int n) {
    if (rt->mode() != Mode::Run) run();
    rt->scan(n);
  }
  std::uint16_t fault_code() const { return rt->fault() ? rt->fault()->code : 0; }
};

// The load or compile errors of a whole program text; empty when it builds.
inline std::string build_errors(std::string_view full_text) {
  std::string errors;
  auto rt = try_build(full_text, errors);
  return rt ? std::string() : errors;
}

// The S:0 arithmetic flags C (1), V (2), Z (4), S (8).
inline int arith_flags(Plc& plc) { return static_cast<int>(plc.i("S:0") & 0xF); }

// `rungs` followed by a rung that samples the overflow trap S:5/0 into B3:1/0 and one that clears
// it, so an intended overflow is visible to the test and does not end in major fault 0020h
// (PT1 20-2).
inline std::string with_trap_sample(std::string_view rungs) {
  return std::string(rungs) + "\nSOR XIC S:5/0 OTE B3:1/0 EOR\nSOR OTU S:5/0 EOR";
}

// A card whose input word counts the times it was read (the input scan, each IIM or REF) and
// which records every output image it is sent.
class CountingInputs : public DiscreteIoModule {
 public:
  using DiscreteIoModule::DiscreteIoModule;
  void input_scan(std::span<std::uint16_t> image) override {
    if (!image.empty()) image[0] = ++reads_;
  }
  bool passive() const override { return false; }  // every input scan differs
  std::vector<std::vector<std::uint16_t>> outputs;
  void output_scan(std::span<const std::uint16_t> image) override {
    outputs.emplace_back(image.begin(), image.end());
    DiscreteIoModule::output_scan(image);
  }

 private:
  std::uint16_t reads_ = 0;
};

// Options that put a CountingInputs card in every slot, collected in `cards` in slot order.
inline RuntimeOptions counting_cards(std::vector<CountingInputs*>& cards) {
  RuntimeOptions opts;
  opts.module_factory = [&cards](const SlotConfig& s) -> std::unique_ptr<Module> {
    auto m = std::make_unique<CountingInputs>(s.slot, s.catalog, s.scan_in, s.scan_out);
    cards.push_back(m.get());
    return m;
  };
  return opts;
}

}  // namespace softslc::test
