#include "parser/program.h"

#include <cmath>
#include <cstring>

namespace softslc {

bool Operand::same_as(const Operand& o) const {
  if (kind != o.kind) return false;
  switch (kind) {
    case Kind::Address: return address == o.address;
    case Kind::Integer: return integer == o.integer;
    // Floats compare by bit pattern: fmt writes them with enough digits to round-trip exactly.
    // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): the bit pattern is the point (-0.0, NaNs)
    case Kind::Float: return std::memcmp(&real, &o.real, sizeof real) == 0;
    case Kind::Symbol:
    case Kind::Expression: return spelling == o.spelling;
  }
  return false;
}

std::string Operand::text() const {
  if (kind == Kind::Address && spelling.empty()) return to_string(address);
  return spelling;
}

const ProgramFile* Program::find_file(int number) const {
  for (const auto& f : files)
    if (f.number == number) return &f;
  return nullptr;
}

const SlotConfig* Program::find_slot(int slot) const {
  for (const auto& s : slots)
    if (s.slot == slot) return &s;
  return nullptr;
}

const Symbol* Program::find_symbol(std::string_view name) const {
  for (const auto& s : symbols)
    if (!s.name.empty() && s.name == name) return &s;
  return nullptr;
}

const DataLogQueue* Program::find_data_log(int number) const {
  for (const auto& q : data_logs)
    if (q.number == number) return &q;
  return nullptr;
}

namespace {

struct Comparer {
  std::string* diff;
  bool fail(const std::string& what) {
    if (diff && diff->empty()) *diff = what;
    return false;
  }

  bool elements(const std::vector<RungElement>& a, const std::vector<RungElement>& b, const std::string& where) {
    if (a.size() != b.size()) return fail(where + ": element count differs");
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].kind != b[i].kind) return fail(where + ": element " + std::to_string(i) + " kind differs");
      if (a[i].kind == RungElement::Kind::Branch) {
        if (a[i].legs.size() != b[i].legs.size()) return fail(where + ": branch leg count differs");
        for (std::size_t l = 0; l < a[i].legs.size(); ++l)
          if (!elements(a[i].legs[l], b[i].legs[l], where + " leg " + std::to_string(l))) return false;
        continue;
      }
      const auto& x = a[i].instruction;
      const auto& y = b[i].instruction;
      if (x.opcode != y.opcode || x.operands.size() != y.operands.size())
        return fail(where + ": instruction " + std::to_string(i) + " differs");
      for (std::size_t k = 0; k < x.operands.size(); ++k)
        if (!x.operands[k].same_as(y.operands[k]))
          return fail(where + ": operand '" + x.operands[k].text() + "' vs '" + y.operands[k].text() + "'");
    }
    return true;
  }
};

}  // namespace

bool same_program(const Program& a, const Program& b, std::string* first_difference) {
  Comparer c{first_difference};
  if (a.processor.catalog != b.processor.catalog || a.processor.series != b.processor.series ||
      a.processor.frn != b.processor.frn || a.processor_description != b.processor_description)
    return c.fail("processor differs");
  if (a.project != b.project) return c.fail("project differs");
  if (a.slots.size() != b.slots.size()) return c.fail("slot count differs");
  for (std::size_t i = 0; i < a.slots.size(); ++i) {
    const auto& x = a.slots[i];
    const auto& y = b.slots[i];
    if (x.slot != y.slot || x.catalog != y.catalog || x.description != y.description || x.scan_in != y.scan_in ||
        x.scan_out != y.scan_out || x.g_file != y.g_file || x.has_g_file != y.has_g_file || x.iocard != y.iocard ||
        x.m0_size != y.m0_size || x.m1_size != y.m1_size || x.id_code != y.id_code || x.options != y.options)
      return c.fail("slot " + std::to_string(x.slot) + " differs");
  }
  if (a.files.size() != b.files.size()) return c.fail("program file count differs");
  for (std::size_t i = 0; i < a.files.size(); ++i) {
    const auto& x = a.files[i];
    const auto& y = b.files[i];
    if (x.number != y.number || x.name != y.name || x.rungs.size() != y.rungs.size())
      return c.fail("program file " + std::to_string(x.number) + " differs");
    for (std::size_t r = 0; r < x.rungs.size(); ++r) {
      std::string where = "file " + std::to_string(x.number) + " rung " + std::to_string(r);
      if (x.rungs[r].comment != y.rungs[r].comment) return c.fail(where + ": comment differs");
      if (!c.elements(x.rungs[r].elements, y.rungs[r].elements, where)) return false;
    }
  }
  if (a.data.size() != b.data.size()) return c.fail("data block count differs");
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    const auto& x = a.data[i];
    const auto& y = b.data[i];
    bool floats_equal = x.floats.size() == y.floats.size() &&
                        (x.floats.empty() || std::memcmp(x.floats.data(), y.floats.data(), x.floats.size() * sizeof(double)) == 0);
    if (x.type != y.type || x.file != y.file || x.start_element != y.start_element || x.words != y.words ||
        !floats_equal || x.strings != y.strings || x.opaque_text != y.opaque_text ||
        (!x.type && x.file_name != y.file_name))
      return c.fail("DATA " + x.file_name + " differs");
  }
  if (a.forces.size() != b.forces.size()) return c.fail("force block count differs");
  for (std::size_t i = 0; i < a.forces.size(); ++i) {
    const auto& x = a.forces[i];
    const auto& y = b.forces[i];
    if (x.type != y.type || x.slot != y.slot || x.words.size() != y.words.size())
      return c.fail("FORCE block " + std::to_string(i) + " differs");
    for (std::size_t w = 0; w < x.words.size(); ++w)
      if (x.words[w].on != y.words[w].on || x.words[w].off != y.words[w].off)
        return c.fail("FORCE block " + std::to_string(i) + " word " + std::to_string(w) + " differs");
  }
  if (a.data_logs.size() != b.data_logs.size()) return c.fail("DATALOG count differs");
  for (std::size_t i = 0; i < a.data_logs.size(); ++i) {
    const auto& x = a.data_logs[i];
    const auto& y = b.data_logs[i];
    if (x.number != y.number || x.records != y.records || x.date != y.date || x.time != y.time ||
        x.delimiter != y.delimiter || x.fields != y.fields)
      return c.fail("DATALOG " + std::to_string(x.number) + " differs");
  }
  if (a.symbols.size() != b.symbols.size()) return c.fail("symbol count differs");
  for (std::size_t i = 0; i < a.symbols.size(); ++i)
    if (a.symbols[i].name != b.symbols[i].name || !(a.symbols[i].address == b.symbols[i].address) ||
        a.symbols[i].description != b.symbols[i].description || a.symbols[i].automax != b.symbols[i].automax)
      return c.fail("symbol " + a.symbols[i].name + " differs");
  return true;
}

}  // namespace softslc
