// The online view (server/web.h): WebModel's requests and messages on the seal-in example, the
// journal of changes made from the page, and WebView's HTTP/WebSocket bounds on loopback with
// Boost.Beast as the client (the browser tests in tests/serve/browser drive the page itself).
#include <gtest/gtest.h>

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>

#include "server/web.h"
#include "tests/serve/serve_test_util.h"

namespace softslc::serve::testing {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using nlohmann::json;

std::filesystem::path seal_in() { return std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/seal_in/seal_in.slc"; }

// The block of instruction `index` in rung `rung` of an update's ladder.
json block(const json& update, int rung, int index) {
  for (const auto& r : update["ladder"]["files"][0]["rungs"])
    if (r["number"] == rung)
      for (const auto& b : r["blocks"])
        if (b["index"] == index) return b;
  return nullptr;
}

TEST(WebModel, ProgramOutlineHasEveryRungHeightDataFilesAndSlots) {
  LiveController live(seal_in(), std::nullopt, {});
  WebModel model(live, nullptr);
  const json p = json::parse(model.program_message());
  EXPECT_EQ(p["type"], "program");
  EXPECT_EQ(p["project"], "SEAL_IN");
  ASSERT_EQ(p["files"].size(), 1u);
  EXPECT_EQ(p["files"][0]["number"], 2);
  EXPECT_EQ(p["files"][0]["heights"].size(), 7u);  // six rungs and END
  std::vector<std::string> names;
  for (const auto& d : p["data"]) names.push_back(d["name"]);
  for (const char* want : {"O", "I", "S", "B3", "T4", "C5", "N7", "F8"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  ASSERT_EQ(p["slots"].size(), 2u);
  EXPECT_EQ(p["slots"][0]["slot"], 1);
  EXPECT_EQ(p["slots"][0]["in"], 1);
  EXPECT_EQ(p["symbols"]["O:2.0/0"], "MOTOR");
}

TEST(WebModel, OutlineHeightsAreTheHeightsUpdatesDraw) {
  // The page places rungs from the outline's heights: a box with value rows drawn taller in an
  // update than in the outline would overlap the next rung.
  for (const char* example : {"examples/ladder/seal_in/seal_in.slc", "examples/ladder/faults/math_faults.slc"}) {
    LiveController live(std::filesystem::path(SOFTSLC_SOURCE_DIR) / example, std::nullopt, {});
    WebModel model(live, nullptr);
    const json heights = json::parse(model.program_message())["files"][0]["heights"];
    WebWatch watch;
    const json u = json::parse(model.handle(R"({"op":"view","first":0,"last":100})", watch));
    const json& rungs = u["ladder"]["files"][0]["rungs"];
    ASSERT_EQ(rungs.size(), heights.size()) << example;
    for (std::size_t i = 0; i < rungs.size(); ++i)
      EXPECT_EQ(rungs[i]["top"].get<int>() + rungs[i]["height"].get<int>(), heights[i].get<int>()) << example << " rung " << i;
  }
}

TEST(WebModel, StartSealsTheMotorInAndTheUpdateShowsPowerFlow) {
  LiveController live(seal_in(), std::nullopt, {});
  WebModel model(live, nullptr);
  WebWatch watch;
  live.step(2);  // past the first pass, so pressing START is a rising edge for the CTU on rung 4
  json u = json::parse(model.handle(R"({"op":"view","file":2,"first":0,"last":6})", watch));
  EXPECT_EQ(watch.last, 6);
  EXPECT_EQ(block(u, 0, 4)["mnemonic"], "OTE");
  EXPECT_EQ(block(u, 0, 4)["true"], false);
  EXPECT_EQ(block(u, 0, 2)["true"], true);  // XIO STOP_PB, not pressed
  json r = json::parse(model.handle(R"({"op":"set","address":"I:1/0","value":"1"})", watch));
  EXPECT_EQ(r["type"], "update");
  live.step(1);
  u = json::parse(model.update(watch));
  EXPECT_EQ(block(u, 0, 0)["true"], true);
  EXPECT_EQ(block(u, 0, 4)["true"], true);
  EXPECT_EQ(block(u, 0, 4)["powered"], true);
  model.handle(R"({"op":"set","address":"START_PB","value":0})", watch);
  live.step(1);
  u = json::parse(model.update(watch));
  EXPECT_EQ(block(u, 0, 0)["true"], false);
  EXPECT_EQ(block(u, 0, 4)["true"], true) << "sealed in through XIC MOTOR";
  EXPECT_EQ(live.controller().get_int("C5:0.ACC"), 1);
}

TEST(WebModel, ForceModeAndStepThroughRequests) {
  LiveController live(seal_in(), std::nullopt, {});
  WebModel model(live, nullptr);
  WebWatch watch;
  json u = json::parse(model.handle(R"({"op":"force","address":"STOP_PB","state":"on"})", watch));
  EXPECT_EQ(u["status"]["forces"]["I:1.0/1"], true);
  live.step(1);
  EXPECT_TRUE(live.controller().get_bit("I:1/1"));
  u = json::parse(model.handle(R"({"op":"force","address":"I:1/1","state":"remove"})", watch));
  EXPECT_TRUE(u["status"]["forces"].empty());
  u = json::parse(model.handle(R"({"op":"mode","mode":"program"})", watch));
  EXPECT_EQ(u["status"]["mode"], "program");
  u = json::parse(model.handle(R"({"op":"mode","mode":"run"})", watch));
  EXPECT_EQ(u["status"]["mode"], "run");
  model.handle(R"({"op":"pause"})", watch);
  const auto scans = live.controller().scans();
  u = json::parse(model.handle(R"({"op":"step","scans":3})", watch));
  EXPECT_EQ(u["status"]["scans"], scans + 3);
  EXPECT_EQ(u["status"]["paused"], true);
}

TEST(WebModel, ComparesShowTheirTruthFromCurrentValues) {
  auto text = std::string("START 1747-L532\nLADDER 2 MAIN\nSOR GRT N7:0 10 OTE B3:0/0 EOR\n"
                          "SOR LIM 5 N7:0 20 OTE B3:0/1 EOR\nSOR MEQ N7:0 15 3 OTE B3:0/2 EOR\n");
  const auto path = std::filesystem::temp_directory_path() / "softslc_web_compares.slc";
  { std::ofstream(path) << text; }
  LiveController live(path, std::nullopt, {});
  WebModel model(live, nullptr);
  WebWatch watch;
  model.handle(R"({"op":"view","first":0,"last":2})", watch);
  model.handle(R"({"op":"set","address":"N7:0","value":"11"})", watch);
  json u = json::parse(model.update(watch));
  EXPECT_EQ(block(u, 0, 0)["true"], true);   // 11 > 10
  EXPECT_EQ(block(u, 1, 0)["true"], true);   // 5 <= 11 <= 20
  EXPECT_EQ(block(u, 2, 0)["true"], false);  // 11 & 15 = 11, not 3 & 15
  model.handle(R"({"op":"set","address":"N7:0","value":"35"})", watch);
  u = json::parse(model.update(watch));
  EXPECT_EQ(block(u, 0, 0)["true"], true);   // 35 > 10
  EXPECT_EQ(block(u, 1, 0)["true"], false);  // outside 5..20
  EXPECT_EQ(block(u, 2, 0)["true"], true);   // 35 & 15 = 3
  std::filesystem::remove(path);
}

TEST(WebModel, BadRequestsAreAnsweredWithAnErrorAndChangeNothing) {
  LiveController live(seal_in(), std::nullopt, {});
  WebModel model(live, nullptr);
  WebWatch watch;
  for (const char* bad : {"", "[", "42", R"({"op":7})", R"({"op":"launch"})", R"({"op":"view","file":9})",
                          R"({"op":"table","name":"N99"})", R"({"op":"mode","mode":"fast"})",
                          R"({"op":"force","address":"I:1/0","state":"maybe"})", R"({"op":"set","address":"N7:0","value":"x"})",
                          R"({"op":"set","address":"NOPE","value":"1"})", R"({"op":"force","address":"N7:0/0","state":"on"})",
                          R"({"op":"trend","addresses":["a","b","c","d","e","f","g","h","i"]})"}) {
    const json r = json::parse(model.handle(bad, watch));
    EXPECT_EQ(r["type"], "error") << bad;
  }
  EXPECT_EQ(live.writes(), 0u);
  // A view past the end is clamped to the END rung; a long one to kMaxViewRungs.
  model.handle(R"({"op":"view","first":100,"last":900})", watch);
  EXPECT_EQ(watch.first, 6);
  EXPECT_EQ(watch.last, 6);
}

TEST(WebModel, ReadOnlyRefusesEveryChange) {
  LiveOptions lo;
  lo.read_only = true;
  LiveController live(seal_in(), std::nullopt, lo);
  WebModel model(live, nullptr);
  WebWatch watch;
  for (const char* change : {R"({"op":"set","address":"N7:0","value":"1"})", R"({"op":"force","address":"I:1/0","state":"on"})",
                             R"({"op":"mode","mode":"program"})", R"({"op":"clear_fault"})", R"({"op":"step"})"}) {
    const json r = json::parse(model.handle(change, watch));
    EXPECT_EQ(r["type"], "error") << change;
  }
  EXPECT_EQ(live.controller().mode(), Mode::Run);
}

TEST(WebModel, TablesCarryWordsAndFloatsFormatted) {
  LiveController live(seal_in(), std::nullopt, {});
  WebModel model(live, nullptr);
  WebWatch watch;
  json u = json::parse(model.handle(R"({"op":"table","name":"T4"})", watch));
  ASSERT_TRUE(u["table"].is_object());
  EXPECT_EQ(u["table"]["words"][1], 100);  // T4:0.PRE
  model.handle(R"({"op":"set","address":"F8:0","value":"1.5"})", watch);
  u = json::parse(model.handle(R"({"op":"table","name":"F8"})", watch));
  EXPECT_EQ(u["table"]["values"][0], "1.5");
}

TEST(WebModel, ModuleFilesAreListedAndReadThroughTheModule) {
  // The 1747-SN scanner of the chapter 4 example (slot 1): its M0 and M1 files are listed, and an
  // M1 table window is read through the module, word for word what the ladder's M1 reads see.
  const auto dir = std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/1747-sn";
  LiveController live(dir / "ch4_m1_status.slc", dir / "ch4_m1_status.bench", {});
  live.step(5);
  WebModel model(live, nullptr);
  const json p = json::parse(model.program_message());
  std::vector<std::string> modules;
  for (const auto& d : p["data"])
    if (d.contains("module")) modules.push_back(d["name"]);
  EXPECT_EQ(modules, (std::vector<std::string>{"M0:1", "M1:1"}));
  WebWatch watch;
  const json u = json::parse(model.handle(R"({"op":"table","name":"M1:1","offset":0})", watch));
  ASSERT_TRUE(u["table"].is_object()) << u.dump();
  ASSERT_GT(u["table"]["words"].size(), 0u);
  for (std::size_t w = 0; w < u["table"]["words"].size() && w < 8; ++w)
    EXPECT_EQ(u["table"]["words"][w].get<int>(),
              static_cast<std::uint16_t>(live.controller().get_int("M1:1." + std::to_string(w))))
        << "M1:1." << w;
}

TEST(WebModel, ChangesFromThePageAreJournaledAndReplay) {
  const auto journal = std::filesystem::temp_directory_path() / "softslc_web_journal.txt";
  LiveOptions lo;
  lo.journal = journal;
  {
    LiveController live(seal_in(), std::nullopt, lo);
    WebModel model(live, nullptr);
    WebWatch watch;
    model.handle(R"({"op":"set","address":"START_PB","value":"1"})", watch);
    live.step(2);
    model.handle(R"({"op":"force","address":"STOP_PB","state":"on"})", watch);
    live.step(2);
    model.handle(R"({"op":"force","address":"STOP_PB","state":"remove"})", watch);
    model.handle(R"({"op":"mode","mode":"program"})", watch);
    live.step(1);
    model.handle(R"({"op":"mode","mode":"run"})", watch);
    model.handle(R"({"op":"set","address":"F8:0","value":"2.25"})", watch);
    live.step(1);
    live.finish();
  }
  const auto r = replay(journal);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.writes, 6u);
  ASSERT_TRUE(r.controller);
  EXPECT_DOUBLE_EQ(r.controller->get_float("F8:0"), 2.25);
  std::filesystem::remove(journal);
}

TEST(WebModel, ASessionThatFaultsReplaysToTheSameVirtualTimes) {
  // A divide by zero pressed from the page faults the processor (0020h at END); pacing goes on
  // running scans, each passing virtual time. The journal's scan counts must replay to the same
  // times (Controller::scan(n) stops at the fault; the journal counts scans of one).
  const auto journal = std::filesystem::temp_directory_path() / "softslc_web_fault_journal.txt";
  LiveOptions lo;
  lo.journal = journal;
  {
    LiveController live(std::filesystem::path(SOFTSLC_SOURCE_DIR) / "examples/ladder/faults/math_faults.slc", std::nullopt,
                        lo);
    WebModel model(live, nullptr);
    WebWatch watch;
    live.advance(20'000'000);
    model.handle(R"({"op":"set","address":"DO_DIVIDE","value":"1"})", watch);
    live.advance(60'000'000);
    ASSERT_TRUE(live.controller().fault());
    EXPECT_EQ(live.controller().fault()->code, 0x0020);
    model.handle(R"({"op":"set","address":"DO_DIVIDE","value":"0"})", watch);
    // Clear the overflow trap (else END faults again: examples/ladder/faults/math_faults.test) and
    // the fault, and go back to Run from the page: the processor runs again without faulting.
    model.handle(R"({"op":"set","address":"S:5/0","value":"0"})", watch);
    json u = json::parse(model.handle(R"({"op":"clear_fault"})", watch));
    EXPECT_TRUE(u["status"]["fault"].is_null()) << u["status"].dump();
    u = json::parse(model.handle(R"({"op":"mode","mode":"run"})", watch));
    EXPECT_EQ(u["type"], "update") << u.dump();
    live.advance(100'000'000);
    u = json::parse(model.update(watch));
    EXPECT_EQ(u["status"]["mode"], "run") << u["status"].dump();
    EXPECT_TRUE(u["status"]["fault"].is_null()) << u["status"].dump();
    live.finish();
  }
  const auto r = replay(journal);
  EXPECT_TRUE(r.ok) << r.message;
  std::filesystem::remove(journal);
}

// ---- WebView on loopback ----

class WebViewTest : public ::testing::Test {
 protected:
  void start(std::size_t max_connections = 16) {
    live_.emplace(seal_in(), std::nullopt, LiveOptions{});
    ServerOptions so;
    so.port = 0;
    server_ = std::make_unique<Server>(io_, *live_, so);
    server_->start();
    WebOptions wo;
    wo.port = 0;
    wo.max_connections = max_connections;
    wo.max_message = 512;
    web_ = std::make_unique<WebView>(io_, *live_, *server_, wo);
    web_->start();
    port_ = web_->port();
    thread_ = std::thread([this] { io_.run(); });
  }
  void TearDown() override {
    if (!thread_.joinable()) return;
    asio::post(io_, [this] { web_->stop(); server_->stop(); io_.stop(); });
    thread_.join();
  }
  asio::ip::tcp::socket connect() {
    asio::ip::tcp::socket s(client_io_);
    s.connect({asio::ip::make_address("127.0.0.1"), port_});
    return s;
  }
  http::response<http::string_body> get(const std::string& target, const std::string& host) {
    auto s = connect();
    http::request<http::empty_body> req{http::verb::get, target, 11};
    req.set(http::field::host, host);
    http::write(s, req);
    beast::flat_buffer b;
    http::response<http::string_body> res;
    http::read(s, b, res);
    return res;
  }
  std::string host() const { return "127.0.0.1:" + std::to_string(port_); }

  asio::io_context io_;
  asio::io_context client_io_;
  std::optional<LiveController> live_;
  std::unique_ptr<Server> server_;
  std::unique_ptr<WebView> web_;
  std::thread thread_;
  std::uint16_t port_ = 0;
};

TEST_F(WebViewTest, ServesThePageFromTheBinary) {
  start();
  auto res = get("/", host());
  EXPECT_EQ(res.result(), http::status::ok);
  EXPECT_NE(res.body().find("<script src=\"app.js\">"), std::string::npos);
  res = get("/app.js", host());
  EXPECT_EQ(res.result(), http::status::ok);
  EXPECT_EQ(res[http::field::content_type], "text/javascript; charset=utf-8");
  EXPECT_EQ(get("/../etc/passwd", host()).result(), http::status::not_found);
  EXPECT_EQ(get("/", "localhost:1").result(), http::status::ok);
}

TEST_F(WebViewTest, RefusesAHostNameOtherThanLocalhost) {
  start();
  // DNS rebinding: a page from evil.example whose name now resolves to 127.0.0.1.
  EXPECT_EQ(get("/", "evil.example:8044").result(), http::status::forbidden);
}

TEST_F(WebViewTest, WebSocketSendsTheProgramThenUpdatesAndRefusesCrossOrigin) {
  start();
  {
    websocket::stream<asio::ip::tcp::socket> ws(connect());
    ws.handshake(host(), "/ws");
    beast::flat_buffer b;
    ws.read(b);
    EXPECT_EQ(json::parse(beast::buffers_to_string(b.data()))["type"], "program");
    b.consume(b.size());
    ws.read(b);
    EXPECT_EQ(json::parse(beast::buffers_to_string(b.data()))["type"], "update");
    ws.close(websocket::close_code::normal);
  }
  websocket::stream<asio::ip::tcp::socket> ws(connect());
  ws.set_option(websocket::stream_base::decorator(
      [](websocket::request_type& req) { req.set(http::field::origin, "http://evil.example"); }));
  beast::error_code ec;
  ws.handshake(host(), "/ws", ec);
  EXPECT_TRUE(ec) << "a WebSocket from another origin must be refused";
}

TEST_F(WebViewTest, AMessageOverTheLimitClosesOnlyThatWebSocket) {
  start();
  websocket::stream<asio::ip::tcp::socket> ws(connect());
  ws.handshake(host(), "/ws");
  ws.write(asio::buffer(std::string(2000, ' ')));
  beast::flat_buffer b;
  beast::error_code ec;
  for (int i = 0; i < 50 && !ec; ++i) {
    ws.read(b, ec);
    b.consume(b.size());
  }
  EXPECT_TRUE(ec) << "the server closes a connection that sent more than max_message bytes";
  EXPECT_EQ(get("/", host()).result(), http::status::ok);
}

TEST_F(WebViewTest, APageThatDoesNotReadItsRepliesIsClosed) {
  // Requests keep coming but the page reads nothing: once the socket buffers are full, replies
  // queue up to kMaxQueued and the server closes the connection instead of growing its memory.
  start();
  websocket::stream<asio::ip::tcp::socket> ws(connect());
  ws.handshake(host(), "/ws");
  beast::error_code ec;
  const std::string request = R"({"op":"view","file":2,"first":0,"last":6})";
  for (int i = 0; i < 5000 && !ec; ++i) ws.write(asio::buffer(request), ec);
  beast::flat_buffer b;
  while (!ec) {
    ws.read(b, ec);
    b.consume(b.size());
  }
  std::size_t open = 1;
  for (int i = 0; i < 100 && open > 0; ++i) {
    std::promise<std::size_t> n;
    asio::post(io_, [&] { n.set_value(web_->connections()); });
    open = n.get_future().get();
    if (open > 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(open, 0u) << "the server dropped the page";
}

TEST_F(WebViewTest, ConnectionsPastTheLimitAreClosed) {
  start(2);
  websocket::stream<asio::ip::tcp::socket> a(connect()), b(connect());
  a.handshake(host(), "/ws");
  b.handshake(host(), "/ws");
  websocket::stream<asio::ip::tcp::socket> c(connect());
  beast::error_code ec;
  c.handshake(host(), "/ws", ec);
  EXPECT_TRUE(ec);
}

}  // namespace
}  // namespace softslc::serve::testing
