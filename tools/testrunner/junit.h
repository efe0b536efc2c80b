// The JUnit XML report of a test run, for CI servers (Jenkins, GitLab, GitHub test reporters).
//
// The document is built with tinyxml2 (element by element, so names and failure texts are
// escaped by the library, never by string concatenation) and written atomically: to a temporary
// file in the destination's directory, flushed to disk, then renamed over the destination, so a
// CI job that reads the report never sees half of one.
//
// Shape: <testsuites> with one <testsuite> per test file (in run order), one <testcase> per
// test with its host time in seconds, its file and line, and, when it failed, a <failure> whose
// `message` is the failing step ("seal_in.test:9: expect MOTOR == 1") and whose text is the
// full failure as the console prints it. Each testcase also carries its virtual time and program
// scans as <properties>, which unlike host time are the same on every machine.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tools/testrunner/executor.h"

namespace softslc::testing {

struct JUnitCase {
  std::string file;  // the test file as shown in messages; cases of one file form a suite
  std::string name;
  std::uint32_t line = 0;
  std::int64_t host_ns = 0;
  VirtualTime virtual_time = 0;
  std::uint64_t scans = 0;
  std::optional<Failure> failure;
};

// The XML text of the report for `cases`, in order (suites in order of first appearance).
std::string junit_document(const std::vector<JUnitCase>& cases);

// `bytes` as valid XML 1.0 text in UTF-8: every byte sequence that is not well-formed UTF-8, and
// every control character XML forbids, becomes U+FFFD. A test name or path that is not UTF-8
// would otherwise make the report unreadable to every JUnit consumer.
std::string valid_xml_text(std::string_view bytes);


}  // namespace softslc::testing
