#include "server/eip.h"

#include <cstring>

namespace softslc::eip {

namespace {

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  put16(out, static_cast<std::uint16_t>(v & 0xFFFF));
  put16(out, static_cast<std::uint16_t>(v >> 16));
}
std::uint16_t get16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(get16(b, at)) | (static_cast<std::uint32_t>(get16(b, at + 2)) << 16);
}

constexpr std::uint16_t kItemNullAddress = 0x0000;
constexpr std::uint16_t kItemUnconnectedData = 0x00B2;
constexpr std::uint16_t kItemIdentity = 0x000C;
constexpr std::uint16_t kItemServices = 0x0100;

constexpr std::uint8_t kServiceExecutePccc = 0x4B;
constexpr std::uint8_t kServiceUnconnectedSend = 0x52;
constexpr std::uint8_t kCipServiceNotSupported = 0x08;
constexpr std::uint8_t kCipPathUnknown = 0x05;
constexpr std::uint8_t kCipNotEnoughData = 0x13;

// Class and instance of a padded logical path (8- or 16-bit class/instance segments).
struct Path {
  std::uint16_t cls = 0;
  std::uint16_t instance = 0;
  bool ok = false;
};
Path parse_path(std::span<const std::uint8_t> p) {
  Path r;
  bool have_class = false, have_instance = false;
  for (std::size_t i = 0; i < p.size();) {
    const std::uint8_t seg = p[i];
    if ((seg == 0x20 || seg == 0x24) && i + 1 < p.size()) {
      (seg == 0x20 ? r.cls : r.instance) = p[i + 1];
      (seg == 0x20 ? have_class : have_instance) = true;
      i += 2;
    } else if ((seg == 0x21 || seg == 0x25) && i + 3 < p.size()) {
      (seg == 0x21 ? r.cls : r.instance) = get16(p, i + 2);
      (seg == 0x21 ? have_class : have_instance) = true;
      i += 4;
    } else {
      return r;
    }
  }
  r.ok = have_class && have_instance;
  return r;
}

std::vector<std::uint8_t> cip_status(std::uint8_t service, std::uint8_t general) {
  return {static_cast<std::uint8_t>(service | 0x80), 0, general, 0};
}

}  // namespace

std::optional<Header> decode_header(std::span<const std::uint8_t> b) {
  if (b.size() < kHeaderSize) return std::nullopt;
  Header h;
  h.command = get16(b, 0);
  h.length = get16(b, 2);
  h.session = get32(b, 4);
  h.status = get32(b, 8);
  std::memcpy(h.context.data(), b.data() + 12, 8);
  h.options = get32(b, 20);
  return h;
}

std::vector<std::uint8_t> encode_frame(Header h, std::span<const std::uint8_t> data) {
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderSize + data.size());
  put16(out, h.command);
  put16(out, static_cast<std::uint16_t>(data.size()));
  put32(out, h.session);
  put32(out, h.status);
  out.insert(out.end(), h.context.begin(), h.context.end());
  put32(out, h.options);
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

std::optional<std::vector<CpfItem>> decode_cpf(std::span<const std::uint8_t> b) {
  if (b.size() < 2) return std::nullopt;
  const std::uint16_t count = get16(b, 0);
  if (count > 4) return std::nullopt;
  std::vector<CpfItem> items;
  std::size_t at = 2;
  for (std::uint16_t i = 0; i < count; ++i) {
    if (b.size() - at < 4) return std::nullopt;
    CpfItem item;
    item.type = get16(b, at);
    const std::uint16_t len = get16(b, at + 2);
    at += 4;
    if (b.size() - at < len) return std::nullopt;
    item.data = b.subspan(at, len);
    at += len;
    items.push_back(item);
  }
  if (at != b.size()) return std::nullopt;
  return items;
}

std::vector<std::uint8_t> list_identity_data(const Identity& id) {
  std::vector<std::uint8_t> item;
  put16(item, 1);  // encapsulation protocol version
  // The socket address is big-endian (sin_family, sin_port, sin_addr, 8 zero bytes).
  for (std::uint8_t b : {std::uint8_t{0}, std::uint8_t{2}, static_cast<std::uint8_t>(id.port >> 8),
                         static_cast<std::uint8_t>(id.port & 0xFF), static_cast<std::uint8_t>(id.ipv4 >> 24),
                         static_cast<std::uint8_t>(id.ipv4 >> 16), static_cast<std::uint8_t>(id.ipv4 >> 8),
                         static_cast<std::uint8_t>(id.ipv4)})
    item.push_back(b);
  item.insert(item.end(), 8, 0);
  put16(item, id.vendor);
  put16(item, id.device_type);
  put16(item, id.product_code);
  item.push_back(id.major);
  item.push_back(id.minor);
  put16(item, 0);  // status word
  put32(item, id.serial);
  const std::size_t n = id.product_name.size() < 32 ? id.product_name.size() : 32;
  item.push_back(static_cast<std::uint8_t>(n));
  item.insert(item.end(), id.product_name.begin(), id.product_name.begin() + static_cast<std::ptrdiff_t>(n));
  item.push_back(0x03);  // state: operational
  std::vector<std::uint8_t> out;
  put16(out, 1);
  put16(out, kItemIdentity);
  put16(out, static_cast<std::uint16_t>(item.size()));
  out.insert(out.end(), item.begin(), item.end());
  return out;
}

Outcome EipSession::handle(std::span<const std::uint8_t> frame) {
  Outcome o;
  auto h = decode_header(frame);
  if (!h || frame.size() != kHeaderSize + h->length) {
    o.close = true;
    o.log = "frame length does not match its header";
    return o;
  }
  const auto data = frame.subspan(kHeaderSize);
  Header reply = *h;
  reply.status = 0;
  switch (h->command) {
    case kNop: return o;
    case kListServices: {
      std::vector<std::uint8_t> d;
      put16(d, 1);
      put16(d, kItemServices);
      put16(d, 20);
      put16(d, 1);       // version
      put16(d, 0x0120);  // CIP over TCP (bit 5), class 0/1 over UDP (bit 8)
      const char name[16] = "Communications";
      d.insert(d.end(), name, name + 16);
      o.reply = encode_frame(reply, d);
      return o;
    }
    case kListIdentity: o.reply = encode_frame(reply, list_identity_data(identity_)); return o;
    case kListInterfaces: {
      std::vector<std::uint8_t> d;
      put16(d, 0);
      o.reply = encode_frame(reply, d);
      return o;
    }
    case kRegisterSession: {
      if (data.size() != 4) {
        o.close = true;
        o.log = "RegisterSession with " + std::to_string(data.size()) + " data bytes (4 expected)";
        return o;
      }
      if (get16(data, 0) != 1 || registered_) {
        reply.status = registered_ ? kStatusInvalidCommand : kStatusUnsupportedProtocol;
        o.reply = encode_frame(reply, data);
        return o;
      }
      registered_ = true;
      reply.session = handle_;
      o.reply = encode_frame(reply, data);
      return o;
    }
    case kUnRegisterSession:
      o.close = true;
      o.log = "session unregistered";
      return o;
    case kSendRRData: return send_rr_data(*h, data);
    default:
      reply.status = kStatusInvalidCommand;
      o.reply = encode_frame(reply, {});
      o.log = "unsupported encapsulation command " + std::to_string(h->command);
      return o;
  }
}

Outcome EipSession::send_rr_data(const Header& h, std::span<const std::uint8_t> data) {
  Outcome o;
  Header reply = h;
  if (!registered_ || h.session != handle_) {
    reply.status = kStatusInvalidSession;
    o.reply = encode_frame(reply, {});
    o.log = "SendRRData on an unregistered session";
    return o;
  }
  // Interface handle (u32), timeout (u16), then the CPF.
  std::optional<std::vector<CpfItem>> items;
  if (data.size() >= 6) items = decode_cpf(data.subspan(6));
  if (!items || items->size() != 2 || (*items)[0].type != kItemNullAddress || !(*items)[0].data.empty() ||
      (*items)[1].type != kItemUnconnectedData) {
    o.close = true;
    o.log = "SendRRData without a null address item and an unconnected data item";
    return o;
  }
  auto cip_reply = cip((*items)[1].data, 0, o.log);
  if (!cip_reply) {
    o.close = true;
    return o;
  }
  std::vector<std::uint8_t> d;
  put32(d, 0);  // interface handle: CIP
  put16(d, 0);  // timeout
  put16(d, 2);
  put16(d, kItemNullAddress);
  put16(d, 0);
  put16(d, kItemUnconnectedData);
  put16(d, static_cast<std::uint16_t>(cip_reply->size()));
  d.insert(d.end(), cip_reply->begin(), cip_reply->end());
  reply.status = 0;
  o.reply = encode_frame(reply, d);
  return o;
}

std::optional<std::vector<std::uint8_t>> EipSession::cip(std::span<const std::uint8_t> req, int depth,
                                                         std::string& log) {
  if (req.size() < 2) {
    log = "CIP request shorter than its service and path size";
    return std::nullopt;
  }
  const std::uint8_t service = req[0];
  const std::size_t path_bytes = static_cast<std::size_t>(req[1]) * 2;
  if (req.size() - 2 < path_bytes) {
    log = "CIP request path runs past the end";
    return std::nullopt;
  }
  const Path path = parse_path(req.subspan(2, path_bytes));
  const auto body = req.subspan(2 + path_bytes);
  if (service == kServiceUnconnectedSend && depth == 0) {
    if (!path.ok || path.cls != 0x06 || path.instance != 1) return cip_status(service, kCipPathUnknown);
    // Priority/tick time, timeout ticks, embedded request size, the request, a pad byte when
    // its size is odd, then the route path (ignored: this processor is the only node).
    if (body.size() < 4) return cip_status(service, kCipNotEnoughData);
    const std::uint16_t size = get16(body, 2);
    if (body.size() - 4 < size) return cip_status(service, kCipNotEnoughData);
    return cip(body.subspan(4, size), depth + 1, log);
  }
  if (service != kServiceExecutePccc) return cip_status(service, kCipServiceNotSupported);
  if (!path.ok || path.cls != 0x67 || path.instance != 1) return cip_status(service, kCipPathUnknown);
  // Requestor ID: its length byte counts itself; at least the length, vendor and serial (7).
  if (body.empty() || body[0] < 7 || body.size() < body[0]) {
    log = "Execute PCCC without a whole requestor ID";
    return std::nullopt;
  }
  const auto requestor = body.subspan(0, body[0]);
  std::string error;
  auto request = pccc::decode(body.subspan(body[0]), &error);
  if (!request) {
    log = "malformed PCCC command: " + error;
    return std::nullopt;
  }
  std::string refusal;
  const auto pccc_reply = pccc::execute(*request, target_, &refusal);
  if (!refusal.empty()) log = "PCCC request refused: " + refusal;
  std::vector<std::uint8_t> out = {static_cast<std::uint8_t>(service | 0x80), 0, 0, 0};
  out.insert(out.end(), requestor.begin(), requestor.end());
  out.insert(out.end(), pccc_reply.begin(), pccc_reply.end());
  return out;
}

}  // namespace softslc::eip
