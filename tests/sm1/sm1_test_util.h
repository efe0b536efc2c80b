// Helpers for the 1203-SM1 tests: programs with a 1203-SM1 in slot 1, built through the same
// loader as the CLI and the test runner (tests/modules/modules_test_util.h).
#pragma once

#include <string>

#include "../modules/modules_test_util.h"
#include "modules/sm1/sm1_module.h"

namespace softslc::test {

// A program with an SLC 5/03 (or `processor`), the 1203-SM1 SLOT line `sm1_slot` (without
// "SLOT 1 1203-SM1") in slot 1, and `rungs` in file 2.
inline std::string sm1_program(const std::string& sm1_slot, const std::string& rungs = "SOR XIC B3:0/15 OTE B3:0/14 EOR \n",
                               const std::string& processor = "1747-L532") {
  return "START " + processor + "\n" + "SLOT 0 " + processor + " SCAN_IN 0 SCAN_OUT 0\n" + "SLOT 1 1203-SM1 " + sm1_slot +
         "\n" + "PROJECT \"SM1TEST\"\n" + "LADDER 2 MAIN\n" + rungs + "DATA N10:0 \n% N10:0 % 0 0 0 0 0 0 0 0 0 0 \n" +
         "DATA N11:0 \n% N11:0 % 0 0 0 0 0 0 0 0 0 0 \n";
}

inline const std::string kEnhanced = "SCAN_IN 32 SCAN_OUT 32 ID_CODE 13616";
inline const std::string kBasic = "SCAN_IN 8 SCAN_OUT 8 ID_CODE 3516";
inline const std::string kOneDrive = "scanport SM1 slot=1 {\n  drive DRIVE1 channel=1 port=2\n}\n";

inline std::string sm1_example(const std::string& name) {
  return read_text(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/1203-sm1/" + name);
}

inline Sm1Module& sm1(Bench& b, int slot = 1) {
  auto* m = dynamic_cast<Sm1Module*>(b.rt->module(slot));
  if (!m) throw std::runtime_error("no 1203-SM1 in slot " + std::to_string(slot));
  return *m;
}

inline std::int64_t observed(Bench& b, std::string_view device, std::string_view what, std::size_t k = 0) {
  auto v = b.rt->observe(device, what);
  if (!v || v->size() <= k) throw std::runtime_error("no observation " + std::string(what) + " of " + std::string(device));
  return (*v)[k];
}

}  // namespace softslc::test
