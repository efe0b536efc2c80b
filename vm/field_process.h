// Field processes: simulated plant dynamics that act on data-table words in virtual time.
//
// Design. A module owns a chassis slot and talks to the processor through its image; a field
// process owns no slot. It stands for the physics on the far side of the I/O: a tank, an oven, a
// flow loop, whose measurement the program reads in one word (its PV) and whose actuator the
// program drives from another (its CV). The runtime attaches each process once, after the data
// table is laid out; the process resolves its words and schedules its own periodic work on the
// runtime's event queue, so it runs between scans at fixed virtual times, in (time, sequence)
// order like every module event, and a run is reproducible bit for bit. It reads and writes only
// the words it resolved at attach time, through FieldProcessHost (never a pointer into the table).
// Tests reach a process by name with Runtime::inject / Runtime::observe, like any bench device.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/data_table.h"
#include "vm/event_queue.h"
#include "vm/module.h"
#include "vm/virtual_time.h"

namespace softslc {

// The module host (clock, mode, event queue) plus the data-table words a process resolved.
class FieldProcessHost : public ModuleHost {
 public:
  virtual const DataTableLayout& layout() const = 0;
  // Word `index` of the data table (an index the process resolved through layout()).
  virtual std::uint16_t read_word(std::uint32_t index) const = 0;
  virtual void write_word(std::uint32_t index, std::uint16_t value) = 0;
};

class FieldProcess {
 public:
  virtual ~FieldProcess() = default;
  // The device name tests use.
  virtual std::string name() const = 0;
  // Resolves the process's words and starts it. Returns why it cannot run (an address the
  // program's data table does not have), or an empty string.
  virtual std::string attach(FieldProcessHost& host) = 0;
  virtual DeviceStatus inject(const DeviceFault& /*fault*/) { return {}; }
  virtual std::optional<std::vector<std::int64_t>> observe(std::string_view /*device*/, std::string_view /*what*/) const {
    return std::nullopt;
  }
};

using FieldProcessFactory = std::function<std::unique_ptr<FieldProcess>()>;

}  // namespace softslc
