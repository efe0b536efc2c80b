#include "vm/ml_pto.h"

#include "vm/bytecode.h"
#include "vm/data_table.h"

namespace softslc {

namespace {
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::uint16_t bit(int b) { return static_cast<std::uint16_t>(1u << b); }
// The status bits the sub-system owns (everything but RP, EH, CS, JP, JC).
constexpr std::uint16_t kStatusBits = bit(pto::kDoneBit) | bit(pto::kDecelBit) | bit(pto::kRunBit) | bit(pto::kAccelBit) |
                                      bit(pto::kIdleBit) | bit(pto::kErrorBit) | bit(pto::kNormalBit) | bit(pto::kEnableBit) |
                                      bit(pto::kJogPulseStatusBit) | bit(pto::kJogContinuousStatusBit);
}  // namespace

void PulseTrainOutputs::attach(const CompiledProgram& program) {
  const DataTableLayout& layout = *program.layout;
  for (const FunctionFile f : {FunctionFile::PTO, FunctionFile::PTOX}) {
    const FileLayout& fl = layout.function_file(f);
    if (!fl.present) continue;
    file_ = static_cast<int>(f);
    base_ = fl.base;
    elements_ = static_cast<int>(fl.elements);
    layout_ = f == FunctionFile::PTOX ? pto::kPtox : pto::kPto;
  }
  if (file_ < 0) return;
  // The controller's highest output frequency (OFS's range): 20,000 Hz on the MicroLogix 1200/1500
  // (1762-RM001C p. 6-12) and the 1100 Series A, 40,000 on the 1100 Series B (1763-RM001C p. 140);
  // 100,000 on the 1400 [U]. The outputs OUT may name [U]: 2 (1200), 2-3 (1100, 1500), 2-4 (1400).
  const ProcessorModel& p = program.processor;
  switch (p.micrologix) {
    case MicroLogixModel::ML1100: max_frequency_ = p.series >= 'B' ? 40'000 : 20'000; last_output_ = 3; break;
    case MicroLogixModel::ML1400: max_frequency_ = 100'000; last_output_ = 4; break;
    case MicroLogixModel::ML1200: max_frequency_ = 20'000; last_output_ = 2; break;
    default: max_frequency_ = 20'000; last_output_ = 3; break;
  }
  const FileLayout& out = layout.files[0];
  const SlotImage& slot0 = layout.output_slots[0];
  if (out.present && slot0.present && slot0.words > 0) output_word_ = static_cast<std::int64_t>(out.base) + static_cast<std::int64_t>(slot0.first);
}

std::int64_t PulseTrainOutputs::read(const std::uint16_t* e, int word, bool wide) const {
  if (!wide) return e[word];  // OF, OFS, JF on the PTO: 0-65,535 (UINT on the 1100 Series B)
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(e[word]) | static_cast<std::uint32_t>(e[word + 1]) << 16);
}

void PulseTrainOutputs::write(std::uint16_t* e, int word, bool wide, std::int64_t v) const {
  e[word] = static_cast<std::uint16_t>(v & 0xFFFF);
  if (wide) e[word + 1] = static_cast<std::uint16_t>((v >> 16) & 0xFFFF);
}

void PulseTrainOutputs::set_output(std::uint16_t* w, int b, bool on) const {
  if (output_word_ < 0 || b < 0 || b > 15) return;
  std::uint16_t& word = w[output_word_];
  word = static_cast<std::uint16_t>(on ? word | bit(b) : word & ~bit(b));
}

void PulseTrainOutputs::enter_run(std::uint16_t* w) {
  for (int n = 0; n < elements_; ++n) {
    std::uint16_t* e = w + base_ + static_cast<std::size_t>(n) * static_cast<std::size_t>(layout_.words);
    if (state_[static_cast<std::size_t>(n)].running) set_output(w, state_[static_cast<std::size_t>(n)].output, false);
    state_[static_cast<std::size_t>(n)] = Element{};
    e[pto::kBits] = static_cast<std::uint16_t>((e[pto::kBits] & ~kStatusBits) | bit(pto::kIdleBit));
    e[pto::kErrorCode] = 0;
    write(e, layout_.frequency_status, layout_.long_frequencies, 0);
    write(e, layout_.produced, true, 0);
  }
}

// What keeps a start from running, in the order softslc checks it [U]: the output, the frequency,
// the length, the accel/decel pulses (ADP within 0..TOP/2; 1762-RM001C p. 6-12 defines TOP as the
// whole profile, "accel/run/decel inclusive").
std::int16_t PulseTrainOutputs::configuration_error(const std::uint16_t* e) const {
  const auto out = static_cast<std::int16_t>(e[pto::kOutput]);
  if (out < first_output_ || out > last_output_) return kErrorOutput;
  const std::int64_t of = read(e, layout_.frequency, layout_.long_frequencies);
  if (of < 1 || of > max_frequency_) return kErrorFrequency;
  const std::int64_t top = read(e, layout_.total, true);
  if (top < 0) return kErrorLength;
  const std::int64_t adp = read(e, layout_.accel_decel, true);
  if (adp < 0 || adp > top / 2) return kErrorAccelDecel;
  return 0;
}

void PulseTrainOutputs::stop(std::uint16_t* e, Element& s, std::uint16_t* w) {
  set_output(w, s.output, false);
  s.running = false;
  e[pto::kBits] = static_cast<std::uint16_t>(e[pto::kBits] & ~(bit(pto::kRunBit) | bit(pto::kNormalBit)));
  write(e, layout_.frequency_status, layout_.long_frequencies, 0);
}

bool PulseTrainOutputs::idle() const {
  for (int n = 0; n < elements_; ++n)
    if (state_[static_cast<std::size_t>(n)].running) return false;
  return true;
}

void PulseTrainOutputs::scan(int n, bool rung, VirtualTime now, std::uint16_t* w) {
  if (file_ < 0 || n < 0 || n >= elements_) return;
  Element& s = state_[static_cast<std::size_t>(n)];
  std::uint16_t* e = w + base_ + static_cast<std::size_t>(n) * static_cast<std::size_t>(layout_.words);
  std::uint16_t bits = e[pto::kBits];
  const bool was_enabled = bits & bit(pto::kEnableBit);
  bool completed_now = false;

  // 1. Bring a running profile up to `now`.
  if (s.running) {
    const auto elapsed = static_cast<__int128>(now - s.start);
    const auto produced = static_cast<std::int64_t>(std::min<__int128>(elapsed * s.frequency / kNsPerSecond, s.total));
    write(e, layout_.produced, true, produced);
    if (produced >= s.total) {
      stop(e, s, w);
      completed_now = true;
    } else if (bits & bit(pto::kHardStopBit)) {
      // EH: all pulses stop at once and the PTO is in error [U].
      stop(e, s, w);
      e[pto::kErrorCode] = static_cast<std::uint16_t>(kErrorHardStop);
    } else if (bits & bit(pto::kControlStopBit)) {
      // CS: a controlled stop, without an error and without DN [U]; no decel ramp is simulated.
      stop(e, s, w);
    } else {
      // The level of the output now: high in the first half of each period [U].
      const auto half_periods = static_cast<std::int64_t>(elapsed * 2 * s.frequency / kNsPerSecond);
      set_output(w, s.output, half_periods % 2 == 0);
    }
    bits = e[pto::kBits];
  }

  // 2. An error is held until the rung is false with EH clear [U].
  std::int16_t er = static_cast<std::int16_t>(e[pto::kErrorCode]);
  if (er != 0 && !rung && !(bits & bit(pto::kHardStopBit))) er = 0;

  // 3. A start: the rung goes from false to true with the PTO idle (1763-RM001C p. 129: the PTO
  // "must be in an idle state"; the edge is softslc's reading of "the rung ... becomes true" [U]).
  if (rung && !was_enabled && !s.running && er == 0) {
    er = (bits & bit(pto::kHardStopBit)) ? kErrorHardStop : configuration_error(e);
    if (er == 0) {
      s.running = true;
      s.start = now;
      s.output = static_cast<std::int16_t>(e[pto::kOutput]);
      s.frequency = read(e, layout_.frequency, layout_.long_frequencies);
      s.total = read(e, layout_.total, true);
      write(e, layout_.produced, true, 0);
      bits = static_cast<std::uint16_t>(bits & ~bit(pto::kDoneBit));
      if (s.total == 0) {
        s.running = false;
        completed_now = true;
      } else {
        set_output(w, s.output, true);
      }
    }
  }
  e[pto::kErrorCode] = static_cast<std::uint16_t>(er);

  // 4. Status as the manual defines it (1762-RM001C pp. 6-9..6-12, 1766-RM001A p. 146).
  // DN: set when the PTO completes; cleared while the rung is false, except that a completion seen
  // with the rung false stays set until the next scan of the instruction.
  bool done = bits & bit(pto::kDoneBit);
  if (completed_now) done = true;
  else if (!rung) done = false;
  const bool error = er != 0;
  std::uint16_t status = 0;
  if (done) status |= bit(pto::kDoneBit);
  if (s.running) status |= bit(pto::kRunBit);
  if (!s.running && !error) status |= bit(pto::kIdleBit);
  if (error) status |= bit(pto::kErrorBit);
  if (!error && (s.running || done)) status |= bit(pto::kNormalBit);
  if (rung) status |= bit(pto::kEnableBit);
  e[pto::kBits] = static_cast<std::uint16_t>((bits & ~kStatusBits) | status);
  write(e, layout_.frequency_status, layout_.long_frequencies, s.running ? s.frequency : 0);
}

}  // namespace softslc
