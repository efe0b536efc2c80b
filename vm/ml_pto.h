// The MicroLogix pulse train outputs: the PTO sub-system behind the PTO/PTOX function file and the
// PTO/PTOX instruction (docs/semantics.md "The PTO function file").
//
// Design. On the controller the PTO is a parallel sub-system: the ladder talks to it only by
// scanning a PTO instruction, whose scans start it and refresh its status (1763-RM001C p. 129:
// status is "updated each time the PTO instruction is scanned while it is running"). softslc keeps
// exactly that interface. A start records the virtual time and the profile (OUT, OF, TOP latched);
// from then on every quantity is a function of virtual time, computed with integer arithmetic when
// the instruction is scanned: pulses produced = floor(elapsed * OF / 1 s), capped at TOP; the output
// level is high in the first half of each period. Nothing runs between scans, so there is no event
// to schedule and no wall clock; the same program and inputs give the same pulses, status and
// output image at the same virtual times. The output image bit O:0/OUT shows the pulse level at
// each scan of the instruction (what a scan could sample); OPP counts every pulse, also those no
// scan sees. Accel/decel (ADP, RP) are validated but not ramped [U]; jog is not simulated.
//
// The state per element is a few integers (no allocation); the interpreter owns one
// PulseTrainOutputs and calls scan() from the PTO/PTOX handler.
#pragma once

#include <array>
#include <cstdint>

#include "parser/address.h"
#include "vm/virtual_time.h"

namespace softslc {

struct CompiledProgram;

class PulseTrainOutputs {
 public:
  // Finds the PTO or PTOX file and the embedded output word O:0.0 in the program's layout; absent
  // (present() false) on processors without one.
  void attach(const CompiledProgram& program);
  bool present() const { return file_ >= 0; }
  // Entering Run: every element idle (IS set; DN, RS, ED, NS, EN and the other status bits clear, ER,
  // OFS and OPP 0) and its output low [U].
  void enter_run(std::uint16_t* w);
  // A scan of PTO n (PTOX n) with rung condition `rung` at virtual time `now`.
  void scan(int n, bool rung, VirtualTime now, std::uint16_t* w);
  // No element is producing pulses. An idle element's scan is a function of its function-file
  // words and the rung alone (a running one's status and output follow virtual time), which lets
  // the runtime repeat scans of a program with a PTO (docs/semantics.md "Repeated scans").
  bool idle() const;

  // Error codes in PTO:n.ER (docs/semantics.md "The PTO function file": the manual's error table was
  // not reached; these numbers are softslc's [U]).
  static constexpr std::int16_t kErrorOutput = -1;      // OUT is not a pulse train output of this controller
  static constexpr std::int16_t kErrorHardStop = 1;     // EH set while running (or at a start)
  static constexpr std::int16_t kErrorFrequency = 3;    // OF out of 1..the controller's maximum
  static constexpr std::int16_t kErrorAccelDecel = 4;   // ADP < 0 or ADP > TOP / 2
  static constexpr std::int16_t kErrorLength = 7;       // TOP < 0

 private:
  struct Element {
    bool running = false;
    VirtualTime start = 0;
    std::int64_t frequency = 0;  // Hz, latched at the start
    std::int64_t total = 0;      // pulses, latched at the start
    int output = -1;             // O:0.0 bit, latched at the start
  };
  std::int64_t read(const std::uint16_t* e, int word, bool wide) const;
  void write(std::uint16_t* e, int word, bool wide, std::int64_t v) const;
  void set_output(std::uint16_t* w, int bit, bool on) const;
  void stop(std::uint16_t* e, Element& s, std::uint16_t* w);
  std::int16_t configuration_error(const std::uint16_t* e) const;

  int file_ = -1;               // FunctionFile number (PTO or PTOX), -1 when absent
  std::uint32_t base_ = 0;      // first word of element 0
  int elements_ = 0;
  pto::Layout layout_{};
  std::int64_t max_frequency_ = 0;
  int first_output_ = 2, last_output_ = 2;  // the outputs OUT may name
  std::int64_t output_word_ = -1;           // O:0.0 in the data table
  std::array<Element, pto::kPtoxElements> state_{};
};

}  // namespace softslc
