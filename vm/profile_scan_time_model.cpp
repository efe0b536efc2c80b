#include "vm/profile_scan_time_model.h"

#include "instructions/mfile_access_time.h"
#include "vm/module.h"

namespace softslc {

ProfileScanTimeModel::ProfileScanTimeModel(TimingProfile profile, std::string timing_key)
    : profile_(std::move(profile)), timing_key_(std::move(timing_key)) {}

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
  auto us = mfile_access_us(timing_key_, row, words);
  return us ? microseconds(*us) : 0;
}

std::shared_ptr<const ScanTimeModel> make_scan_time_model(const ProcessorModel& processor,
                                                          const TimingProfile* user) {
  const std::string key = processor.timing_key();
  if (user && user->processor == key) return std::make_shared<ProfileScanTimeModel>(*user, key);
  if (auto p = builtin_timing_profile(key)) return std::make_shared<ProfileScanTimeModel>(std::move(*p), key);
  return std::make_shared<DefaultScanTimeModel>();
}

}  // namespace softslc
