// Two controllers on one simulated MSG network (docs/semantics.md "MSG and SVC"), built through the
// public Runtime API as the test runner builds them: a leader "A" at node 1 running the program under
// test and a peer "B" at node 2. Shared by the SLC MSG tests (tests/vm/message_test.cpp) and the
// MicroLogix MSG tests (tests/micrologix/msg_test.cpp).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vm/profile_scan_time_model.h"
#include "vm_test_util.h"

namespace softslc::test {

// A whole program text, loaded as a peer's program.
inline std::shared_ptr<const Program> load_peer_program(std::string_view text) {
  LoadResult lr = load_program(std::string(text), "peer.slc");
  if (!lr.ok()) throw std::runtime_error(lr.render_diagnostics());
  return std::make_shared<const Program>(std::move(*lr.program));
}

// A peer whose scans take 3 s (its housekeeping): it answers a message only at its end of scan, after
// a message timer of 1 or 2 s has run out.
inline RuntimeOptions slow_target(std::string_view catalog) {
  RuntimeOptions o;
  o.time_model = std::make_shared<SlowModel>(make_scan_time_model(*resolve_processor(catalog)), 3 * kNsPerS);
  return o;
}

struct MessageLine {
  std::unique_ptr<Runtime> a;
  Runtime* b = nullptr;

  MessageLine(std::string_view a_text, std::string_view b_text, RuntimeOptions a_opts = {}, RuntimeOptions b_opts = {}) {
    PeerController peer;
    peer.name = "B";
    peer.node = 2;
    peer.program = load_peer_program(b_text);
    peer.options = std::make_shared<const RuntimeOptions>(std::move(b_opts));
    a_opts.node = 1;
    a_opts.peers.push_back(std::move(peer));
    std::string errors;
    a = try_build(a_text, errors, std::move(a_opts));
    if (!a) throw std::runtime_error("network did not build:\n" + errors);
    b = a->peer("B");
    if (!b) throw std::runtime_error("no peer B");
  }
  std::int64_t ai(std::string_view addr) const { return a->value(addr).as_int(); }
  std::int64_t bi(std::string_view addr) const { return b->value(addr).as_int(); }
  bool abit(std::string_view addr) const { return a->value(addr).as_bool(); }
  // Sets a word or bit of A, or of B, as a test does between scans.
  void set(std::string_view addr, std::int64_t v) { ASSERT_TRUE(a->set(addr, Value::of_int(v))); }
  void setb(std::string_view addr, std::int64_t v) { ASSERT_TRUE(b->set(addr, Value::of_int(v))); }
  void run() { ASSERT_TRUE(a->set_mode(Mode::Run)); }
  bool until(std::string_view bit, Nanoseconds limit = kNsPerS) {
    return a->run_until([&](const Runtime& r) { return r.value(bit).as_bool(); }, limit);
  }
};

}  // namespace softslc::test
