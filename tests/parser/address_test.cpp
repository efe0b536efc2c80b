// Address grammar: every SLC address form the program format accepts, its fields and its
// canonical spelling; and the positioned errors for malformed addresses.
#include <gtest/gtest.h>

#include "parser/loader.h"

namespace softslc {
namespace {

Address parse_ok(std::string_view text) {
  std::string err;
  auto a = parse_address(text, &err);
  EXPECT_TRUE(a.has_value()) << text << ": " << err;
  return a.value_or(Address{});
}

struct AddressCase {
  const char* text;
  FileType type;
  int file;
  int element;
  int word;
  int bit;
  const char* canonical;
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const AddressCase& c, std::ostream* os) { *os << c.text; }

class AddressForms : public ::testing::TestWithParam<AddressCase> {};

TEST_P(AddressForms, ParsesFieldsAndCanonicalSpelling) {
  const auto& c = GetParam();
  Address a = parse_ok(c.text);
  EXPECT_EQ(a.type, c.type) << c.text;
  EXPECT_EQ(a.file, c.file) << c.text;
  EXPECT_EQ(a.element, c.element) << c.text;
  EXPECT_EQ(a.word, c.word) << c.text;
  EXPECT_EQ(a.bit, c.bit) << c.text;
  EXPECT_EQ(to_string(a), c.canonical) << c.text;
  // The canonical spelling parses back to the same address.
  EXPECT_EQ(parse_ok(c.canonical), a) << c.text;
}

// Forms from the issue and the reference facts (RM 1-2, PT1 4-8/4-9, RM 1-6, 1-8).
INSTANTIATE_TEST_SUITE_P(
    AllForms, AddressForms,
    ::testing::Values(AddressCase{"I:1/3", FileType::Input, 1, 1, 0, 3, "I:1.0/3"},
                      AddressCase{"I:1.0/3", FileType::Input, 1, 1, 0, 3, "I:1.0/3"},
                      AddressCase{"O:2.1/15", FileType::Output, 0, 2, 1, 15, "O:2.1/15"},
                      AddressCase{"O:5", FileType::Output, 0, 5, 0, -1, "O:5.0"},
                      AddressCase{"S:1/15", FileType::Status, 2, 1, -1, 15, "S:1/15"},
                      AddressCase{"S2:24", FileType::Status, 2, 24, -1, -1, "S:24"},
                      AddressCase{"B3:0/7", FileType::Bit, 3, 0, -1, 7, "B3:0/7"},
                      AddressCase{"B3/62", FileType::Bit, 3, 3, -1, 14, "B3:3/14"},  // PT1 4-8: B3/62 = B3:3/14
                      AddressCase{"N7:10", FileType::Integer, 7, 10, -1, -1, "N7:10"},
                      AddressCase{"N7:10/4", FileType::Integer, 7, 10, -1, 4, "N7:10/4"},
                      AddressCase{"F8:2", FileType::Float, 8, 2, -1, -1, "F8:2"},
                      AddressCase{"T4:0.ACC", FileType::Timer, 4, 0, 2, -1, "T4:0.ACC"},
                      AddressCase{"T4:0.1", FileType::Timer, 4, 0, 1, -1, "T4:0.PRE"},  // PT1 4-9: T4:0.1 = .PRE
                      AddressCase{"T4:0/DN", FileType::Timer, 4, 0, 0, 13, "T4:0/DN"},
                      AddressCase{"T4:0/EN", FileType::Timer, 4, 0, 0, 15, "T4:0/EN"},
                      AddressCase{"T4:0/13", FileType::Timer, 4, 0, 0, 13, "T4:0/DN"},
                      AddressCase{"T9:0.0", FileType::Timer, 9, 0, 0, -1, "T9:0.0"},  // fuzz-found: control word
                      AddressCase{"T4:0", FileType::Timer, 4, 0, -1, -1, "T4:0"},
                      AddressCase{"T4:0/TT", FileType::Timer, 4, 0, 0, 14, "T4:0/TT"},
                      AddressCase{"C5:1.PRE", FileType::Counter, 5, 1, 1, -1, "C5:1.PRE"},
                      AddressCase{"C5:1/OV", FileType::Counter, 5, 1, 0, 12, "C5:1/OV"},
                      AddressCase{"C5:1/UN", FileType::Counter, 5, 1, 0, 11, "C5:1/UN"},
                      AddressCase{"C5:1/CU", FileType::Counter, 5, 1, 0, 15, "C5:1/CU"},
                      AddressCase{"R6:0.LEN", FileType::Control, 6, 0, 1, -1, "R6:0.LEN"},
                      AddressCase{"R6:0.POS", FileType::Control, 6, 0, 2, -1, "R6:0.POS"},
                      AddressCase{"R6:0/FD", FileType::Control, 6, 0, 0, 8, "R6:0/FD"},
                      AddressCase{"R6:0/UL", FileType::Control, 6, 0, 0, 10, "R6:0/UL"},
                      AddressCase{"M0:1.100/13", FileType::M0, 0, 1, 100, 13, "M0:1.100/13"},
                      AddressCase{"M1:3.210", FileType::M1, 1, 3, 210, -1, "M1:3.210"},
                      AddressCase{"M0:2", FileType::M0, 0, 2, 0, -1, "M0:2.0"},
                      AddressCase{"L41:0", FileType::Long, 41, 0, -1, -1, "L41:0"},
                      AddressCase{"ST9:3", FileType::String, 9, 3, -1, -1, "ST9:3"}));

TEST(Address, IndexedForm) {
  Address a = parse_ok("#N7:10");
  EXPECT_TRUE(a.indexed);
  EXPECT_EQ(a.element, 10);
  EXPECT_EQ(to_string(a), "#N7:10");
}

TEST(Address, IndirectElement) {
  Address a = parse_ok("N7:[N10:1]");
  ASSERT_TRUE(a.indirect_element().has_value());
  EXPECT_EQ(a.indirect_element()->type, FileType::Integer);
  EXPECT_EQ(a.indirect_element()->file, 10);
  EXPECT_EQ(a.indirect_element()->element, 1);
  EXPECT_EQ(to_string(a), "N7:[N10:1]");
}

TEST(Address, IndirectFile) {
  Address a = parse_ok("N[N10:0]:5");
  ASSERT_TRUE(a.indirect_file().has_value());
  EXPECT_EQ(a.indirect_file()->file, 10);
  EXPECT_EQ(a.element, 5);
  EXPECT_EQ(to_string(a), "N[N10:0]:5");
}

TEST(Address, IndirectBitOffset) {
  Address a = parse_ok("B3/[N7:0]");
  ASSERT_TRUE(a.indirect_bit().has_value());
  EXPECT_TRUE(a.bit_offset_form);
  EXPECT_EQ(to_string(a), "B3/[N7:0]");
}

TEST(Address, IndirectWithSubElementReference) {
  Address a = parse_ok("#F28:[T4:0.ACC]");
  ASSERT_TRUE(a.indirect_element().has_value());
  EXPECT_EQ(a.indirect_element()->type, FileType::Timer);
  EXPECT_EQ(a.indirect_element()->word, 2);
  EXPECT_EQ(to_string(a), "#F28:[T4:0.ACC]");
}

// The indirect references live out of line (docs/performance.md "Load time"): a direct address has
// none, a copy holds its own, and equality compares what they say, not where they are.
TEST(Address, IndirectReferencesCopyAndCompareByValue) {
  EXPECT_FALSE(parse_ok("N7:3").is_indirect());
  EXPECT_FALSE(parse_ok("#N7:3").is_indirect());
  Address a = parse_ok("N7:[N10:1]/[N10:2]");
  ASSERT_TRUE(a.is_indirect());
  Address b = a;
  EXPECT_EQ(a, b);
  EXPECT_EQ(to_string(b), "N7:[N10:1]/[N10:2]");
  b.set_indirect_bit(IndirectRef{FileType::Integer, 10, 3, -1});
  EXPECT_NE(a, b);
  EXPECT_EQ(a.indirect_bit()->element, 2);  // the original is untouched
  EXPECT_EQ(to_string(b), "N7:[N10:1]/[N10:3]");
  EXPECT_NE(parse_ok("N7:[N10:1]"), parse_ok("N7:[N10:2]"));
  EXPECT_NE(parse_ok("N7:[N10:1]"), parse_ok("N7:1"));
  Address moved = std::move(b);
  EXPECT_EQ(to_string(moved), "N7:[N10:1]/[N10:3]");
}

// The size the load-time work brought an Address to on LP64 (docs/performance.md "Load time"):
// a regression here is a regression of the 1M-rung load.
TEST(Address, IsSmallOnLp64) {
  if constexpr (sizeof(void*) == 8) {
    EXPECT_LE(sizeof(Address), 24u);
  }
}

struct BadAddress {
  const char* text;
  const char* message_part;
};
// How ctest and gtest name this case (else "GetParam() = 32-byte object <54-29 ...>").
void PrintTo(const BadAddress& c, std::ostream* os) { *os << c.text; }

class MalformedAddresses : public ::testing::TestWithParam<BadAddress> {};

TEST_P(MalformedAddresses, AreRejectedWithAReason) {
  std::string err;
  EXPECT_FALSE(parse_address(GetParam().text, &err).has_value()) << GetParam().text;
  EXPECT_NE(err.find(GetParam().message_part), std::string::npos) << GetParam().text << " → " << err;
}

INSTANTIATE_TEST_SUITE_P(
    Errors, MalformedAddresses,
    ::testing::Values(BadAddress{"T4:0/XX", "unknown bit name 'XX' (timer bits are EN, TT, DN)"},
                      BadAddress{"C5:0.FOO", "unknown sub-element 'FOO'"},
                      BadAddress{"T4:0.DN", "DN is a bit, written after '/' (T4:0/DN), not '.'"},
                      BadAddress{"MG11:0.EN", "EN is a bit, written after '/'"},
                      BadAddress{"STI:0.UIE", "UIE is a bit, written after '/'"},
                      BadAddress{"N7:0/", "expected a bit number"},
                      BadAddress{"N:5", "expected a file number after 'N'"},
                      BadAddress{"S3:1", "file S is always file 2"},
                      BadAddress{"N7/5", "bit-offset form"},
                      BadAddress{"N7:[N10:1", "expected ']'"},
                      BadAddress{"N7:[F8:1]", "integer word"},
                      BadAddress{"M0:1.[", "direct word address"},
                      BadAddress{"N7:", "expected an element number"},
                      BadAddress{"N7:1 junk", "not an address"},
                      BadAddress{"B3/4096", "bit offset must be 0-4095"},
                      // address_fuzz: an indirect function-file part printed as CS:0.
                      BadAddress{"CS:[N102:1]", "function file CS0 is addressed directly"},
                      BadAddress{"RTC:0.[N7:0]", "function file RTC is addressed directly"},
                      BadAddress{"RTC:0/[N7:0]", "function file RTC is addressed directly"}));

TEST(Number, AllConstantForms) {
  NumberValue v;
  ASSERT_TRUE(parse_number_text("42", v));
  EXPECT_EQ(v.integer, 42);
  ASSERT_TRUE(parse_number_text("-32768", v));
  EXPECT_EQ(v.integer, -32768);
  ASSERT_TRUE(parse_number_text("0x00FF", v));
  EXPECT_EQ(v.integer, 255);
  ASSERT_TRUE(parse_number_text("0FF0h", v));
  EXPECT_EQ(v.integer, 0x0FF0);
  ASSERT_TRUE(parse_number_text("0XA200", v));
  EXPECT_EQ(v.integer, 0xA200);
  ASSERT_TRUE(parse_number_text("0.01666667", v));
  EXPECT_TRUE(v.is_float);
  EXPECT_DOUBLE_EQ(v.real, 0.01666667);
  ASSERT_TRUE(parse_number_text("-1.5e2", v));
  EXPECT_DOUBLE_EQ(v.real, -150.0);
  EXPECT_FALSE(parse_number_text("12x", v));
  EXPECT_FALSE(parse_number_text("99999999999999999999999", v));
}

}  // namespace
}  // namespace softslc
