// Message layer: every error path of page B-29, the order the checks run in, the padding
// quirk of Figure B.2's footnote, buffer edges, link timing, and a fuzz-style totality check.
#include <random>

#include "tests/scanport/scanport_test_util.h"

namespace softslc::scanport::test {
namespace {

// The reply's header and data words (at most `n` words).
Words reply(Drive* d, const Request& r, std::size_t n = kBufferWords) {
  return first(encode_response(transact(d, r)), n);
}

// The error response words for `r` with `code` and data length `length`.
Words error_words(const Request& r, std::uint16_t code, std::uint16_t length = 2) {
  Words w{0x0014, r.class_code, r.instance, r.attribute, length, code};
  while (w.size() < 5u + (length + 1u) / 2u) w.push_back(0);
  return w;
}

void expect_error(Drive* d, const Request& r, std::uint16_t code, std::uint16_t length = 2) {
  EXPECT_EQ(hex(reply(d, r)), hex(error_words(r, code, length)));
}

TEST(MessageErrors, CodesTableIsThePageB29Table) {
  const std::uint16_t codes[] = {0, 1, 2, 3, 4, 5, 6, 7, 0xFD, 0xFE};
  ASSERT_EQ(std::size(kErrors), std::size(codes));
  for (std::size_t i = 0; i < std::size(codes); ++i) EXPECT_EQ(kErrors[i].code, codes[i]);
  EXPECT_EQ(find_error(8), nullptr);
  EXPECT_EQ(kErrorService, 0x0014);
}

TEST(MessageErrors, ServiceNotSupported2) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x02, 0x0F, 5, 1), 2);                    // no such service
  expect_error(&d, make_request(0x14, 0x0F, 5, 1), 2);                    // the error service itself
  expect_error(&d, make_request(0x32, 0x0F, 5, 0, bytes_of({1, 0})), 2);  // scattered on the parameter class
  expect_error(&d, make_request(0x10, 0x92, 0, 0, bytes_of({1})), 2, 6);  // product is read-only (pads to 6)
  expect_error(&d, make_request(0x01, 0x0F, 0, 0), 2, 6);                 // read full of the class itself
  expect_error(&d, make_request(0x05, 0x0F, 5, 0), 2);                    // reset is class-level only
  expect_error(&d, make_request(0x16, 0x0F, 5, 0), 2);
}

TEST(MessageErrors, OptionalServicesAbsentGiveServiceNotSupported) {
  DriveDescription desc = builtin_drive("1305");
  desc.optional_features = {};
  Drive d(desc);
  for (std::uint16_t s : {0x05, 0x15, 0x16}) expect_error(&d, make_request(s, 0x0F, 0, 0), 2, 6);
  expect_error(&d, make_request(0x4B, 0x0F, 5, 1), 2);
  // Links are a class ("Not all SCANport devices support these messages"): class not supported.
  expect_error(&d, make_request(0x0E, 0x99, 5, 0), 3);
  // Mandatory services still work.
  EXPECT_EQ(transact(&d, make_request(0x0E, 0x0F, 5, 1)).error(), ErrorCode::kNone);
}

TEST(MessageErrors, ClassNotSupported3) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x0E, 0x01, 0, 1), 3);
  expect_error(&d, make_request(0x0E, 0xFFFF, 0xFFFF, 0xFFFF), 3);
  // Class is checked before service: both unknown gives 3.
  expect_error(&d, make_request(0x77, 0x77, 0, 0), 3);
}

TEST(MessageErrors, InstanceNotSupported4) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x0E, 0x0F, 217, 1), 4);
  expect_error(&d, make_request(0x0E, 0x0F, 0xFFFF, 1), 4);
  expect_error(&d, make_request(0x0E, 0x92, 2, 1), 4, 6);  // one microprocessor; product replies pad to 6
  expect_error(&d, make_request(0x32, 0x93, 1, 0, bytes_of({1, 0})), 4);
  expect_error(&d, make_request(0x0E, 0x99, 0, 0), 4, 6);
  expect_error(&d, make_request(0x0E, 0x99, 217, 0), 4, 6);
}

TEST(MessageErrors, AttributeNotSupported5) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x0E, 0x0F, 5, 0), 5);
  expect_error(&d, make_request(0x0E, 0x0F, 5, 3), 5);  // link path: size always 0, not in the table
  expect_error(&d, make_request(0x0E, 0x0F, 5, 22), 5);
  expect_error(&d, make_request(0x0E, 0x0F, 5, 0x0101), 5);  // "Values are always less than 256"
  expect_error(&d, make_request(0x0E, 0x0F, 0, 1), 5, 6);
  expect_error(&d, make_request(0x10, 0x0F, 5, 7, bytes_of({0x4141})), 5);  // only the value is settable
  expect_error(&d, make_request(0x01, 0x0F, 7, 1), 5);
  expect_error(&d, make_request(0x05, 0x0F, 0, 1), 5, 6);
  expect_error(&d, make_request(0x0E, 0x92, 0, 2), 5, 6);
  expect_error(&d, make_request(0x0E, 0x92, 1, 0), 5, 6);
  expect_error(&d, make_request(0x0E, 0x99, 5, 1), 5, 6);
  expect_error(&d, make_request(0x32, 0x93, 0, 1, bytes_of({1, 0})), 5);
  // Enum strings: a value without a string, and a parameter without any.
  expect_error(&d, make_request(0x4B, 0x0F, 5, 14), 5);
  expect_error(&d, make_request(0x4B, 0x0F, 7, 0), 5);
}

TEST(MessageErrors, ValueOutOfRange6) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x10, 0x0F, 7, 1, bytes_of({0xEA61})), 6);  // max 0xEA60
  expect_error(&d, make_request(0x10, 0x0F, 5, 1, bytes_of({14})), 6);      // max 13
  EXPECT_EQ(d.value(7), 0x64);
  EXPECT_EQ(d.value(5), 7);
  // Signed parameters take the two's complement of the data: User Data 1 (data type 3) -1 is
  // in range, Anlg Out Offset (-100..100) -101 is not.
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 151, 1, bytes_of({0xFFFF}))).error(), ErrorCode::kNone);
  EXPECT_EQ(d.value(151), -1);
  expect_error(&d, make_request(0x10, 0x0F, 61, 1, bytes_of({static_cast<std::uint16_t>(-101)})), 6);
  // Links: a parameter that does not exist, or the parameter itself.
  expect_error(&d, make_request(0x10, 0x99, 5, 0, bytes_of({217})), 6, 6);  // link replies pad to 6
  expect_error(&d, make_request(0x10, 0x99, 5, 0, bytes_of({5})), 6, 6);
  EXPECT_EQ(d.link(5), 6);
}

TEST(MessageErrors, ReadOnlyParameterGivesServiceFailed1) {
  Drive d = drive_1305();
  expect_error(&d, make_request(0x10, 0x0F, 2, 1, bytes_of({100})), 1);
  expect_error(&d, make_request(0x10, 0x0F, 4, 1, bytes_of({0})), 1);
  // Read-only is checked before range: an out-of-range value still reports 1.
  expect_error(&d, make_request(0x10, 0x0F, 2, 1, bytes_of({0xFFFF})), 1);
}

TEST(MessageErrors, RunningConflict7) {
  Drive d = drive_1305();
  d.set_reference(16384);
  d.set_logic_command(0x0002);  // start
  d.advance_to(milliseconds(100));
  ASSERT_TRUE(d.running());
  expect_error(&d, make_request(0x10, 0x0F, 1, 1, bytes_of({100})), 7);  // Maximum Freq: stopped only
  expect_error(&d, make_request(0x10, 0x0F, 1, 1, bytes_of({0})), 7);    // state before range
  expect_error(&d, make_request(0x05, 0x0F, 0, 0), 7, 6);
  expect_error(&d, make_request(0x15, 0x0F, 0, 0), 7, 6);
  // Parameters not marked stopped-only and Save stay allowed while running.
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 7, 1, bytes_of({200}))).error(), ErrorCode::kNone);
  EXPECT_EQ(transact(&d, make_request(0x16, 0x0F, 0, 0)).error(), ErrorCode::kNone);
  // A scattered write reports 7 in the entry, and the other entries still happen.
  EXPECT_EQ(hex(reply(&d, make_request(0x34, 0x93, 0, 0, bytes_of({1, 100, 8, 300})))),
            hex({0x0034, 0x0093, 0, 0, 8, 0x8001, 7, 8, 0}));
  EXPECT_EQ(d.value(8), 300);
  // Still "running" while the motor coasts down after a stop.
  d.set_logic_command(0x0001);
  d.advance_to(milliseconds(110));
  ASSERT_TRUE(d.running());
  expect_error(&d, make_request(0x05, 0x0F, 0, 0), 7, 6);
  d.advance_to(seconds(30));
  ASSERT_FALSE(d.running());
  EXPECT_EQ(transact(&d, make_request(0x05, 0x0F, 0, 0)).error(), ErrorCode::kNone);
}

TEST(MessageErrors, InvalidLengthFD) {
  Drive d = drive_1305();
  // Longer than the 96 bytes a non-scattered message may carry.
  Request r = make_request(0x10, 0x0F, 7, 1, std::vector<std::uint8_t>(97, 0));
  expect_error(&d, r, 0xFD);
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 7, 1, std::vector<std::uint8_t>(96, 0))).error(), ErrorCode::kNone);
  // A length word running off the 100-word buffer (190 data bytes).
  std::array<std::uint16_t, kBufferWords> m0{0x0032, 0x0093, 0, 0, 192};
  expect_error(&d, decode_request(m0), 0xFD);
  // A buffer span shorter than the length says.
  const Words shortbuf = {0x0010, 0x000f, 0x0005, 0x0001, 0x0002};
  expect_error(&d, decode_request(shortbuf), 0xFD);
  // Scattered lists: empty, not whole entries, more than 47 entries.
  expect_error(&d, make_request(0x32, 0x93, 0, 0), 0xFD);
  expect_error(&d, make_request(0x32, 0x93, 0, 0, bytes_of({1, 0, 2})), 0xFD);
  expect_error(&d, make_request(0x34, 0x93, 0, 0, std::vector<std::uint8_t>(std::size_t{48} * 4, 0)), 0xFD);
  // Set Attribute Single with less data than the value needs.
  expect_error(&d, make_request(0x10, 0x0F, 7, 1, {0x05}), 0xFD);
  expect_error(&d, make_request(0x10, 0x0F, 7, 1), 0xFD);
  expect_error(&d, make_request(0x10, 0x99, 5, 0, {0x07}), 0xFD, 6);  // the drive's reply: link replies pad to 6
  // The length check comes first, even with nothing connected.
  expect_error(nullptr, make_request(0x32, 0x93, 0, 0), 0xFD);
}

TEST(MessageErrors, TimeoutFEWhenNoDrive) {
  // "The message timed out before the response was given. Check the SCANport connection."
  const Words n10 = {0x000e, 0x000f, 0x0000, 0x0002, 0x0000};
  EXPECT_EQ(hex(first(run_figure_b3(nullptr, n10), 8)), hex({0x0014, 0x000f, 0x0000, 0x0002, 0x0002, 0x00fe, 0, 0}));
  EXPECT_EQ(transact(nullptr, make_request(0x10, 0x0F, 5, 1, bytes_of({6}))).error(), ErrorCode::kTimeout);
}

TEST(MessageErrors, ExtraRequestDataIsIgnored) {
  Drive d = drive_1305();
  // A ladder program that leaves a length in N10:4 for a read still gets the read.
  EXPECT_EQ(hex(reply(&d, make_request(0x0E, 0x0F, 5, 1, bytes_of({1, 2, 3})))), hex({0x000e, 0x000f, 5, 1, 2, 7}));
  // A write uses the value's size and ignores the rest.
  EXPECT_EQ(transact(&d, make_request(0x10, 0x0F, 5, 1, bytes_of({3, 0xFFFF}))).error(), ErrorCode::kNone);
  EXPECT_EQ(d.value(5), 3);
}

TEST(MessageScattered, EntryErrorsSetTheHighBit) {
  Drive d = drive_1305();
  // Read: 0 and 217 do not exist (4); a request word with bit 15 set names no parameter either.
  EXPECT_EQ(hex(reply(&d, make_request(0x32, 0x93, 0, 0, bytes_of({0, 0, 217, 0, 0x8005, 0, 5, 0xABCD})))),
            hex({0x0032, 0x0093, 0, 0, 16, 0x8000, 4, 0x80d9, 4, 0x8005, 4, 5, 7}));
  // Write: out of range (6), read-only (1), fine.
  EXPECT_EQ(hex(reply(&d, make_request(0x34, 0x93, 0, 0, bytes_of({7, 0xFFFF, 2, 1, 8, 50})))),
            hex({0x0034, 0x0093, 0, 0, 12, 0x8007, 6, 0x8002, 1, 8, 0}));
  EXPECT_EQ(d.value(8), 50);
  EXPECT_EQ(d.value(7), 0x64);
}

TEST(MessageScattered, FortySevenEntriesFillTheBuffer) {
  Drive d = drive_1305();
  Words list;
  for (std::uint16_t p = 1; p <= kMaxScatteredEntries; ++p) {
    list.push_back(p);
    list.push_back(0);
  }
  const Request r = make_request(0x32, 0x93, 0, 0, bytes_of(list));
  EXPECT_EQ(r.length, 188);
  std::array<std::uint16_t, kBufferWords> m0{};
  const Words req = encode_request(r);
  ASSERT_EQ(req.size(), 99u);  // fits in one M0 buffer
  std::copy(req.begin(), req.end(), m0.begin());
  const Response resp = transact(&d, decode_request(m0));
  ASSERT_FALSE(resp.is_error());
  const Words w = encode_response(resp);
  ASSERT_EQ(w.size(), 99u);
  EXPECT_EQ(w[4], 188);
  EXPECT_EQ(w[5], 1);
  EXPECT_EQ(w[6], 120);
  EXPECT_EQ(w[5 + 2 * 46], 47);
}

TEST(MessagePadding, FigureB2QuirkPadsEveryReplyToSix) {
  // "These products always return a length which is a multiple of six" (Figure B.2 footnote,
  // the 1336 PLUS). With the quirk on every object, the replies that the 1305 sends unpadded
  // grow to the next multiple of six and the extra bytes are zero.
  DriveDescription desc = builtin_drive("1305");
  desc.response_padding.fill(6);
  Drive d(desc);
  EXPECT_EQ(hex(reply(&d, make_request(0x0E, 0x0F, 0, 2))), hex({0x000e, 0x000f, 0, 2, 6, 0x00d8, 0, 0}));
  EXPECT_EQ(hex(reply(&d, make_request(0x0E, 0x0F, 5, 1))), hex({0x000e, 0x000f, 5, 1, 6, 7, 0, 0}));
  EXPECT_EQ(reply(&d, make_request(0x0E, 0x0F, 5, 7))[4], 18);  // 17 -> 18
  EXPECT_EQ(reply(&d, make_request(0x01, 0x0F, 7, 0))[4], 54);  // 53 -> 54
  EXPECT_EQ(reply(&d, make_request(0x4B, 0x0F, 5, 1))[4], 12);  // already a multiple
  EXPECT_EQ(reply(&d, make_request(0x10, 0x0F, 5, 1, bytes_of({6})))[4], 0);
  EXPECT_EQ(hex(reply(&d, make_request(0x32, 0x93, 0, 0, bytes_of({1, 0})))),
            hex({0x0032, 0x0093, 0, 0, 6, 1, 120, 0}));
  expect_error(&d, make_request(0x0E, 0x0F, 5, 22), 5, 6);
  expect_error(&d, make_request(0x0E, 0x44, 0, 0), 3, 6);
  // The module's own errors are not the device's and stay unpadded.
  expect_error(&d, make_request(0x32, 0x93, 0, 0), 0xFD, 2);
  // A padded 47-entry scattered reply (192 bytes) is longer than the buffer: the length word
  // says 192 and the words that do not fit are dropped.
  Words list;
  for (std::uint16_t p = 1; p <= kMaxScatteredEntries; ++p) list.insert(list.end(), {p, 0});
  const Words w = encode_response(transact(&d, make_request(0x32, 0x93, 0, 0, bytes_of(list))));
  EXPECT_EQ(w.size(), static_cast<std::size_t>(kBufferWords));
  EXPECT_EQ(w[4], 192);
}

TEST(MessagePadding, NoPaddingDevice) {
  DriveDescription desc = builtin_drive("1305");
  desc.response_padding.fill(1);
  Drive d(desc);
  EXPECT_EQ(hex(reply(&d, make_request(0x0E, 0x0F, 0, 2))), hex({0x000e, 0x000f, 0, 2, 2, 0x00d8}));
  EXPECT_EQ(hex(reply(&d, make_request(0x0E, 0x92, 0, 1), 6)), hex({0x000e, 0x0092, 0, 1, 16, 0x7542}));
}

TEST(MessageBuffers, LayoutConstants) {
  EXPECT_EQ(request_buffer_word(0), 0);
  EXPECT_EQ(request_buffer_word(7), 700);  // eight buffers in the 800-word M0 file
  EXPECT_EQ(response_buffer_word(1), 100);
  EXPECT_EQ(response_buffer_word(3), 300);  // channel 3 ends at M1:e.399, the 400-word M1 file
  EXPECT_EQ(kBufferDataBytes, 190);
}

TEST(MessageBuffers, DecodeLooksAtOneBufferOnly) {
  // A span covering the whole M0 file: the request in buffer 0 must not read buffer 1.
  std::vector<std::uint16_t> m0(800, 0x4141);
  m0[0] = 0x0010;
  m0[1] = 0x000f;
  m0[2] = 7;
  m0[3] = 1;
  m0[4] = 200;  // runs past word 99
  const Request r = decode_request(m0);
  EXPECT_EQ(r.data.size(), 190u);
  EXPECT_TRUE(r.truncated());
  // Missing header words read as 0.
  const Request empty = decode_request(std::span<const std::uint16_t>());
  EXPECT_EQ(encode_request(empty), Words({0, 0, 0, 0, 0}));
}

TEST(MessageBuffers, WriteResponseClearsTheRestAndFitsShortBuffers) {
  Drive d = drive_1305();
  std::array<std::uint16_t, 6> small{};
  small.fill(0xFFFF);
  write_response(transact(&d, make_request(0x0E, 0x0F, 5, 7)), small);
  EXPECT_EQ(hex(Words(small.begin(), small.end())), hex({0x000e, 0x000f, 5, 7, 0x0011, 0x4610}));
}

TEST(MessageTiming, FramesAndTransactionTime) {
  const LinkTiming t;
  EXPECT_EQ(frame_time(t), 888'000);  // 111 bits at 125 kbit/s
  EXPECT_EQ(frames_for(0, t), 1);
  EXPECT_EQ(frames_for(6, t), 2);
  EXPECT_EQ(frames_for(7, t), 3);
  EXPECT_EQ(frames_for(188, t), 33);

  Drive d = drive_1305();
  const LinkTiming lt = link_timing(&d);
  EXPECT_EQ(lt.device_processing, milliseconds(2));
  // Figure B.4: request 0 bytes (1 frame), reply 6 bytes (2 frames).
  const Request r = make_request(0x0E, 0x0F, 0, 2);
  EXPECT_EQ(transaction_time(r, transact(&d, r), lt), std::int64_t{3} * 888'000 + milliseconds(2));
  // Figure B.8: reply 53 bytes (1 + 9 frames).
  const Request full = make_request(0x01, 0x0F, 7, 0);
  EXPECT_EQ(transaction_time(full, transact(&d, full), lt), std::int64_t{11} * 888'000 + milliseconds(2));
  // A timeout: the request goes out, then the module waits.
  EXPECT_EQ(transaction_time(r, transact(nullptr, r), lt), 888'000 + seconds(1));
  // Refused by the module: never on the link.
  const Request bad = make_request(0x32, 0x93, 0, 0);
  EXPECT_EQ(transaction_time(bad, transact(&d, bad), lt), 0);
  // A 0xFD from the drive itself (set with too little data) did use the link.
  const Request shortset = make_request(0x10, 0x0F, 7, 1, {1});
  EXPECT_EQ(transaction_time(shortset, transact(&d, shortset), lt), std::int64_t{4} * 888'000 + milliseconds(2));
}

TEST(MessageTiming, ExecuteMessageIsTheWrappersSeam) {
  Drive d = drive_1305();
  std::vector<std::uint16_t> m0(800, 0);
  const Words n10 = {0x0010, 0x000f, 0x0005, 0x0001, 0x0002, 0x0006};  // Figure B.7, in buffer 3
  std::copy(n10.begin(), n10.end(), m0.begin() + request_buffer_word(3));
  const Transaction t =
      execute_message(&d, std::span<const std::uint16_t>(m0).subspan(request_buffer_word(3), kBufferWords));
  EXPECT_EQ(hex(encode_response(t.response)), hex({0x0010, 0x000f, 0x0005, 0x0001, 0x0000}));
  EXPECT_EQ(t.duration, std::int64_t{2} * 888'000 + milliseconds(2) + 888'000);
  EXPECT_EQ(d.value(5), 6);
  const Transaction none = execute_message(nullptr, n10);
  EXPECT_EQ(none.response.error(), ErrorCode::kTimeout);
  EXPECT_EQ(none.duration, std::int64_t{2} * 888'000 + seconds(1));
}

// Any 16-bit words in a request buffer (the ladder controls them) give a defined reply: the
// echo or 0x0014 with a documented code, never more than the buffer, and the drive's values stay
// within their limits. The generator favours the codes the module knows so that deep paths are
// reached; std::mt19937's sequence is fixed by the standard, so the run is reproducible.
TEST(MessageTotality, RandomBuffersAlwaysGiveDefinedReplies) {
  Drive d = drive_1305();
  std::mt19937 rng(20240531);
  const std::uint16_t services[] = {0x01, 0x05, 0x0E, 0x10, 0x15, 0x16, 0x32, 0x34, 0x4B, 0x00, 0x14, 0xFFFF};
  const std::uint16_t classes[] = {0x0F, 0x92, 0x93, 0x99, 0x00, 0xFFFF};
  auto pick = [&](const auto& arr) { return arr[rng() % std::size(arr)]; };
  auto small = [&](std::uint32_t n) { return static_cast<std::uint16_t>(rng() % n); };
  std::uint64_t digest = 1469598103934665603ull;
  for (int iteration = 0; iteration < 200'000; ++iteration) {
    std::array<std::uint16_t, kBufferWords> m0{};
    for (auto& w : m0) w = static_cast<std::uint16_t>(rng());
    const bool structured = rng() % 8 != 0;
    if (structured) {
      m0[0] = pick(services);
      m0[1] = pick(classes);
      m0[2] = rng() % 4 ? small(230) : static_cast<std::uint16_t>(rng());
      m0[3] = rng() % 4 ? small(24) : static_cast<std::uint16_t>(rng());
      m0[4] = rng() % 4 ? static_cast<std::uint16_t>(small(50) * 2) : static_cast<std::uint16_t>(rng());
      if (m0[0] == 0x32 || m0[0] == 0x34) {
        for (int i = 5; i < kBufferWords; i += 2) m0[i] = rng() % 4 ? small(230) : static_cast<std::uint16_t>(rng());
        m0[4] = static_cast<std::uint16_t>(4 * (1 + small(48)));
      }
    }
    const std::size_t span = rng() % 16 == 0 ? rng() % kBufferWords : kBufferWords;
    const Request r = decode_request(std::span<const std::uint16_t>(m0.data(), span));
    const Response resp = transact(&d, r);
    const Words w = encode_response(resp);
    ASSERT_LE(w.size(), static_cast<std::size_t>(kBufferWords));
    ASSERT_TRUE(resp.service == r.service || resp.service == kErrorService);
    ASSERT_EQ(resp.class_code, r.class_code);
    ASSERT_EQ(resp.instance, r.instance);
    ASSERT_EQ(resp.attribute, r.attribute);
    if (resp.is_error()) {
      ASSERT_NE(find_error(static_cast<std::uint16_t>(resp.error())), nullptr);
    }
    for (std::uint16_t x : w) digest = (digest ^ x) * 1099511628211ull;
    // Now and then the drive runs, so the running-conflict paths are reached too.
    if (iteration % 5000 == 0) d.set_logic_command(iteration % 10000 == 0 ? 0x0002 : 0x0001);
    if (iteration % 1000 == 0) d.advance_to(d.now() + milliseconds(50));
  }
  for (int n = 1; n <= d.parameter_count(); ++n) {
    ASSERT_GE(d.value(n), d.parameter(n)->minimum) << n;
    ASSERT_LE(d.value(n), d.parameter(n)->maximum) << n;
    ASSERT_GE(d.stored_value(n), d.parameter(n)->minimum) << n;
    ASSERT_LE(d.stored_value(n), d.parameter(n)->maximum) << n;
  }
  // Printed so a change in behaviour shows up as a changed digest when investigating.
  RecordProperty("digest", std::to_string(digest));
}

// Two drives fed the same messages and time give byte-identical replies.
TEST(MessageTotality, Deterministic) {
  auto run = [] {
    Drive d = drive_1305();
    std::mt19937 rng(7);
    Words all;
    for (int i = 0; i < 5000; ++i) {
      std::array<std::uint16_t, kBufferWords> m0{};
      m0[0] = std::array<std::uint16_t, 4>{0x0E, 0x10, 0x32, 0x34}[rng() % 4];
      m0[1] = std::array<std::uint16_t, 3>{0x0F, 0x93, 0x99}[rng() % 3];
      m0[2] = static_cast<std::uint16_t>(rng() % 220);
      m0[3] = static_cast<std::uint16_t>(rng() % 3);
      m0[4] = static_cast<std::uint16_t>(4 * (1 + rng() % 5));
      for (int k = 5; k < 25; ++k) m0[k] = static_cast<std::uint16_t>(rng() % 300);
      d.set_logic_command(static_cast<std::uint16_t>(rng() % 4));
      d.set_reference(static_cast<std::uint16_t>(rng()));
      d.advance_to(d.now() + static_cast<Nanoseconds>(rng() % 3'000'000));
      const Words w = encode_response(transact(&d, decode_request(m0)));
      all.insert(all.end(), w.begin(), w.end());
      all.push_back(d.feedback());
      all.push_back(d.logic_status());
    }
    return all;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace softslc::scanport::test
