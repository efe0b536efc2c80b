#include "modules/devicenet/bus_timing.h"

namespace softslc::devicenet {

std::string_view to_string(Baud b) {
  switch (b) {
    case Baud::k125: return "125K";
    case Baud::k250: return "250K";
    case Baud::k500: return "500K";
  }
  return "?";
}

std::optional<Baud> parse_baud(std::string_view text) {
  if (text == "125K") return Baud::k125;
  if (text == "250K") return Baud::k250;
  if (text == "500K") return Baud::k500;
  return std::nullopt;
}

Nanoseconds io_message_time(Baud b, int bytes) {
  if (bytes <= 8) return frame_time(b, bytes < 0 ? 0 : bytes);
  // Fragments: 1 fragmentation byte + up to 7 data bytes each.
  Nanoseconds t = 0;
  for (int left = bytes; left > 0; left -= 7) t += frame_time(b, 1 + (left < 7 ? left : 7));
  return t;
}

Nanoseconds explicit_message_time(Baud b, int body_bytes) {
  if (1 + body_bytes <= 8) return frame_time(b, 1 + body_bytes);
  // Fragments: header + fragmentation byte + up to 6 body bytes, each answered by a 3-byte ack.
  Nanoseconds t = 0;
  for (int left = body_bytes; left > 0; left -= 6) t += frame_time(b, 2 + (left < 6 ? left : 6)) + frame_time(b, 3);
  return t;
}

}  // namespace softslc::devicenet
