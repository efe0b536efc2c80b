// Static scan-time prediction (`softslc scantime`): what a program costs per rung, per file and
// per scan on a given processor, before it is downloaded anywhere.
//
// For each rung: worst case (every instruction executed with rung-in true, every branch leg, each at
// the longer of its true and false times), best case (every instruction executed with rung-in false, as when the first condition of the
// rung is false — the SLC still scans the rest of the rung), and the M0/M1 access part on its
// own. Instruction times come from a TimingProfile (estimates unless a source says otherwise);
// M0/M1 access times come from the manuals' table (instructions/mfile_access_time.h), exact.
//
// Which M accesses happen when: condition instructions (XIC, compares, ...) read their operands
// whether the rung is true or false, and OTE writes its bit either way, so their accesses count
// in both cases; every other output touches its operands only when its rung-in is true, so its
// accesses count in the worst case only. The whole-scan figures follow JSR calls from file 2
// (worst: every JSR is taken; best: none is), and add the per-scan overhead: housekeeping plus
// the input and output scan of every module in the chassis.
//
// Hot spots rank the rungs whose M-file accesses cost most, with the manuals' remedies stated
// for that rung (1747-SN manual appendix B, "Minimizing the Scan Time").
#pragma once

#include <string>
#include <vector>

#include "parser/program.h"
#include "vm/timing_profile.h"

namespace softslc {

struct RungScanTime {
  int file = 2;
  int rung = 0;
  SourcePos pos;
  Nanoseconds worst = 0;
  Nanoseconds best = 0;
  Nanoseconds mfile = 0;  // the M0/M1 part of `worst`
  int mfile_accesses = 0;
};

struct FileScanTime {
  int file = 2;
  Nanoseconds worst = 0;
  Nanoseconds best = 0;
  Nanoseconds mfile = 0;
};

struct HotSpot {
  int file = 2;
  int rung = 0;
  Nanoseconds mfile = 0;
  std::vector<std::string> remedies;  // concrete, for this rung
};

struct ScanTimePrediction {
  std::string catalog;       // processor catalog
  std::string processor;     // timing key
  std::string profile_name;
  bool uses_estimates = false;  // some figure used comes from an estimated source
  std::vector<RungScanTime> rungs;  // every rung of every file, in file then rung order
  std::vector<FileScanTime> files;  // every program file, in file order (not including callees)
  Nanoseconds housekeeping = 0;
  Nanoseconds io_scan = 0;
  Nanoseconds overhead = 0;      // housekeeping + io_scan
  Nanoseconds total_worst = 0;   // file 2 with every JSR taken (callees expanded) + overhead
  Nanoseconds total_best = 0;    // file 2 with no JSR taken + overhead
  Nanoseconds total_mfile = 0;   // the M0/M1 part of total_worst
  std::vector<HotSpot> hot_spots;  // rungs with M-file accesses, most expensive first
  std::vector<std::string> notes;
};

// Predicts the scan time of `program` on the profile's processor. `processor` gives the
// catalog/series whose M-file row applies (it must have profile.processor as its timing key).
ScanTimePrediction predict_scan_time(const Program& program, const ProcessorModel& processor,
                                     const TimingProfile& profile);

}  // namespace softslc
