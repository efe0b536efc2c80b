#include "modules/scanport/messages.h"

#include <algorithm>

namespace softslc::scanport {
namespace {

// Little-endian byte writer: the SCANport byte order inside M-file words.
class Bytes {
 public:
  explicit Bytes(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint64_t v) { out_.push_back(static_cast<std::uint8_t>(v)); }
  void u16(std::uint64_t v) { le(v, 2); }
  // Two's complement of v in `size` bytes, low byte first.
  void le(std::uint64_t v, int size) {
    for (int i = 0; i < size; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void text(std::string_view s, int width) {
    for (int i = 0; i < width; ++i)
      out_.push_back(static_cast<std::uint8_t>(i < static_cast<int>(s.size()) ? s[static_cast<std::size_t>(i)] : ' '));
  }
  // A counted string: the count byte (always the full width) then the space-padded text.
  void counted(std::string_view s, int width) {
    u8(static_cast<std::uint64_t>(width));
    text(s, width);
  }

 private:
  std::vector<std::uint8_t>& out_;
};

// `size` bytes from data at `at`, little-endian, sign-extended when `is_signed`.
std::int64_t read_le(const std::vector<std::uint8_t>& data, std::size_t at, int size, bool is_signed) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= std::uint64_t{data[at + static_cast<std::size_t>(i)]} << (8 * i);
  if (is_signed && size < 8 && (v >> (8 * size - 1)) & 1) v |= ~std::uint64_t{0} << (8 * size);
  return static_cast<std::int64_t>(v);
}

std::uint16_t word_at(const std::vector<std::uint8_t>& data, std::size_t at) {
  return static_cast<std::uint16_t>(data[at] | (data[at + 1] << 8));
}

ObjectKind kind_of(const Request& r) {
  switch (r.class_code) {
    case static_cast<std::uint16_t>(ObjectClass::kParameter):
      return r.instance == 0 ? ObjectKind::kParameterClass : ObjectKind::kParameter;
    case static_cast<std::uint16_t>(ObjectClass::kProduct): return ObjectKind::kProduct;
    case static_cast<std::uint16_t>(ObjectClass::kScattered): return ObjectKind::kScattered;
    case static_cast<std::uint16_t>(ObjectClass::kParameterLink): return ObjectKind::kParameterLink;
    default: return ObjectKind::kOther;
  }
}

// The outcome of one object handler: an error, or the data of the success response.
struct Reply {
  ErrorCode error = ErrorCode::kNone;
  std::vector<std::uint8_t> data;
};

Reply fail(ErrorCode e) { return Reply{e, {}}; }

const ParameterAttributeInfo* find_parameter_attribute(std::uint16_t id) {
  for (const auto& a : kParameterAttributes)
    if (a.id == id) return &a;
  return nullptr;
}

void append_attribute(Bytes& out, const Drive& d, int n, ParameterAttribute a) {
  const ParameterSpec& p = *d.parameter(n);
  const int size = p.size();
  const auto& sc = p.scaling;
  switch (a) {
    case ParameterAttribute::kValue: out.le(static_cast<std::uint64_t>(d.value(n)), size); break;
    case ParameterAttribute::kLinkPathSize: out.u8(0); break;
    case ParameterAttribute::kDescriptor: out.u16(p.descriptor); break;
    case ParameterAttribute::kDataType: out.u8(static_cast<std::uint8_t>(p.type)); break;
    case ParameterAttribute::kDataSize: out.u8(static_cast<std::uint64_t>(size)); break;
    case ParameterAttribute::kName: out.counted(p.name, kNameChars); break;
    case ParameterAttribute::kUnits: out.counted(p.units, kUnitsChars); break;
    case ParameterAttribute::kHelp: out.u8(0); break;
    case ParameterAttribute::kMinimum: out.le(static_cast<std::uint64_t>(p.minimum), size); break;
    case ParameterAttribute::kMaximum: out.le(static_cast<std::uint64_t>(p.maximum), size); break;
    case ParameterAttribute::kDefault: out.le(static_cast<std::uint64_t>(p.default_value), size); break;
    case ParameterAttribute::kScalingMultiplier: out.u16(sc.multiplier); break;
    case ParameterAttribute::kScalingDivisor: out.u16(sc.divisor); break;
    case ParameterAttribute::kScalingBase: out.u16(sc.base); break;
    case ParameterAttribute::kScalingOffset: out.u16(static_cast<std::uint16_t>(sc.offset)); break;
    case ParameterAttribute::kMultiplierLink: out.u16(sc.multiplier_link); break;
    case ParameterAttribute::kDivisorLink: out.u16(sc.divisor_link); break;
    case ParameterAttribute::kBaseLink: out.u16(sc.base_link); break;
    case ParameterAttribute::kOffsetLink: out.u16(sc.offset_link); break;
    case ParameterAttribute::kDecimalPrecision: out.u8(sc.precision); break;
  }
}

// Class 0x0F.
Reply parameter_object(Drive& d, const Request& r, Service s) {
  Reply rep;
  Bytes out(rep.data);
  if (r.instance == 0) {
    switch (s) {
      case Service::kGetAttributeSingle:
        if (r.attribute != kLastParameterNumberAttribute) return fail(ErrorCode::kAttributeNotSupported);
        out.u16(static_cast<std::uint64_t>(d.parameter_count()));
        return rep;
      case Service::kResetToDefaults:
      case Service::kRestoreFromStorage:
      case Service::kSaveToStorage:
        if (r.attribute != 0) return fail(ErrorCode::kAttributeNotSupported);
        return fail(s == Service::kResetToDefaults      ? d.reset_to_defaults()
                    : s == Service::kRestoreFromStorage ? d.restore()
                                                        : d.save());
      default: return fail(ErrorCode::kServiceNotSupported);
    }
  }
  const ParameterSpec* p = d.parameter(r.instance);
  if (!p) return fail(ErrorCode::kInstanceNotSupported);
  const int n = p->number;
  switch (s) {
    case Service::kGetAttributeAll:
      if (r.attribute != 0) return fail(ErrorCode::kAttributeNotSupported);
      for (const auto& a : kParameterAttributes) append_attribute(out, d, n, a.attribute);
      return rep;
    case Service::kGetAttributeSingle: {
      const auto* a = find_parameter_attribute(r.attribute);
      if (!a) return fail(ErrorCode::kAttributeNotSupported);
      append_attribute(out, d, n, a->attribute);
      return rep;
    }
    case Service::kSetAttributeSingle: {
      if (r.attribute != static_cast<std::uint16_t>(ParameterAttribute::kValue))
        return fail(ErrorCode::kAttributeNotSupported);
      if (static_cast<int>(r.data.size()) < p->size()) return fail(ErrorCode::kInvalidLength);
      return fail(d.write_value(n, read_le(r.data, 0, p->size(), info(p->type).is_signed)));
    }
    case Service::kReadEnumString: {
      // The attribute word carries the value (or bit number) whose text is asked for.
      auto text = d.enum_string(n, r.attribute);
      if (!text) return fail(ErrorCode::kAttributeNotSupported);
      out.text(*text, kEnumChars);
      return rep;
    }
    default: return fail(ErrorCode::kServiceNotSupported);
  }
}

// Class 0x92 (Get Attribute Single only; the class table filters the rest).
Reply product_object(const Drive& d, const Request& r) {
  Reply rep;
  Bytes out(rep.data);
  const auto& id = d.product();
  if (r.instance == 0) {
    switch (r.attribute) {
      case kProductNumberAttribute: out.u16(id.number); return rep;
      case kProductTextAttribute: out.text(id.text, kProductTextChars); return rep;
      case kProductSeriesAttribute: out.u16(id.series); return rep;
      default: return fail(ErrorCode::kAttributeNotSupported);
    }
  }
  if (r.instance > id.software_versions.size()) return fail(ErrorCode::kInstanceNotSupported);
  if (r.attribute != kSoftwareVersionAttribute) return fail(ErrorCode::kAttributeNotSupported);
  out.u16(id.software_versions[r.instance - 1u]);
  return rep;
}

// Class 0x93. Each entry succeeds or fails on its own; the message itself succeeds.
Reply scattered_object(Drive& d, const Request& r, Service s) {
  if (r.instance != 0) return fail(ErrorCode::kInstanceNotSupported);
  if (r.attribute != 0) return fail(ErrorCode::kAttributeNotSupported);
  Reply rep;
  Bytes out(rep.data);
  for (std::size_t at = 0; at + kScatteredEntryBytes <= r.data.size(); at += kScatteredEntryBytes) {
    const std::uint16_t number = word_at(r.data, at);
    const std::uint16_t word = word_at(r.data, at + 2);
    ErrorCode e = ErrorCode::kNone;
    std::uint16_t result = 0;
    if (!d.parameter(number)) {
      e = ErrorCode::kInstanceNotSupported;
    } else if (d.parameter(number)->size() > 2) {
      // An entry has one 16-bit value word.
      e = ErrorCode::kAttributeNotSupported;
    } else if (s == Service::kGetAttributeScattered) {
      result = static_cast<std::uint16_t>(d.value(number));
    } else {
      e = d.write_value(number, *d.value_from_word(number, word));
    }
    if (e != ErrorCode::kNone) {
      out.u16(number | kScatteredErrorFlag);
      out.u16(static_cast<std::uint16_t>(e));
    } else {
      out.u16(number);
      out.u16(result);
    }
  }
  return rep;
}

// Class 0x99.
Reply link_object(Drive& d, const Request& r, Service s) {
  if (!d.parameter(r.instance)) return fail(ErrorCode::kInstanceNotSupported);
  if (r.attribute != kLinkAttribute) return fail(ErrorCode::kAttributeNotSupported);
  if (s == Service::kGetAttributeSingle) {
    Reply rep;
    Bytes(rep.data).u16(d.link(r.instance));
    return rep;
  }
  if (r.data.size() < 2) return fail(ErrorCode::kInvalidLength);
  return fail(d.write_link(r.instance, word_at(r.data, 0)));
}

void pad(std::vector<std::uint8_t>& data, int granule) {
  while (granule > 1 && data.size() % static_cast<std::size_t>(granule) != 0) data.push_back(0);
}

Response echo(const Request& r) { return Response{r.service, r.class_code, r.instance, r.attribute, {}}; }

}  // namespace

// ---------------------------------------------------------------------------------------------

Request make_request(std::uint16_t service, std::uint16_t class_code, std::uint16_t instance, std::uint16_t attribute,
                     std::vector<std::uint8_t> data) {
  Request r{service, class_code, instance, attribute, static_cast<std::uint16_t>(data.size()), std::move(data)};
  return r;
}

std::vector<std::uint8_t> bytes_of(std::span<const std::uint16_t> words) {
  std::vector<std::uint8_t> out;
  for (std::uint16_t w : words) Bytes(out).u16(w);
  return out;
}

std::vector<std::uint8_t> bytes_of(std::initializer_list<std::uint16_t> words) {
  return bytes_of(std::span<const std::uint16_t>(words.begin(), words.size()));
}

Request decode_request(std::span<const std::uint16_t> buffer) {
  if (buffer.size() > static_cast<std::size_t>(kBufferWords)) buffer = buffer.first(kBufferWords);
  auto word = [&](std::size_t i) -> std::uint16_t { return i < buffer.size() ? buffer[i] : 0; };
  Request r{word(0), word(1), word(2), word(3), word(4), {}};
  const std::size_t available = buffer.size() > kHeaderWords ? (buffer.size() - kHeaderWords) * 2 : 0;
  const std::size_t take = std::min<std::size_t>(r.length, available);
  r.data.reserve(take);
  for (std::size_t i = 0; i < take; ++i) {
    const std::uint16_t w = buffer[kHeaderWords + i / 2];
    r.data.push_back(static_cast<std::uint8_t>(i % 2 == 0 ? w & 0xFF : w >> 8));
  }
  return r;
}

std::vector<std::uint16_t> encode_request(const Request& r) {
  std::vector<std::uint16_t> w{r.service, r.class_code, r.instance, r.attribute, r.length};
  for (std::size_t i = 0; i < r.data.size(); i += 2)
    w.push_back(static_cast<std::uint16_t>(r.data[i] | (i + 1 < r.data.size() ? r.data[i + 1] << 8 : 0)));
  return w;
}

ErrorCode Response::error() const {
  if (!is_error()) return ErrorCode::kNone;
  const std::uint16_t code = data.size() >= 2 ? word_at(data, 0) : 0;
  return static_cast<ErrorCode>(code);
}

Response error_response(const Request& r, ErrorCode code, int granule) {
  Response resp = echo(r);
  resp.service = kErrorService;
  Bytes(resp.data).u16(static_cast<std::uint16_t>(code));
  pad(resp.data, granule);
  return resp;
}

ErrorCode check_length(const Request& r) {
  if (r.truncated()) return ErrorCode::kInvalidLength;
  const ServiceInfo* s = find_service(r.service);
  if (r.length > (s ? s->max_request_bytes : kMaxRequestBytes)) return ErrorCode::kInvalidLength;
  if (s && (s->service == Service::kGetAttributeScattered || s->service == Service::kSetAttributeScattered) &&
      (r.length == 0 || r.length % kScatteredEntryBytes != 0))
    return ErrorCode::kInvalidLength;
  return ErrorCode::kNone;
}

Response serve(Drive& d, const Request& r) {
  if (ErrorCode e = check_length(r); e != ErrorCode::kNone) return error_response(r, e);
  const ClassInfo* c = find_class(r.class_code);
  if (!c || !d.supports(c->object_class))
    return error_response(r, ErrorCode::kClassNotSupported, d.padding(ObjectKind::kOther));
  const ObjectKind kind = kind_of(r);
  const ServiceInfo* s = find_service(r.service);
  if (!s || !d.supports(s->service) || !c->answers(s->service))
    return error_response(r, ErrorCode::kServiceNotSupported, d.padding(kind));

  Reply rep;
  switch (c->object_class) {
    case ObjectClass::kParameter: rep = parameter_object(d, r, s->service); break;
    case ObjectClass::kProduct: rep = product_object(d, r); break;
    case ObjectClass::kScattered: rep = scattered_object(d, r, s->service); break;
    case ObjectClass::kParameterLink: rep = link_object(d, r, s->service); break;
  }
  if (rep.error != ErrorCode::kNone) return error_response(r, rep.error, d.padding(kind));
  Response resp = echo(r);
  resp.data = std::move(rep.data);
  pad(resp.data, d.padding(kind));
  return resp;
}

Response transact(Drive* drive, const Request& r) {
  if (ErrorCode e = check_length(r); e != ErrorCode::kNone) return error_response(r, e);
  if (!drive) return error_response(r, ErrorCode::kTimeout);
  return serve(*drive, r);
}

std::vector<std::uint16_t> encode_response(const Response& r) {
  const auto length = static_cast<std::uint16_t>(std::min<std::size_t>(r.data.size(), 0xFFFF));
  std::vector<std::uint16_t> w{r.service, r.class_code, r.instance, r.attribute, length};
  // Padding beyond the buffer (only a padded 47-entry scattered reply is that long) is dropped;
  // the length word still reports what the device sent.
  for (std::size_t i = 0; i < r.data.size() && w.size() < static_cast<std::size_t>(kBufferWords); i += 2)
    w.push_back(static_cast<std::uint16_t>(r.data[i] | (i + 1 < r.data.size() ? r.data[i + 1] << 8 : 0)));
  return w;
}

void write_response(const Response& r, std::span<std::uint16_t> buffer) {
  const auto words = encode_response(r);
  for (std::size_t i = 0; i < buffer.size(); ++i) buffer[i] = i < words.size() ? words[i] : 0;
}

// ---------------------------------------------------------------------------------------------

LinkTiming link_timing(const Drive* drive) {
  LinkTiming t;
  if (drive) t.device_processing = drive->message_processing_time();
  return t;
}

int frames_for(int data_bytes, const LinkTiming& t) {
  return t.header_frames + (data_bytes + t.data_bytes_per_frame - 1) / t.data_bytes_per_frame;
}

Nanoseconds frame_time(const LinkTiming& t) { return t.frame_bits * kNsPerS / t.bit_rate; }

Nanoseconds transaction_time(const Request& request, const Response& response, const LinkTiming& t) {
  const ErrorCode e = response.error();
  if (e == ErrorCode::kInvalidLength && response.is_error() && check_length(request) != ErrorCode::kNone) return 0;
  const Nanoseconds out = frames_for(request.length, t) * frame_time(t);
  if (e == ErrorCode::kTimeout) return out + t.response_timeout;
  return out + t.device_processing + frames_for(static_cast<int>(response.data.size()), t) * frame_time(t);
}

Transaction execute_message(Drive* drive, std::span<const std::uint16_t> m0_buffer) {
  Transaction t;
  t.request = decode_request(m0_buffer);
  t.response = transact(drive, t.request);
  t.duration = transaction_time(t.request, t.response, link_timing(drive));
  return t;
}

}  // namespace softslc::scanport
