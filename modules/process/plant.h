// The bench `process` node: a first-order-plus-dead-time plant (optionally a second lag) that
// reads a control-variable word and writes a process-variable word every period of virtual time.
//
// Design. The plant is a linear state-space model
//   x' = A x + B (u(t - L) + d),   y = C x + offset
// with u the CV word (CV counts, 0-16383 = 0-100 % as the PID writes it), L the dead time, d an
// injected load disturbance, and y the PV word in PV counts. One lag (tau) is the classic FOPDT
// process; a second lag (tau2) makes it second order. The model is discretised exactly for a
// zero-order hold over the sampling period with Eigen: [Ad Bd; 0 I] = exp([A B; 0 0] * T), taken
// once when the bench is read, so each step is a small matrix-vector product and the response at
// the sampling instants is the continuous plant's own (no integration error that would depend on
// the period). The dead time is a FIFO of whole periods. Every period the plant samples the CV
// word, steps, and writes round(y), clamped to a 16-bit word, into the PV word. It runs in every
// processor mode (the physics does not stop when the program does), on the runtime's event
// queue, so runs are reproducible bit for bit. docs/bench-format.md, "Simulated processes".
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "modules/bench/bench.h"
#include "parser/diagnostics.h"
#include "vm/field_process.h"

namespace softslc {

struct PlantConfig {
  std::string name;
  Address cv;                 // the word the plant reads (the PID's control variable)
  Address pv;                 // the word the plant writes (the PID's process variable)
  double gain = 1.0;          // PV counts per CV count at steady state
  Nanoseconds tau = 0;        // first lag
  Nanoseconds tau2 = 0;       // second lag (0: first order)
  Nanoseconds dead_time = 0;
  Nanoseconds period = 10'000'000;  // sampling period (10 ms)
  double offset = 0.0;        // PV when the plant is at rest with CV = 0 (ambient)
  double initial_pv = 0.0;    // PV at time 0, at equilibrium
};

// Reads one `process` node; errors are positioned in the bench file. nullopt after an error.
std::optional<PlantConfig> read_plant_node(const BenchNode& node, DiagnosticList& diags);

// Why `a` is not a 16-bit word of `layout` (the plant's words must be in the program's data
// table), or an empty string.
std::string plant_word_problem(const Address& a, const DataTableLayout& layout);

// A process for RuntimeOptions::field_processes.
std::unique_ptr<FieldProcess> make_plant(const PlantConfig& config);

}  // namespace softslc
