// Writing a Program back as canonical RSLogix 500 export text (`softslc fmt`).
//
// The output is the export layout (START, SLOT lines, PROJECT, LADDER files with "% Rung: n %"
// markers, DATA blocks in the export's row shapes, FORCE blocks), then softslc's SYMBOL/DESC
// lines. Addresses use their canonical spelling (B3/62 becomes B3:3/14). The guarantee, tested on
// every example and on the fixture: parsing the output gives the same program as parsing the input.
#pragma once

#include <string>

#include "parser/program.h"

namespace softslc {

std::string format_program(const Program& program);

// The canonical spelling of one rung: "SOR XIC B3:0/0 OTE O:2.0/0 EOR".
std::string format_rung(const Rung& rung);

// Shortest text that parses back to the same double, always with a '.' or exponent so it
// stays a float constant ("1.0", "0.01666667").
std::string format_float(double v);

}  // namespace softslc
