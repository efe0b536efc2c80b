// What must hold for any bytes a network client sends `softslc serve` (server/pccc.h,
// server/eip.h, server/modbus.h, and the online view's requests, server/web.h): the decoders never read past their input or throw, a PCCC command that
// decodes always gets a reply with the request's TNS and CMD | 40h, and an encapsulation frame
// either gets a well-formed reply frame, nothing (NOP), or closes the connection. Each property
// returns an empty string when it holds, else what broke. The fuzz targets run them on random
// bytes; serve_tests runs them on the protocol documents' frames.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "server/eip.h"
#include "server/live.h"
#include "server/modbus.h"
#include "server/modbus_rtu.h"
#include "server/pccc.h"
#include "server/web.h"

#include <nlohmann/json.hpp>

namespace softslc::fuzz {

// One live controller for every input: loading a program per input would make the fuzzer slow;
// writes accumulate, which is what a long-running server sees too.
inline serve::LiveController& serve_live() {
  static serve::LiveController live(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/serve/hmi_panel.slc",
                                    std::nullopt, {});
  return live;
}

inline std::span<const std::uint8_t> as_bytes(std::string_view in) {
  return {reinterpret_cast<const std::uint8_t*>(in.data()), in.size()};
}

inline std::string check_pccc_property(std::string_view input) {
  const auto bytes = as_bytes(input);
  std::string error;
  auto request = pccc::decode(bytes, &error);
  if (!request) return error.empty() ? "PCCC decode failed without saying why" : std::string();
  const auto reply = pccc::execute(*request, serve_live());
  if (reply.size() < 4) return "PCCC reply shorter than CMD, STS, TNS";
  if (reply[0] != (request->cmd | pccc::kReplyBit)) return "PCCC reply CMD is not the request's | 40h";
  if ((reply[2] | (reply[3] << 8)) != request->tns) return "PCCC reply TNS differs from the request's";
  if (reply.size() > 4 + 24 + pccc::kMaxDataBytes) return "PCCC reply longer than the largest read";
  return {};
}

// The input is tried twice: as a whole frame on a fresh connection, and as the CPF data of a
// SendRRData on a registered session (so the fuzzer reaches CIP and PCCC without having to
// guess the session handle).
inline std::string check_eip_property(std::string_view input) {
  const auto check_outcome = [](const eip::Outcome& o) -> std::string {
    if (o.reply.empty()) return {};
    auto h = eip::decode_header(o.reply);
    if (!h || h->length + eip::kHeaderSize != o.reply.size()) return "reply frame length disagrees with its header";
    return {};
  };
  {
    eip::EipSession session(serve_live(), serve_live().identity(), 7);
    if (auto broken = check_outcome(session.handle(as_bytes(input))); !broken.empty()) return broken;
  }
  eip::EipSession session(serve_live(), serve_live().identity(), 7);
  const std::uint8_t reg[28] = {0x65, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
  (void)session.handle(reg);
  if (input.size() > 60000) return {};
  std::vector<std::uint8_t> frame = {0x6F, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 0};
  frame.insert(frame.end(), input.begin(), input.end());
  const auto len = static_cast<std::uint16_t>(frame.size() - eip::kHeaderSize);
  frame[2] = static_cast<std::uint8_t>(len & 0xFF);
  frame[3] = static_cast<std::uint8_t>(len >> 8);
  return check_outcome(session.handle(frame));
}

// A Modbus TCP frame (the input, with the MBAP length fixed up when it has a header, so the
// fuzzer reaches the functions) either closes the connection with a reason or gets a reply frame
// whose MBAP header is the request's transaction and unit with the right length, and whose
// function is the request's, or the request's | 80h followed by one exception code 01-04.
inline std::string check_modbus_property(std::string_view input) {
  if (input.size() > 300) return {};
  std::vector<std::uint8_t> frame(input.begin(), input.end());
  if (frame.size() >= modbus::kHeaderSize && frame.size() - 6 <= 0xFFFF) {
    frame[4] = static_cast<std::uint8_t>((frame.size() - 6) >> 8);
    frame[5] = static_cast<std::uint8_t>((frame.size() - 6) & 0xFF);
  }
  const modbus::Map map{3, 3, 7, 7};  // the HMI example's B3 and N7
  std::string error;
  const auto reply = modbus::handle(frame, map, serve_live(), &error);
  if (!reply) return error.empty() ? "Modbus frame refused without saying why" : std::string();
  const auto& r = *reply;
  if (r.size() < modbus::kHeaderSize + 2) return "Modbus reply shorter than a header, function and one byte";
  if (static_cast<std::size_t>(r[4] << 8 | r[5]) + 6 != r.size()) return "Modbus reply length disagrees with its MBAP header";
  if (r[0] != frame[0] || r[1] != frame[1] || r[6] != frame[6]) return "Modbus reply transaction or unit differs";
  if (r[2] != 0 || r[3] != 0) return "Modbus reply protocol identifier is not 0";
  if (r[7] == (frame[7] | 0x80)) {
    if (r.size() != modbus::kHeaderSize + 2 || r[8] < 1 || r[8] > 4) return "Modbus exception reply malformed";
  } else if (r[7] != frame[7]) {
    return "Modbus reply function differs from the request's";
  }
  if (r.size() > modbus::kHeaderSize + modbus::kMaxPdu) return "Modbus reply longer than the largest PDU";
  return {};
}

// Bytes on a Modbus RTU line (server/modbus_rtu.h), to slave 1 with the map of the TCP property.
// The first byte says how the rest arrives: in chunks of (b & 3Fh) + 1 bytes, with the line
// falling silent after each chunk when b & 40h. Every reply is a whole frame from slave 1 with a
// good CRC, at most 256 bytes, whose function is a request's or an exception (| 80h, one code
// 01-04); the buffer never holds more than 256 bytes; after a final silence it is empty.
inline std::string check_modbus_rtu_property(std::string_view input) {
  if (input.empty() || input.size() > 4096) return {};
  const auto how = static_cast<std::uint8_t>(input[0]);
  const std::size_t chunk = (how & 0x3Fu) + 1u;
  const bool silences = (how & 0x40u) != 0;
  const auto bytes = as_bytes(input.substr(1));
  modbus::RtuSlave slave(1, modbus::Map{3, 3, 7, 7});
  const auto check = [&](const modbus::RtuEvents& e) -> std::string {
    if (slave.buffered() > modbus::kRtuMaxFrame) return "Modbus RTU buffer past 256 bytes";
    for (const auto& r : e.replies) {
      if (r.size() < 5 || r.size() > modbus::kRtuMaxFrame) return "Modbus RTU reply of " + std::to_string(r.size()) + " bytes";
      if (r[0] != 1) return "Modbus RTU reply not from slave 1";
      const std::uint16_t crc = modbus::crc16(std::span(r).first(r.size() - 2));
      if (r[r.size() - 2] != (crc & 0xFF) || r[r.size() - 1] != (crc >> 8)) return "Modbus RTU reply CRC wrong";
      if ((r[1] & 0x80) && (r.size() != 5 || r[2] < 1 || r[2] > 4)) return "Modbus RTU exception reply malformed";
    }
    return {};
  };
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    if (auto broken = check(slave.receive(bytes.subspan(at, std::min(chunk, bytes.size() - at)), serve_live())); !broken.empty())
      return broken;
    if (silences)
      if (auto broken = check(slave.silence(serve_live())); !broken.empty()) return broken;
  }
  if (auto broken = check(slave.silence(serve_live())); !broken.empty()) return broken;
  if (slave.waiting_for_silence() && !slave.silence(serve_live()).replies.empty()) return "Modbus RTU replied on a second silence";
  if (slave.buffered() != 0) return "Modbus RTU bytes left after the line fell silent";
  return {};
}

// A message from a page of the online view (at most WebOptions::max_message bytes; WebView
// closes the connection on a longer one) gets a JSON object back, an update or an error, never an
// exception, and what the page watches stays within its bounds.
inline std::string check_web_property(std::string_view input) {
  if (input.size() > 4096) return {};
  static serve::WebModel model(serve_live(), nullptr);
  static serve::WebWatch watch;
  std::string reply;
  try {
    reply = model.handle(input, watch);
  } catch (const std::exception& e) {
    return std::string("WebModel::handle threw: ") + e.what();
  }
  const auto j = nlohmann::json::parse(reply, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("type")) return "web reply is not a JSON object with a type";
  if (j["type"] != "update" && j["type"] != "error") return "web reply is neither an update nor an error";
  if (watch.last >= watch.first && watch.last - watch.first >= serve::kMaxViewRungs) return "web view wider than kMaxViewRungs";
  if (watch.trend.size() > serve::kMaxTrend) return "more trend addresses than kMaxTrend";
  if (j["type"] == "update" && j["table"].is_object() && j["table"]["words"].size() > serve::kMaxTableWords)
    return "web table window larger than kMaxTableWords";
  return {};
}

}  // namespace softslc::fuzz
