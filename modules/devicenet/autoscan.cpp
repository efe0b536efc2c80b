#include "modules/devicenet/autoscan.h"

namespace softslc::devicenet::autoscan {

Decision decide(int node, int allocation, const Identity& id, const std::array<IoSupport, 4>& reported) {
  Decision d;
  const IoSupport* chosen = nullptr;
  IoType type = IoType::Cos;
  for (IoType t : kPreference)
    if (reported[static_cast<std::size_t>(t)].supported) {
      chosen = &reported[static_cast<std::size_t>(t)];
      type = t;
      break;
    }
  if (chosen == nullptr) return d;
  const int produce = chosen->produce;
  const int consume = type == IoType::Strobe ? 0 : chosen->consume;
  if (produce > allocation || consume > allocation) {
    d.verdict = Verdict::TooLarge;
    return d;
  }
  if (!fits(node, allocation)) {
    d.verdict = Verdict::OutsideTable;
    return d;
  }
  ScanlistEntry e;
  e.node = node;
  e.key.vendor = id.vendor;
  e.key.device_type = id.device_type;
  e.key.product_code = id.product_code;
  e.key.major = id.major;
  e.key.minor = id.minor;
  ConnectionConfig& c = e.conn(type);
  c.enabled = true;
  c.rx = produce;
  c.tx = consume;
  c.epr = default_epr(type);
  const int offset = byte_offset(node, allocation);
  const TableRef at{TableRef::Area::MFile, offset / 2, (offset % 2) * 8};
  if (produce > 0) e.inputs.push_back(MapSegment{type, 0, 0, at, produce * 8});
  if (consume > 0) e.outputs.push_back(MapSegment{type, 0, 0, at, consume * 8});
  d.verdict = Verdict::Accepted;
  d.entry = std::move(e);
  return d;
}

}  // namespace softslc::devicenet::autoscan
