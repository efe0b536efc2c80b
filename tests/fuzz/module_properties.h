// The properties the module fuzz targets check: the bench-file parser and the M-file message
// decoders that ladder-controlled words feed (SCANport request buffers, DeviceNet explicit-message
// transaction blocks, DEM control blocks). Shared with module_fuzz_regressions_test.cpp, which
// replays every input the fuzzers found. Each returns an empty string when the property holds,
// else what broke; crashes, leaks, out-of-bounds accesses and UB are the sanitizers' to catch.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "modules/devicenet/dem.h"
#include "modules/devicenet/transaction.h"
#include "modules/module_setup.h"
#include "modules/scanport/drive_json.h"
#include "modules/scanport/messages.h"
#include "parser/loader.h"
#include "tests/devicenet/devicenet_test_util.h"
#include "vm/runtime.h"

namespace softslc::fuzz {

// Fuzz bytes as 16-bit words, low byte first (a trailing odd byte is the low byte of a last word).
inline std::vector<std::uint16_t> words_of(std::string_view bytes) {
  std::vector<std::uint16_t> w((bytes.size() + 1) / 2, 0);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    w[i / 2] = static_cast<std::uint16_t>(w[i / 2] | static_cast<std::uint8_t>(bytes[i]) << (i % 2 ? 8 : 0));
  return w;
}

// ---- bench files -------------------------------------------------------------------------------
// The bench text is set up against one example program of each module family with a bench (the
// 1747-SN appendix A block-transfer program, the 1203-SM1 appendix B messaging program, the
// 1747-SDN chapter 8 DEM program, the AutoMax Figure 4.3 Multibus head program). Every
// diagnostic points inside the bench file; a bench that sets up cleanly is run for 50 ms of
// virtual time: whatever it describes, the runtime neither crashes nor hangs.
struct BenchFuzzProgram {
  std::string name;
  std::string source;
  Program program;
};
inline const std::vector<BenchFuzzProgram>& bench_fuzz_programs() {
  static const std::vector<BenchFuzzProgram> loaded = [] {
    std::vector<BenchFuzzProgram> v;
    for (const char* path : {"1747-sn/throughput_bt.slc", "1203-sm1/appb_messaging.slc", "1747-sdn/ch8_dem_drive_parameter.slc",
                             "automax/fig4_3_multibus_head.slc"}) {
      std::ifstream in(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/" + path, std::ios::binary);
      std::string source(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>{});
      auto r = load_program(source, path);
      if (!r.ok()) throw std::runtime_error(std::string("bench fuzz program does not load:\n") + r.render_diagnostics());
      v.push_back({path, std::move(source), *r.program});
    }
    return v;
  }();
  return loaded;
}

inline std::string check_bench_property(std::string_view bytes) {
  std::size_t lines = 1;
  for (char c : bytes) lines += c == '\n';
  for (const auto& [name, source, program] : bench_fuzz_programs()) {
    ModuleSetup setup = load_module_setup_text(program, std::string(bytes), "fuzz.bench");
    for (const auto& d : setup.bench_diagnostics.items())
      if (d.line > lines) return "diagnostic at line " + std::to_string(d.line) + " beyond the bench's " + std::to_string(lines);
    (void)setup.render(name, source);
    if (!setup.ok()) continue;
    auto created = Runtime::create(program, setup.options);
    if (!created.ok()) return name + ": compiles without a bench but not with this one:\n" + created.render_errors();
    Runtime& rt = *created.runtime;
    if (!rt.set_mode(Mode::Run)) continue;  // refused with a message: fine
    const VirtualTime start = rt.now();
    rt.run_for(50 * kNsPerMs);
    if (rt.now() < start) return name + ": virtual time went backwards";
  }
  return {};
}

// ---- SCANport request buffers (1203-SM1 M0:e.n00) --------------------------------------------
// Up to four 100-word request buffers, sent in turn to one 1305 drive (so a Set can change what a
// later Get reads). Each must decode to a request whose data is exactly the bytes its length word
// covers within the buffer, re-encode to the same header and data, and get an answer that fits the
// 100-word response buffer: the echo, or an error response with a defined code; a request the
// module's own length check refuses (0xFD) never reaches the drive; the same request to a fresh
// drive and to none answers deterministically.
inline std::string check_scanport_message_property(std::string_view bytes) {
  using namespace scanport;
  const auto words = words_of(bytes);
  static const DriveDescription k1305 = builtin_drive("1305");  // parsed once: JSON is not under test
  Drive drive(k1305);
  for (std::size_t at = 0, n = 0; at < words.size() && n < 4; at += kBufferWords, ++n) {
    const std::size_t count = std::min<std::size_t>(kBufferWords, words.size() - at);
    std::array<std::uint16_t, kBufferWords> m0{};
    std::copy_n(words.begin() + static_cast<std::ptrdiff_t>(at), count, m0.begin());

    const Request r = decode_request(m0);
    const std::size_t expected = std::min<std::size_t>(r.length, kBufferDataBytes);
    if (r.data.size() != expected)
      return "request of length " + std::to_string(r.length) + " decoded " + std::to_string(r.data.size()) + " data bytes";
    const auto encoded = encode_request(r);
    const std::size_t header_and_data = kHeaderWords + (r.data.size() + 1) / 2;
    if (encoded.size() != header_and_data) return "encode_request wrote " + std::to_string(encoded.size()) + " words";
    for (std::size_t k = 0; k < header_and_data; ++k) {
      // The last data word's high byte is padding when the length is odd.
      const std::uint16_t mask = (k == header_and_data - 1 && k >= kHeaderWords && r.data.size() % 2) ? 0x00FF : 0xFFFF;
      if ((encoded[k] & mask) != (m0[k] & mask)) return "request word " + std::to_string(k) + " does not re-encode";
    }

    const ErrorCode length_check = check_length(r);
    const Transaction t = execute_message(&drive, m0);
    if (length_check != ErrorCode::kNone && t.response.error() != ErrorCode::kInvalidLength)
      return "a request failing the length check was answered without 0xFD";
    if (t.response.is_error() && t.response.error() == ErrorCode::kNone) return "an error response without a code";
    if (t.response.class_code != r.class_code || t.response.instance != r.instance || t.response.attribute != r.attribute)
      return "the response does not echo the request";
    if (t.duration < 0) return "negative transaction time";
    const auto reply = encode_response(t.response);
    if (reply.size() > static_cast<std::size_t>(kBufferWords)) return "response longer than the M1 buffer";
    std::array<std::uint16_t, kBufferWords> m1{};
    m1.fill(0xDEAD);
    write_response(t.response, m1);
    if (!std::equal(reply.begin(), reply.end(), m1.begin())) return "write_response differs from encode_response";
    if (std::any_of(m1.begin() + static_cast<std::ptrdiff_t>(reply.size()), m1.end(), [](auto w) { return w != 0; }))
      return "write_response left stale words";

    const Transaction none = execute_message(nullptr, m0);
    const ErrorCode expect_none = length_check != ErrorCode::kNone ? ErrorCode::kInvalidLength : ErrorCode::kTimeout;
    if (none.response.error() != expect_none) return "with no drive the answer is not 0xFD/0xFE";
  }
  return {};
}

// ---- DeviceNet explicit-message transaction blocks (1747-SDN M0:224...255) -------------------
// Every 32 words decode to a request whose data is exactly what its size byte covers (capped at
// 52 bytes); check_request() flags exactly the bad port and sizes; encoding the decoded block and
// decoding again gives it back. Up to four blocks are then submitted to the scanner of the
// manual's example network (with a drive at node 20), 0-1.5 s apart: it never holds more than its
// ten transactions, and what it shows in M1:224...255 is a well-formed response block.
// The manual's example network with the drive at node 20 (tests/devicenet/devicenet_test_util.h),
// built from device models parsed once, in Run, its port started and its nodes connected.
struct StartedNetwork {
  devicenet::Network net{devicenet::Baud::k500};
  std::unique_ptr<devicenet::Scanner> sdn;

  StartedNetwork() {
    using namespace devicenet;
    static const DeviceModel redistation = builtin_device_model("redistation");
    static const DeviceModel photoeye = builtin_device_model("series-9000-photoeye");
    static const DeviceModel drive = builtin_device_model("ac-drive");
    net.attach(test::kRediStationNode, redistation);
    net.attach(test::kPhotoeyeNode, photoeye);
    net.attach(test::kDriveNode, drive);
    sdn = std::make_unique<Scanner>(net, test::example_config(/*with_drive=*/true));
    const std::uint16_t run[1] = {bit(CommandBit::Run)};
    sdn->write_output_image(run);
    advance_ms(2200);  // the 2 s Duplicate MAC ID check, then the first connections
  }
  void advance_ms(std::int64_t ms) { net.advance_to(net.now() + milliseconds(ms)); }
};

inline bool same_request(const devicenet::RequestBlock& a, const devicenet::RequestBlock& b) {
  return a.command == b.command && a.txid == b.txid && a.port == b.port && a.size == b.size && a.service == b.service &&
         a.mac == b.mac && a.class_id == b.class_id && a.instance == b.instance && a.attribute == b.attribute &&
         a.data == b.data;
}

inline std::string check_transaction_property(std::string_view bytes) {
  using namespace devicenet;
  const auto words = words_of(bytes);
  std::vector<Block> blocks;
  std::vector<int> gaps_ms;
  for (std::size_t at = 0; at < words.size() && blocks.size() < 4; at += 33) {
    Block b{};
    std::copy_n(words.begin() + static_cast<std::ptrdiff_t>(at), std::min<std::size_t>(32, words.size() - at), b.begin());
    blocks.push_back(b);
    gaps_ms.push_back(at + 32 < words.size() ? words[at + 32] % 1500 : 100);
  }
  for (const auto& b : blocks) {
    const RequestBlock r = decode_request(b);
    const std::size_t expected = static_cast<std::size_t>(std::clamp(r.size - kRequestPathBytes, 0, kMaxRequestDataBytes));
    if (r.data.size() != expected) return "size " + std::to_string(r.size) + " decoded " + std::to_string(r.data.size()) + " data bytes";
    const bool well_formed = r.port == 0 && r.size >= kRequestPathBytes && r.size <= kMaxBodyBytes;
    if (check_request(r).has_value() == well_formed) return "check_request disagrees with the port and size rules";
    if (!same_request(decode_request(encode_request(r)), r)) return "request block does not round-trip";
  }
  if (blocks.empty()) return {};

  StartedNetwork x;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    x.sdn->submit_request_block(blocks[k]);
    x.advance_ms(gaps_ms[k]);
    if (x.sdn->transactions_in_use() > static_cast<std::size_t>(kMaxQueuedTransactions))
      return std::to_string(x.sdn->transactions_in_use()) + " transactions in use";
    Block m1{};
    for (int w = 0; w < 32; ++w) x.sdn->read_m(devicenet::MFile::M1, layout::kTransactionBlock + w, m1[static_cast<std::size_t>(w)]);
    const ResponseBlock shown = decode_response(m1);
    if (shown.data.size() > static_cast<std::size_t>(kMaxBodyBytes)) return "response block with more than 58 bytes";
    if (auto head = x.sdn->head_response(); head && encode_response(*head) != m1)
      return "M1:224 does not show the head of the response queue";
  }
  return {};
}

// ---- DEM control blocks --------------------------------------------------------------------
// Two DEM instructions (two 70-word control blocks written by the ladder, arbitrary) share the
// module's one DEM slot. The rest of the input drives them: per step, each DEM's rung in, the
// ladder setting AB or clearing EN, and 0-700 ms of virtual time. After every step:
//   - a DEM that finished has DN with error 0, or ER with error 1-4, never both;
//   - one that holds the slot past its timeout preset has been timed out (the manual's lockup guard);
//   - only a DEM that does not hold the slot waits (WS); the scanner holds at most ten transactions.
inline std::string check_dem_property(std::string_view bytes) {
  using namespace devicenet;
  const auto words = words_of(bytes);
  std::array<std::array<std::uint16_t, dem::kWords>, 2> cb{};
  for (std::size_t i = 0; i < std::min<std::size_t>(words.size(), 2 * dem::kWords); ++i)
    cb[i / dem::kWords][i % dem::kWords] = words[i];
  const std::string_view steps = bytes.size() > 4 * dem::kWords ? bytes.substr(4 * dem::kWords) : std::string_view{};

  StartedNetwork x;
  dem::DemPort port(*x.sdn);
  std::array<VirtualTime, 2> accepted_at{};
  std::array<Nanoseconds, 2> timeout{};
  std::size_t n = 0;
  for (char c : steps) {
    if (++n > 64) break;
    const auto s = static_cast<std::uint8_t>(c);
    if (s & 0x04) cb[0][dem::kStatusWord] |= dem::kAB;
    if (s & 0x08) cb[0][dem::kStatusWord] &= static_cast<std::uint16_t>(~dem::kEN);
    x.advance_ms((s >> 4) * 50);
    for (std::uint32_t k = 0; k < 2; ++k) {
      const auto before = port.owner();
      const bool enabled_before = cb[k][dem::kStatusWord] & dem::kEN;
      port.on_rung(k, cb[k], (s >> k) & 1, x.net.now());
      const std::uint16_t w0 = cb[k][dem::kStatusWord];
      // Accepted in this call: newly holding the slot, or — after AB or a reply finished it and
      // the ladder had cleared EN — finished and accepted again in the same execution.
      if (port.owner() == k && (w0 & dem::kEN) && (before != k || !enabled_before)) {
        accepted_at[k] = x.net.now();
        timeout[k] = dem::timeout_for_preset(static_cast<std::uint8_t>(cb[k][dem::kTimeoutWord] & dem::kPresetMask));
      }
      if (before == k && port.owner() != k) {
        const bool dn = w0 & dem::kDN, er = w0 & dem::kER;
        const int code = w0 & dem::kErrorMask;
        if (dn == er) return "a finished DEM has " + std::string(dn ? "both DN and ER" : "neither DN nor ER");
        if (dn && code != 0) return "DN with error code " + std::to_string(code);
        if (er && (code < 1 || code > 4)) return "ER with error code " + std::to_string(code);
      }
      if (port.owner() == k && timeout[k] > 0 && x.net.now() - accepted_at[k] >= timeout[k])
        return "a DEM holds the slot past its timeout";
      if (port.owner() == k && (w0 & dem::kWS)) return "the DEM holding the slot is waiting";
    }
    if (x.sdn->transactions_in_use() > static_cast<std::size_t>(kMaxQueuedTransactions))
      return std::to_string(x.sdn->transactions_in_use()) + " transactions in use";
  }
  return {};
}

}  // namespace softslc::fuzz
