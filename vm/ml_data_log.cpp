#include "vm/ml_data_log.h"

#include <cstdio>
#include <cstring>

#include "parser/formatter.h"
#include "vm/bytecode.h"

namespace softslc {

namespace {
// Slots of a record before its fields: the date (yyyymmdd) and the time (hhmmss) at the DLG.
constexpr std::size_t kStampSlots = 2;
}  // namespace

void DataLogs::attach(const CompiledProgram& program) {
  index_.fill(-1);
  queues_.clear();
  const DataTableLayout& layout = *program.layout;
  const FileLayout& dls = layout.function_file(FunctionFile::DLS);
  const FileLayout& rtc = layout.function_file(FunctionFile::RTC);
  if (!dls.present || !rtc.present) return;
  rtc_ = rtc.base;
  for (const CompiledDataLog& spec : program.data_logs) {
    Queue q;
    q.spec = &spec;
    q.dls = dls.base + static_cast<std::uint32_t>(spec.number) * dls.words_per_element;
    q.stride = kStampSlots + spec.fields.size();
    q.slots.assign(static_cast<std::size_t>(spec.records) * q.stride, 0);
    index_[static_cast<std::size_t>(spec.number)] = static_cast<std::int16_t>(queues_.size());
    queues_.push_back(std::move(q));
  }
}

void DataLogs::publish(const Queue& q, std::uint16_t* w) const {
  w[q.dls + dls::kFileSize] = static_cast<std::uint16_t>(q.spec->records);
  w[q.dls + dls::kRecordsStored] = static_cast<std::uint16_t>(q.count);
}

void DataLogs::scan(int queue, bool rung, std::uint16_t* w) {
  const std::int16_t at = index_[static_cast<std::size_t>(queue & 0xFF)];
  if (at < 0) return;  // check refuses a DLG of an unconfigured queue
  Queue& q = queues_[static_cast<std::size_t>(at)];
  std::uint16_t& bits = w[q.dls + dls::kBits];
  constexpr std::uint16_t kEn = 1u << dls::kEnableBit, kDn = 1u << dls::kDoneBit, kOv = 1u << dls::kOverflowBit;
  const bool was_enabled = (bits & kEn) != 0;
  bits = static_cast<std::uint16_t>(rung ? bits | kEn : bits & ~kEn);
  if (!rung || was_enabled) return;
  // "If a queue is full and another record is saved, the oldest record is over-written"
  // (AG-UM008C p. 3-66); OV says so and stays set until the program clears it (p. 3-65).
  const std::size_t capacity = static_cast<std::size_t>(q.spec->records);
  std::size_t slot;
  if (q.count == capacity) {
    slot = q.head;
    q.head = (q.head + 1) % capacity;
    bits = static_cast<std::uint16_t>(bits | kOv);
  } else {
    slot = (q.head + q.count) % capacity;
    ++q.count;
  }
  // DN: "set (1) by the DLG instruction when the queue becomes full" (AG-UM008C p. 3-65).
  if (q.count == capacity) bits = static_cast<std::uint16_t>(bits | kDn);
  std::int64_t* r = &q.slots[slot * q.stride];
  // "If the Real Time Clock module is disabled in the controller, <date> is formatted as 00/00/0000,
  // and <time> is formatted as 00:00:00" (1763-RM001C p. 442).
  const std::uint16_t* clock = w + rtc_;
  const bool disabled = (clock[rtc::kStatusWord] >> rtc::kDisabledBit) & 1u;
  r[0] = disabled ? 0 : clock[rtc::kYear] * 10000LL + clock[rtc::kMonth] * 100LL + clock[rtc::kDay];
  r[1] = disabled ? 0 : clock[rtc::kHour] * 10000LL + clock[rtc::kMinute] * 100LL + clock[rtc::kSecond];
  for (std::size_t i = 0; i < q.spec->fields.size(); ++i) {
    const Location& f = q.spec->fields[i];
    std::int64_t v = static_cast<std::int16_t>(w[f.word]);
    if (f.vtype == ValueType::Int32) {
      std::int32_t l = 0;
      std::memcpy(&l, &w[f.word], sizeof l);
      v = l;
    } else if (f.vtype == ValueType::Float32) {
      std::uint32_t raw = 0;  // kept as its bit pattern, formatted at retrieval
      std::memcpy(&raw, &w[f.word], sizeof raw);
      v = raw;
    }
    r[kStampSlots + i] = v;
  }
  publish(q, w);
}

std::string DataLogs::format(const Queue& q, std::size_t record) const {
  const std::int64_t* r = &q.slots[((q.head + record) % static_cast<std::size_t>(q.spec->records)) * q.stride];
  std::string out;
  const auto item = [&](const std::string& text) {
    if (!out.empty()) out += q.spec->delimiter;
    out += text;
  };
  char buf[16];
  if (q.spec->date) {
    // mm/dd/yyyy: "01/10/2000" (1766-RM001A p. 519, Queue 0).
    std::snprintf(buf, sizeof buf, "%02d/%02d/%04d", static_cast<int>(r[0] / 100 % 100), static_cast<int>(r[0] % 100),
                  static_cast<int>(r[0] / 10000));
    item(buf);
  }
  if (q.spec->time) {
    // hh:mm:ss: "20:00:00" (1763-RM001C p. 435, Queue 5).
    std::snprintf(buf, sizeof buf, "%02d:%02d:%02d", static_cast<int>(r[1] / 10000), static_cast<int>(r[1] / 100 % 100),
                  static_cast<int>(r[1] % 100));
    item(buf);
  }
  for (std::size_t i = 0; i < q.spec->fields.size(); ++i) {
    const std::int64_t v = r[kStampSlots + i];
    if (q.spec->fields[i].vtype == ValueType::Float32) {
      const auto raw = static_cast<std::uint32_t>(v);
      float f = 0;
      std::memcpy(&f, &raw, sizeof f);
      item(format_float(f));
    } else {
      item(std::to_string(v));
    }
  }
  return out;
}

std::optional<std::string> DataLogs::retrieve(int queue, std::uint16_t* w) {
  if (queue < 0 || queue > 255 || index_[static_cast<std::size_t>(queue)] < 0) return std::nullopt;
  Queue& q = queues_[static_cast<std::size_t>(index_[static_cast<std::size_t>(queue)])];
  if (q.count == 0) return std::nullopt;
  std::string text = format(q, 0);
  // "The oldest record is retrieved first and then, deleted"; RST "is decremented when a record is
  // read"; DN "is cleared when a record is retrieved" (AG-UM008C pp. 3-65, 3-66).
  q.head = (q.head + 1) % static_cast<std::size_t>(q.spec->records);
  --q.count;
  w[q.dls + dls::kBits] = static_cast<std::uint16_t>(w[q.dls + dls::kBits] & ~(1u << dls::kDoneBit));
  publish(q, w);
  return text;
}

std::vector<std::string> DataLogs::records(int queue) const {
  std::vector<std::string> out;
  if (queue < 0 || queue > 255 || index_[static_cast<std::size_t>(queue)] < 0) return out;
  const Queue& q = queues_[static_cast<std::size_t>(index_[static_cast<std::size_t>(queue)])];
  for (std::size_t i = 0; i < q.count; ++i) out.push_back(format(q, i));
  return out;
}

void DataLogs::keep_records_of(const DataLogs& other) {
  for (Queue& q : queues_) {
    const std::int16_t at = other.index_[static_cast<std::size_t>(q.spec->number)];
    if (at < 0) continue;
    const Queue& o = other.queues_[static_cast<std::size_t>(at)];
    if (o.slots.size() != q.slots.size()) continue;
    q.slots = o.slots;
    q.head = o.head;
    q.count = o.count;
  }
}

std::vector<int> DataLogs::queues() const {
  std::vector<int> out;
  for (int n = 0; n < 256; ++n)
    if (index_[static_cast<std::size_t>(n)] >= 0) out.push_back(n);
  return out;
}

}  // namespace softslc
