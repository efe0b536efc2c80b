// MicroLogix data logging: the DLG instruction, its queues and the Data Log Status file DLS0:q
// (1763-RM001C pp. 433-442, 1766-RM001A pp. 518-529, AG-UM008C pp. 3-58..3-67; docs/semantics.md
// "Data logging: DLG and the DLS file").
//
// Each DATALOG queue is a first-in first-out store of records in the controller's battery-backed
// data log memory, outside the data table: the storage is allocated once when the program is
// attached, so a DLG allocates nothing. A record holds the RTC date and time and the field values
// as they were when the DLG executed; it is formatted as text only when it is retrieved (the
// manuals' record string: date mm/dd/yyyy, time hh:mm:ss, the values, the queue's delimiter).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vm/data_table.h"

namespace softslc {

struct CompiledProgram;
struct CompiledDataLog;

class DataLogs {
 public:
  // Allocates every configured queue's storage and finds the DLS and RTC files in the layout.
  void attach(const CompiledProgram& program);
  // A scan of DLG q with rung condition `rung`: EN follows the rung; a false-to-true transition
  // (EN was clear) captures one record (1763-RM001C p. 439).
  void scan(int queue, bool rung, std::uint16_t* w);
  // Retrieval "via communications" (1763-RM001C p. 442): the oldest record of queue q as its text,
  // removed from the queue (RST decremented, DN cleared); nullopt when the queue is empty or not
  // configured.
  std::optional<std::string> retrieve(int queue, std::uint16_t* w);
  // The records of queue q as text, oldest first, without removing them (for display).
  std::vector<std::string> records(int queue) const;
  // The configured queue numbers, ascending.
  std::vector<int> queues() const;
  // Takes the stored records of `other` (the same program's queues: a power cycle keeps them).
  void keep_records_of(const DataLogs& other);

 private:
  struct Queue {
    const CompiledDataLog* spec = nullptr;
    std::uint32_t dls = 0;          // word 0 of its DLS element
    std::size_t stride = 0;         // slots per record: date, time, then one per field
    std::vector<std::int64_t> slots;  // records * stride, a ring
    std::size_t head = 0;           // the oldest record
    std::size_t count = 0;          // records stored (RST)
  };
  std::string format(const Queue& q, std::size_t record) const;
  void publish(const Queue& q, std::uint16_t* w) const;  // FSZ and RST into DLS0:q

  std::vector<Queue> queues_;
  std::array<std::int16_t, 256> index_{};  // queue number -> index in queues_, -1 = none
  std::uint32_t rtc_ = 0;                  // word 0 of RTC:0
};

}  // namespace softslc
