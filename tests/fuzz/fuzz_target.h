// The libFuzzer entry point every target shares: feed the input to one property (properties.h,
// module_properties.h) and abort with its message when it breaks, so libFuzzer keeps the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#define SOFTSLC_FUZZ_TARGET(property)                                                          \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {         \
    const std::string broken = property({reinterpret_cast<const char*>(data), size});          \
    if (!broken.empty()) {                                                                      \
      std::fprintf(stderr, "%s\n", broken.c_str());                                             \
      std::abort();                                                                             \
    }                                                                                           \
    return 0;                                                                                   \
  }
