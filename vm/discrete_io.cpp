#include "vm/discrete_io.h"

#include <algorithm>

namespace softslc {

DiscreteIoModule::DiscreteIoModule(int slot, std::string catalog, int input_words, int output_words)
    : Module(slot, std::move(catalog), input_words, output_words),
      field_inputs_(static_cast<std::size_t>(std::max(input_words, 0)), 0),
      field_outputs_(static_cast<std::size_t>(std::max(output_words, 0)), 0) {}

void DiscreteIoModule::input_scan(std::span<std::uint16_t> image) {
  const std::size_t n = std::min(image.size(), field_inputs_.size());
  std::copy_n(field_inputs_.begin(), n, image.begin());
}

void DiscreteIoModule::output_scan(std::span<const std::uint16_t> image) {
  const std::size_t n = std::min(image.size(), field_outputs_.size());
  std::copy_n(image.begin(), n, field_outputs_.begin());
}

bool DiscreteIoModule::set_field_input(int word, std::uint16_t value, std::uint16_t mask) {
  if (word < 0 || static_cast<std::size_t>(word) >= field_inputs_.size()) return false;
  auto& w = field_inputs_[static_cast<std::size_t>(word)];
  const std::uint16_t before = w;
  w = static_cast<std::uint16_t>((w & ~mask) | (value & mask));
  // The discrete input interrupt sees the terminals change (RM 11-20: it reads the card itself).
  if (w != before && host()) host()->field_input_changed(slot(), word, before, w);
  return true;
}

std::optional<std::uint16_t> DiscreteIoModule::field_input(int word) const {
  if (word < 0 || static_cast<std::size_t>(word) >= field_inputs_.size()) return std::nullopt;
  return field_inputs_[static_cast<std::size_t>(word)];
}

std::optional<std::uint16_t> DiscreteIoModule::field_output(int word) const {
  if (word < 0 || static_cast<std::size_t>(word) >= field_outputs_.size()) return std::nullopt;
  return field_outputs_[static_cast<std::size_t>(word)];
}

MemoryModule::MemoryModule(int slot, std::string catalog, int input_words, int output_words, int m0_words,
                           int m1_words)
    : DiscreteIoModule(slot, std::move(catalog), input_words, output_words),
      m0_(static_cast<std::size_t>(std::max(m0_words, 0)), 0),
      m1_(static_cast<std::size_t>(std::max(m1_words, 0)), 0) {}

int MemoryModule::m_file_words(MFile f) const { return static_cast<int>(words(f).size()); }

MAccess MemoryModule::read_m(MFile f, int word, std::uint16_t& value) {
  if (word < 0 || word >= m_file_words(f)) return MAccess::NoSuchWord;
  if (forbidden_.count({f, word})) return MAccess::Forbidden;
  ++reads_;
  value = words(f)[static_cast<std::size_t>(word)];
  return MAccess::Ok;
}

MAccess MemoryModule::write_m(MFile f, int word, std::uint16_t value) {
  if (word < 0 || word >= m_file_words(f)) return MAccess::NoSuchWord;
  if (forbidden_.count({f, word}) || read_only_.count({f, word})) return MAccess::Forbidden;
  ++writes_;
  words(f)[static_cast<std::size_t>(word)] = value;
  return MAccess::Ok;
}

void MemoryModule::on_mode_change(Mode, Mode to) { last_mode_ = to; }

}  // namespace softslc
