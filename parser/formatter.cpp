#include "parser/formatter.h"

#include <algorithm>

#include <charconv>
#include <cstdio>

namespace softslc {

std::string format_float(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

namespace {

std::string format_operand(const Operand& op) {
  switch (op.kind) {
    case Operand::Kind::Address: return to_string(op.address);
    case Operand::Kind::Symbol:
    case Operand::Kind::Expression: return op.spelling;
    case Operand::Kind::Float: return format_float(op.real);
    case Operand::Kind::Integer: {
      const auto& sp = op.spelling;
      bool hex = sp.find("0x") != std::string::npos || sp.find("0X") != std::string::npos ||
                 (!sp.empty() && (sp.back() == 'h' || sp.back() == 'H'));
      // HSL/RAC's counter written as RSLogix shows it (HSC0): the checker reads it as its number.
      if (sp.size() == 4 && sp.compare(0, 3, "HSC") == 0 && sp[3] - '0' == op.integer) return sp;
      if (hex && op.integer >= 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "0x%04llX", static_cast<unsigned long long>(op.integer));
        return buf;
      }
      return std::to_string(op.integer);
    }
  }
  return {};
}

void format_elements(const std::vector<RungElement>& elems, std::string& out) {
  for (const auto& e : elems) {
    if (e.kind == RungElement::Kind::Branch) {
      out += "BST ";
      for (std::size_t l = 0; l < e.legs.size(); ++l) {
        if (l > 0) out += "NXB ";
        format_elements(e.legs[l], out);
      }
      out += "BND ";
      continue;
    }
    out += spec(e.instruction.opcode).mnemonic;
    out += ' ';
    const auto& ops = e.instruction.operands;
    for (std::size_t i = 0; i < ops.size(); ++i) {
      // A MicroLogix Modbus MSG's command in two digits, as RSLogix shows it ("03 Read Holding Registers").
      const bool modbus_command = e.instruction.opcode == Opcode::MSG_ML && i == 1 && ops.size() > 2 &&
                                  ops[1].kind == Operand::Kind::Integer && ops[1].integer >= 0 && ops[1].integer < 10 &&
                                  ops[2].kind == Operand::Kind::Symbol && ops[2].spelling == "MODBUS";
      out += (modbus_command ? "0" : "") + format_operand(ops[i]) + ' ';
    }
  }
}

std::string pad_left(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

std::string hex_word(std::int64_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0X%04X", static_cast<unsigned>(v & 0xFFFF));
  return buf;
}

std::string file_prefix(const DataBlock& d) {
  std::string s(file_letter(*d.type));
  if (fixed_file_number(*d.type) < 0) s += std::to_string(d.file);
  return s;
}

// The HSC: each element on three rows as RSLogix exports it (59-BSGS.SLC): PFN ER bits bits MOD;
// the long words ACC HIP LOP OVF UNF; OMB HPO LPO (hsc::kExportValues values an element).
void format_hsc_data(const DataBlock& d, std::string& out) {
  for (std::size_t i = 0; i + hsc::kExportValues <= d.words.size(); i += hsc::kExportValues) {
    const int element = d.start_element + static_cast<int>(i / hsc::kExportValues);
    out += "% " + d.file_name.substr(0, d.file_name.find(':')) + ":" + std::to_string(element) + " %\n";
    const auto v = [&](std::size_t k) { return d.words[i + k]; };
    out += pad_left(std::to_string(static_cast<std::uint16_t>(v(0))), 6) + " " +
           pad_left(std::to_string(static_cast<std::uint16_t>(v(1))), 6) + " " + hex_word(v(2)) + " " + hex_word(v(3)) + " " +
           pad_left(std::to_string(static_cast<std::uint16_t>(v(4))), 6) + "\n";
    for (std::size_t k = 5; k < 10; ++k) out += " " + pad_left(std::to_string(v(k)), 12);
    out += "\n";
    for (std::size_t k = 10; k < 13; ++k) out += (k > 10 ? " " : "") + pad_left(std::to_string(static_cast<std::uint16_t>(v(k))), 6);
    out += "\n";
  }
  out += "\n";
}

void format_data(const DataBlock& d, std::string& out) {
  out += "DATA " + d.file_name + " \n";
  if (!d.type) {
    out += d.opaque_text + "\n\n";
    return;
  }
  const FileType t = *d.type;
  if (is_function_file(t) && is_pulse_train_file(d.file)) {
    // PTO/PTOX: one row of nine values per element (OUT bits ER OF OFS JF TOP OPP ADP), the bit word in hex.
    const std::string name(function_file_name(d.file));
    for (std::size_t i = 0; i < d.words.size(); ++i) {
      const std::size_t k = i % pto::kValuesPerElement;
      if (k == 0) out += "% " + name + "0:" + std::to_string(i / pto::kValuesPerElement) + " %";
      out += " " + (k == 1 ? hex_word(static_cast<std::uint16_t>(d.words[i])) : std::to_string(d.words[i]));
      if (k + 1 == pto::kValuesPerElement) out += "\n";
    }
    out += "\n";
    return;
  }
  if (is_function_file(t) && d.file == static_cast<int>(FunctionFile::HSC)) return format_hsc_data(d, out);
  if (is_function_file(t) && d.file == static_cast<int>(FunctionFile::EII)) {
    // The EII: one row per element, PFN ER bits IS, the bit word in hex, as RSLogix exports it.
    for (std::size_t i = 0; i < d.words.size(); ++i) {
      const std::size_t k = i % static_cast<std::size_t>(eii::kWords);
      if (k == 0) out += "% EII0:" + std::to_string(i / static_cast<std::size_t>(eii::kWords)) + " %";
      const auto w = static_cast<std::uint16_t>(d.words[i]);
      out += " " + (k == static_cast<std::size_t>(eii::kBits) ? hex_word(w) : std::to_string(w));
      if (k + 1 == static_cast<std::size_t>(eii::kWords)) out += "\n";
    }
    out += "\n";
    return;
  }
  if (is_function_file(t)) {
    // The STI: one row of PFN ER bits SPM as RSLogix exports it (SPM is 0-65,535).
    out += "% .PFN    .ER  bits   .SPM  %\n";
    for (std::size_t i = 0; i < d.words.size(); ++i) {
      const auto w = static_cast<std::uint16_t>(d.words[i]);
      out += (i ? " " : "") + (i == static_cast<std::size_t>(sti::kBits) ? hex_word(w) : pad_left(std::to_string(w), 6));
    }
    out += " % " + d.file_name + " %\n\n";
    return;
  }
  const std::string prefix = file_prefix(d);
  if (is_io(t)) {
    out += "% " + prefix + ":" + std::to_string(d.start_element) + ".0 %";
    for (auto w : d.words) out += ' ' + hex_word(w);
    out += " \n\n";
    return;
  }
  if (is_structured(t)) {
    out += t == FileType::Control ? "% .CTL   .LEN   .POS    %\n" : "% .CTL   .PRE   .ACC    %\n";
    for (std::size_t i = 0; i + 2 < d.words.size(); i += 3) {
      int element = d.start_element + static_cast<int>(i / 3);
      out += hex_word(d.words[i]) + ' ' + pad_left(std::to_string(d.words[i + 1]), 6) + ' ' +
             pad_left(std::to_string(d.words[i + 2]), 6) + " % " + prefix + ":" + std::to_string(element) + " %\n";
    }
    out += '\n';
    return;
  }
  if (is_multiword_data(t)) {
    // MG and RI: one row per element, its words 0-24 (0-19) in order.
    const auto per_element = static_cast<std::size_t>(words_per_element(t));
    for (std::size_t i = 0; i < d.words.size(); i += per_element) {
      out += "% " + prefix + ":" + std::to_string(d.start_element + static_cast<int>(i / per_element)) + " %";
      for (std::size_t k = i; k < d.words.size() && k < i + per_element; ++k) out += ' ' + std::to_string(d.words[k]);
      out += " \n";
    }
    out += '\n';
    return;
  }
  if (t == FileType::String) {
    for (std::size_t i = 0; i < d.strings.size(); ++i)
      out += "% " + prefix + ":" + std::to_string(d.start_element + i) + " % \"" + d.strings[i] + "\"\n";
    out += '\n';
    return;
  }
  const bool is_float = t == FileType::Float;
  const std::size_t count = is_float ? d.floats.size() : d.words.size();
  const std::size_t per_row = (t == FileType::Long || is_float) ? 5 : 10;
  const std::size_t width = t == FileType::Long ? 12 : 7;
  for (std::size_t i = 0; i < count; i += per_row) {
    out += "% " + prefix + ":" + std::to_string(d.start_element + i) + " %";
    for (std::size_t k = i; k < count && k < i + per_row; ++k)
      out += ' ' + pad_left(is_float ? format_float(d.floats[k]) : std::to_string(d.words[k]), width - 1);
    out += " \n";
  }
  out += '\n';
}

void format_force(const ForceBlock& f, std::string& out) {
  char slot[8];
  std::snprintf(slot, sizeof slot, "%02d", f.slot);
  std::string name = std::string(file_letter(f.type)) + ":" + slot;
  out += "FORCE " + name + "\n% ON     OFF  %\n";
  for (std::size_t w = 0; w < f.words.size(); ++w)
    out += hex_word(f.words[w].on) + ' ' + hex_word(f.words[w].off) + " % FORCE " + std::string(file_letter(f.type)) +
           ":" + std::to_string(f.slot) + "." + std::to_string(w) + " %\n";
  out += "\n";
}

}  // namespace

std::string format_rung(const Rung& rung) {
  std::string out = "SOR ";
  format_elements(rung.elements, out);
  out += "EOR";
  return out;
}

std::string format_program(const Program& p) {
  std::string out = "START " + p.processor.catalog;
  if (p.series_given) out += std::string(" SERIES ") + *p.series_given;
  if (p.frn_given) out += " FRN " + std::to_string(*p.frn_given);
  if (!p.processor_description.empty()) out += "    % " + p.processor_description + " %";
  out += "\n\n";
  // The embedded I/O a MicroLogix brings (an implicit slot 0) is not written, nor a header for it.
  if (std::any_of(p.slots.begin(), p.slots.end(), [](const SlotConfig& s) { return !s.implicit; }))
    out += "% PROCESSOR RACK CONFIGURATION INFORMATION %\n% SLOT CONFIGURATION INFORMATION %\n";
  for (const auto& s : p.slots) {
    if (s.implicit) continue;  // the controller's embedded I/O, added when the file has no SLOT 0
    out += "SLOT " + std::to_string(s.slot) + " " + s.catalog;
    if (!s.description.empty()) out += "   % " + s.description + " %";
    out += "  SCAN_IN " + std::to_string(s.scan_in) + " SCAN_OUT " + std::to_string(s.scan_out);
    if (s.has_g_file) {
      out += "  G_FILE " + std::to_string(s.g_file.size()) + "\n    ";
      for (auto w : s.g_file) out += ' ' + std::to_string(w);
    }
    if (!s.iocard.empty()) {
      out += " IOCARD";
      for (auto v : s.iocard) out += ' ' + std::to_string(v);
    }
    if (s.m0_size) out += " M0_SIZE " + std::to_string(*s.m0_size);
    if (s.m1_size) out += " M1_SIZE " + std::to_string(*s.m1_size);
    if (s.id_code) out += " ID_CODE " + std::to_string(*s.id_code);
    for (const auto& [k, v] : s.options) out += " OPTION " + k + "=" + v;
    out += '\n';
  }
  out += "\n\n";
  if (!p.project.empty()) out += "PROJECT \"" + p.project + "\"\n\n";
  for (const auto& f : p.files) {
    out += "LADDER " + std::to_string(f.number);
    if (!f.name.empty()) out += " \"" + f.name + "\"";
    out += '\n';
    for (std::size_t r = 0; r < f.rungs.size(); ++r) {
      out += "% Rung: " + std::to_string(r) + " %\n";
      if (!f.rungs[r].comment.empty()) out += "% " + f.rungs[r].comment + " %\n";
      out += format_rung(f.rungs[r]) + " \n";
    }
    out += '\n';
  }
  for (const auto& d : p.data) format_data(d, out);
  for (const auto& f : p.forces) format_force(f, out);
  for (const auto& q : p.data_logs) {
    out += "DATALOG " + std::to_string(q.number) + " RECORDS " + std::to_string(q.records);
    if (q.date) out += " DATE";
    if (q.time) out += " TIME";
    out += q.delimiter == '\t' ? " DELIMITER TAB" : q.delimiter == ' ' ? " DELIMITER SPACE" : " DELIMITER COMMA";
    for (const auto& f : q.fields) out += " " + to_string(f);
    out += '\n';
  }
  if (!p.data_logs.empty()) out += '\n';
  for (const auto& s : p.symbols) {
    if (s.automax) {
      out += std::string(keyword_of(s.automax->kind)) + " " + s.name + s.automax->suffix;
      if (s.automax->kind != AutomaxDef::Kind::MemDef) {
        std::string fields;
        for (const auto& f : s.automax->fields) fields += (fields.empty() ? "" : ",") + f.key + "=" + f.spelling;
        out += "[" + fields + "]";
      }
      if (!s.description.empty()) out += " % " + s.description + " %";
      out += '\n';
    } else if (s.name.empty()) {
      out += "DESC " + to_string(s.address) + " % " + s.description + " %\n";
    } else {
      out += "SYMBOL " + to_string(s.address) + " " + s.name;
      if (!s.description.empty()) out += " % " + s.description + " %";
      out += '\n';
    }
  }
  return out;
}

}  // namespace softslc
