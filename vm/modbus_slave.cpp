#include "vm/modbus_slave.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <functional>
#include <sstream>

namespace softslc::modbus {

namespace {

// The function codes the slave executes, in the order of their counters in the communication parameters
// (30518-30526, 1766-RM001A p. 618); any other is exception 01.
constexpr std::uint8_t kSlaveFunctions[] = {kReadCoils,          kReadDiscreteInputs, kReadHoldingRegisters,
                                            kReadInputRegisters, kWriteSingleCoil,    kWriteSingleRegister,
                                            kDiagnostics,        kWriteMultipleCoils, kWriteMultipleRegisters};
// The index of `fc` in kSlaveFunctions, or -1.
int slave_function_index(std::uint8_t fc) {
  const auto* at = std::find(std::begin(kSlaveFunctions), std::end(kSlaveFunctions), fc);
  return at == std::end(kSlaveFunctions) ? -1 : static_cast<int>(at - std::begin(kSlaveFunctions));
}

// Where a range of protocol addresses lands: a data file and its first word (registers) or bit.
struct Place {
  int file = 0;
  std::uint32_t first = 0;
};

// Resolves `count` registers (bits == false) or bits from `address` in one space, or the exception.
struct Resolved {
  std::optional<Place> place;
  std::uint8_t exception = 0;
  std::string why;
};

Resolved resolve(const pccc::Target& target, int file, std::uint32_t space, std::uint32_t address, std::uint32_t count,
                 bool bits) {
  Resolved r;
  if (address + count > space) {
    r.exception = kIllegalDataAddress;
    r.why = "addresses " + std::to_string(address) + "-" + std::to_string(address + count - 1) + " are outside the map";
    return r;
  }
  const auto info = target.file(file);
  const std::uint32_t words = info ? info->elements * static_cast<std::uint32_t>(info->words_per_element) : 0;
  const std::uint32_t units = bits ? words * 16 : words;
  if (address + count > units) {
    r.exception = kIllegalDataAddress;
    r.why = "addresses " + std::to_string(address) + "-" + std::to_string(address + count - 1) + " run past the end of file " +
            std::to_string(file);
    return r;
  }
  r.place = Place{file, address};
  return r;
}

// Registers: the holding/input register file at 0-255, the status file at 1500-1565.
Resolved resolve_registers(const pccc::Target& target, int file, std::uint32_t address, std::uint32_t count) {
  if (address >= kStatusRegisterBase) {
    Resolved r = resolve(target, kStatusFile, kStatusRegisters, address - kStatusRegisterBase, count, false);
    if (!r.place && address - kStatusRegisterBase >= kStatusRegisters) r.why = "address " + std::to_string(address) + " is not mapped";
    return r;
  }
  return resolve(target, file, kRegisterSpace, address, count, false);
}

// A reply PDU: the request's function and its data, or function | 80h and an exception code.
class Reply {
 public:
  explicit Reply(std::uint8_t function) : function_(function) { out_.push_back(function); }
  std::vector<std::uint8_t>& bytes() { return out_; }
  std::vector<std::uint8_t> finish() { return std::move(out_); }
  std::vector<std::uint8_t> exception(std::uint8_t code) { return {static_cast<std::uint8_t>(function_ | 0x80), code}; }

 private:
  std::uint8_t function_;
  std::vector<std::uint8_t> out_;
};

std::vector<std::uint8_t> read_bits(Reply& reply, pccc::Target& target, const Place& p, std::uint32_t count) {
  const std::uint32_t first_word = p.first / 16;
  const std::uint32_t last_word = (p.first + count - 1) / 16;
  std::vector<std::uint16_t> words(last_word - first_word + 1);
  target.read(p.file, first_word, words);
  auto& out = reply.bytes();
  const std::size_t bytes = (count + 7) / 8;
  out.push_back(static_cast<std::uint8_t>(bytes));
  const std::size_t at = out.size();
  out.resize(at + bytes, 0);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t bit = p.first + i;
    if ((words[bit / 16 - first_word] >> (bit % 16)) & 1u) out[at + i / 8] = static_cast<std::uint8_t>(out[at + i / 8] | 1u << (i % 8));
  }
  return reply.finish();
}

// Writes bits through the target, one masked write per word touched.
std::string write_bits(pccc::Target& target, const Place& p, std::uint32_t count,
                       const std::function<bool(std::uint32_t)>& bit_value) {
  const std::uint32_t first_word = p.first / 16;
  const std::uint32_t last_word = (p.first + count - 1) / 16;
  std::vector<std::uint16_t> values(last_word - first_word + 1, 0), masks(values.size(), 0);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t bit = p.first + i;
    const auto m = static_cast<std::uint16_t>(1u << (bit % 16));
    masks[bit / 16 - first_word] = static_cast<std::uint16_t>(masks[bit / 16 - first_word] | m);
    if (bit_value(i)) values[bit / 16 - first_word] = static_cast<std::uint16_t>(values[bit / 16 - first_word] | m);
  }
  return target.write(p.file, first_word, values, masks);
}

}  // namespace

std::optional<Map> parse_map(const std::string& text) {
  std::vector<int> files;
  std::istringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    std::size_t at = 0;
    while (at < part.size() && std::isalpha(static_cast<unsigned char>(part[at]))) ++at;
    if (at == part.size() || part.size() - at > 3) return std::nullopt;
    int n = 0;
    for (std::size_t i = at; i < part.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(part[i]))) return std::nullopt;
      n = n * 10 + (part[i] - '0');
    }
    files.push_back(n);
  }
  if (files.size() != 4) return std::nullopt;
  return Map{files[0], files[1], files[2], files[3]};
}

std::string parse_slave_option(std::string_view text, SlaveOptions& options) {
  const std::size_t eq = text.find('=');
  const std::string_view key = text.substr(0, eq);
  const std::string value(eq == std::string_view::npos ? std::string_view{} : text.substr(eq + 1));
  const auto whole = [&]() -> std::optional<int> {
    int v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || value.size() > 6 || ec != std::errc{} || end != value.data() + value.size()) return std::nullopt;
    return v;
  };
  if (eq == std::string_view::npos || (key != "address" && key != "baud" && key != "map"))
    return "'" + std::string(text) + "' is not a Modbus RTU slave setting: expected address=N (1-247), baud=N or "
           "map=C,D,I,H (the coil, contact, input register and holding register files, e.g. map=B3,B3,N7,N7)";
  if (key == "address") {
    const auto v = whole();
    if (!v || *v < kMinSlaveAddress || *v > kMaxSlaveAddress)
      return "address is a Modbus slave address, 1-247 (0 is the broadcast address, 248-255 are reserved), not '" +
             value + "'";
    options.address = *v;
    return {};
  }
  if (key == "baud") {
    const auto v = whole();
    if (!v || std::find(std::begin(kSlaveBauds), std::end(kSlaveBauds), *v) == std::end(kSlaveBauds))
      return "baud is one of the channel's rates 300, 600, 1200, 2400, 4800, 9600, 19200 or 38400 (AG-UM008C p. 3-49), "
             "not '" + value + "'";
    options.baud = *v;
    return {};
  }
  const auto map = parse_map(value);
  if (!map) return "map takes four data files C,D,I,H (e.g. map=B3,B3,N7,N7), not '" + value + "'";
  options.map = *map;
  return {};
}

std::string check_map(const Map& map, const pccc::Target& target) {
  const std::pair<const char*, int> spaces[] = {{"coil", map.coils},
                                                 {"contact", map.contacts},
                                                 {"input register", map.input_registers},
                                                 {"holding register", map.holding_registers}};
  for (const auto& [name, file] : spaces) {
    const auto info = target.file(file);
    if (file < 3 || file > 255 || !info || (info->type != FileType::Bit && info->type != FileType::Integer))
      return std::string("the Modbus ") + name + " file must be a B or N file numbered 3-255 in the program (" +
             "1763-RM001C p. 530), not file " + std::to_string(file);
  }
  return {};
}

CommParameters comm_parameters(const Map& map) {
  CommParameters p{};
  p[0] = static_cast<std::uint16_t>(map.coils);
  p[1] = static_cast<std::uint16_t>(map.contacts);
  p[2] = static_cast<std::uint16_t>(map.input_registers);
  p[3] = static_cast<std::uint16_t>(map.holding_registers);
  return p;
}

void SlaveCounters::count_request(std::uint8_t fc) {
  static_assert(std::size(kSlaveFunctions) == std::size(SlaveCounters{}.function));
  ++to_slave;
  if (const int i = slave_function_index(fc); i >= 0) ++function[i];
}

void SlaveCounters::write(CommParameters& p) const {
  for (std::size_t i = 0; i < std::size(function); ++i) p[17 + i] = function[i];
  p[27] = responded;
  p[28] = to_slave;
  p[29] = seen;
  p[30] = link_errors;
}

CommParameters comm_parameters(const Map& map, int address, const SlaveCounters& counters) {
  CommParameters p = comm_parameters(map);
  p[6] = static_cast<std::uint16_t>(address);
  counters.write(p);
  return p;
}

std::vector<std::uint8_t> handle_pdu(std::span<const std::uint8_t> pdu, const Map& map, pccc::Target& target,
                                     std::string* refusal, const CommParameters* comm) {
  if (pdu.empty()) return {};
  const std::uint8_t fc = pdu[0];
  Reply reply(fc);
  const auto refuse = [&](std::uint8_t code, const std::string& why) {
    if (refusal) *refusal = "function " + std::to_string(fc) + ": " + why;
    return reply.exception(code);
  };
  // Every function below has a 2-byte address and a 2-byte quantity or value first.
  if (slave_function_index(fc) < 0) return refuse(kIllegalFunction, "function code not supported");
  if (fc == kDiagnostics) {
    if (pdu.size() < 3 || be16(pdu, 1) != 0) return refuse(kIllegalFunction, "only diagnostics subfunction 0 (echo)");
    auto& out = reply.bytes();
    out.insert(out.end(), pdu.begin() + 1, pdu.end());
    return reply.finish();
  }
  if (pdu.size() < 5) return refuse(kIllegalDataValue, "request shorter than its address and quantity");
  const std::uint32_t address = be16(pdu, 1);
  const std::uint32_t quantity = be16(pdu, 3);

  switch (fc) {
    case kReadCoils:
    case kReadDiscreteInputs: {
      if (pdu.size() != 5 || quantity < 1 || quantity > 2000) return refuse(kIllegalDataValue, "quantity outside 1-2000");
      const auto r = resolve(target, fc == kReadCoils ? map.coils : map.contacts, kCoilSpace, address, quantity, true);
      if (!r.place) return refuse(r.exception, r.why);
      return read_bits(reply, target, *r.place, quantity);
    }
    case kReadHoldingRegisters:
    case kReadInputRegisters: {
      if (pdu.size() != 5 || quantity < 1 || quantity > 125) return refuse(kIllegalDataValue, "quantity outside 1-125");
      if (fc == kReadInputRegisters && address >= kCommParameterBase && address < kCommParameterBase + kCommParameterCount) {
        if (address + quantity > kCommParameterBase + kCommParameterCount)
          return refuse(kIllegalDataAddress, "the communication parameters end at 30532");
        const CommParameters values = comm ? *comm : comm_parameters(map);
        auto& out = reply.bytes();
        out.push_back(static_cast<std::uint8_t>(quantity * 2));
        for (std::uint32_t i = 0; i < quantity; ++i) put16(out, values[address - kCommParameterBase + i]);
        return reply.finish();
      }
      const auto r = resolve_registers(target, fc == kReadHoldingRegisters ? map.holding_registers : map.input_registers,
                                       address, quantity);
      if (!r.place) return refuse(r.exception, r.why);
      std::vector<std::uint16_t> words(quantity);
      target.read(r.place->file, r.place->first, words);
      auto& out = reply.bytes();
      out.push_back(static_cast<std::uint8_t>(quantity * 2));
      for (auto w : words) put16(out, w);
      return reply.finish();
    }
    case kWriteSingleCoil: {
      if (pdu.size() != 5 || (quantity != 0xFF00 && quantity != 0x0000))
        return refuse(kIllegalDataValue, "a coil is written FF00h (on) or 0000h (off)");
      const auto r = resolve(target, map.coils, kCoilSpace, address, 1, true);
      if (!r.place) return refuse(r.exception, r.why);
      if (auto why = write_bits(target, *r.place, 1, [&](std::uint32_t) { return quantity == 0xFF00; }); !why.empty())
        return refuse(kServerDeviceFailure, why);
      auto& out = reply.bytes();
      out.insert(out.end(), pdu.begin() + 1, pdu.end());
      return reply.finish();
    }
    case kWriteSingleRegister: {
      if (pdu.size() != 5) return refuse(kIllegalDataValue, "request length");
      const auto r = resolve_registers(target, map.holding_registers, address, 1);
      if (!r.place) return refuse(r.exception, r.why);
      const std::uint16_t value = static_cast<std::uint16_t>(quantity);
      const std::uint16_t mask = 0xFFFF;
      if (auto why = target.write(r.place->file, r.place->first, {&value, 1}, {&mask, 1}); !why.empty())
        return refuse(kServerDeviceFailure, why);
      auto& out = reply.bytes();
      out.insert(out.end(), pdu.begin() + 1, pdu.end());
      return reply.finish();
    }
    case kWriteMultipleCoils:
    case kWriteMultipleRegisters: {
      const bool coils = fc == kWriteMultipleCoils;
      const std::uint32_t limit = coils ? 1968 : 123;
      if (quantity < 1 || quantity > limit) return refuse(kIllegalDataValue, "quantity outside 1-" + std::to_string(limit));
      const std::uint32_t bytes = coils ? (quantity + 7) / 8 : quantity * 2;
      if (pdu.size() < 6 || pdu[5] != bytes || pdu.size() != 6 + bytes)
        return refuse(kIllegalDataValue, "byte count disagrees with the quantity");
      const auto data = pdu.subspan(6);
      const auto r = coils ? resolve(target, map.coils, kCoilSpace, address, quantity, true)
                           : resolve_registers(target, map.holding_registers, address, quantity);
      if (!r.place) return refuse(r.exception, r.why);
      std::string why;
      if (coils) {
        why = write_bits(target, *r.place, quantity, [&](std::uint32_t i) { return (data[i / 8] >> (i % 8)) & 1u; });
      } else {
        std::vector<std::uint16_t> values(quantity), masks(quantity, 0xFFFF);
        for (std::uint32_t i = 0; i < quantity; ++i) values[i] = be16(data, static_cast<std::size_t>(i) * 2);
        why = target.write(r.place->file, r.place->first, values, masks);
      }
      if (!why.empty()) return refuse(kServerDeviceFailure, why);
      put16(reply.bytes(), static_cast<std::uint16_t>(address));
      put16(reply.bytes(), static_cast<std::uint16_t>(quantity));
      return reply.finish();
    }
    default: break;
  }
  return refuse(kIllegalFunction, "function code not supported");
}

}  // namespace softslc::modbus
