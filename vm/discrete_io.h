// Generic discrete I/O: the module behind every SLOT without a specialty module.
//
// A discrete card is a row of field terminals. Its input words are whatever the field drives
// (set from outside through set_field_input, which is what Runtime::set("I:1/0", 1) calls); its
// output words are what the last output scan delivered (observable through field_output). It has
// no M0/M1 files and no timed behaviour. Combination cards (SCAN_IN and SCAN_OUT both non-zero)
// work the same way, with separate input and output words.
//
// MemoryModule is the test double for specialty modules: discrete I/O plus M0/M1 files held in
// plain arrays, with individual words that can be marked read-only or forbidden (so tests can
// see the processor fault on a refused access) and counters of accesses made.
#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "vm/module.h"

namespace softslc {

class DiscreteIoModule : public Module {
 public:
  DiscreteIoModule(int slot, std::string catalog, int input_words, int output_words);

  void input_scan(std::span<std::uint16_t> image) override;
  void output_scan(std::span<const std::uint16_t> image) override;
  bool set_field_input(int word, std::uint16_t value, std::uint16_t mask) override;
  std::optional<std::uint16_t> field_input(int word) const override;
  std::optional<std::uint16_t> field_output(int word) const override;
  // Its inputs change only through set_field_input (a tool, or in DiscreteModule an event after the
  // input delay) and nothing else happens between scans.
  bool passive() const override { return true; }

 private:
  std::vector<std::uint16_t> field_inputs_;
  std::vector<std::uint16_t> field_outputs_;
};

class MemoryModule : public DiscreteIoModule {
 public:
  MemoryModule(int slot, std::string catalog, int input_words, int output_words, int m0_words, int m1_words);

  int m_file_words(MFile f) const override;
  MAccess read_m(MFile f, int word, std::uint16_t& value) override;
  MAccess write_m(MFile f, int word, std::uint16_t value) override;
  void on_mode_change(Mode from, Mode to) override;

  // Test controls.
  void forbid(MFile f, int word) { forbidden_.insert({f, word}); }
  void make_read_only(MFile f, int word) { read_only_.insert({f, word}); }
  std::uint16_t m_word(MFile f, int word) const { return words(f).at(static_cast<std::size_t>(word)); }
  void set_m_word(MFile f, int word, std::uint16_t v) { words(f).at(static_cast<std::size_t>(word)) = v; }
  std::uint64_t reads() const { return reads_; }
  std::uint64_t writes() const { return writes_; }
  Mode last_mode() const { return last_mode_; }

 private:
  std::vector<std::uint16_t>& words(MFile f) { return f == MFile::M0 ? m0_ : m1_; }
  const std::vector<std::uint16_t>& words(MFile f) const { return f == MFile::M0 ? m0_ : m1_; }

  std::vector<std::uint16_t> m0_;
  std::vector<std::uint16_t> m1_;
  std::set<std::pair<MFile, int>> forbidden_;
  std::set<std::pair<MFile, int>> read_only_;
  std::uint64_t reads_ = 0;
  std::uint64_t writes_ = 0;
  Mode last_mode_ = Mode::Program;
};

}  // namespace softslc
