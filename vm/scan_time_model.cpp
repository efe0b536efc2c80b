#include "vm/scan_time_model.h"

#include "vm/module.h"

namespace softslc {

Nanoseconds DefaultScanTimeModel::instruction_cost(Opcode op, bool rung_in) const {
  // Leading instructions (LBL, SBR) are markers that always pass power; they cost what an input does.
  if (spec(op).role != Role::Output) return kInputInstruction;
  return rung_in ? kOutputTrue : kOutputFalse;
}

Nanoseconds DefaultScanTimeModel::input_scan_cost(const Module& m) const {
  return m.input_words() > 0 ? kModuleBase + kPerImageWord * m.input_words() : 0;
}

Nanoseconds DefaultScanTimeModel::output_scan_cost(const Module& m) const {
  return m.output_words() > 0 ? kModuleBase + kPerImageWord * m.output_words() : 0;
}

}  // namespace softslc
