// Golden tests: every example message of the 1203-SM1 manual's appendix B, word for word.
//
// Each test writes the request words (N10 of Figure B.3's program, which the program copies to
// M0 buffer 0) exactly as the figure shows them, checks that building the same request from
// its fields gives those words, runs it against the shipped 1305 drive, and compares the
// response buffer (M1:e.100, copied to N11) with the figure, including the zero words the figure
// shows after the response. All values are hexadecimal, as in the figures. Where the manual
// contradicts itself the test says which source it follows (docs/1203-sm1.md, "Contradictions").
#include "tests/scanport/scanport_test_util.h"

namespace softslc::scanport::test {
namespace {

// Runs `n10` on a fresh 1305 and compares N11 with `n11` (the figure's N11 rows, in order).
void expect_exchange(Drive& d, const Words& n10, const Words& n11) {
  const Words got = run_figure_b3(&d, n10);
  EXPECT_EQ(hex(first(got, n11.size())), hex(n11));
  // Everything after the figure's words is 0 as well (the module clears the buffer).
  for (std::size_t i = n11.size(); i < got.size(); ++i) ASSERT_EQ(got[i], 0u) << "N11:" << i;
}

// The request built from its fields must give the figure's N10 words.
void expect_request_words(const Request& r, const Words& n10) {
  EXPECT_EQ(hex(encode_request(r)), hex(n10));
  const Request back = decode_request(n10);
  EXPECT_EQ(back.service, r.service);
  EXPECT_EQ(back.class_code, r.class_code);
  EXPECT_EQ(back.instance, r.instance);
  EXPECT_EQ(back.attribute, r.attribute);
  EXPECT_EQ(back.length, r.length);
  EXPECT_EQ(back.data, r.data);
}

// Page B-7, "Read Number of Parameters", Figure B.4: 216 (0xD8) parameters, length 6 with two
// discard words.
TEST(AppendixB, ReadNumberOfParametersFigureB4) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x000f, 0x0000, 0x0002, 0x0000};
  expect_request_words(make_request(0x0E, 0x0F, 0, 2), n10);
  expect_exchange(d, n10, {0x000e, 0x000f, 0x0000, 0x0002, 0x0006, 0x00d8, 0x0000, 0x0000, 0x0000, 0x0000});
}

// Page B-8, "Read Parameter Value", Figure B.5: parameter 5 = 7.
TEST(AppendixB, ReadParameterValueFigureB5) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x000f, 0x0005, 0x0001, 0x0000};
  expect_request_words(make_request(0x0E, 0x0F, 5, 1), n10);
  expect_exchange(d, n10, {0x000e, 0x000f, 0x0005, 0x0001, 0x0002, 0x0007, 0x0000, 0x0000, 0x0000, 0x0000});
}

// Page B-9, "Read Parameter Name Text", Figure B.6: count 0x10 in the low byte of N11:5, then
// "Freq Select 1" padded to 16 characters; length 17.
TEST(AppendixB, ReadParameterNameTextFigureB6) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x000f, 0x0005, 0x0007, 0x0000};
  expect_request_words(make_request(0x0E, 0x0F, 5, 7), n10);
  expect_exchange(d, n10,
                  {0x000e, 0x000f, 0x0005, 0x0007, 0x0011, 0x4610, 0x6572, 0x2071, 0x6553, 0x656c,  // N11:0
                   0x7463, 0x3120, 0x2020, 0x0020, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});  // N11:10
}

// Page B-10, "Write Value to Parameter", Figure B.7: 6 into parameter 5; empty reply.
TEST(AppendixB, WriteValueToParameterFigureB7) {
  Drive d = drive_1305();
  const Words n10 = {0x0010, 0x000f, 0x0005, 0x0001, 0x0002, 0x0006};
  expect_request_words(make_request(0x10, 0x0F, 5, 1, bytes_of({0x0006})), n10);
  expect_exchange(d, n10, {0x0010, 0x000f, 0x0005, 0x0001, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});
  // "The drive accepted the message, and parameter number 5 now has a value of 6."
  EXPECT_EQ(d.value(5), 6);
}

// Pages B-11 to B-13, "Read Full Parameter", Figure B.8 and its attribute table: parameter 7
// "Accel Time 1", "Secs", 53 bytes, not word aligned.
TEST(AppendixB, ReadFullParameterFigureB8) {
  Drive d = drive_1305();
  const Words n10 = {0x0001, 0x000f, 0x0007, 0x0000, 0x0000};
  expect_request_words(make_request(0x01, 0x0F, 7, 0), n10);
  expect_exchange(d, n10,
                  {0x0001, 0x000f, 0x0007, 0x0000, 0x0035, 0x0064, 0x6400, 0x0200, 0x1002, 0x6341,    // N11:0
                   0x6563, 0x206c, 0x6954, 0x656d, 0x3120, 0x2020, 0x2020, 0x5304, 0x6365, 0x0073,    // N11:10
                   0x0000, 0xea60, 0x03e8, 0x0001, 0x000a, 0x0001, 0x0000, 0x0000, 0x0000, 0x0000,    // N11:20
                   0x0000, 0x0001, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});  // N11:30
}

// The attribute table of page B-12: each attribute read alone gives the bytes the table places
// at its starting address in Figure B.8.
TEST(AppendixB, ReadFullParameterAttributesMatchSingleReadsPageB12) {
  Drive d = drive_1305();
  const Response all = transact(&d, make_request(0x01, 0x0F, 7, 0));
  ASSERT_FALSE(all.is_error());
  std::size_t offset = 0;
  for (const auto& a : kParameterAttributes) {
    const Response one = transact(&d, make_request(0x0E, 0x0F, 7, a.id));
    ASSERT_FALSE(one.is_error()) << "attribute " << int(a.id);
    ASSERT_LE(offset + one.data.size(), all.data.size());
    EXPECT_EQ(std::vector<std::uint8_t>(all.data.begin() + static_cast<std::ptrdiff_t>(offset),
                                        all.data.begin() + static_cast<std::ptrdiff_t>(offset + one.data.size())),
              one.data)
        << "attribute " << int(a.id) << " (" << a.meaning << ")";
    offset += one.data.size();
  }
  EXPECT_EQ(offset, 53u);
  // Table spot checks: descriptor 0x0064 at N11:6 hi / N11:7 lo, data type 2 at N11:7 hi, size 2
  // at N11:8 lo, name count 16 at N11:8 hi, units count 4 at N11:17 lo, precision 1 at N11:31 lo.
  EXPECT_EQ(all.data[3] | all.data[4] << 8, 0x0064);
  EXPECT_EQ(all.data[5], 2);
  EXPECT_EQ(all.data[6], 2);
  EXPECT_EQ(all.data[7], 16);
  EXPECT_EQ(all.data[24], 4);
  EXPECT_EQ(all.data[52], 1);
}

// Page B-15, "Set Default Parameter Values", Figure B.9.
TEST(AppendixB, SetDefaultParameterValuesFigureB9) {
  Drive d = drive_1305();
  const Words n10 = {0x0005, 0x000f, 0x0000, 0x0000, 0x0000};
  expect_request_words(make_request(0x05, 0x0F, 0, 0), n10);
  expect_exchange(d, n10, {0x0005, 0x000f, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});
  // "set all parameter values in the SCANport device's EEPROM and RAM to the factory default
  // values": Accel Time 1 was 0x0064, its default is 0x03E8.
  EXPECT_EQ(d.value(7), 0x03E8);
  EXPECT_EQ(d.stored_value(7), 0x03E8);
}

// Page B-16, "Restore Parameter Values from Non-volatile Storage", Figure B.10.
TEST(AppendixB, RestoreFromNonVolatileStorageFigureB10) {
  Drive d = drive_1305();
  ASSERT_EQ(d.write_value(7, 600), ErrorCode::kNone);
  const Words n10 = {0x0015, 0x000f, 0x0000, 0x0000, 0x0000};
  expect_request_words(make_request(0x15, 0x0F, 0, 0), n10);
  expect_exchange(d, n10, {0x0015, 0x000f, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});
  EXPECT_EQ(d.value(7), 0x0064);  // back to what storage held
}

// Page B-17, "Save Parameter Values to Non-volatile Storage", Figure B.11.
TEST(AppendixB, SaveToNonVolatileStorageFigureB11) {
  Drive d = drive_1305();
  ASSERT_EQ(d.write_value(7, 600), ErrorCode::kNone);
  const Words n10 = {0x0016, 0x000f, 0x0000, 0x0000, 0x0000};
  expect_request_words(make_request(0x16, 0x0F, 0, 0), n10);
  expect_exchange(d, n10, {0x0016, 0x000f, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});
  EXPECT_EQ(d.stored_value(7), 600);
}

// Page B-18, "Read Enum String for Value in Parameter", Figure B.12: value 1 of parameter 5 is
// "Remote Pot", always 12 characters.
TEST(AppendixB, ReadEnumStringFigureB12) {
  Drive d = drive_1305();
  const Words n10 = {0x004b, 0x000f, 0x0005, 0x0001, 0x0000};
  expect_request_words(make_request(0x4B, 0x0F, 5, 1), n10);
  expect_exchange(d, n10,
                  {0x004b, 0x000f, 0x0005, 0x0001, 0x000c, 0x6552, 0x6f6d, 0x6574, 0x5020, 0x746f,    // N11:0
                   0x2020, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0000});  // N11:10
}

// Page B-19, "Read Product Number", Figure B.13: product number 3.
TEST(AppendixB, ReadProductNumberFigureB13) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x0092, 0x0000, 0x0000, 0x0000};
  expect_request_words(make_request(0x0E, 0x92, 0, 0), n10);
  expect_exchange(d, n10, {0x000e, 0x0092, 0x0000, 0x0000, 0x0006, 0x0003, 0x0000, 0x0000});
}

// Page B-20, "Read Product Text", Figure B.14: 16 characters ("Bul 1336 PLUS" padded) and one
// discard word, length 0x12.
TEST(AppendixB, ReadProductTextFigureB14) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x0092, 0x0000, 0x0001, 0x0000};
  expect_request_words(make_request(0x0E, 0x92, 0, 1), n10);
  expect_exchange(d, n10,
                  {0x000e, 0x0092, 0x0000, 0x0001, 0x0012, 0x7542, 0x206c, 0x3331, 0x3633, 0x5020,  // N11:0
                   0x554c, 0x2053, 0x2020, 0x0000});                                                // N11:10
}

// Page B-21, "Read Product Series Number", Figure B.15: series 1 = A.
TEST(AppendixB, ReadProductSeriesFigureB15) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x0092, 0x0000, 0x0003, 0x0000};
  expect_request_words(make_request(0x0E, 0x92, 0, 3), n10);
  expect_exchange(d, n10, {0x000e, 0x0092, 0x0000, 0x0003, 0x0006, 0x0001, 0x0000, 0x0000});
}

// Page B-22, "Read Product Software Version", Figure B.16: microprocessor 1 (instance 1) runs
// 0x00CA = FRN 2.02.
TEST(AppendixB, ReadProductSoftwareVersionFigureB16) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x0092, 0x0001, 0x0001, 0x0000};
  expect_request_words(make_request(0x0E, 0x92, 1, 1), n10);
  expect_exchange(d, n10, {0x000e, 0x0092, 0x0001, 0x0001, 0x0006, 0x00ca, 0x0000, 0x0000});
}

// Pages B-23 to B-25, "Scattered Read", Figure B.17: parameters 1-3 read 0x0078, 0, 0.
TEST(AppendixB, ScatteredReadFigureB17) {
  Drive d = drive_1305();
  const Words n10 = {0x0032, 0x0093, 0x0000, 0x0000, 0x000c, 0x0001, 0x0000, 0x0002, 0x0000, 0x0003,  // N10:0
                     0x0000};                                                                          // N10:10
  expect_request_words(make_request(0x32, 0x93, 0, 0, bytes_of({1, 0, 2, 0, 3, 0})), n10);
  expect_exchange(d, n10,
                  {0x0032, 0x0093, 0x0000, 0x0000, 0x000c, 0x0001, 0x0078, 0x0002, 0x0000, 0x0003,  // N11:0
                   0x0000});                                                                        // N11:10
}

// Pages B-25 to B-27, "Scattered Write". The table on page B-25 writes 1, 2 and 0x0258 to
// parameters 5, 6 and 7 and shows the reply (5, 0), (6, 0), (7, 0). Figure B.18 instead repeats
// Figure B.17's scattered-read words under service 0x0034; we follow the table
// (docs/1203-sm1.md, "Contradictions").
TEST(AppendixB, ScatteredWriteTablePageB25) {
  Drive d = drive_1305();
  const Words n10 = {0x0034, 0x0093, 0x0000, 0x0000, 0x000c, 0x0005, 0x0001, 0x0006, 0x0002, 0x0007,  // N10:0
                     0x0258};                                                                          // N10:10
  expect_request_words(make_request(0x34, 0x93, 0, 0, bytes_of({5, 1, 6, 2, 7, 0x0258})), n10);
  expect_exchange(d, n10,
                  {0x0034, 0x0093, 0x0000, 0x0000, 0x000c, 0x0005, 0x0000, 0x0006, 0x0000, 0x0007,  // N11:0
                   0x0000});                                                                        // N11:10
  EXPECT_EQ(d.value(5), 1);
  EXPECT_EQ(d.value(6), 2);
  EXPECT_EQ(d.value(7), 0x0258);
}

// Figure B.18 as printed: its N11 (0001 0078 0002 0000 0003 0000) cannot be a scattered-write
// reply, because page B-26 says an entry without the high bit "contains a zero" while 0x0078
// sits beside parameter 1 unflagged. Running its N10 words gives the reply the text defines:
// parameter 1 refuses 0 (below its minimum 30: error 6) and parameters 2 and 3 are read-only
// monitors (error 1), each flagged with bit 15.
TEST(AppendixB, ScatteredWriteFigureB18AsPrinted) {
  Drive d = drive_1305();
  const Words n10 = {0x0034, 0x0093, 0x0000, 0x0000, 0x000c, 0x0001, 0x0000, 0x0002, 0x0000, 0x0003,  // N10:0
                     0x0000};                                                                          // N10:10
  expect_exchange(d, n10,
                  {0x0034, 0x0093, 0x0000, 0x0000, 0x000c, 0x8001, 0x0006, 0x8002, 0x0001, 0x8003,  // N11:0
                   0x0001});                                                                        // N11:10
  EXPECT_EQ(d.value(1), 120);  // unchanged
}

// Page B-27, "Read Parameter Link from Parameter Number", Figure B.19: parameter 5 is linked to
// parameter 6; length 6 with two discard words.
TEST(AppendixB, ReadParameterLinkFigureB19) {
  Drive d = drive_1305();
  const Words n10 = {0x000e, 0x0099, 0x0005, 0x0000, 0x0000};
  expect_request_words(make_request(0x0E, 0x99, 5, 0), n10);
  expect_exchange(d, n10, {0x000e, 0x0099, 0x0005, 0x0000, 0x0006, 0x0006, 0x0000, 0x0000});
}

// Page B-28, "Write Parameter Link from Parameter Number". The table writes link 7 (M0:e.005 =
// 0007); Figure B.20 and its text write 6, the link parameter 5 already has. We follow the table
// and check that the figure's request gives the same reply.
TEST(AppendixB, WriteParameterLinkTablePageB28) {
  Drive d = drive_1305();
  const Words n10 = {0x0010, 0x0099, 0x0005, 0x0000, 0x0002, 0x0007};
  expect_request_words(make_request(0x10, 0x99, 5, 0, bytes_of({7})), n10);
  expect_exchange(d, n10, {0x0010, 0x0099, 0x0005, 0x0000, 0x0000});
  EXPECT_EQ(d.link(5), 7);
  // Reading it back the Figure B.19 way now gives 7.
  expect_exchange(d, {0x000e, 0x0099, 0x0005, 0x0000, 0x0000},
                  {0x000e, 0x0099, 0x0005, 0x0000, 0x0006, 0x0007, 0x0000, 0x0000});
}

TEST(AppendixB, WriteParameterLinkFigureB20AsPrinted) {
  Drive d = drive_1305();
  expect_exchange(d, {0x0010, 0x0099, 0x0005, 0x0000, 0x0002, 0x0006}, {0x0010, 0x0099, 0x0005, 0x0000, 0x0000});
  EXPECT_EQ(d.link(5), 6);
}

// The examples as one session on one drive. Every reply still matches its figure because the
// session reads before it writes: the writes (Figure B.7, the scattered write, the link write)
// and save/restore/defaults come after every read of what they change.
TEST(AppendixB, AllExamplesInOneSession) {
  Drive d = drive_1305();
  struct Step {
    Words n10, n11;
  };
  const Step steps[] = {
      {{0x000e, 0x000f, 0x0000, 0x0002, 0x0000}, {0x000e, 0x000f, 0x0000, 0x0002, 0x0006, 0x00d8, 0, 0}},
      {{0x000e, 0x000f, 0x0005, 0x0001, 0x0000}, {0x000e, 0x000f, 0x0005, 0x0001, 0x0002, 0x0007}},
      {{0x0001, 0x000f, 0x0007, 0x0000, 0x0000},
       {0x0001, 0x000f, 0x0007, 0x0000, 0x0035, 0x0064, 0x6400, 0x0200, 0x1002, 0x6341, 0x6563, 0x206c, 0x6954,
        0x656d, 0x3120, 0x2020, 0x2020, 0x5304, 0x6365, 0x0073, 0x0000, 0xea60, 0x03e8, 0x0001, 0x000a, 0x0001,
        0x0000, 0x0000, 0x0000, 0x0000, 0x0000, 0x0001}},
      {{0x000e, 0x000f, 0x0005, 0x0007, 0x0000},
       {0x000e, 0x000f, 0x0005, 0x0007, 0x0011, 0x4610, 0x6572, 0x2071, 0x6553, 0x656c, 0x7463, 0x3120, 0x2020,
        0x0020}},
      {{0x004b, 0x000f, 0x0005, 0x0001, 0x0000},
       {0x004b, 0x000f, 0x0005, 0x0001, 0x000c, 0x6552, 0x6f6d, 0x6574, 0x5020, 0x746f, 0x2020}},
      {{0x000e, 0x0092, 0x0000, 0x0000, 0x0000}, {0x000e, 0x0092, 0x0000, 0x0000, 0x0006, 0x0003, 0, 0}},
      {{0x000e, 0x0092, 0x0000, 0x0001, 0x0000},
       {0x000e, 0x0092, 0x0000, 0x0001, 0x0012, 0x7542, 0x206c, 0x3331, 0x3633, 0x5020, 0x554c, 0x2053, 0x2020, 0}},
      {{0x000e, 0x0092, 0x0000, 0x0003, 0x0000}, {0x000e, 0x0092, 0x0000, 0x0003, 0x0006, 0x0001, 0, 0}},
      {{0x000e, 0x0092, 0x0001, 0x0001, 0x0000}, {0x000e, 0x0092, 0x0001, 0x0001, 0x0006, 0x00ca, 0, 0}},
      {{0x0032, 0x0093, 0, 0, 0x000c, 1, 0, 2, 0, 3, 0}, {0x0032, 0x0093, 0, 0, 0x000c, 1, 0x0078, 2, 0, 3, 0}},
      {{0x000e, 0x0099, 0x0005, 0x0000, 0x0000}, {0x000e, 0x0099, 0x0005, 0x0000, 0x0006, 0x0006, 0, 0}},
      {{0x0010, 0x000f, 0x0005, 0x0001, 0x0002, 0x0006}, {0x0010, 0x000f, 0x0005, 0x0001, 0x0000}},
      {{0x0034, 0x0093, 0, 0, 0x000c, 5, 1, 6, 2, 7, 0x0258}, {0x0034, 0x0093, 0, 0, 0x000c, 5, 0, 6, 0, 7, 0}},
      {{0x0010, 0x0099, 0x0005, 0x0000, 0x0002, 0x0007}, {0x0010, 0x0099, 0x0005, 0x0000, 0x0000}},
      {{0x0016, 0x000f, 0, 0, 0}, {0x0016, 0x000f, 0, 0, 0}},
      {{0x0015, 0x000f, 0, 0, 0}, {0x0015, 0x000f, 0, 0, 0}},
      {{0x0005, 0x000f, 0, 0, 0}, {0x0005, 0x000f, 0, 0, 0}},
  };
  for (const auto& s : steps) {
    SCOPED_TRACE(hex(s.n10));
    expect_exchange(d, s.n10, s.n11);
  }
}

}  // namespace
}  // namespace softslc::scanport::test
