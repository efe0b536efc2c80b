// Ladder diagrams: rungs laid out once, on a grid of character cells, then drawn as text or SVG.
//
// layout_ladder() is the single layout pass. It places every instruction of the chosen rungs the
// way RSLogix 500 draws them — contacts and coils with their description, symbol and address
// above, output boxes with one row per operand, branches as nested legs joined by vertical
// connectors, input instructions from the left rail and the rung's outputs against the right rail,
// the rung number at the left and the rung comment above — and records the result as plain
// geometry: instruction blocks and wire segments in cell coordinates. The renderers only draw that
// geometry (render_text(): one character per cell; render_svg(): a cell is kCellW x kCellH
// pixels), so the two forms cannot disagree, and a later consumer (the browser view of `softslc
// serve`) can take the same geometry as data.
//
// State. With a LadderState the layout also carries values and power flow, as RSLogix shows a
// program online: each instruction's own truth (XIC/XIO/OTE/OTL/OTU from their bit; other input
// instructions from the last scan's record, see LadderState) and whether power reaches it, worked
// out left to right through the rung's structure (power into a branch reaches every leg; power out
// of a branch is the OR of its legs). Box operands that name data show their value below them.
//
// Block geometry, in cells (x to the right, y down, relative to the block):
//   contact/coil  width max(7, longest label) + 2; label lines on top; the rail on the last line
//   box           a frame of max(label + operand) + 4 cells, the rail through its title row
//   sequence      blocks side by side, rails aligned (the sequence's rail is its lowest block rail)
//   branch        legs stacked, each leg's rail one row below the previous leg's block; a vertical
//                 connector in the first and last column from the first leg's rail to the last's
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/data_table.h"

namespace softslc::ladder {

// What a rendering knows of a running (or stored) controller.
struct LadderState {
  // The value of an address, or nullopt when it cannot be read.
  std::function<std::optional<Value>(const Address&)> value;
  // Truth of input instructions other than XIC/XIO (compares, OSR, ...) in the last scan, per
  // program file, rung and instruction index (code order: depth first through branch legs).
  // Missing entries count as false (not known to have passed power).
  std::map<int, std::vector<std::vector<std::optional<bool>>>> input_truth;
};

enum class Shape : std::uint8_t { Contact, Coil, Box };

struct InstructionBlock {
  int x = 0, y = 0, w = 0, h = 0;  // the block in rung cells, labels included
  int rail = 0;                    // the row (absolute) the rung wire passes through
  Shape shape = Shape::Box;
  std::string mnemonic;
  std::string glyph;               // contacts and coils: "] [", "]/[", "( )", "(L)", "(U)"
  std::vector<std::string> above;  // contacts and coils: description lines, symbol, address
  // Boxes: one row per line: label on the left, text on the right (operand, symbol, value).
  std::vector<std::pair<std::string, std::string>> rows;
  int index = 0;                   // the instruction's index in its rung (code order)
  std::uint32_t line = 0;          // source line
  bool has_state = false;
  bool powered = false;            // power reaches the instruction's left side
  bool truth = false;              // the instruction is true (highlighted)
};

struct Wire {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // horizontal (y0 == y1) or vertical (x0 == x1), inclusive
  bool powered = false;
};

struct RungLayout {
  int file = 2;
  int number = 0;
  bool end_rung = false;               // the END rung RSLogix draws after a file's last rung
  std::vector<std::string> comment;    // comment lines (wrapped), drawn above the rung
  int top = 0;                         // first grid row of the rung body (below the comment)
  int height = 0;                      // rows of the rung body
  int rail = 0;                        // row of the rung's main wire
  std::vector<InstructionBlock> blocks;
  std::vector<Wire> wires;
};

struct FileLayout {
  int number = 2;
  std::string name;
  int total_rungs = 0;
  std::vector<RungLayout> rungs;
};

struct LadderLayout {
  int width = 0;  // cells, rails included: the left rail is at kLeftRail, the right at width - 1
  bool has_state = false;
  std::vector<FileLayout> files;
};

inline constexpr int kLeftRail = 5;  // columns 0..3 hold the rung number
inline constexpr int kMinWidth = 78;

struct LayoutOptions {
  std::optional<int> file;       // one program file; nullopt = all
  int first_rung = 0;
  int last_rung = -1;            // -1 = to the end
  const LadderState* state = nullptr;
};

// Lays the chosen rungs out. Throws nothing; an unknown file or rung range gives an empty layout
// (the caller checks the options against the program first).
LadderLayout layout_ladder(const Program& program, const LayoutOptions& options);

// Text: one character per cell. Wires are '-' (powered '='), connectors '|' and '+'.
std::string render_text(const LadderLayout& layout);
// SVG: cells of kCellW x kCellH pixels; powered wires and true instructions green.
inline constexpr int kCellW = 8;
inline constexpr int kCellH = 16;
std::string render_svg(const LadderLayout& layout, const std::string& title);
// The layout itself as JSON (files, rungs, blocks, wires in cell coordinates): the data a web page
// draws from, so a browser view needs no second layout.
std::string render_json(const LadderLayout& layout);

}  // namespace softslc::ladder
