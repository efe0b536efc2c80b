#include "tools/trace/ladder_layout.h"

#include "tools/trace/trace.h"

#include <algorithm>
#include <cctype>

#include <nlohmann/json.hpp>

namespace softslc::ladder {

namespace {

// A MicroLogix Modbus MSG (`MSG MG11:0 03 MODBUS LOCAL 0 N7:0 5 1 1 2`) holds its Modbus command, slave
// address and Modbus data address in the places of the read/write command, the target node and the
// target address (docs/semantics.md "The MicroLogix MSG over Modbus RTU"): the box names them as
// RSLogix's setup screen does ("Modbus Command", "MB Data Address").
std::string_view modbus_label(const Instruction& in, std::size_t i, std::string_view label) {
  if (in.opcode != Opcode::MSG_ML || in.operands.size() < 9 || in.operands[2].text() != "MODBUS") return label;
  switch (i) {
    case 1: return "modbus command";
    case 7: return "slave address";
    case 8: return "MB data address";
    default: return label;
  }
}

constexpr int kMaxDescriptionLines = 4;
constexpr int kMinLabelWidth = 12;

// A laid-out part of a rung, coordinates relative to its own top-left corner.
struct Block {
  int w = 0, h = 0, rail = 0;
  std::vector<InstructionBlock> instrs;
  std::vector<Wire> wires;
};

void translate(Block& b, int dx, int dy) {
  for (auto& i : b.instrs) {
    i.x += dx;
    i.y += dy;
    i.rail += dy;
  }
  for (auto& w : b.wires) {
    w.x0 += dx;
    w.x1 += dx;
    w.y0 += dy;
    w.y1 += dy;
  }
}

void append(Block& into, Block&& from) {
  for (auto& i : from.instrs) into.instrs.push_back(std::move(i));
  for (auto& w : from.wires) into.wires.push_back(w);
}

void hwire(Block& b, int x0, int x1, int y, bool powered) {
  if (x1 >= x0) b.wires.push_back({x0, y, x1, y, powered});
}

// Greedy word wrap to `width` columns, at most `max_lines` lines (the last one cut with "...").
std::vector<std::string> wrap(const std::string& text, int width, int max_lines) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  const auto w = static_cast<std::size_t>(std::max(width, 4));
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    std::size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j == i) break;
    std::string word = text.substr(i, j - i);
    i = j;
    while (word.size() > w) {  // a word longer than the column is split
      if (!line.empty()) {
        lines.push_back(line);
        line.clear();
      }
      lines.push_back(word.substr(0, w));
      word = word.substr(w);
    }
    if (line.empty()) line = word;
    else if (line.size() + 1 + word.size() <= w) line += " " + word;
    else {
      lines.push_back(line);
      line = word;
    }
  }
  if (!line.empty()) lines.push_back(line);
  if (static_cast<int>(lines.size()) > max_lines) {
    lines.resize(static_cast<std::size_t>(max_lines));
    std::string& last = lines.back();
    if (last.size() + 3 > w) last.resize(w - 3);
    last += "...";
  }
  return lines;
}

class Layouter {
 public:
  Layouter(const Program& p, const LadderState* state) : program_(p), state_(state) {}

  // Lays out one rung's elements (a sequence) from the left, given the power reaching it.
  Block sequence(const std::vector<RungElement>& elements, bool power_in, bool& power_out) {
    std::vector<Block> parts;
    bool power = power_in;
    for (const auto& e : elements) {
      if (e.kind == RungElement::Kind::Instruction) parts.push_back(instruction(e.instruction, power, power));
      else parts.push_back(branch(e, power, power));
    }
    power_out = power;
    return join(std::move(parts), power_in);
  }

  // Places blocks side by side with their rails on one row.
  static Block join(std::vector<Block> parts, bool power_in) {
    Block seq;
    for (const auto& p : parts) seq.rail = std::max(seq.rail, p.rail);
    if (parts.empty()) {  // an empty leg: a plain wire
      seq.w = 4;
      seq.h = 1;
      hwire(seq, 0, 3, 0, power_in);
      return seq;
    }
    int x = 0;
    for (auto& p : parts) {
      const int dy = seq.rail - p.rail;
      translate(p, x, dy);
      seq.h = std::max(seq.h, dy + p.h);
      x += p.w;
      append(seq, std::move(p));
    }
    seq.w = x;
    return seq;
  }

  Block branch(const RungElement& e, bool power_in, bool& power_out) {
    std::vector<Block> legs;
    std::vector<bool> outs;
    int inner = 0;
    for (const auto& leg : e.legs) {
      bool out = false;
      legs.push_back(sequence(leg, power_in, out));
      outs.push_back(out);
      inner = std::max(inner, legs.back().w);
    }
    power_out = std::any_of(outs.begin(), outs.end(), [](bool b) { return b; });
    Block b;
    b.w = inner + 2;
    int y = 0;
    int first_rail = 0, last_rail = 0;
    for (std::size_t i = 0; i < legs.size(); ++i) {
      Block& leg = legs[i];
      translate(leg, 1, y);
      const int rail = leg.rail + y;  // translate() moved instruction rails, not the block's
      if (i == 0) first_rail = rail;
      last_rail = rail;
      hwire(b, 0, 0, rail, power_in);
      hwire(b, 1 + leg.w, b.w - 1, rail, outs[i]);
      y += leg.h;
      append(b, std::move(leg));
    }
    b.h = y;
    b.rail = first_rail;
    if (last_rail > first_rail) {
      b.wires.push_back({0, first_rail, 0, last_rail, power_in});
      b.wires.push_back({b.w - 1, first_rail, b.w - 1, last_rail, power_out});
    }
    return b;
  }

  Block instruction(const Instruction& in, bool power_in, bool& power_out) {
    const auto& s = spec(in.opcode);
    InstructionBlock ib;
    ib.mnemonic = std::string(s.mnemonic);
    ib.index = next_index_++;
    ib.line = in.pos.line;
    ib.has_state = state_ != nullptr;
    ib.powered = state_ && power_in;
    const Operand* bit = in.operands.empty() ? nullptr : &in.operands[0];
    const std::string glyph = glyph_of(in.opcode);
    ib.truth = state_ && truth_of(in, s.role, ib.index, power_in);
    power_out = state_ && (s.role == Role::Input ? power_in && ib.truth : power_in);
    Block b;
    if (!glyph.empty() && bit) {
      ib.shape = in.opcode == Opcode::XIC || in.opcode == Opcode::XIO ? Shape::Contact : Shape::Coil;
      ib.glyph = glyph;
      const std::string address = bit->is_address() ? to_string(bit->address) : bit->spelling;
      std::string symbol = bit->kind == Operand::Kind::Symbol ? bit->spelling : symbol_of(*bit);
      int width = std::max<int>({kMinLabelWidth, static_cast<int>(address.size()), static_cast<int>(symbol.size())});
      if (const std::string d = description_of(*bit); !d.empty()) ib.above = wrap(d, width, kMaxDescriptionLines);
      if (!symbol.empty()) ib.above.push_back(symbol);
      ib.above.push_back(address);
      ib.w = width + 2;
      ib.h = static_cast<int>(ib.above.size()) + 1;
      ib.rail = ib.h - 1;
      const int g = (ib.w - 3) / 2;  // the glyph's first column
      hwire(b, 0, g - 1, ib.rail, ib.powered);
      hwire(b, g + 3, ib.w - 1, ib.rail, state_ && power_out);
    } else {
      ib.shape = Shape::Box;
      ib.rows.emplace_back(ib.mnemonic, "");
      const auto specs = s.operand_specs();
      for (std::size_t i = 0; i < in.operands.size(); ++i) {
        const Operand& o = in.operands[i];
        std::string label = i < specs.size() ? std::string(modbus_label(in, i, specs[i].label)) : std::string();
        if (!label.empty()) label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
        // A timer's or counter's preset and accumulator are written in the export as numbers but
        // are words of the element: online, RSLogix shows the element's live values there.
        const bool live_word = state_ && !in.operands.empty() && in.operands[0].is_address() &&
                               is_structured(in.operands[0].address.type) && in.operands[0].address.word < 0 &&
                               (label == "Preset" || label == "Accum");
        if (live_word) {
          Address w = in.operands[0].address;
          w.word = label == "Preset" ? 1 : 2;
          auto v = state_->value(w);
          ib.rows.emplace_back(label, v ? v->to_string() : o.text());
          continue;
        }
        ib.rows.emplace_back(label, o.text());
        // A MSG target is the other controller's address: no value of this one's under it.
        const bool remote = i < specs.size() && specs[i].kind == OperandKind::RemoteAddress;
        if (o.is_address() && !remote) {
          if (o.kind == Operand::Kind::Symbol) ib.rows.emplace_back("", to_string(o.address));
          else if (std::string sym = symbol_of(o); !sym.empty()) ib.rows.emplace_back("", sym);
          // A value under each data operand, RSLogix style ("25<"); not for a whole T/C/R element.
          const bool whole = is_structured(o.address.type) && o.address.word < 0 && o.address.bit < 0;
          if (state_ && !whole && !o.address.indexed && !o.address.is_indirect())
            if (auto v = state_->value(o.address)) ib.rows.emplace_back("", v->to_string() + "<");
        }
      }
      std::size_t inner = 10;
      for (const auto& [l, t] : ib.rows) inner = std::max(inner, l.size() + (l.empty() || t.empty() ? 0 : 1) + t.size());
      ib.w = static_cast<int>(inner) + 6;  // wire, frame, inner, frame, wire (2 + 1 + inner + 1 + 2)
      ib.h = static_cast<int>(ib.rows.size()) + 2;
      ib.rail = 1;
      hwire(b, 0, 1, ib.rail, ib.powered);
      hwire(b, ib.w - 2, ib.w - 1, ib.rail, state_ && power_out);
    }
    b.w = ib.w;
    b.h = ib.h;
    b.rail = ib.rail;
    b.instrs.push_back(std::move(ib));
    return b;
  }

  void start_rung(int file, int rung) {
    file_ = file;
    rung_ = rung;
    next_index_ = 0;
  }

 private:
  static std::string glyph_of(Opcode op) {
    switch (op) {
      case Opcode::XIC: return "] [";
      case Opcode::XIO: return "]/[";
      case Opcode::OTE: return "( )";
      case Opcode::OTL: return "(L)";
      case Opcode::OTU: return "(U)";
      default: return {};
    }
  }

  std::string symbol_of(const Operand& o) const {
    if (!o.is_address()) return {};
    for (const auto& s : program_.symbols)
      if (!s.name.empty() && s.address == o.address) return s.name;
    return {};
  }

  std::string description_of(const Operand& o) const {
    if (!o.is_address()) return {};
    for (const auto& s : program_.symbols)
      if (!s.description.empty() && s.address == o.address) return s.description;
    return {};
  }

  bool truth_of(const Instruction& in, Role role, int index, bool power_in) const {
    if (!state_) return false;
    auto bit_value = [&]() -> bool {
      if (in.operands.empty() || !in.operands[0].is_address()) return false;
      auto v = state_->value(in.operands[0].address);
      return v && v->as_bool();
    };
    switch (in.opcode) {
      case Opcode::XIC: return bit_value();
      case Opcode::XIO: return !bit_value();
      case Opcode::OTE:
      case Opcode::OTL:
      case Opcode::OTU: return bit_value();
      default: break;
    }
    if (role != Role::Input) return power_in;
    auto f = state_->input_truth.find(file_);
    if (f == state_->input_truth.end() || rung_ < 0 || static_cast<std::size_t>(rung_) >= f->second.size()) return false;
    const auto& r = f->second[static_cast<std::size_t>(rung_)];
    if (index < 0 || static_cast<std::size_t>(index) >= r.size() || !r[static_cast<std::size_t>(index)]) return false;
    return *r[static_cast<std::size_t>(index)];
  }

  const Program& program_;
  const LadderState* state_;
  int file_ = 2, rung_ = 0, next_index_ = 0;
};

// Whether an element belongs to the right-hand (output) side of a rung: an output instruction, or
// an output branch — one whose every leg starts with an output-side element. A branch whose legs
// start with conditions is drawn from the left, its outputs at the end of their legs.
bool is_output_side(const RungElement& e) {
  if (e.kind == RungElement::Kind::Instruction) return spec(e.instruction.opcode).role == Role::Output;
  for (const auto& leg : e.legs)
    if (leg.empty() || !is_output_side(leg.front())) return false;
  return !e.legs.empty();
}

struct PendingRung {
  RungLayout rung;
  Block left, right;
  bool power_mid = false;  // power leaving the input side
  bool power_in = false;
};

}  // namespace

LadderLayout layout_ladder(const Program& program, const LayoutOptions& options) {
  LadderLayout layout;
  layout.has_state = options.state != nullptr;
  Layouter lay(program, options.state);
  std::vector<std::pair<std::size_t, std::vector<PendingRung>>> pending;  // per file
  int natural = kMinWidth;
  for (const auto& f : program.files) {
    if (options.file && *options.file != f.number) continue;
    FileLayout fl;
    fl.number = f.number;
    fl.name = f.name;
    fl.total_rungs = static_cast<int>(f.rungs.size());
    std::vector<PendingRung> rungs;
    // The END rung (number = rung count) is drawn when the range reaches it, as RSLogix shows it.
    const int count = static_cast<int>(f.rungs.size());
    const int last = options.last_rung < 0 ? count : std::min(options.last_rung, count);
    for (int r = options.first_rung; r <= last; ++r) {
      PendingRung p;
      p.rung.file = f.number;
      p.rung.number = r;
      p.power_in = options.state != nullptr;
      if (r == static_cast<int>(f.rungs.size())) {
        p.rung.end_rung = true;
        rungs.push_back(std::move(p));
        continue;
      }
      const Rung& rung = f.rungs[static_cast<std::size_t>(r)];
      lay.start_rung(f.number, r);
      // The input side from the left rail; the trailing run of output elements against the right.
      std::size_t split = rung.elements.size();
      while (split > 0 && is_output_side(rung.elements[split - 1])) --split;
      std::vector<RungElement> left(rung.elements.begin(), rung.elements.begin() + static_cast<std::ptrdiff_t>(split));
      std::vector<RungElement> right(rung.elements.begin() + static_cast<std::ptrdiff_t>(split), rung.elements.end());
      bool out = false;
      p.left = left.empty() ? Block{} : lay.sequence(left, p.power_in, p.power_mid);
      if (left.empty()) p.power_mid = p.power_in;
      p.right = right.empty() ? Block{} : lay.sequence(right, p.power_mid, out);
      p.rung.comment.clear();
      natural = std::max(natural, kLeftRail + 1 + p.left.w + 4 + p.right.w + 1);
      rungs.push_back(std::move(p));
    }
    layout.files.push_back(std::move(fl));
    pending.emplace_back(layout.files.size() - 1, std::move(rungs));
  }
  layout.width = natural;
  const int right_rail = layout.width - 1;
  for (auto& [fi, rungs] : pending) {
    const ProgramFile* src = program.find_file(layout.files[fi].number);
    for (auto& p : rungs) {
      RungLayout& rl = p.rung;
      if (!rl.end_rung && src) {
        const std::string& c = src->rungs[static_cast<std::size_t>(rl.number)].comment;
        if (!c.empty()) rl.comment = wrap(c, layout.width - kLeftRail - 4, 1000);
      }
      Block body;
      if (rl.end_rung) {
        InstructionBlock end;
        end.shape = Shape::Coil;
        end.mnemonic = "END";
        end.glyph = "<END>";
        end.w = 5;
        end.h = 1;
        end.x = (kLeftRail + right_rail) / 2 - 2;
        end.rail = 0;
        end.index = -1;
        body.instrs.push_back(end);
        hwire(body, kLeftRail + 1, end.x - 1, 0, p.power_in);
        hwire(body, end.x + end.w, right_rail - 1, 0, p.power_in);
        body.h = 1;
      } else {
        const int rail = std::max(p.left.rail, p.right.rail);
        const int lx = kLeftRail + 1;
        const int rx = right_rail - p.right.w;
        translate(p.left, lx, rail - p.left.rail);
        translate(p.right, rx, rail - p.right.rail);
        body.h = std::max({rail + 1, rail - p.left.rail + p.left.h, rail - p.right.rail + p.right.h});
        body.rail = rail;
        hwire(body, lx + p.left.w, rx - 1, rail, p.power_mid);
        append(body, std::move(p.left));
        append(body, std::move(p.right));
      }
      rl.top = static_cast<int>(rl.comment.size());
      rl.rail = body.rail + rl.top;
      rl.height = body.h + 1;  // one empty row between rungs
      translate(body, 0, rl.top);
      rl.blocks = std::move(body.instrs);
      rl.wires = std::move(body.wires);
      layout.files[fi].rungs.push_back(std::move(rl));
    }
  }
  return layout;
}

namespace {

// A character grid for one rung.
struct Grid {
  int w, h;
  std::vector<std::string> rows;
  Grid(int width, int height) : w(width), h(height), rows(static_cast<std::size_t>(height), std::string(static_cast<std::size_t>(width), ' ')) {}
  void put(int x, int y, char c) {
    if (x >= 0 && y >= 0 && x < w && y < h) rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = c;
  }
  char at(int x, int y) const {
    return x >= 0 && y >= 0 && x < w && y < h ? rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] : ' ';
  }
  void text(int x, int y, const std::string& s) {
    for (std::size_t i = 0; i < s.size(); ++i) put(x + static_cast<int>(i), y, s[i]);
  }
};

int centered(int x, int w, std::size_t len) { return x + (w - static_cast<int>(len)) / 2; }

std::string rung_number(int n) {
  std::string s = std::to_string(n);
  return std::string(s.size() < 4 ? 4 - s.size() : 0, '0') + s;
}

std::string file_header(const FileLayout& f) {
  return "LAD " + std::to_string(f.number) + (f.name.empty() ? "" : " - " + f.name) +
         " --- Total Rungs in File = " + std::to_string(f.total_rungs);
}

std::string xml(const std::string& s) { return trace::xml_escape(s); }

}  // namespace

std::string render_text(const LadderLayout& layout) {
  std::string out;
  const int right_rail = layout.width - 1;
  for (const auto& f : layout.files) {
    out += file_header(f) + "\n";
    for (const auto& r : f.rungs) {
      Grid g(layout.width, r.top + r.height);
      for (int y = 0; y < g.h; ++y) {
        g.put(kLeftRail, y, '|');
        g.put(right_rail, y, '|');
      }
      for (std::size_t i = 0; i < r.comment.size(); ++i) g.text(kLeftRail + 2, static_cast<int>(i), r.comment[i]);
      g.text(0, r.rail, rung_number(r.number));
      for (const auto& w : r.wires)
        if (w.y0 == w.y1)
          for (int x = w.x0; x <= w.x1; ++x) g.put(x, w.y0, w.powered ? '=' : '-');
      for (const auto& w : r.wires)
        if (w.x0 == w.x1 && w.y0 != w.y1)
          for (int y = w.y0; y <= w.y1; ++y) {
            const char c = g.at(w.x0, y);
            g.put(w.x0, y, c == '-' || c == '=' || c == '+' ? '+' : '|');
          }
      for (const auto& b : r.blocks) {
        if (b.shape == Shape::Box) {
          const int x0 = b.x + 2, x1 = b.x + b.w - 3;
          for (int x = x0; x <= x1; ++x) {
            g.put(x, b.y, '-');
            g.put(x, b.y + b.h - 1, '-');
          }
          for (int y = b.y; y < b.y + b.h; ++y) {
            const bool corner = y == b.y || y == b.y + b.h - 1;
            g.put(x0, y, corner ? '+' : '|');
            g.put(x1, y, corner ? '+' : '|');
          }
          const int inner = x1 - x0 - 1;
          for (std::size_t i = 0; i < b.rows.size(); ++i) {
            const auto& [label, text] = b.rows[i];
            const int y = b.y + 1 + static_cast<int>(i);
            g.text(x0 + 1, y, label);
            g.text(x0 + 1 + inner - static_cast<int>(text.size()), y, text);
          }
          // A true box is marked by a '*' after its mnemonic.
          if (b.has_state && b.truth) g.put(x0 + 1 + static_cast<int>(b.mnemonic.size()), b.y + 1, '*');
        } else {
          for (std::size_t i = 0; i < b.above.size(); ++i)
            g.text(centered(b.x, b.w, b.above[i].size()), b.y + static_cast<int>(i), b.above[i]);
          const int gx = b.index < 0 ? b.x : b.x + (b.w - 3) / 2;
          g.text(gx, b.rail, b.glyph);
          // A true contact or coil (RSLogix highlights it) is marked by a '*' just left of its glyph.
          if (b.has_state && b.truth && b.index >= 0) g.put(gx - 1, b.rail, '*');
        }
      }
      for (auto& row : g.rows) {
        while (!row.empty() && row.back() == ' ') row.pop_back();
        out += row + "\n";
      }
    }
  }
  return out;
}

std::string render_svg(const LadderLayout& layout, const std::string& title) {
  int rows = 3;  // the title, and a margin under the last rung
  for (const auto& f : layout.files) {
    rows += 1;
    for (const auto& r : f.rungs) rows += r.top + r.height;
  }
  const int W = layout.width * kCellW, H = rows * kCellH;
  const std::string on = "#0a0", off = "#222";
  auto cx = [](int x) { return std::to_string(x * kCellW + kCellW / 2); };
  auto cy = [](int y, int base) { return std::to_string((base + y) * kCellH + kCellH / 2); };
  std::string o;
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(W) + "\" height=\"" + std::to_string(H) +
       "\" viewBox=\"0 0 " + std::to_string(W) + " " + std::to_string(H) +
       "\" font-family=\"monospace\" font-size=\"12\">\n";
  o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o += "<text x=\"4\" y=\"" + std::to_string(kCellH - 3) + "\" font-size=\"13\">" + xml(title) + "</text>\n";
  int base = 2;
  for (const auto& f : layout.files) {
    o += "<text x=\"4\" y=\"" + std::to_string(base * kCellH - 3) + "\" font-weight=\"bold\">" + xml(file_header(f)) +
         "</text>\n";
    base += 1;
    for (const auto& r : f.rungs) {
      const int rows_here = r.top + r.height;
      o += "<g class=\"rung\" data-file=\"" + std::to_string(r.file) + "\" data-rung=\"" + std::to_string(r.number) + "\">\n";
      // Rails and rung number.
      for (int x : {kLeftRail, layout.width - 1})
        o += "<line x1=\"" + cx(x) + "\" y1=\"" + std::to_string(base * kCellH) + "\" x2=\"" + cx(x) + "\" y2=\"" +
             std::to_string((base + rows_here) * kCellH) + "\" stroke=\"" + off + "\" stroke-width=\"2\"/>\n";
      o += "<text x=\"2\" y=\"" + std::to_string((base + r.rail) * kCellH + 12) + "\">" + rung_number(r.number) + "</text>\n";
      for (std::size_t i = 0; i < r.comment.size(); ++i)
        o += "<text class=\"comment\" x=\"" + std::to_string((kLeftRail + 2) * kCellW) + "\" y=\"" +
             std::to_string((base + static_cast<int>(i)) * kCellH + 12) + "\" fill=\"#555\">" + xml(r.comment[i]) + "</text>\n";
      for (const auto& w : r.wires) {
        const std::string colour = w.powered ? on : off;
        const std::string width = w.powered ? "3" : "1.5";
        if (w.y0 == w.y1)
          o += "<line x1=\"" + std::to_string(w.x0 * kCellW) + "\" y1=\"" + cy(w.y0, base) + "\" x2=\"" +
               std::to_string((w.x1 + 1) * kCellW) + "\" y2=\"" + cy(w.y0, base) + "\" stroke=\"" + colour +
               "\" stroke-width=\"" + width + "\"/>\n";
        else
          o += "<line x1=\"" + cx(w.x0) + "\" y1=\"" + cy(w.y0, base) + "\" x2=\"" + cx(w.x0) + "\" y2=\"" + cy(w.y1, base) +
               "\" stroke=\"" + colour + "\" stroke-width=\"" + width + "\"/>\n";
      }
      for (const auto& b : r.blocks) {
        const std::string colour = b.truth ? on : off;
        o += "<g class=\"instruction\" data-mnemonic=\"" + xml(b.mnemonic) + "\" data-index=\"" + std::to_string(b.index) +
             "\"" + (b.has_state ? std::string(" data-true=\"") + (b.truth ? "1" : "0") + "\" data-powered=\"" + (b.powered ? "1" : "0") + "\"" : "") + ">\n";
        if (b.shape == Shape::Box) {
          const int x0 = (b.x + 2) * kCellW, x1 = (b.x + b.w - 2) * kCellW;
          const int y0 = (base + b.y) * kCellH + kCellH / 2, y1 = (base + b.y + b.h - 1) * kCellH + kCellH / 2;
          o += "<rect x=\"" + std::to_string(x0) + "\" y=\"" + std::to_string(y0) + "\" width=\"" + std::to_string(x1 - x0) +
               "\" height=\"" + std::to_string(y1 - y0) + "\" fill=\"" + (b.truth ? "#dfd" : "white") + "\" stroke=\"" + colour +
               "\" stroke-width=\"1.5\"/>\n";
          for (std::size_t i = 0; i < b.rows.size(); ++i) {
            const auto& [label, text] = b.rows[i];
            const int y = (base + b.y + 1 + static_cast<int>(i)) * kCellH + 12;
            o += "<text x=\"" + std::to_string(x0 + 4) + "\" y=\"" + std::to_string(y) + "\"" +
                 (i == 0 ? " font-weight=\"bold\"" : "") + ">" + xml(label) + "</text>\n";
            if (!text.empty())
              o += "<text x=\"" + std::to_string(x1 - 4) + "\" y=\"" + std::to_string(y) + "\" text-anchor=\"end\">" + xml(text) +
                   "</text>\n";
          }
          o += "</g>\n";
          continue;
        }
        for (std::size_t i = 0; i < b.above.size(); ++i)
          o += "<text x=\"" + std::to_string(b.x * kCellW + b.w * kCellW / 2) + "\" y=\"" +
               std::to_string((base + b.y + static_cast<int>(i)) * kCellH + 12) + "\" text-anchor=\"middle\"" +
               (i + 1 == b.above.size() ? " font-weight=\"bold\"" : "") + ">" + xml(b.above[i]) + "</text>\n";
        const int gx = (b.index < 0 ? b.x : b.x + (b.w - 3) / 2) * kCellW;
        const int ym = (base + b.rail) * kCellH + kCellH / 2;
        const int gw = static_cast<int>(b.glyph.size()) * kCellW;
        o += "<rect x=\"" + std::to_string(gx) + "\" y=\"" + std::to_string(ym - 7) + "\" width=\"" + std::to_string(gw) +
             "\" height=\"14\" fill=\"" + (b.truth ? "#bfb" : "white") + "\" stroke=\"none\"/>\n";
        if (b.shape == Shape::Contact) {
          for (int x : {gx + 4, gx + gw - 4})
            o += "<line x1=\"" + std::to_string(x) + "\" y1=\"" + std::to_string(ym - 7) + "\" x2=\"" + std::to_string(x) +
                 "\" y2=\"" + std::to_string(ym + 7) + "\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n";
          if (b.glyph == "]/[")
            o += "<line x1=\"" + std::to_string(gx + 6) + "\" y1=\"" + std::to_string(ym + 6) + "\" x2=\"" +
                 std::to_string(gx + gw - 6) + "\" y2=\"" + std::to_string(ym - 6) + "\" stroke=\"" + colour +
                 "\" stroke-width=\"1.5\"/>\n";
          o += "<line x1=\"" + std::to_string(gx) + "\" y1=\"" + std::to_string(ym) + "\" x2=\"" + std::to_string(gx + 4) +
               "\" y2=\"" + std::to_string(ym) + "\" stroke=\"" + (b.powered ? on : off) + "\" stroke-width=\"1.5\"/>\n";
          o += "<line x1=\"" + std::to_string(gx + gw - 4) + "\" y1=\"" + std::to_string(ym) + "\" x2=\"" + std::to_string(gx + gw) +
               "\" y2=\"" + std::to_string(ym) + "\" stroke=\"" + (b.powered && b.truth ? on : off) + "\" stroke-width=\"1.5\"/>\n";
        } else if (b.index < 0) {
          o += "<text x=\"" + std::to_string(gx + gw / 2) + "\" y=\"" + std::to_string(ym + 4) + "\" text-anchor=\"middle\">" +
               xml(b.glyph) + "</text>\n";
        } else {
          // A coil: two arcs, with L or U between them for latch and unlatch.
          const int l = gx + 5, rr = gx + gw - 5;
          o += "<path d=\"M" + std::to_string(l) + " " + std::to_string(ym - 7) + " Q" + std::to_string(l - 5) + " " +
               std::to_string(ym) + " " + std::to_string(l) + " " + std::to_string(ym + 7) + " M" + std::to_string(rr) + " " +
               std::to_string(ym - 7) + " Q" + std::to_string(rr + 5) + " " + std::to_string(ym) + " " + std::to_string(rr) + " " +
               std::to_string(ym + 7) + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n";
          for (int x0 : {gx, rr})
            o += "<line x1=\"" + std::to_string(x0) + "\" y1=\"" + std::to_string(ym) + "\" x2=\"" + std::to_string(x0 == gx ? l - 3 : gx + gw) +
                 "\" y2=\"" + std::to_string(ym) + "\" stroke=\"" + (b.powered ? on : off) + "\" stroke-width=\"1.5\"/>\n";
          if (b.glyph[1] != ' ')
            o += "<text x=\"" + std::to_string(gx + gw / 2) + "\" y=\"" + std::to_string(ym + 4) + "\" text-anchor=\"middle\">" +
                 std::string(1, b.glyph[1]) + "</text>\n";
        }
        o += "</g>\n";
      }
      o += "</g>\n";
      base += rows_here;
    }
  }
  o += "</svg>\n";
  return o;
}

std::string render_json(const LadderLayout& layout) {
  nlohmann::ordered_json j;
  j["width"] = layout.width;
  j["has_state"] = layout.has_state;
  j["files"] = nlohmann::ordered_json::array();
  for (const auto& f : layout.files) {
    nlohmann::ordered_json jf{{"number", f.number}, {"name", f.name}, {"total_rungs", f.total_rungs}};
    jf["rungs"] = nlohmann::ordered_json::array();
    for (const auto& r : f.rungs) {
      nlohmann::ordered_json jr{{"number", r.number}, {"end_rung", r.end_rung}, {"comment", r.comment},
                                {"top", r.top},       {"height", r.height},     {"rail", r.rail}};
      jr["blocks"] = nlohmann::ordered_json::array();
      for (const auto& b : r.blocks) {
        nlohmann::ordered_json jb{{"mnemonic", b.mnemonic},
                                  {"shape", b.shape == Shape::Contact ? "contact" : b.shape == Shape::Coil ? "coil" : "box"},
                                  {"index", b.index}, {"line", b.line}, {"x", b.x}, {"y", b.y}, {"w", b.w}, {"h", b.h},
                                  {"rail", b.rail}, {"glyph", b.glyph}, {"above", b.above}};
        jb["rows"] = nlohmann::ordered_json::array();
        for (const auto& [label, text] : b.rows) jb["rows"].push_back({label, text});
        if (b.has_state) {
          jb["powered"] = b.powered;
          jb["true"] = b.truth;
        }
        jr["blocks"].push_back(std::move(jb));
      }
      jr["wires"] = nlohmann::ordered_json::array();
      for (const auto& w : r.wires) {
        nlohmann::ordered_json jw{{"x0", w.x0}, {"y0", w.y0}, {"x1", w.x1}, {"y1", w.y1}};
        if (layout.has_state) jw["powered"] = w.powered;
        jr["wires"].push_back(std::move(jw));
      }
      jf["rungs"].push_back(std::move(jr));
    }
    j["files"].push_back(std::move(jf));
  }
  return j.dump(1) + "\n";
}

}  // namespace softslc::ladder
