#include "vm/data_table.h"

#include <cinttypes>
#include <cstdio>

namespace softslc {

namespace {

std::string file_name(const FileLayout& f, int number) {
  std::string s(file_letter(f.type));
  if (fixed_file_number(f.type) < 0) s += std::to_string(number);
  return s;
}

void set_error(std::string* error, std::string msg) {
  if (error) *error = std::move(msg);
}

}  // namespace

std::optional<Location> DataTableLayout::locate(const Address& a, std::string* error, bool as_file_start) const {
  if (a.is_indirect()) {
    set_error(error, "indirect address " + to_string(a) + " has no fixed location");
    return std::nullopt;
  }
  if (a.indexed && !as_file_start) {
    set_error(error, "indexed address " + to_string(a) + " has no fixed location (it depends on S:24)");
    return std::nullopt;
  }
  if (is_mfile(a.type)) {
    set_error(error, to_string(a) + " is in a module's M file, not in the data table");
    return std::nullopt;
  }
  Location loc;
  loc.type = a.type;
  if (is_function_file(a.type)) {
    const std::size_t index = kFunctionFileIndex + a.file;
    if (a.file >= kFunctionFileCount || !files[index].present) {
      set_error(error, to_string(a) + ": function file " + std::string(function_file_name(a.file)) +
                           (communications_status_channel(a.file) >= 0
                                ? " is in the data table only of a program that names it (docs/semantics.md \"The CS file\")"
                                : " is not simulated on this processor"));
      return std::nullopt;
    }
    const FileLayout& f = files[index];
    const int word = a.word < 0 ? 0 : a.word;
    if (a.element < 0 || static_cast<std::uint32_t>(a.element) >= f.elements || word >= f.words_per_element ||
        a.bit > 15) {
      set_error(error, to_string(a) + " is beyond the " + std::string(function_file_name(a.file)) + " function file");
      return std::nullopt;
    }
    loc.file = static_cast<int>(index);
    loc.word = f.base + static_cast<std::uint32_t>(a.element) * f.words_per_element + static_cast<std::uint32_t>(word);
    loc.bit = a.bit;
    // PTO:0.TOP and HSC:0.ACC/.HIP/.LOP/.OVF/.UNF (1762-RM001C p. 5-23) are 32-bit: they read and
    // write as L words do (low word first).
    loc.vtype = a.bit < 0 && function_word_is_long(a.file, word) ? ValueType::Int32 : ValueType::Int16;
    return loc;
  }
  if (is_io(a.type)) {
    const int file = fixed_file_number(a.type);
    const auto& slots = a.type == FileType::Input ? input_slots : output_slots;
    const int word = a.word_in_element();
    if (a.element < 0 || a.element >= kMaxSlots || !slots[static_cast<std::size_t>(a.element)].present) {
      set_error(error, to_string(a) + ": slot " + std::to_string(a.element) + " has no " +
                           (a.type == FileType::Input ? "input" : "output") + " image");
      return std::nullopt;
    }
    const auto& s = slots[static_cast<std::size_t>(a.element)];
    if (word < 0 || static_cast<std::uint32_t>(word) >= s.words) {
      set_error(error, to_string(a) + ": slot " + std::to_string(a.element) + " has " + std::to_string(s.words) +
                           " image word(s)");
      return std::nullopt;
    }
    loc.file = file;
    loc.word = files[static_cast<std::size_t>(file)].base + s.first + static_cast<std::uint32_t>(word);
    loc.bit = a.bit;
    loc.vtype = ValueType::Int16;
    return loc;
  }
  const int file = a.file;
  if (file < 0 || file > 255 || !files[static_cast<std::size_t>(file)].present) {
    set_error(error, to_string(a) + ": file " + std::string(file_letter(a.type)) + std::to_string(file) +
                         " does not exist");
    return std::nullopt;
  }
  const FileLayout& f = files[static_cast<std::size_t>(file)];
  if (f.type != a.type) {
    set_error(error, to_string(a) + ": file " + std::to_string(file) + " is a " + std::string(file_letter(f.type)) +
                         " file");
    return std::nullopt;
  }
  if (a.element < 0 || static_cast<std::uint32_t>(a.element) >= f.elements) {
    set_error(error, to_string(a) + " is beyond the end of " + file_name(f, file) + " (elements 0-" +
                         std::to_string(static_cast<int>(f.elements) - 1) + ")");
    return std::nullopt;
  }
  std::uint32_t sub = 0;
  if (is_structured(a.type)) {
    if (a.word > 2) {
      set_error(error, to_string(a) + ": T, C and R elements have words 0-2");
      return std::nullopt;
    }
    sub = a.word < 0 ? 0 : static_cast<std::uint32_t>(a.word);
  } else if (a.type == FileType::String) {
    // ST10:1.0 is the length word, .1-.41 the data words (RM001 p. 4-28 writes #ST10:1.1 for
    // DATA[0]); without a word the address names the element, that is its length word.
    if (a.word > 41) {
      set_error(error, to_string(a) + ": ST elements have words 0-41 (0 the length, 1-41 the characters)");
      return std::nullopt;
    }
    sub = a.word < 0 ? 0 : static_cast<std::uint32_t>(a.word);
  } else if (is_multiword_data(a.type)) {
    // MG11:0.18, RI12:0.1: the element's words (1762-RM001C p. 21-4, 1766-RM001A p. 435).
    if (a.word >= words_per_element(a.type)) {
      set_error(error, to_string(a) + ": " + std::string(file_letter(a.type)) + " elements have words 0-" +
                           std::to_string(words_per_element(a.type) - 1));
      return std::nullopt;
    }
    sub = a.word < 0 ? 0 : static_cast<std::uint32_t>(a.word);
  } else if (a.word > 0) {
    set_error(error, to_string(a) + ": " + std::string(file_letter(a.type)) + " elements have no sub-elements");
    return std::nullopt;
  }
  loc.file = file;
  loc.word = f.base + static_cast<std::uint32_t>(a.element) * f.words_per_element + sub;
  loc.vtype = is_structured(a.type) ? ValueType::Int16 : value_type_of(a.type);
  if (a.bit >= 0) {
    if (a.type == FileType::Float || a.type == FileType::String) {
      set_error(error, to_string(a) + ": bits of " + std::string(file_letter(a.type)) + " elements are not addressable");
      return std::nullopt;
    }
    // L elements have bits 0-31: the upper 16 live in the second word.
    const int limit = a.type == FileType::Long ? 32 : 16;
    if (a.bit >= limit) {
      set_error(error, to_string(a) + ": bit number beyond the element");
      return std::nullopt;
    }
    loc.word += static_cast<std::uint32_t>(a.bit / 16);
    loc.bit = a.bit % 16;
    loc.vtype = ValueType::Int16;
  }
  return loc;
}

int DataTableLayout::scan_for_file(std::uint32_t word) const {
  // Files lie in file-number order (see the layout in data_table.h), so the first present file
  // that ends after `word` is the only one that can hold it.
  for (std::size_t f = 0; f < files.size(); ++f) {
    const auto& fl = files[f];
    if (fl.present && word < fl.end()) return word >= fl.base ? static_cast<int>(f) : -1;
  }
  return -1;
}

void DataTableLayout::index_files() {
  // The same answer as the scan for every word: each word gets the first present file (in
  // file-number order) whose span holds it; words past total_words stay outside the index.
  word_file_.assign(total_words, kNoFile);
  for (std::size_t f = 0; f < files.size(); ++f) {
    const auto& fl = files[f];
    if (!fl.present) continue;
    for (std::uint32_t w = fl.base; w < fl.end() && w < total_words; ++w)
      if (word_file_[w] == kNoFile) word_file_[w] = static_cast<std::uint16_t>(f);
  }
}

std::string DataTableLayout::describe(std::uint32_t word, int bit) const {
  const int f = file_containing(word);
  if (f < 0) return "?" + std::to_string(word);
  const FileLayout& fl = files[static_cast<std::size_t>(f)];
  const std::uint32_t off = word - fl.base;
  Address a;
  a.type = fl.type;
  a.file = static_cast<std::uint16_t>(f);
  a.bit = bit;
  if (is_function_file(fl.type)) {
    a.file = static_cast<std::uint16_t>(static_cast<std::size_t>(f) - kFunctionFileIndex);
    a.element = static_cast<std::int32_t>(off / fl.words_per_element);
    a.word = static_cast<std::int32_t>(off % fl.words_per_element);
    return to_string(a);
  }
  if (is_io(fl.type)) {
    const auto& slots = fl.type == FileType::Input ? input_slots : output_slots;
    for (int s = 0; s < kMaxSlots; ++s) {
      const auto& si = slots[static_cast<std::size_t>(s)];
      if (si.present && off >= si.first && off < si.first + si.words) {
        a.element = s;
        a.word = static_cast<std::int32_t>(off - si.first);
        return to_string(a);
      }
    }
    return "?" + std::to_string(word);
  }
  a.element = static_cast<std::int32_t>(off / fl.words_per_element);
  const std::uint32_t sub = off % fl.words_per_element;
  if (is_structured(fl.type)) {
    // Word 0 without a bit is listed as the element (T4:0), which is how instructions name it.
    a.word = sub == 0 && bit < 0 ? -1 : static_cast<std::int32_t>(sub);
  } else if (sub != 0) {
    // The second word of an F or L element: only reachable as a raw word (COP).
    return to_string(a) + "+" + std::to_string(sub);
  }
  return to_string(a);
}

std::int64_t Value::as_int() const {
  if (kind != Kind::Float) return integer;
  bool ignored = false;
  return numeric::float_to_integer(real, ValueType::Int32, ignored);
}

std::string Value::to_string() const {
  switch (kind) {
    case Kind::Bit: return integer ? "1" : "0";
    case Kind::Integer: return std::to_string(integer);
    case Kind::Float: {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g", real);
      return buf;
    }
  }
  return "?";
}

namespace numeric {

std::int64_t float_to_integer(double f, ValueType vt, bool& overflow) {
  const double hi = vt == ValueType::Int32 ? 2147483647.0 : 32767.0;
  const double lo = vt == ValueType::Int32 ? -2147483648.0 : -32768.0;
  if (std::isnan(f)) {
    overflow = true;
    return static_cast<std::int64_t>(hi);
  }
  // nearbyint uses the current rounding mode, which softslc never changes from
  // round-to-nearest-even (ML1400 RM p.204: floats round to even).
  const double r = std::nearbyint(f);
  if (r > hi) {
    overflow = true;
    return static_cast<std::int64_t>(hi);
  }
  if (r < lo) {
    overflow = true;
    return static_cast<std::int64_t>(lo);
  }
  return static_cast<std::int64_t>(r);
}

}  // namespace numeric

DataTable::DataTable(std::shared_ptr<const DataTableLayout> layout, std::vector<std::uint16_t> initial)
    : layout_(std::move(layout)), words_(std::move(initial)) {
  words_.resize(layout_->total_words, 0);
}

Value DataTable::read(const Location& loc) const {
  if (loc.bit >= 0) return Value::bit((words_[loc.word] >> loc.bit) & 1u);
  switch (loc.vtype) {
    case ValueType::Int16: return Value::of_int(static_cast<std::int16_t>(words_[loc.word]));
    case ValueType::Int32: return Value::of_int(i32(loc.word));
    case ValueType::Float32: return Value::of_float(f32(loc.word));
  }
  return {};
}

void DataTable::write(const Location& loc, const Value& v) {
  if (loc.bit >= 0) {
    const auto mask = static_cast<std::uint16_t>(1u << loc.bit);
    words_[loc.word] = static_cast<std::uint16_t>(v.as_bool() ? (words_[loc.word] | mask) : (words_[loc.word] & ~mask));
    return;
  }
  bool overflow = false;
  switch (loc.vtype) {
    case ValueType::Int16: {
      // Tools may write raw 16-bit patterns (0..65535) as well as signed values.
      std::int64_t i = v.kind == Value::Kind::Float ? numeric::float_to_integer(v.real, ValueType::Int16, overflow)
                                                    : v.integer;
      words_[loc.word] = static_cast<std::uint16_t>(i);
      break;
    }
    case ValueType::Int32: {
      std::int64_t i = v.kind == Value::Kind::Float ? numeric::float_to_integer(v.real, ValueType::Int32, overflow)
                                                    : v.integer;
      set_i32(loc.word, static_cast<std::int32_t>(i));
      break;
    }
    case ValueType::Float32: set_f32(loc.word, static_cast<float>(v.as_double())); break;
  }
}

}  // namespace softslc
