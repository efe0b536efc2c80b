#include "tools/testrunner/junit.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>

#include <tinyxml2.h>

namespace softslc::testing {

namespace {

// Seconds with millisecond precision, as JUnit readers expect ("0.012").
std::string seconds(std::int64_t ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%lld.%03lld", static_cast<long long>(ns / 1'000'000'000),
                static_cast<long long>((ns / 1'000'000) % 1000));
  return buf;
}

void add_property(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* props, const char* name, const std::string& value) {
  auto* p = doc.NewElement("property");
  p->SetAttribute("name", name);
  p->SetAttribute("value", value.c_str());
  props->InsertEndChild(p);
}

}  // namespace

std::string junit_document(const std::vector<JUnitCase>& cases) {
  tinyxml2::XMLDocument doc;
  doc.InsertEndChild(doc.NewDeclaration());
  auto* root = doc.NewElement("testsuites");
  root->SetAttribute("name", "softslc test");
  doc.InsertEndChild(root);

  struct Totals {
    int tests = 0, failures = 0;
    std::int64_t ns = 0;
  };
  Totals all;
  std::vector<std::string> order;
  std::map<std::string, std::pair<tinyxml2::XMLElement*, Totals>> suites;
  for (const auto& c : cases) {
    auto it = suites.find(c.file);
    if (it == suites.end()) {
      auto* suite = doc.NewElement("testsuite");
      suite->SetAttribute("name", c.file.c_str());
      root->InsertEndChild(suite);
      it = suites.emplace(c.file, std::make_pair(suite, Totals{})).first;
      order.push_back(c.file);
    }
    auto& [suite, totals] = it->second;
    auto* tc = doc.NewElement("testcase");
    tc->SetAttribute("name", c.name.c_str());
    tc->SetAttribute("classname", c.file.c_str());
    tc->SetAttribute("file", c.file.c_str());
    tc->SetAttribute("line", c.line);
    tc->SetAttribute("time", seconds(c.host_ns).c_str());
    auto* props = doc.NewElement("properties");
    add_property(doc, props, "virtual_time", format_duration(c.virtual_time));
    add_property(doc, props, "scans", std::to_string(c.scans));
    tc->InsertEndChild(props);
    if (c.failure) {
      auto* f = doc.NewElement("failure");
      f->SetAttribute("message", c.failure->summary().c_str());
      f->SetAttribute("type", c.failure->error.empty() ? "expectation" : "error");
      f->SetText(c.failure->render("").c_str());
      tc->InsertEndChild(f);
      ++totals.failures;
    }
    suite->InsertEndChild(tc);
    ++totals.tests;
    totals.ns += c.host_ns;
  }
  for (const auto& name : order) {
    auto& [suite, totals] = suites.at(name);
    suite->SetAttribute("tests", totals.tests);
    suite->SetAttribute("failures", totals.failures);
    suite->SetAttribute("errors", 0);
    suite->SetAttribute("skipped", 0);
    suite->SetAttribute("time", seconds(totals.ns).c_str());
    all.tests += totals.tests;
    all.failures += totals.failures;
    all.ns += totals.ns;
  }
  root->SetAttribute("tests", all.tests);
  root->SetAttribute("failures", all.failures);
  root->SetAttribute("errors", 0);
  root->SetAttribute("time", seconds(all.ns).c_str());

  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return valid_xml_text(
      std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() > 0 ? printer.CStrSize() - 1 : 0)));
}

std::string valid_xml_text(std::string_view bytes) {
  // tinyxml2 escapes markup characters but passes other bytes through; test names, file names and
  // failure messages can hold anything. The markup itself is ASCII, so checking the whole printed
  // document is enough.
  static constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD
  std::string out;
  out.reserve(bytes.size());
  std::size_t i = 0;
  while (i < bytes.size()) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c < 0x80) {
      // XML 1.0 allows only tab, line feed and carriage return below 0x20.
      if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') out += kReplacement;
      else out += static_cast<char>(c);
      ++i;
      continue;
    }
    // The length and the smallest code point of a well-formed sequence (no overlong forms, no
    // surrogates, nothing beyond U+10FFFF).
    std::size_t n = 0;
    std::uint32_t cp = 0, min = 0;
    if ((c & 0xE0) == 0xC0) n = 2, cp = c & 0x1F, min = 0x80;
    else if ((c & 0xF0) == 0xE0) n = 3, cp = c & 0x0F, min = 0x800;
    else if ((c & 0xF8) == 0xF0) n = 4, cp = c & 0x07, min = 0x10000;
    bool ok = n > 0 && i + n <= bytes.size();
    for (std::size_t k = 1; ok && k < n; ++k) {
      const auto cc = static_cast<unsigned char>(bytes[i + k]);
      ok = (cc & 0xC0) == 0x80;
      cp = (cp << 6) | (cc & 0x3F);
    }
    ok = ok && cp >= min && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF) && cp != 0xFFFE && cp != 0xFFFF;
    if (ok) {
      out.append(bytes.substr(i, n));
      i += n;
    } else {
      out += kReplacement;
      ++i;
    }
  }
  return out;
}


}  // namespace softslc::testing
