#include "vm/pid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace softslc::pid {

namespace {

constexpr double kFullScale = 16383.0;  // CV and unscaled PV/SP: 0-16383 = 0-100 % (RM001G p. 9-4)

std::int16_t s16(std::uint16_t w) { return static_cast<std::int16_t>(w); }
std::uint16_t u16(std::int64_t v) { return static_cast<std::uint16_t>(static_cast<std::int16_t>(v)); }
std::int64_t clamp16(double v) { return std::clamp<std::int64_t>(std::llround(v), -32768, 32767); }

std::string hex2(unsigned v) {
  static const char* d = "0123456789ABCDEF";
  return std::string{d[(v >> 4) & 0xF], d[v & 0xF]} + "H";
}

void set_bit(std::uint16_t& w, std::uint16_t bit, bool on) {
  w = static_cast<std::uint16_t>(on ? (w | bit) : (w & ~bit));
}

void store_integral(std::span<std::uint16_t, kBlockWords> b, double counts) {
  const double scaled = std::clamp(std::round(counts * kIntegralScale), -2147483648.0, 2147483647.0);
  const auto v = static_cast<std::uint32_t>(static_cast<std::int32_t>(scaled));
  b[kIntegralMsw] = static_cast<std::uint16_t>(v >> 16);
  b[kIntegralLsw] = static_cast<std::uint16_t>(v & 0xFFFF);
}

// Table 9.36, in its order; the setpoint check (31H) needs the loop's history and is done when the
// loop computes. Returns the first failing code with a sentence naming the word.
Error check_parameters(std::span<const std::uint16_t, kBlockWords> b, bool slc502, std::string& why) {
  const int lu = s16(b[kLoopUpdate]), kc = s16(b[kGain]), ti = s16(b[kReset]), td = s16(b[kRate]);
  const int smax = s16(b[kSetpointMax]), smin = s16(b[kSetpointMin]), db = s16(b[kDeadband]);
  const int omax = s16(b[kOutputMax]), omin = s16(b[kOutputMin]);
  auto fail = [&](Error e, std::string text) {
    why = std::move(text);
    return e;
  };
  if (slc502) {
    if (lu <= 0 || lu > 255)
      return fail(Error::LoopUpdate, "loop update time (word 13) is " + std::to_string(lu) + "; the SLC 5/02 takes 1-255");
    if (kc <= 0 || kc > 255)
      return fail(Error::Gain, "gain Kc (word 3) is " + std::to_string(kc) + "; the SLC 5/02 takes 1-255");
    if (ti < 0 || ti > 255)
      return fail(Error::Reset, "reset Ti (word 4) is " + std::to_string(ti) + "; the SLC 5/02 takes 0-255");
    if (td < 0 || td > 255)
      return fail(Error::Rate, "rate Td (word 5) is " + std::to_string(td) + "; the SLC 5/02 takes 0-255");
    if (smax > 16383 || smax < -16383)
      return fail(Error::SetpointMax, "setpoint max (word 7) is " + std::to_string(smax) + "; the SLC 5/02 takes -16383 to 16383");
    if (smin > 16383 || smin < -16383)
      return fail(Error::SetpointMin, "setpoint min (word 8) is " + std::to_string(smin) + "; the SLC 5/02 takes -16383 to 16383");
  } else {
    if (lu <= 0 || lu > 1024)
      return fail(Error::LoopUpdate, "loop update time (word 13) is " + std::to_string(lu) + "; it must be 1-1024 (0.01-10.24 s)");
    if (kc < 0) return fail(Error::Gain, "gain Kc (word 3) is " + std::to_string(kc) + "; it must not be negative");
    if (ti < 0) return fail(Error::Reset, "reset Ti (word 4) is " + std::to_string(ti) + "; it must not be negative");
    if (td < 0) return fail(Error::Rate, "rate Td (word 5) is " + std::to_string(td) + "; it must not be negative");
  }
  const bool scaling = smax != 0 || smin != 0;
  // A zero span cannot scale: Smin = Smax (not both zero) is refused with Smin > Smax
  // (docs/semantics.md, "PID").
  if (scaling && smin >= smax)
    return fail(Error::SetpointScale, "setpoint min (word 8, " + std::to_string(smin) +
                                          ") is not below setpoint max (word 7, " + std::to_string(smax) + ")");
  const int db_max = scaling ? smax - smin : 16383;
  if (db < 0 || db > db_max)
    return fail(Error::Deadband, "deadband (word 9) is " + std::to_string(db) + "; it must be 0-" + std::to_string(db_max) +
                                     (scaling ? " (setpoint max - setpoint min)" : ""));
  if (omax < 0 || omax > 100)
    return fail(Error::OutputMax, "output max (word 11) is " + std::to_string(omax) + "%; it must be 0-100");
  if (omin < 0 || omin > 100)
    return fail(Error::OutputMin, "output min (word 12) is " + std::to_string(omin) + "%; it must be 0-100");
  if (omin > omax)
    return fail(Error::OutputLimits, "output min (word 12, " + std::to_string(omin) + "%) is above output max (word 11, " +
                                         std::to_string(omax) + "%)");
  return Error::None;
}

}  // namespace

std::int32_t integral_sum(std::span<const std::uint16_t, kBlockWords> b) {
  return static_cast<std::int32_t>((static_cast<std::uint32_t>(b[kIntegralMsw]) << 16) | b[kIntegralLsw]);
}

Outcome execute(std::span<std::uint16_t, kBlockWords> b, const Execution& x) {
  Outcome out;
  std::uint16_t flags = b[kFlags];
  std::uint16_t state = b[kState];

  // RM001G p. 9-3: "If a PID instruction goes false, the integral term is cleared." EN follows the
  // rung (table 9.23); DN is set only on scans that compute. The next true execution starts the
  // loop afresh.
  if (!x.rung) {
    flags &= static_cast<std::uint16_t>(~(kEN | kDN));
    b[kFlags] = flags;
    store_integral(b, 0.0);
    b[kDerivativeTerm] = 0;
    b[kState] = 0;
    return out;
  }
  flags |= kEN;
  if (x.first_pass) state &= static_cast<std::uint16_t>(~kInitialized);
  const bool initial = (state & kInitialized) == 0;

  std::string why;
  if (Error e = check_parameters(b, x.slc502, why); e != Error::None) {
    b[kErrorCode] = static_cast<std::uint16_t>((static_cast<unsigned>(e) << 8) | (b[kErrorCode] & 0x00FF));
    b[kFlags] = static_cast<std::uint16_t>(flags & ~kDN);
    out.error = e;
    out.message = "PID error " + hex2(static_cast<unsigned>(e)) + ": " + why + " (1747-RM001G p. 9-21, table 9.36)";
    return out;
  }

  // When to compute. Timed mode (TM = 1, p. 9-7): at the loop update rate (word 13, 0.01 s), on
  // the 10 ms clock the timers use; the stamp advances by whole update periods so the average
  // rate is exact, and a whole period missed sets TF (p. 9-11) and restarts the stamp. STI mode
  // (TM = 0): every execution (the STI period is the loop update time).
  const int lu = s16(b[kLoopUpdate]);
  const auto tick = static_cast<std::uint16_t>(x.now / kTick);
  if (flags & kTM) {
    if (!initial) {
      const auto elapsed = static_cast<std::uint16_t>(tick - b[kUpdateStamp]);
      if (elapsed < lu) {
        out.same_until = (x.now / kTick + (lu - elapsed)) * kTick;
        b[kFlags] = static_cast<std::uint16_t>(flags & ~kDN);
        b[kState] = state;
        return out;
      }
      out.same_until = (x.now / kTick + 1) * kTick;
      const bool too_fast = elapsed >= 2 * lu;
      set_bit(flags, kTF, too_fast);
      b[kUpdateStamp] = too_fast ? tick : static_cast<std::uint16_t>(b[kUpdateStamp] + lu);
    } else {
      out.same_until = (x.now / kTick + 1) * kTick;
      b[kUpdateStamp] = tick;
    }
  } else {
    flags &= static_cast<std::uint16_t>(~kTF);
  }

  // Setpoint and its scaling (p. 9-9 table 9.9; the SC bit "is cleared when setpoint scaling
  // values are specified", p. 9-11). Scaling is specified when Smax and Smin are not both zero.
  const int smax = s16(b[kSetpointMax]), smin = s16(b[kSetpointMin]);
  const bool scaling = smax != 0 || smin != 0;
  set_bit(flags, kSC, !scaling);
  const int sp_lo = scaling ? smin : 0, sp_hi = scaling ? smax : 16383;
  int sp = s16(b[kSetpoint]);
  if (sp < sp_lo || sp > sp_hi) {
    // 31H (table 9.36): on the initial execution a fault; afterwards the loop runs on the old
    // setpoint with SP (bit 11) set.
    flags |= kSP;
    if (initial) {
      b[kErrorCode] = static_cast<std::uint16_t>((0x31u << 8) | (b[kErrorCode] & 0x00FF));
      b[kFlags] = static_cast<std::uint16_t>(flags & ~kDN);
      out.error = Error::Setpoint;
      out.message = "PID error 31H: setpoint (word 2) is " + std::to_string(sp) + ", outside " + std::to_string(sp_lo) +
                    " to " + std::to_string(sp_hi) + " on the initial execution (1747-RM001G p. 9-21, table 9.36)";
      return out;
    }
    sp = std::clamp<int>(s16(b[kOldSetpoint]), sp_lo, sp_hi);
  } else {
    flags &= static_cast<std::uint16_t>(~kSP);
    b[kOldSetpoint] = static_cast<std::uint16_t>(sp);
  }
  const double span = scaling ? static_cast<double>(smax - smin) : kFullScale;
  const auto to_counts = [&](double eu) { return scaling ? (eu - smin) * kFullScale / span : eu; };
  const auto to_units = [&](double counts) { return scaling ? smin + counts * span / kFullScale : counts; };

  // Process variable (p. 9-13 table 9.20): PV is set outside 0-16383; the loop uses the clamped value.
  const int pv_raw = x.pv;
  set_bit(flags, kPV, pv_raw < 0 || pv_raw > 16383);
  const double pv = std::clamp(pv_raw, 0, 16383);
  const bool reverse_error = (flags & kCM) != 0;  // E = PV - SP
  const double sp_counts = to_counts(sp);
  const double error = reverse_error ? pv - sp_counts : sp_counts - pv;
  const std::int64_t scaled_pv = clamp16(to_units(pv));
  b[kScaledPv] = u16(scaled_pv);
  b[kScaledError] = u16(std::clamp<std::int64_t>(reverse_error ? scaled_pv - sp : sp - scaled_pv, -32768, 32767));

  // Zero-crossing deadband (p. 9-8/9-9): entered only when the error crosses zero (PV passes
  // through the setpoint) within the band, left when the error leaves it; inside, E counts as 0.
  const double band = to_counts(s16(b[kDeadband]) + (scaling ? smin : 0));
  const bool was_negative = (state & kErrorNegative) != 0;
  bool in_band = (state & kInDeadband) != 0;
  if (band <= 0.0 || std::fabs(error) > band) {
    in_band = false;
  } else if (!in_band && !initial && (error == 0.0 || (error < 0.0) != was_negative)) {
    in_band = true;
  }
  set_bit(state, kInDeadband, in_band);
  set_bit(state, kErrorNegative, error < 0.0);
  set_bit(flags, kDB, in_band);
  const double e = in_band ? 0.0 : error;

  // Gains (p. 9-6, 9-7, 9-10 to 9-11, table 9.1). RG and DA exist on the 5/03 and later only.
  const bool rg = !x.slc502 && (flags & kRG) != 0;
  const bool derivative_on_error = !x.slc502 && (flags & kDA) != 0;
  const double kc = s16(b[kGain]) * (rg ? 0.01 : 0.1);
  const double ti_s = s16(b[kReset]) * (rg ? 0.01 : 0.1) * 60.0;
  const double td_s = s16(b[kRate]) * (x.slc502 ? 0.1 : 0.01) * 60.0;
  const double dt = lu * 0.01;
  const double bias = std::clamp<int>(s16(b[kBias]), -16383, 16383);

  // Derivative (p. 9-2, 9-12): of the PV (DA = 0), signed as the error sees it, or of the error
  // (DA = 1); filtered by a first-order lag whose cut-off is 16 times the derivative corner
  // frequency (time constant Td/16), discretised by backward Euler.
  const double d_input = derivative_on_error ? error : (reverse_error ? pv : -pv);
  double d_term = 0.0;
  if (td_s > 0.0 && !initial) {
    const double tf = td_s / 16.0;
    d_term = (tf * s16(b[kDerivativeTerm]) + kc * td_s * (d_input - s16(b[kDerivativeInput]))) / (tf + dt);
  }
  b[kDerivativeInput] = u16(clamp16(d_input));

  const double p_term = kc * e;
  double integral = integral_sum(b) / kIntegralScale;
  const int omax = s16(b[kOutputMax]), omin = s16(b[kOutputMin]);
  const double upper = omax * kFullScale / 100.0, lower = omin * kFullScale / 100.0;
  const bool limiting = (flags & kOL) != 0;
  const double hi = limiting ? upper : kFullScale, lo = limiting ? lower : 0.0;

  double cv = 0.0;
  if (flags & kAM) {
    // Manual (p. 9-9): the program sets the CV; output limiting still applies. The integral sum
    // tracks so that the return to auto starts from this CV (bumpless): P + I + bias = CV.
    const double manual = x.cv;
    set_bit(flags, kUL, manual > upper);
    set_bit(flags, kLL, manual < lower);
    cv = std::clamp(manual, std::max(lo, 0.0), std::min(hi, kFullScale));
    integral = cv - p_term - bias;
    d_term = 0.0;
  } else {
    double delta_i = 0.0;
    if (ti_s > 0.0 && !initial) delta_i = kc * e * dt / ti_s;
    double calculated = p_term + integral + delta_i + d_term + bias;
    // Anti-reset windup: while the output is held at a limit, the integral does not grow
    // further into it.
    if ((calculated > hi && delta_i > 0.0) || (calculated < lo && delta_i < 0.0)) {
      calculated -= delta_i;
    } else {
      integral += delta_i;
    }
    set_bit(flags, kUL, calculated > upper);
    set_bit(flags, kLL, calculated < lower);
    cv = std::clamp(calculated, std::max(lo, 0.0), std::min(hi, kFullScale));
  }
  store_integral(b, integral);
  b[kDerivativeTerm] = u16(clamp16(d_term));
  const auto cv_word = static_cast<std::int16_t>(std::llround(cv));
  b[kOutputPercent] = static_cast<std::uint16_t>(std::llround(cv_word * 100.0 / kFullScale));
  state |= kInitialized;
  b[kState] = state;
  b[kFlags] = static_cast<std::uint16_t>(flags | kDN);
  out.write_cv = true;
  out.cv = cv_word;
  return out;
}

}  // namespace softslc::pid
