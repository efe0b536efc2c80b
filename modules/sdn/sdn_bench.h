// What a 1747-SDN bench node describes: the DeviceNet cable on the scanner's port, the devices on
// it, and the scanner's configuration as RSNetWorx would download it (docs/bench-format.md,
// "1747-SDN"). interpret_sdn_bench() reads it once; every module built from it starts from the same
// state.
//
//   devicenet NAME slot=N node=0 baud=500K [network_baud=500K] [interscan_delay_ms=10]
//             [background_poll_ratio=1] {
//     autoscan enabled=false allocation_bytes=4
//     node NAME address=7 [model=redistation | description=FILE.json] {   # a device on the cable ...
//       poll rx=1 tx=1 [epr_ms=75] [background=false]   # ... and/or its scanlist entry
//       key vendor=1 device_type=24 product_code=2705 major=2 minor=3
//       input from=poll byte=0 bit=0 bits=8 to=M1:2/0
//       output to=poll byte=0 bit=0 bits=8 from=M0:2/0
//     }
//   }
//
// The scanner attributes and the entry children are the keys of the library's scanner
// configuration JSON (docs/1747-sdn.md, "Scanner configuration"): the bench is turned into that
// JSON and checked by parse_scanner_config, so both spellings have one set of rules. A node with
// connection children is in the scanlist; one with a model is on the cable; a node may be both,
// either (a scanlist entry without a device shows code 78; a device without an entry is what
// AutoScan finds).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "modules/bench/bench.h"
#include "modules/devicenet/device_model.h"
#include "modules/devicenet/scanlist.h"

namespace softslc {

struct SdnDeviceSpec {
  std::string name;  // bench name, how tests reach it
  int address = 0;
  devicenet::DeviceModel model;
};

struct SdnNodeName {
  std::string name;
  int address = 0;
};

struct SdnBench {
  std::string name;  // the network's bench name (bus-level faults)
  devicenet::Baud network_baud = devicenet::Baud::k125;
  devicenet::ScannerConfig config;
  std::vector<SdnDeviceSpec> devices;  // in bench order
  std::vector<SdnNodeName> nodes;      // every named node (devices and scanlist-only entries)
};

// Interprets a `devicenet` node; problems are reported at their positions in `diags`. Scanlist
// issues the scanner would show as code 71 are warnings (the module runs and shows 71). Device
// description files (description=) are read relative to the directory of `bench_path`.
std::shared_ptr<const SdnBench> interpret_sdn_bench(const BenchNode& node, DiagnosticList& diags,
                                                    const std::string& bench_path = "");

}  // namespace softslc
