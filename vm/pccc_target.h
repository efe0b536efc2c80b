// pccc::Target: a processor's data files as a protocol answerer reaches them (read and write words,
// the diagnostic status block, M0/M1 through the modules). Declared here, below server/, because two
// layers answer through it: `softslc serve`'s PCCC and Modbus servers (server/pccc.h, server/modbus.h,
// with the live controller as the target) and a simulated MicroLogix whose channel 0 is a Modbus RTU
// slave on another controller's line (vm/modbus_slave.h, with the peer's data table as the target).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "parser/address.h"

namespace softslc::pccc {

// What a PCCC command (server/pccc.h, execute) and a Modbus request (vm/modbus_slave.h, handle_pdu) need
// from the processor.
class Target {
 public:
  struct File {
    FileType type = FileType::Integer;
    std::uint32_t elements = 0;
    int words_per_element = 1;
  };
  virtual ~Target() = default;
  virtual std::optional<File> file(int number) const = 0;
  // Reads words of a file (offset and count already checked against the file).
  virtual void read(int number, std::uint32_t offset, std::span<std::uint16_t> out) const = 0;
  // Writes words with masks; returns an empty string on success, else why it was refused.
  virtual std::string write(int number, std::uint32_t offset, std::span<const std::uint16_t> values,
                            std::span<const std::uint16_t> masks) = 0;
  // The diagnostic status block (CMD 06 FNC 03 reply data).
  virtual std::vector<std::uint8_t> diagnostic_status() const = 0;
  // The M0 (m1 false) or M1 file of the module in `slot`: its size in words, or nullopt when the
  // slot has no module with such a file. The default: no module has M files.
  virtual std::optional<std::uint32_t> module_file_words(int /*slot*/, bool /*m1*/) const { return std::nullopt; }
  // Reads or writes M-file words through the module, one word at a time in order; an empty string
  // on success, else the module's refusal (a read stops at the refused word; a write has
  // performed the words before it).
  virtual std::string read_module(int /*slot*/, bool /*m1*/, std::uint32_t /*word*/, std::span<std::uint16_t> /*out*/) {
    return "no module M files";
  }
  virtual std::string write_module(int /*slot*/, bool /*m1*/, std::uint32_t /*word*/,
                                   std::span<const std::uint16_t> /*values*/, std::span<const std::uint16_t> /*masks*/) {
    return "no module M files";
  }
};

}  // namespace softslc::pccc
