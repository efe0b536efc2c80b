#include "server/web.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <nlohmann/json.hpp>
#include <optional>

#include "parser/checker.h"
#include "tools/trace/ladder_layout.h"

namespace softslc::serve {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using nlohmann::json;

namespace {

std::optional<Value> value_of(const Controller& c, const Address& a) {
  try {
    return c.get(to_string(a));
  } catch (const ControllerError&) {
    return std::nullopt;
  }
}

std::optional<double> number_of(const Controller& c, const Operand& o) {
  if (o.kind == Operand::Kind::Integer) return static_cast<double>(o.integer);
  if (o.kind == Operand::Kind::Float) return o.real;
  if (!o.is_address() || o.address.indexed || o.address.is_indirect()) return std::nullopt;
  if (auto v = value_of(c, o.address)) return v->as_double();
  return std::nullopt;
}

// A compare instruction's truth from the current values (the rules of the interpreter's compare:
// LIM with low <= high tests inside the band, outside it otherwise; MEQ on 16-bit words); nullopt
// for any other instruction or an operand not known between scans.
std::optional<bool> compare_truth(const Controller& c, const Instruction& in) {
  std::vector<double> v;
  for (const auto& o : in.operands) {
    auto n = number_of(c, o);
    if (!n) return std::nullopt;
    v.push_back(*n);
  }
  const auto need = [&](std::size_t n) { return v.size() == n; };
  switch (in.opcode) {
    case Opcode::EQU: if (need(2)) return v[0] == v[1]; break;
    case Opcode::NEQ: if (need(2)) return v[0] != v[1]; break;
    case Opcode::LES: if (need(2)) return v[0] < v[1]; break;
    case Opcode::LEQ: if (need(2)) return v[0] <= v[1]; break;
    case Opcode::GRT: if (need(2)) return v[0] > v[1]; break;
    case Opcode::GEQ: if (need(2)) return v[0] >= v[1]; break;
    case Opcode::LIM:
      if (need(3)) return v[0] <= v[2] ? (v[0] <= v[1] && v[1] <= v[2]) : (v[1] >= v[0] || v[1] <= v[2]);
      break;
    case Opcode::MEQ:
      if (need(3)) {
        const auto w = [](double d) { return static_cast<std::uint16_t>(static_cast<std::int64_t>(d)); };
        return (w(v[0]) & w(v[1])) == (w(v[2]) & w(v[1]));
      }
      break;
    default: break;
  }
  return std::nullopt;
}

void collect_truth(const Controller& c, const std::vector<RungElement>& elements, std::vector<std::optional<bool>>& out) {
  for (const auto& e : elements) {
    if (e.kind == RungElement::Kind::Branch) {
      for (const auto& leg : e.legs) collect_truth(c, leg, out);
      continue;
    }
    out.push_back(compare_truth(c, e.instruction));
  }
}

std::string hex4(std::uint16_t v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04X", v);
  return buf;
}

// "N7" / "M0:1": the data file or module file a table request names.
struct TableRef {
  int file = -1;        // data file number
  int slot = -1;        // M0/M1: the module's slot
  bool m1 = false;
};
std::optional<TableRef> parse_table(const Controller& c, std::string_view name) {
  TableRef t;
  if (name.size() > 3 && (name.substr(0, 3) == "M0:" || name.substr(0, 3) == "M1:")) {
    t.m1 = name[1] == '1';
    int slot = 0;
    for (char ch : name.substr(3)) {
      if (ch < '0' || ch > '9' || slot > 100) return std::nullopt;
      slot = slot * 10 + (ch - '0');
    }
    t.slot = slot;
    return t;
  }
  if (name == "O") t.file = 0;
  else if (name == "I") t.file = 1;
  else if (name == "S") t.file = 2;
  else {
    std::size_t at = 0;
    while (at < name.size() && std::isalpha(static_cast<unsigned char>(name[at]))) ++at;
    int n = 0;
    if (at == 0 || at == name.size() || name.size() - at > 3) return std::nullopt;
    for (char ch : name.substr(at)) {
      if (ch < '0' || ch > '9') return std::nullopt;
      n = n * 10 + (ch - '0');
    }
    t.file = n;
  }
  auto info = c.file_info(t.file);
  if (!info) return std::nullopt;
  return t;
}

std::string file_name(const Controller::FileInfo& f) {
  switch (f.type) {
    case FileType::Output: return "O";
    case FileType::Input: return "I";
    case FileType::Status: return "S";
    default: return std::string(file_letter(f.type)) + std::to_string(f.number);
  }
}

}  // namespace

WebModel::WebModel(LiveController& live, std::function<void()> on_resume) : live_(live), on_resume_(std::move(on_resume)) {
  const Controller& c = live_.controller();
  const Program& p = c.program();
  json j;
  j["type"] = "program";
  j["project"] = p.project;
  j["processor"] = p.processor.display_name;
  j["catalog"] = p.processor.catalog;
  j["read_only"] = live_.read_only();
  // Every rung's height in rows (comment and body), from one layout of each file without state:
  // the page sizes its scroll space from these and asks only for the rungs in view.
  // The layout is made with values, as updates are, so boxes have their value rows here too.
  ladder::LadderState values;
  values.value = [&c](const Address& a) { return value_of(c, a); };
  j["files"] = json::array();
  for (const auto& f : p.files) {
    ladder::LayoutOptions lo;
    lo.file = f.number;
    lo.state = &values;
    const auto layout = ladder::layout_ladder(p, lo);
    json heights = json::array();
    if (!layout.files.empty())
      for (const auto& r : layout.files.front().rungs) heights.push_back(r.top + r.height);
    j["files"].push_back({{"number", f.number}, {"name", f.name}, {"heights", std::move(heights)}, {"width", layout.width}});
  }
  j["data"] = json::array();
  for (int n = 0; n < 256; ++n)
    if (auto info = c.file_info(n))
      j["data"].push_back({{"name", file_name(*info)}, {"type", std::string(file_letter(info->type))}, {"number", n},
                           {"elements", info->elements}, {"words_per_element", info->words_per_element}});
  for (const auto& slot : p.slots)
    for (bool m1 : {false, true})
      if (auto words = live_.module_file_words(slot.slot, m1))
        j["data"].push_back({{"name", std::string(m1 ? "M1:" : "M0:") + std::to_string(slot.slot)},
                             {"type", m1 ? "M1" : "M0"}, {"number", slot.slot}, {"elements", *words},
                             {"words_per_element", 1}, {"module", slot.catalog}});
  // The I/O image order (slot 1's words first): the page names image words I:slot.word.
  std::vector<const SlotConfig*> slots;
  for (const auto& slot : p.slots) slots.push_back(&slot);
  std::sort(slots.begin(), slots.end(), [](const SlotConfig* a, const SlotConfig* b) { return a->slot < b->slot; });
  j["slots"] = json::array();
  for (const SlotConfig* slot : slots)
    if (slot->slot > 0)
      j["slots"].push_back({{"slot", slot->slot}, {"catalog", slot->catalog}, {"in", slot->scan_in}, {"out", slot->scan_out}});
  j["symbols"] = json::object();
  for (const auto& s : p.symbols)
    if (!s.name.empty()) j["symbols"][to_string(s.address)] = s.name;
  program_message_ = j.dump();
}

std::string WebModel::error(const std::string& message) const {
  return json{{"type", "error"}, {"message", message}}.dump();
}

std::string WebModel::handle(std::string_view request, WebWatch& watch) {
  json j = json::parse(request, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("op") || !j["op"].is_string()) return error("not a request");
  const std::string op = j["op"];
  const auto str = [&](const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string(); };
  const auto integer = [&](const char* key, long long fallback) {
    return j.contains(key) && j[key].is_number_integer() ? j[key].get<long long>() : fallback;
  };
  std::string refused;
  if (op == "view") {
    const Program& p = live_.controller().program();
    const int file = static_cast<int>(integer("file", 2));
    const ProgramFile* f = p.find_file(file);
    if (!f) return error("no program file " + std::to_string(file));
    const long long total = static_cast<long long>(f->rungs.size()) + 1;  // the END rung too
    long long first = std::clamp(integer("first", 0), 0LL, total - 1);
    long long last = std::clamp(integer("last", first), first, total - 1);
    last = std::min(last, first + kMaxViewRungs - 1);
    watch.file = file;
    watch.first = static_cast<int>(first);
    watch.last = static_cast<int>(last);
  } else if (op == "table") {
    const std::string name = str("name");
    if (!name.empty() && !parse_table(live_.controller(), name)) return error("no data file " + name);
    watch.table = name;
    watch.table_offset = static_cast<std::uint32_t>(std::clamp(integer("offset", 0), 0LL, 1LL << 20));
  } else if (op == "trend") {
    if (!j.contains("addresses") || !j["addresses"].is_array() || j["addresses"].size() > kMaxTrend)
      return error("trend: at most " + std::to_string(kMaxTrend) + " addresses");
    std::vector<std::string> addresses;
    for (const auto& a : j["addresses"]) {
      if (!a.is_string() || a.get<std::string>().size() > 64) return error("trend: addresses are strings");
      try {
        live_.controller().get(a.get<std::string>());
      } catch (const ControllerError& e) {
        return error(e.what());
      }
      addresses.push_back(a);
    }
    watch.trend = std::move(addresses);
  } else if (op == "set") {
    std::string value = j.contains("value") && j["value"].is_number() ? j["value"].dump() : str("value");
    refused = live_.set_value(str("address"), value);
  } else if (op == "force") {
    const std::string state = str("state");
    if (state != "on" && state != "off" && state != "remove") return error("force: state is on, off or remove");
    refused = live_.force(str("address"), state == "remove" ? std::nullopt : std::optional<bool>(state == "on"));
  } else if (op == "mode") {
    const std::string m = str("mode");
    if (m == "program") refused = live_.set_mode(Mode::Program);
    else if (m == "run") refused = live_.set_mode(Mode::Run);
    else if (m == "test") refused = live_.set_mode(Mode::Test);
    else return error("mode: program, run or test");
  } else if (op == "clear_fault") {
    refused = live_.clear_fault();
  } else if (op == "pause" || op == "resume" || op == "step") {
    if (live_.read_only()) refused = "the server is read-only (--read-only)";
    else if (op == "pause") live_.pause();
    else if (op == "resume") {
      live_.resume();
      if (on_resume_) on_resume_();
    } else {
      live_.step(static_cast<int>(std::clamp(integer("scans", 1), 1LL, 1000LL)));
    }
  } else {
    return error("unknown request '" + op + "'");
  }
  if (!refused.empty()) return error(refused);
  return update(watch);
}

std::string WebModel::table_json(const WebWatch& watch) {
  Controller& c = live_.controller();
  auto ref = parse_table(c, watch.table);
  if (!ref) return "null";
  json t;
  t["name"] = watch.table;
  t["offset"] = watch.table_offset;
  std::vector<std::uint16_t> words;
  if (ref->slot >= 0) {
    const std::uint32_t total = live_.module_file_words(ref->slot, ref->m1).value_or(0);
    const std::uint32_t from = std::min(watch.table_offset, total);
    words.resize(std::min(total - from, kMaxTableWords));
    if (auto why = live_.read_module(ref->slot, ref->m1, from, words); !why.empty()) t["error"] = why;
    t["total"] = total;
  } else {
    const auto info = *c.file_info(ref->file);
    const std::uint32_t total = info.words();
    // A window starts on an element boundary, so the page can name every word.
    const auto wpe = static_cast<std::uint32_t>(info.words_per_element);
    const std::uint32_t from = std::min(watch.table_offset / wpe * wpe, total);
    words.resize(std::min(total - from, kMaxTableWords / wpe * wpe));
    c.read_file_words(ref->file, from, words);
    t["total"] = total;
    t["offset"] = from;
    // Floats and longs as the controller formats them (the page does not decode word pairs).
    if (info.type == FileType::Float || info.type == FileType::Long) {
      json values = json::array();
      for (std::uint32_t e = from / wpe; e < (from + static_cast<std::uint32_t>(words.size())) / wpe; ++e)
        values.push_back(c.get(file_name(info) + ":" + std::to_string(e)).to_string());
      t["values"] = std::move(values);
    }
  }
  t["words"] = words;
  return t.dump();
}

std::string WebModel::update(const WebWatch& watch) {
  Controller& c = live_.controller();
  json s;
  s["time"] = c.now();
  s["scans"] = c.scans();
  s["mode"] = std::string(to_string(c.mode()));
  s["paused"] = live_.paused();
  s["writes"] = live_.writes();
  s["s6"] = hex4(static_cast<std::uint16_t>(c.get_int("S:6")));
  if (const auto& f = c.fault())
    s["fault"] = {{"code", hex4(f->code)}, {"file", f->file}, {"rung", f->rung}, {"message", f->message}};
  else
    s["fault"] = nullptr;
  s["forces"] = live_.forces();
  json trend = json::array();
  for (const auto& a : watch.trend) {
    try {
      trend.push_back(c.get(a).as_double());
    } catch (const ControllerError&) {
      trend.push_back(nullptr);
    }
  }
  std::string out = R"({"type":"update","status":)" + s.dump() + R"(,"trend":)" + trend.dump() +
                    R"(,"table":)" + table_json(watch) + R"(,"ladder":)";
  const Program& p = c.program();
  const ProgramFile* f = p.find_file(watch.file);
  if (!f || watch.last < watch.first) return out + "null}";
  ladder::LadderState state;
  state.value = [&c](const Address& a) { return value_of(c, a); };
  auto& rungs = state.input_truth[watch.file];
  rungs.resize(f->rungs.size());
  for (int r = watch.first; r <= watch.last && r < static_cast<int>(f->rungs.size()); ++r)
    collect_truth(c, f->rungs[static_cast<std::size_t>(r)].elements, rungs[static_cast<std::size_t>(r)]);
  ladder::LayoutOptions lo;
  lo.file = watch.file;
  lo.first_rung = watch.first;
  lo.last_rung = watch.last;
  lo.state = &state;
  return out + ladder::render_json(ladder::layout_ladder(p, lo)) + "}";
}

// ---- The network side ----

namespace {

// Counts a connection for as long as a session holds it.
struct ConnectionSlot {
  explicit ConnectionSlot(std::shared_ptr<std::size_t> c) : count(std::move(c)) { ++*count; }
  ~ConnectionSlot() { --*count; }
  ConnectionSlot(const ConnectionSlot&) = delete;
  ConnectionSlot& operator=(const ConnectionSlot&) = delete;
  std::shared_ptr<std::size_t> count;
};

// Host: an IP address or localhost, with an optional port. A name anything else resolves is
// refused, so a page served from elsewhere whose name is rebound to 127.0.0.1 gets nothing.
bool local_host(std::string_view host) {
  if (host.empty() || host.size() > 64) return false;
  std::string_view name = host;
  if (name.front() == '[') {  // [::1]:8044
    const auto close = name.find(']');
    if (close == std::string_view::npos) return false;
    boost::system::error_code ec;
    asio::ip::make_address(std::string(name.substr(1, close - 1)), ec);
    return !ec;
  }
  if (const auto colon = name.rfind(':'); colon != std::string_view::npos) name = name.substr(0, colon);
  if (name == "localhost") return true;
  boost::system::error_code ec;
  asio::ip::make_address(std::string(name), ec);
  return !ec;
}

}  // namespace

struct WebView::Client : std::enable_shared_from_this<Client> {
  Client(beast::tcp_stream stream, WebView& v, std::shared_ptr<ConnectionSlot> s)
      : ws(std::move(stream)), view(v), slot(std::move(s)) {}

  void start(const http::request<http::string_body>& req) {
    beast::get_lowest_layer(ws).expires_never();
    ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws.read_message_max(view.options_.max_message);
    ws.async_accept(req, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->send(self->view.model_.program_message(), false);
      try {
        self->send(self->view.model_.update(self->watch), false);
      } catch (const std::exception& e) {
        spdlog::error("web: an update failed: {}", e.what());
      }
      self->read();
    });
  }
  void read() {
    ws.async_read(in, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        if (ec == websocket::error::message_too_big)
          spdlog::warn("web: a message larger than {} bytes; connection closed", self->view.options_.max_message);
        self->closed = true;
        return;
      }
      const std::string request = beast::buffers_to_string(self->in.data());
      self->in.consume(self->in.size());
      if (self->view.stopped_) return;
      // WebModel answers every request (the fuzz property checks it); should anything still
      // throw, the page gets an error and the server goes on: an exception must not leave io.run().
      std::string reply;
      try {
        reply = self->view.model_.handle(request, self->watch);
      } catch (const std::exception& e) {
        spdlog::error("web: a request failed: {}", e.what());
        reply = json{{"type", "error"}, {"message", e.what()}}.dump();
      }
      if (!reply.empty()) self->send(std::move(reply), false);
      self->read();
    });
  }
  // Sends a message; a periodic update (`droppable`) only when nothing is waiting, a reply
  // always unless kMaxQueued are waiting (then the page is not reading: it is closed).
  void send(std::string message, bool droppable) {
    if (closed) return;
    if (droppable && !out.empty()) return;
    if (out.size() >= kMaxQueued) {
      spdlog::warn("web: a page is not reading its replies; connection closed");
      close();
      return;
    }
    out.push_back(std::move(message));
    if (out.size() == 1) write_next();
  }
  void write_next() {
    ws.text(true);
    ws.async_write(asio::buffer(out.front()), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        self->closed = true;
        return;
      }
      self->out.pop_front();
      if (!self->out.empty()) self->write_next();
    });
  }
  void close() {
    closed = true;
    beast::error_code ignored;
    beast::get_lowest_layer(ws).socket().shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
    beast::get_lowest_layer(ws).socket().close(ignored);
  }

  websocket::stream<beast::tcp_stream> ws;
  WebView& view;
  std::shared_ptr<ConnectionSlot> slot;
  beast::flat_buffer in;
  std::deque<std::string> out;
  WebWatch watch;
  bool closed = false;
};

struct WebView::HttpSession : std::enable_shared_from_this<HttpSession> {
  HttpSession(asio::ip::tcp::socket s, WebView& v, std::shared_ptr<ConnectionSlot> sl)
      : stream(std::move(s)), view(v), slot(std::move(sl)) {}

  void read() {
    parser.emplace();
    parser->header_limit(8192);
    parser->body_limit(4096);
    stream.expires_after(view.options_.request_timeout);
    http::async_read(stream, buffer, *parser, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return;  // closed, timed out or malformed: the session ends
      self->handle(self->parser->release());
    });
  }
  void handle(const http::request<http::string_body>& req) {
    const auto host = req[http::field::host];
    if (!local_host(std::string_view(host.data(), host.size())))
      return respond(req, http::status::forbidden, "text/plain", "softslc serve: only a local address or localhost\n");
    if (websocket::is_upgrade(req)) {
      const auto origin = req[http::field::origin];
      const std::string expected = "http://" + std::string(host);
      if (req.target() != "/ws")
        return respond(req, http::status::not_found, "text/plain", "not found\n");
      if (!origin.empty() && std::string(origin) != expected) {
        spdlog::warn("web: refused a WebSocket from origin {}", std::string(origin));
        return respond(req, http::status::forbidden, "text/plain", "cross-origin WebSocket refused\n");
      }
      auto client = std::make_shared<Client>(std::move(stream), view, std::move(slot));
      view.clients_.push_back(client);  // for the periodic updates
      client->start(req);
      return;
    }
    if (req.method() != http::verb::get && req.method() != http::verb::head)
      return respond(req, http::status::method_not_allowed, "text/plain", "GET only\n");
    std::string_view target(req.target().data(), req.target().size());
    target = target.substr(0, target.find('?'));
    if (target == "/") target = "/index.html";
    for (const auto& a : web_assets())
      if (a.path == target) return respond(req, http::status::ok, a.type, std::string(a.content));
    respond(req, http::status::not_found, "text/plain", "not found\n");
  }
  void respond(const http::request<http::string_body>& req, http::status status, std::string_view type, std::string body) {
    auto res = std::make_shared<http::response<http::string_body>>(status, req.version());
    res->set(http::field::server, "softslc");
    res->set(http::field::content_type, beast::string_view(type.data(), type.size()));
    res->set(http::field::cache_control, "no-store");
    res->set("X-Content-Type-Options", "nosniff");
    res->keep_alive(req.keep_alive() && status == http::status::ok);
    if (req.method() != http::verb::head) res->body() = std::move(body);
    res->prepare_payload();
    http::async_write(stream, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
      if (ec) return;
      if (res->keep_alive()) return self->read();
      beast::error_code ignored;
      self->stream.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
    });
  }

  beast::tcp_stream stream;
  WebView& view;
  std::shared_ptr<ConnectionSlot> slot;
  beast::flat_buffer buffer{16384};
  std::optional<http::request_parser<http::string_body>> parser;
};

WebView::WebView(asio::io_context& io, LiveController& live, Server& server, WebOptions options)
    : model_(live, [&server] { server.restart_pacing(); }),
      options_(std::move(options)),
      acceptor_(io),
      timer_(io) {}

WebView::~WebView() = default;

void WebView::start() {
  listen_on(acceptor_, asio::ip::tcp::endpoint(asio::ip::make_address(options_.listen), options_.port));
  accept();
  tick();
}

void WebView::stop() {
  stopped_ = true;
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  timer_.cancel();
  for (auto& w : clients_)
    if (auto c = w.lock()) c->close();
  clients_.clear();
}

std::uint16_t WebView::port() const {
  boost::system::error_code ec;
  const auto ep = acceptor_.local_endpoint(ec);
  return ec ? 0 : ep.port();
}

void WebView::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, asio::ip::tcp::socket socket) {
    if (ec) {
      if (ec == asio::error::operation_aborted || stopped_) return;
      spdlog::warn("web: accept failed: {}", ec.message());
    } else if (*connections_ >= options_.max_connections) {
      spdlog::warn("web: connection limit ({}) reached; connection closed", options_.max_connections);
      boost::system::error_code ignored;
      socket.close(ignored);
    } else {
      auto slot = std::make_shared<ConnectionSlot>(connections_);
      std::make_shared<HttpSession>(std::move(socket), *this, std::move(slot))->read();
    }
    if (!stopped_) accept();
  });
}

void WebView::tick() {
  timer_.expires_after(options_.update_period);
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopped_) return;
    std::erase_if(clients_, [](const std::weak_ptr<Client>& w) {
      auto c = w.lock();
      return !c || c->closed;
    });
    for (auto& w : clients_) {
      auto c = w.lock();
      if (!c || !c->out.empty()) continue;
      try {
        c->send(model_.update(c->watch), true);
      } catch (const std::exception& e) {
        spdlog::error("web: an update failed: {}", e.what());
      }
    }
    tick();
  });
}

}  // namespace softslc::serve
