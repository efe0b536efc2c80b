// The rung the load and parse benchmarks repeat: five shapes in turn (a contact branch into a
// coil, a timer, a counter with an ADD, a compare-then-move, an output with a counter contact),
// each on its own element number (i mod 200), so a generated program is realistic mixed ladder
// whose size grows linearly with its rung count.
#pragma once

#include <string>

namespace softslc::bench {

inline std::string generated_rung(int i) {
  const std::string n = std::to_string(i % 200);
  switch (i % 5) {
    case 0:
      return "SOR XIC I:1/" + std::to_string(i % 16) + " BST XIC B3:" + n + "/1 NXB XIO B3:" + n + "/2 BND OTE B3:" + n +
             "/3 EOR\n";
    case 1: return "SOR XIC B3:" + n + "/3 TON T4:" + n + " 0.01 100 0 EOR\n";
    case 2: return "SOR XIC T4:" + n + "/DN BST CTU C5:" + n + " 10 0 NXB ADD N7:" + n + " 1 N7:" + n + " BND EOR\n";
    case 3: return "SOR GEQ N7:" + n + " 100 BST MOV 0 N7:" + n + " NXB OTL B3:" + n + "/4 BND EOR\n";
    default: return "SOR XIC B3:" + n + "/4 XIO C5:" + n + "/DN OTE O:2/" + std::to_string(i % 16) + " EOR\n";
  }
}

}  // namespace softslc::bench
