#include "modules/devicenet/dem.h"

#include <algorithm>

namespace softslc::devicenet::dem {

Nanoseconds timeout_for_preset(std::uint8_t preset) {
  if (preset == 0) return 0;
  return seconds(preset == 1 ? 2 : preset);
}

void write_setup(std::span<std::uint16_t, kWords> cb, const Setup& s) {
  const int n = std::min(static_cast<int>(s.send.size()), kMaxSendBytes);
  cb[kTimeoutWord] = static_cast<std::uint16_t>((cb[kTimeoutWord] & ~kPresetMask) | s.timeout_s);
  cb[kRequestWord] = static_cast<std::uint16_t>(cb[kRequestWord] & 0xFF00) | 1u;
  cb[7] = static_cast<std::uint16_t>(n);
  cb[8] = static_cast<std::uint16_t>(s.service << 8 | s.mac);
  cb[9] = s.class_id;
  cb[10] = s.instance;
  cb[11] = s.attribute;
  for (int w = kSendDataWord; w < kReplyWord; ++w) cb[static_cast<std::size_t>(w)] = 0;
  for (int k = 0; k < n; ++k) {
    std::uint16_t& w = cb[static_cast<std::size_t>(kSendDataWord) + static_cast<std::size_t>(k / 2)];
    const std::uint16_t b = s.send[static_cast<std::size_t>(k)];
    w = static_cast<std::uint16_t>(k % 2 == 0 ? (w & 0xFF00) | b : (w & 0x00FF) | b << 8);
  }
}

RequestBlock request_from_control_block(std::span<const std::uint16_t, kWords> cb, std::uint8_t txid) {
  std::array<std::uint16_t, 32> block{};
  std::copy_n(cb.begin() + kRequestWord, 32, block.begin());
  // Word 7 counts the send data; the transaction block's size counts class, instance and attribute
  // too (transaction.h). Clamped so an oversized entry stays oversized (status 14).
  const int send = block[1] & 0xFF;
  block[1] = static_cast<std::uint16_t>((block[1] & 0xFF00) | std::min(send + kRequestPathBytes, 255));
  block[0] = static_cast<std::uint16_t>(txid << 8 | static_cast<std::uint8_t>(TxnCommand::Execute));
  return decode_request(block);
}

Error error_for_response(const ResponseBlock& r) {
  if (r.status != static_cast<std::uint8_t>(TxnStatus::Success)) return Error::Scanner;
  if (r.service == (service::kErrorResponse | service::kReplyBit)) return Error::Cip;
  return Error::None;
}

void DemPort::finish(std::span<std::uint16_t, kWords> cb, Error e, bool done) {
  std::uint16_t& w0 = cb[kStatusWord];
  w0 = static_cast<std::uint16_t>((w0 & ~(kErrorMask | kDN | kER)) | static_cast<std::uint16_t>(e));
  w0 = static_cast<std::uint16_t>(w0 | (done ? kDN : kER));
  owner_.reset();
}

void DemPort::on_rung(std::uint32_t owner, std::span<std::uint16_t, kWords> cb, bool rung_in, VirtualTime now) {
  std::uint16_t& w0 = cb[kStatusWord];

  // The message this control block has in flight.
  if (owner_ == owner) {
    if ((w0 & kAB) != 0) {
      // "The ER bit will be set as soon as the AB bit is set" (p.99).
      scanner_.delete_transaction(txid_);
      finish(cb, Error::User, false);
    } else if (const auto r = scanner_.completed_response(txid_)) {
      const Block reply = encode_response(*r);
      std::copy(reply.begin(), reply.end(), cb.begin() + kReplyWord);
      scanner_.delete_transaction(txid_);
      const Error e = error_for_response(*r);
      finish(cb, e, e == Error::None);
    } else if (timeout_ > 0 && now - start_ >= timeout_) {
      scanner_.delete_transaction(txid_);
      finish(cb, Error::Timeout, false);
    } else {
      cb[kAccumulatorWord] = static_cast<std::uint16_t>(std::min<Nanoseconds>((now - start_) / kNsPerS, 0xFFFF));
    }
  }

  if (!rung_in) {
    // A DEM still waiting for the slot gives up; a finished one clears EN (p.100).
    w0 = static_cast<std::uint16_t>(w0 & ~kWS);
    if ((w0 & kEN) != 0 && (w0 & (kDN | kER)) != 0) w0 = static_cast<std::uint16_t>(w0 & ~kEN);
    // An abandoned message never completes: its EN clears here, so the next transition sends again.
    if (abandoned_ == owner) {
      w0 = static_cast<std::uint16_t>(w0 & ~kEN);
      abandoned_.reset();
    }
    return;
  }
  if ((w0 & kEN) != 0 || owner_ == owner) return;  // accepted already (or still in flight)
  if (owner_) {
    w0 = static_cast<std::uint16_t>(w0 | kWS);  // "the module is still processing another DEM"
    return;
  }
  // Accepted: the false-to-true transition (or a retrigger after EN was cleared) starts a message.
  w0 = static_cast<std::uint16_t>((w0 & ~(kDN | kER | kWS | kAB | kErrorMask)) | kEN);
  std::uint8_t txid = next_txid_;
  for (int k = 0; k < 255 && (txid == 0 || scanner_.txid_in_use(txid)); ++k) txid = static_cast<std::uint8_t>(txid % 255 + 1);
  next_txid_ = static_cast<std::uint8_t>(txid % 255 + 1);
  cb[kRequestWord] = static_cast<std::uint16_t>(txid << 8 | static_cast<std::uint8_t>(TxnCommand::Execute));
  for (int w = kReplyWord; w < kWords; ++w) cb[static_cast<std::size_t>(w)] = 0;
  cb[kAccumulatorWord] = 0;
  cb[kScaledZeroWord] = static_cast<std::uint16_t>((now / kTick) & 0xFFFF);
  owner_ = owner;
  txid_ = txid;
  start_ = now;
  timeout_ = timeout_for_preset(static_cast<std::uint8_t>(cb[kTimeoutWord] & kPresetMask));
  // If all ten transactions are in use the module deletes the request (p.149): the DEM then waits
  // for its timeout, as the manual warns ("to avoid a message lockup", p.96).
  scanner_.handle_request(request_from_control_block(cb, txid));
}

void DemPort::abandon() {
  if (owner_) scanner_.delete_transaction(txid_);
  abandoned_ = owner_;
  owner_.reset();
}

}  // namespace softslc::devicenet::dem
