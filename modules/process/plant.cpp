#include "modules/process/plant.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <deque>
#include <system_error>

#include "parser/loader.h"
#include "vm/duration.h"

namespace softslc {

namespace {

// Limits that keep a bench file from asking for unbounded work or memory: the dead-time FIFO
// holds dead_time / period samples.
constexpr Nanoseconds kMinPeriod = 1'000'000;            // 1 ms
constexpr Nanoseconds kMaxPeriod = 10'000'000'000;       // 10 s
constexpr Nanoseconds kMaxTime = 3'600'000'000'000;      // lags and dead time up to 1 h
constexpr std::int64_t kMaxDelaySamples = 100'000;

std::optional<double> read_real(BenchReader& r, std::string_view key, double lo, double hi) {
  auto t = r.text(key);
  if (!t) return std::nullopt;
  double v = 0.0;
  const std::string& s = *t;
  const char* e = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), e, v);
  if (ec != std::errc() || p != e || !std::isfinite(v) || v < lo || v > hi) {
    auto text = [](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", x);
      return std::string(buf);
    };
    r.error_at(key, std::string(key) + "=" + *t + ": expected a number " + text(lo) + " to " + text(hi));
    return std::nullopt;
  }
  return v;
}

std::optional<Address> read_word_address(BenchReader& r, std::string_view key, bool output_allowed) {
  auto t = r.text(key);
  if (!t) return std::nullopt;
  std::string why;
  auto a = parse_address(*t, &why);
  const bool file_ok = a && (a->type == FileType::Integer || a->type == FileType::Bit ||
                             (output_allowed && a->type == FileType::Output));
  if (!a || !file_ok || a->has_bit() || a->is_indirect() || a->indexed) {
    r.error_at(key, std::string(key) + "=" + *t + ": expected a direct word address of an N or B file" +
                        (output_allowed ? " or an O: word" : "") +
                        (a ? "" : " (" + why + ")") +
                        (!output_allowed ? "; an I: word would be overwritten by the input scan" : ""));
    return std::nullopt;
  }
  return a;
}

class Plant final : public FieldProcess {
 public:
  explicit Plant(const PlantConfig& c) : c_(c) {
    // Continuous model: one or two lags in series, gain on the first.
    const bool second = c_.tau2 > 0;
    const int n = second ? 2 : 1;
    const double t1 = static_cast<double>(c_.tau) * 1e-9;
    const double t2 = static_cast<double>(c_.tau2) * 1e-9;
    const double period = static_cast<double>(c_.period) * 1e-9;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    c_out_ = Eigen::RowVectorXd::Zero(n);
    // A lag of time constant 0 is a pass-through: modelled as a very fast lag (1 us), whose
    // discretisation over the period is exact to double precision.
    const double k1 = 1.0 / std::max(t1, 1e-6);
    a(0, 0) = -k1;
    b(0) = c_.gain * k1;
    if (second) {
      const double k2 = 1.0 / std::max(t2, 1e-6);
      a(1, 0) = k2;
      a(1, 1) = -k2;
      c_out_(1) = 1.0;
    } else {
      c_out_(0) = 1.0;
    }
    // Zero-order-hold discretisation: exp of the augmented matrix [[A, B], [0, 0]] * T.
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + 1, n + 1);
    m.topLeftCorner(n, n) = a * period;
    m.topRightCorner(n, 1) = b * period;
    const Eigen::MatrixXd e = m.exp();
    ad_ = e.topLeftCorner(n, n);
    bd_ = e.topRightCorner(n, 1);
    // At rest at initial_pv: every lag holds the same deviation, and the dead-time line holds the
    // CV that keeps it there.
    const double deviation = c_.initial_pv - c_.offset;
    x_ = Eigen::VectorXd::Constant(n, deviation);  // with two lags both hold it
    const double u0 = c_.gain != 0.0 ? deviation / c_.gain : 0.0;
    delay_.assign(static_cast<std::size_t>(c_.dead_time / c_.period), u0);
  }

  std::string name() const override { return c_.name; }

  std::string attach(FieldProcessHost& host) override {
    host_ = &host;
    if (std::string why = plant_word_problem(c_.cv, host.layout()); !why.empty()) return "cv=" + why;
    if (std::string why = plant_word_problem(c_.pv, host.layout()); !why.empty()) return "pv=" + why;
    cv_word_ = host.layout().locate(c_.cv)->word;
    pv_word_ = host.layout().locate(c_.pv)->word;
    write_pv();
    host.schedule_at(host.now() + c_.period, [this](VirtualTime t) { step(t); });
    return {};
  }

  DeviceStatus inject(const DeviceFault& f) override {
    if (f.device != c_.name) return {};
    if (f.fault == "load" && f.args.size() == 1) {
      double v = 0.0;
      const std::string& s = f.args[0];
      auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v) || std::fabs(v) > 1e6)
        return DeviceStatus::refused("load " + s + ": expected a number of CV counts");
      disturbance_ = v;
      return DeviceStatus::done();
    }
    if (f.fault == "normal" && f.args.empty()) {
      disturbance_ = 0.0;
      return DeviceStatus::done();
    }
    return DeviceStatus::refused("a process takes 'load COUNTS' (a load disturbance added to its CV) or 'normal'");
  }

  std::optional<std::vector<std::int64_t>> observe(std::string_view device, std::string_view what) const override {
    if (device != c_.name) return std::nullopt;
    if (what == "pv") return std::vector<std::int64_t>{pv_value()};
    if (what == "steps") return std::vector<std::int64_t>{steps_};
    return std::nullopt;
  }

 private:
  std::int64_t pv_value() const {
    const double y = (c_out_ * x_)(0) + c_.offset;
    return std::clamp<std::int64_t>(std::llround(y), -32768, 32767);
  }
  void write_pv() { host_->write_word(pv_word_, static_cast<std::uint16_t>(static_cast<std::int16_t>(pv_value()))); }

  void step(VirtualTime t) {
    const double u = static_cast<std::int16_t>(host_->read_word(cv_word_));
    double applied = u;
    if (!delay_.empty()) {
      delay_.push_back(u);
      applied = delay_.front();
      delay_.pop_front();
    }
    x_ = ad_ * x_ + bd_ * (applied + disturbance_);
    ++steps_;
    write_pv();
    host_->schedule_at(t + c_.period, [this](VirtualTime next) { step(next); });
  }

  PlantConfig c_;
  FieldProcessHost* host_ = nullptr;
  std::uint32_t cv_word_ = 0, pv_word_ = 0;
  Eigen::MatrixXd ad_;
  Eigen::VectorXd bd_;
  Eigen::RowVectorXd c_out_;
  Eigen::VectorXd x_;
  std::deque<double> delay_;
  double disturbance_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace

std::optional<PlantConfig> read_plant_node(const BenchNode& node, DiagnosticList& diags) {
  BenchReader r(node, diags);
  PlantConfig c;
  c.name = node.name;
  if (node.name.empty()) r.error("a process needs a name (tests reach it by name): process NAME cv=... pv=...");
  if (!node.children.empty()) r.error("a process has no child nodes");
  r.require("cv", "WORD (the control variable the plant reads, e.g. N7:1)");
  r.require("pv", "WORD (the process variable the plant writes, e.g. N7:0)");
  r.require("tau", "TIME (the plant's time constant, e.g. 5s)");
  if (auto a = read_word_address(r, "cv", true)) c.cv = *a;
  if (auto a = read_word_address(r, "pv", false)) c.pv = *a;
  if (auto v = read_real(r, "gain", -100.0, 100.0)) c.gain = *v;
  if (auto v = read_real(r, "offset", -32768.0, 32767.0)) c.offset = *v;
  if (auto v = read_real(r, "initial_pv", -32768.0, 32767.0)) c.initial_pv = *v;
  else c.initial_pv = c.offset;
  auto time = [&](std::string_view key, Nanoseconds lo, Nanoseconds hi, Nanoseconds& out) {
    if (auto d = r.duration(key)) {
      if (*d < lo || *d > hi)
        r.error_at(key, std::string(key) + " must be " + format_duration(lo) + " to " + format_duration(hi));
      else
        out = *d;
    }
  };
  time("tau", 0, kMaxTime, c.tau);
  time("tau2", 0, kMaxTime, c.tau2);
  time("dead_time", 0, kMaxTime, c.dead_time);
  time("period", kMinPeriod, kMaxPeriod, c.period);
  if (c.dead_time % c.period != 0)
    r.error_at("dead_time", "dead_time must be a whole number of periods (period=" + format_duration(c.period) + ")");
  else if (c.dead_time / c.period > kMaxDelaySamples)
    r.error_at("dead_time", "dead_time is more than " + std::to_string(kMaxDelaySamples) + " periods");
  if (c.pv == c.cv && node.find("pv") && node.find("cv")) r.error_at("pv", "pv and cv must be different words");
  r.finish();
  if (r.failed()) return std::nullopt;
  return c;
}

std::string plant_word_problem(const Address& a, const DataTableLayout& layout) {
  std::string why;
  auto loc = layout.locate(a, &why);
  if (loc && loc->vtype == ValueType::Int16 && loc->bit < 0) return {};
  return to_string(a) + " is not a word of the program's data table" + (why.empty() ? "" : " (" + why + ")") +
         "; the program must use it, or a DATA block size its file";
}

std::unique_ptr<FieldProcess> make_plant(const PlantConfig& config) { return std::make_unique<Plant>(config); }

}  // namespace softslc
