#include "vm/profile_scan_time_model.h"

#include "instructions/mfile_access_time.h"
#include "vm/module.h"

namespace softslc {

ProfileScanTimeModel::ProfileScanTimeModel(TimingProfile profile, std::string timing_key)
    : profile_(std::move(profile)), timing_key_(std::move(timing_key)) {
  for (std::size_t r = 0; r < mfile_costs_.size(); ++r) {
    const auto row = static_cast<MFileAccess>(r);
    const auto one = mfile_access_us(timing_key_, row, 1), two = mfile_access_us(timing_key_, row, 2);
    if (one && two) mfile_costs_[r] = {microseconds(*one), microseconds(*two - *one)};
  }
}

Nanoseconds ProfileScanTimeModel::instruction_cost(Opcode op, bool rung_in) const {
  const auto& t = profile_.instruction(op);
  return rung_in ? t.true_ns : t.false_ns;
}

Nanoseconds ProfileScanTimeModel::input_scan_cost(const Module& m) const {
  return profile_.input_scan(m.catalog(), m.input_words());
}

Nanoseconds ProfileScanTimeModel::output_scan_cost(const Module& m) const {
  return profile_.output_scan(m.catalog(), m.output_words());
}

Nanoseconds ProfileScanTimeModel::mfile_access_cost(MFileAccess row, int words) const {
  const auto r = static_cast<std::size_t>(row);
  if (words < 1 || r >= mfile_costs_.size()) return 0;  // mfile_access_us has no figure: no charge
  return mfile_costs_[r].first_word + mfile_costs_[r].next_word * (words - 1);
}

std::shared_ptr<const ScanTimeModel> make_scan_time_model(const ProcessorModel& processor,
                                                          const TimingProfile* user) {
  const std::string key = processor.timing_key();
  if (user && user->processor == key) return std::make_shared<ProfileScanTimeModel>(*user, key);
  if (auto p = builtin_timing_profile(key)) return std::make_shared<ProfileScanTimeModel>(std::move(*p), key);
  return std::make_shared<DefaultScanTimeModel>();
}

}  // namespace softslc
