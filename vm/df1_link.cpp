#include "vm/df1_link.h"

#include <algorithm>
#include <charconv>
#include <tuple>

namespace softslc {

bool has_df1_channel0(const ProcessorModel& p) {
  if (p.is_micrologix()) return true;
  return p.family == ProcessorFamily::Slc503 || p.family == ProcessorFamily::Slc504 ||
         p.family == ProcessorFamily::Slc505;
}

Df1Config df1_defaults(const ProcessorModel& p) {
  Df1Config c;
  if (p.micrologix == MicroLogixModel::ML1000) {
    // AG-UM008C p. 6-14 table 6.2: 9600 baud; "N retries", N = 6 for series C and later discrete and all
    // analog (255 for series A and B discrete, which softslc does not tell apart); ACK timeout 1 second.
    c.baud = 9600;
    c.nak_retries = 6;
    c.enq_retries = 6;
  }
  return c;
}

namespace {

constexpr int kBauds[] = {110, 300, 600, 1200, 2400, 4800, 9600, 19200, 38400};

std::string name_of(const ProcessorModel& p) { return p.display_name; }

}  // namespace

std::string df1_configure(const ProcessorModel& p, const Df1Options& o, Df1Config& out) {
  if (!has_df1_channel0(p))
    return "channel 0: the " + name_of(p) + " has no RS-232 channel to configure for DF1 full-duplex (its only "
           "channel is DH-485; DF1 full-duplex is the SLC 5/03-5/05's channel 0, 1747-RM001G p. 13-49, and the "
           "MicroLogix's, 1762-RM001C p. 21-2)";
  Df1Config c = df1_defaults(p);
  if (p.micrologix == MicroLogixModel::ML1000) {
    // Table 6.2's Options column is "None" for everything but the baud rate and the node address.
    const char* fixed = o.parity_even            ? "parity"
                        : o.error_check          ? "error detection"
                        : o.ack_timeout          ? "ACK timeout"
                        : o.nak_retries          ? "NAK retries"
                        : o.enq_retries          ? "ENQ retries"
                        : o.duplicate_detect     ? "duplicate packet detection"
                                                 : nullptr;
    if (fixed)
      return std::string("channel 0: the MicroLogix 1000's DF1 full-duplex ") + fixed + " is not configurable (AG-UM008C "
             "p. 6-14 table 6.2: only the baud rate and the node address have options)";
  }
  if (o.baud) {
    const bool known = std::find(std::begin(kBauds), std::end(kBauds), *o.baud) != std::end(kBauds);
    const bool slc = !p.is_micrologix();
    if (!known || (*o.baud == 110 && !slc))
      return "channel 0: baud " + std::to_string(*o.baud) + " is not a rate the " + name_of(p) + " offers (" +
             (slc ? std::string("110, ") : std::string()) +
             "300, 600, 1200, 2400, 4800, 9600, 19200 or 38400; 1766-RM001A p. 592, AG-UM008C p. 6-14)";
    c.baud = *o.baud;
  }
  if (o.parity_even) c.parity_even = *o.parity_even;
  if (o.error_check) c.error_check = *o.error_check;
  if (o.ack_timeout) {
    if (*o.ack_timeout < 1 || *o.ack_timeout > 65535)
      return "channel 0: ack_timeout " + std::to_string(*o.ack_timeout) +
             " is out of range 1-65535 (counts of 20 ms, 1766-RM001A p. 592)";
    c.ack_timeout = *o.ack_timeout;
  }
  for (auto [value, name, field] : {std::tuple{o.nak_retries, "nak_retries", &c.nak_retries},
                                    std::tuple{o.enq_retries, "enq_retries", &c.enq_retries}}) {
    if (!value) continue;
    if (*value < 0 || *value > 255)
      return std::string("channel 0: ") + name + " " + std::to_string(*value) + " is out of range 0-255 (1766-RM001A p. 592)";
    *field = *value;
  }
  if (o.duplicate_detect) c.duplicate_detect = *o.duplicate_detect;
  out = c;
  return {};
}

std::string df1_parse_option(std::string_view text, Df1Options& o) {
  if (text == "crc" || text == "bcc") {
    o.error_check = text == "crc" ? Df1ErrorCheck::Crc : Df1ErrorCheck::Bcc;
    return {};
  }
  const std::size_t eq = text.find('=');
  const std::string_view key = text.substr(0, eq);
  const std::string_view value = eq == std::string_view::npos ? std::string_view{} : text.substr(eq + 1);
  auto number = [&](std::optional<int>& field) -> std::string {
    int v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || ec != std::errc{} || end != value.data() + value.size() || value.size() > 6)
      return std::string(key) + " takes a whole number (" + std::string(key) + "=N), not '" + std::string(value) + "'";
    field = v;
    return {};
  };
  if (eq == std::string_view::npos)
    return "'" + std::string(text) + "' is not a DF1 setting: expected baud=N, parity=none|even, crc, bcc, "
           "ack_timeout=N (x20 ms), nak_retries=N, enq_retries=N or duplicate_detect=on|off";
  if (key == "baud") return number(o.baud);
  if (key == "ack_timeout") return number(o.ack_timeout);
  if (key == "nak_retries") return number(o.nak_retries);
  if (key == "enq_retries") return number(o.enq_retries);
  if (key == "parity") {
    if (value != "none" && value != "even") return "parity is none or even (1766-RM001A p. 592), not '" + std::string(value) + "'";
    o.parity_even = value == "even";
    return {};
  }
  if (key == "duplicate_detect") {
    if (value != "on" && value != "off") return "duplicate_detect is on or off, not '" + std::string(value) + "'";
    o.duplicate_detect = value == "on";
    return {};
  }
  return "'" + std::string(key) + "' is not a DF1 setting: expected baud, parity, crc, bcc, ack_timeout, nak_retries, "
         "enq_retries or duplicate_detect";
}

// ---- Frames -------------------------------------------------------------------------------------------

std::uint8_t df1_bcc(const std::vector<std::uint8_t>& packet) {
  unsigned sum = 0;
  for (std::uint8_t b : packet) sum += b;
  return static_cast<std::uint8_t>(-sum & 0xFFu);
}

std::uint16_t crc16(const std::vector<std::uint8_t>& bytes) {
  std::uint16_t crc = 0;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int i = 0; i < 8; ++i) crc = (crc & 1u) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001u) : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

std::uint16_t df1_crc(const std::vector<std::uint8_t>& packet) {
  std::vector<std::uint8_t> with_etx = packet;
  with_etx.push_back(kEtx);
  return crc16(with_etx);
}

std::vector<std::uint8_t> df1_frame(const std::vector<std::uint8_t>& packet, Df1ErrorCheck check) {
  std::vector<std::uint8_t> f{kDle, kStx};
  for (std::uint8_t b : packet) {
    f.push_back(b);
    if (b == kDle) f.push_back(kDle);  // "A data 10h is sent as 10 10 (DLE DLE)" (1770-6.5.16 p. 2-8 table 2.D)
  }
  f.push_back(kDle);
  f.push_back(kEtx);
  if (check == Df1ErrorCheck::Bcc) {
    f.push_back(df1_bcc(packet));
  } else {
    const std::uint16_t crc = df1_crc(packet);
    f.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    f.push_back(static_cast<std::uint8_t>(crc >> 8));
  }
  return f;
}

Nanoseconds df1_character_time(const Df1Config& c, int characters) {
  const std::int64_t bits = static_cast<std::int64_t>(characters) * c.bits_per_character();
  return (bits * kNsPerS + c.baud - 1) / c.baud;
}

namespace {

void put_field(std::vector<std::uint8_t>& p, int v) {
  if (v >= 0 && v < 255) {
    p.push_back(static_cast<std::uint8_t>(v));
  } else {
    p.push_back(0xFF);
    const auto u = static_cast<std::uint32_t>(v);  // the field's two bytes, low first
    p.push_back(static_cast<std::uint8_t>(u & 0xFF));
    p.push_back(static_cast<std::uint8_t>((u >> 8) & 0xFF));
  }
}

void put_header(std::vector<std::uint8_t>& p, int dst, int src, std::uint8_t cmd, std::uint8_t sts, std::uint16_t tns) {
  p.push_back(static_cast<std::uint8_t>(dst));
  p.push_back(static_cast<std::uint8_t>(src));
  p.push_back(cmd);
  p.push_back(sts);
  p.push_back(static_cast<std::uint8_t>(tns & 0xFF));
  p.push_back(static_cast<std::uint8_t>(tns >> 8));
}

void put_words(std::vector<std::uint8_t>& p, const std::vector<std::uint16_t>& words) {
  for (std::uint16_t w : words) {
    p.push_back(static_cast<std::uint8_t>(w & 0xFF));
    p.push_back(static_cast<std::uint8_t>(w >> 8));
  }
}

std::uint8_t command_code(const Df1Command& c) {
  if (c.cif) return c.write ? 0x08 : 0x01;
  return 0x0F;
}

}  // namespace

std::vector<std::uint8_t> df1_command_packet(const Df1Command& c) {
  std::vector<std::uint8_t> p;
  put_header(p, c.dst, c.src, command_code(c), 0, c.tns);
  if (c.cif) {
    // The unprotected read and write address a byte offset into the common interface file.
    const int byte_offset = 2 * c.element;
    p.push_back(static_cast<std::uint8_t>(byte_offset & 0xFF));
    p.push_back(static_cast<std::uint8_t>((byte_offset >> 8) & 0xFF));
    if (c.write) put_words(p, c.data);
    else p.push_back(static_cast<std::uint8_t>(2 * c.words));
    return p;
  }
  p.push_back(c.write ? 0xAA : 0xA2);
  p.push_back(static_cast<std::uint8_t>(2 * c.words));
  put_field(p, c.file);
  p.push_back(static_cast<std::uint8_t>(c.type_code));
  put_field(p, c.element);
  put_field(p, 0);
  if (c.write) put_words(p, c.data);
  return p;
}

std::vector<std::uint8_t> df1_reply_packet(const Df1Command& c, std::uint8_t sts, const std::vector<std::uint16_t>& data) {
  std::vector<std::uint8_t> p;
  // "The processor ... exchanges these addresses in the reply" (1747-RM001G p. 13-49).
  put_header(p, c.src, c.dst, static_cast<std::uint8_t>(command_code(c) | 0x40), sts, c.tns);
  put_words(p, data);
  return p;
}

// ---- Counters -----------------------------------------------------------------------------------------

std::optional<Df1Count> df1_count_named(std::string_view name) {
  constexpr std::pair<std::string_view, Df1Count> kNames[] = {
      {"sent", Df1Count::Sent},           {"received", Df1Count::Received},
      {"undelivered", Df1Count::Undelivered}, {"enqs sent", Df1Count::EnqsSent},
      {"naks received", Df1Count::NaksReceived}, {"enqs received", Df1Count::EnqsReceived},
      {"bad packets", Df1Count::BadPackets}, {"duplicates", Df1Count::Duplicates},
  };
  for (const auto& [n, c] : kNames)
    if (n == name) return c;
  return std::nullopt;
}

std::int64_t Df1Counters::at(Df1Count c, VirtualTime now) const {
  std::int64_t n = settled_[static_cast<std::size_t>(c)];
  for (auto it = pending_.begin(); it != pending_.end() && it->first <= now; ++it)
    if (it->second == c) ++n;
  return n;
}

void Df1Counters::settle(VirtualTime now) {
  while (!pending_.empty() && pending_.begin()->first <= now) {
    ++settled_[static_cast<std::size_t>(pending_.begin()->second)];
    pending_.erase(pending_.begin());
  }
}

// ---- A transfer ---------------------------------------------------------------------------------------

Df1Outcome df1_transfer(Df1Port& from, Df1Port* to, bool line_ok, VirtualTime start, int frame_bytes, std::uint32_t key) {
  const Df1Config& c = from.config;
  const bool heard = line_ok && to != nullptr;
  const Nanoseconds frame = df1_character_time(c, frame_bytes);
  const Nanoseconds symbol = df1_character_time(c, 2);  // DLE ACK, DLE NAK, DLE ENQ
  Df1Outcome out;
  int naks = 0, enqs = 0;
  from.counters.settle(start);
  if (to) to->counters.settle(start);
  VirtualTime t = std::max(start, from.transmitter_free);
  auto give_up = [&](VirtualTime when) {
    from.counters.add(Df1Count::Undelivered, when);
    out.done = when;
    from.transmitter_free = when;
    return out;
  };
  for (;;) {
    // The frame goes out; its last character has gone at t + frame.
    ++out.frames;
    from.counters.add(Df1Count::Sent, t);
    VirtualTime end = t + frame;
    // What the far end answers: nothing when it hears nothing; NAK for a frame whose check fails (noise, or a
    // receiver that checks the other way); otherwise ACK, and the packet goes to its sink unless it is a
    // duplicate that the receiver detects.
    std::optional<bool> response;  // true ACK, false NAK
    if (heard) {
      const bool corrupted = from.corrupt_frames > 0;
      if (corrupted) --from.corrupt_frames;
      if (corrupted || to->config.error_check != c.error_check) {
        to->counters.add(Df1Count::BadPackets, end);
        to->last_response_ack = false;
        response = false;
      } else {
        if (to->config.duplicate_detect && to->last_key == key) {
          to->counters.add(Df1Count::Duplicates, end);
        } else {
          to->counters.add(Df1Count::Received, end);
          out.deliveries.push_back(end);
        }
        to->last_key = key;
        to->last_response_ack = true;
        response = true;
        if (from.lose_ack) {
          // The ACK is destroyed on the way back and the noise leaves the receiver answering NAK to an ENQ
          // (1770-6.5.16 p. 4-13).
          from.lose_ack = false;
          to->last_response_ack = false;
          response.reset();
        }
      }
    }
    // Waiting for a response: an ENQ after each ACK timeout, answered with the receiver's last response.
    while (!response) {
      const VirtualTime timeout = end + c.ack_timeout_ns();
      if (enqs >= c.enq_retries) return give_up(timeout);
      ++enqs;
      from.counters.add(Df1Count::EnqsSent, timeout);
      end = timeout + symbol;
      if (heard) {
        to->counters.add(Df1Count::EnqsReceived, end);
        response = to->last_response_ack;
      }
    }
    const VirtualTime answered = end + symbol;
    if (*response) {
      out.acked = true;
      out.done = answered;
      from.transmitter_free = answered;
      return out;
    }
    ++naks;
    from.counters.add(Df1Count::NaksReceived, answered);
    if (naks > c.nak_retries) return give_up(answered);
    t = answered;
  }
}

}  // namespace softslc
