// Shared by the MicroLogix function-file tests (STI, HSC, PTO): each named sub-element address
// parses to its word and bit and prints back exactly as written.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "parser/address.h"
#include "parser/loader.h"

namespace softslc::test {

struct NamedSubElement {
  const char* text;  // "STI:0/UIE", "HSC:0.ACC", ...
  int word, bit;     // bit -1: a word
};

inline void expect_named_sub_elements(std::initializer_list<NamedSubElement> cases) {
  for (const NamedSubElement& c : cases) {
    SCOPED_TRACE(c.text);
    std::string err;
    const auto a = parse_address(c.text, &err);
    ASSERT_TRUE(a.has_value()) << err;
    EXPECT_EQ(a->word, c.word);
    EXPECT_EQ(a->bit, c.bit);
    EXPECT_EQ(to_string(*a), c.text) << "prints by name";
  }
}

}  // namespace softslc::test
