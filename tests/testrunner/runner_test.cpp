// The runner and the command: discovery order, --filter, --list, exit codes, the summary line,
// output order independent of --jobs, and the JUnit report (parsed back with tinyxml2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include "testrunner_test_util.h"
#include "tools/testrunner/junit.h"
#include "tools/testrunner/test_command.h"

namespace softslc::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::Sandbox;

// Options for Sandbox::command: the paths, no host times (so outputs compare exactly), and the
// fields a test sets.
struct Options : RunOptions {
  explicit Options(std::vector<std::string> p) {
    paths = std::move(p);
    host_times = false;
  }
  Options& with_filter(std::string f) { filter = std::move(f); return *this; }
  Options& with_junit(std::string j) { junit = std::move(j); return *this; }
  Options& with_jobs(int n) { jobs = n; return *this; }
  Options& listing() { list = true; return *this; }
  Options& timed() { host_times = true; return *this; }
};

TestCommandOptions command_options(std::string path, int jobs) {
  TestCommandOptions o;
  o.paths = {std::move(path)};
  o.jobs = jobs;
  return o;
}

TEST(Glob, MatchesWholeNames) {
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_TRUE(glob_match("*", "anything"));
  EXPECT_TRUE(glob_match("start*", "start seals the motor in"));
  EXPECT_TRUE(glob_match("*motor*", "start seals the motor in"));
  EXPECT_TRUE(glob_match("?tart*in", "start seals the motor in"));
  EXPECT_TRUE(glob_match("a*b*c", "aXbYbZc"));
  EXPECT_FALSE(glob_match("start", "start seals the motor in"));
  EXPECT_FALSE(glob_match("*motor", "start seals the motor in"));
  EXPECT_FALSE(glob_match("Start*", "start"));
  EXPECT_FALSE(glob_match("a*b*c", "aXbYbZ"));
}

TEST(Discovery, RecursiveSortedAndOnlyTestFiles) {
  Sandbox box;
  for (const char* name : {"suite/b.test", "suite/a/z.test", "suite/a/b.test", "suite/a.test", "suite/notes.txt",
                           "suite/a/c.test.bak"})
    box.write(name, "");
  std::vector<std::string> errors;
  auto files = discover_test_files({(box.dir() / "suite").string(), (box.dir() / "suite/b.test").string()}, errors);
  EXPECT_TRUE(errors.empty());
  std::vector<std::string> names;
  names.reserve(files.size());
  for (const auto& f : files) names.push_back(box.strip(f.display));
  // Byte order of the relative path ('.' sorts before '/'); a file named twice runs once.
  EXPECT_EQ(names, (std::vector<std::string>{"suite/a.test", "suite/a/b.test", "suite/a/z.test", "suite/b.test"}));

  discover_test_files({(box.dir() / "missing").string()}, errors);
  EXPECT_EQ(errors.size(), 1u);
  EXPECT_EQ(box.strip(errors.at(0)), "no such file or directory: 'missing'");
}

const char* const kPassing =
    "program ../lamp.slc\n"
    "test \"lamp on\"\n  set SWITCH = 1\n  scan 1\n  expect LAMP == 1\n"
    "test \"lamp off\"\n  scan 1\n  expect LAMP == 0\n";
const char* const kFailing =
    "program ../lamp.slc\n"
    "test \"wrong\"\n  scan 1\n  expect LAMP == 1\n"
    "test \"slow\"\n  set I:1/1 = 1\n  run until DELAYED == 1 within 100ms\n"
    "test \"fine\"\n  scan 1\n";

TEST(Command, SummaryLineAndExitCodes) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  auto ok = box.command(Options({"s/pass.test"}));
  EXPECT_EQ(ok.rc, kAllPassed);
  EXPECT_EQ(ok.out, "PASS s/pass.test: lamp on\nPASS s/pass.test: lamp off\n2 passed, 0 failed\n");
  EXPECT_EQ(ok.err, "");

  box.write("s/fail.test", kFailing);
  auto failed = box.command(Options({"s"}));
  EXPECT_EQ(failed.rc, kTestsFailed);
  EXPECT_THAT(failed.out, ::testing::EndsWith("\n3 passed, 2 failed\n"));
  EXPECT_THAT(failed.out, HasSubstr("FAIL s/fail.test: wrong\n    s/fail.test:4: expect LAMP == 1\n"));
}

TEST(Command, HostTimesAreOnPassLinesOnly) {
  Sandbox box;
  box.write("s/fail.test", kFailing);
  auto r = box.command(Options({"s"}).timed());
  const auto at = r.out.find("\nPASS s/fail.test: fine (");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_EQ(test::strip_host_ms(r.out.substr(at)), "\nPASS s/fail.test: fine\n1 passed, 2 failed\n") << r.out;
  EXPECT_THAT(r.out, HasSubstr("FAIL s/fail.test: wrong\n"));
}

TEST(Command, BadTestFilesStopTheRunWithExitCode2) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  box.write("s/zbad.test", "program ../lamp.slc\ntest \"bad\"\n  expect NOPE == 1\n");
  auto r = box.command(Options({"s"}).timed());
  EXPECT_EQ(r.rc, kUsageError);
  EXPECT_EQ(r.out, "");  // nothing ran
  EXPECT_EQ(r.err,
            "s/zbad.test:3:10: error: unknown symbol 'NOPE': not a SYMBOL of lamp.slc\n"
            "  expect NOPE == 1\n"
            "         ^\n"
            "error: 1 test file has errors; no test was run\n");
}

TEST(Command, UsageErrors) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  box.write("empty/readme.txt", "");

  auto missing = box.command(Options({"nowhere"}).timed());
  EXPECT_EQ(missing.rc, kUsageError);
  EXPECT_EQ(missing.err, "error: no such file or directory: 'nowhere'\n");

  auto none = box.command(Options({"empty"}).timed());
  EXPECT_EQ(none.rc, kUsageError);
  EXPECT_EQ(none.err, "error: no *.test files found\n");

  auto unmatched = box.command(Options({"s"}).with_filter("nothing*").timed());
  EXPECT_EQ(unmatched.rc, kUsageError);
  EXPECT_EQ(unmatched.err, "error: no test matches --filter 'nothing*'\n");

  std::ostringstream out, err;
  EXPECT_EQ(run_test_command({}, out, err), kUsageError);
  EXPECT_EQ(err.str(), "error: no test files or directories given\n");
}

// Pasted rungs (issue 14): bare `SOR ... EOR` lines copied out of RSLogix are program file 2 of
// the processor the test file's program line names (`program FILE processor CATALOG`), or of
// `softslc test --processor`; a MicroLogix 1400 brings its embedded I/O (slot 0).
const char* const kPastedRungs = "SOR XIC I:0/0 OTE O:0/0 EOR\nSOR XIC O:0/0 TON T4:0 1.0 2 0 EOR\n";
const char* const kPastedTests =
    "test \"input drives the output and the timer\"\n"
    "  set I:0/0 = 1\n  scan 2\n  expect O:0/0 == 1\n  run 2.5s\n  expect T4:0/DN == 1\n";

TEST(Command, PastedRungsRunAsFileTwoOfTheNamedProcessor) {
  Sandbox box;
  box.write("p/rungs.txt", kPastedRungs);
  box.write("p/named.test", std::string("program rungs.txt processor Bul.1766\n") + kPastedTests);
  auto named = box.command(Options({"p/named.test"}));
  EXPECT_EQ(named.rc, kAllPassed) << named.out << named.err;
  EXPECT_EQ(named.out, "PASS p/named.test: input drives the output and the timer\n1 passed, 0 failed\n");

  // Without a processor: one error saying how to name one, not an error per rung.
  box.write("p/unnamed.test", std::string("program rungs.txt\n") + kPastedTests);
  auto unnamed = box.command(Options({"p/unnamed.test"}));
  EXPECT_EQ(unnamed.rc, kUsageError);
  EXPECT_THAT(unnamed.err, HasSubstr("p/rungs.txt: error: these are pasted rungs (no START or LADDER statement): "
                                     "name their processor, `program p/rungs.txt processor Bul.1763` in the test "
                                     "file or `softslc test --processor Bul.1763`\n"));
  EXPECT_THAT(unnamed.err, Not(HasSubstr("LADDER statement\n")));

  // `softslc test --processor` is the default for pasted programs whose test file names none.
  Options with_default({"p/unnamed.test"});
  with_default.pasted_processor = resolve_processor("Bul.1766");
  auto defaulted = box.command(with_default);
  EXPECT_EQ(defaulted.rc, kAllPassed) << defaulted.err;
}

TEST(Command, ProcessorOnAProgramLineIsCheckedAndOnlyForPastedRungs) {
  Sandbox box;
  box.write("p/rungs.txt", kPastedRungs);
  box.write("p/bad.test", std::string("program rungs.txt processor 1747-L999\n") + kPastedTests);
  auto bad = box.command(Options({"p/bad.test"}));
  EXPECT_EQ(bad.rc, kUsageError);
  EXPECT_THAT(bad.err, HasSubstr("p/bad.test:1:29: error: processor 1747-L999: unknown catalog; known: "));
  box.write("p/series.test", std::string("program rungs.txt processor Bul.1766:b\n") + kPastedTests);
  EXPECT_THAT(box.command(Options({"p/series.test"})).err,
              HasSubstr("p/series.test:1:29: error: processor Bul.1766:b: write CATALOG or CATALOG:SERIES"));
  box.write("p/empty.test", std::string("program rungs.txt processor\n") + kPastedTests);
  EXPECT_THAT(box.command(Options({"p/empty.test"})).err, HasSubstr("p/empty.test:1:"));
  // A whole program names its own processor.
  box.write("p/whole.test", "program ../lamp.slc processor Bul.1766\ntest \"t\"\n  scan 1\n");
  auto whole = box.command(Options({"p/whole.test"}));
  EXPECT_EQ(whole.rc, kUsageError);
  EXPECT_THAT(whole.err, HasSubstr("lamp.slc: error: 'processor' names the processor of pasted rungs, and this is a "
                                   "whole program with its own"));
  // The command's own option is checked before anything runs.
  TestCommandOptions o = command_options((box.dir() / "p/whole.test").string(), 1);
  o.processor = "Bul.9999";
  std::ostringstream out, err;
  EXPECT_EQ(run_test_command(o, out, err), kUsageError);
  EXPECT_THAT(err.str(), ::testing::StartsWith("error: --processor Bul.9999: unknown catalog; known: "));
}

TEST(Command, FilterAndList) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  box.write("s/table.test",
            "program ../lamp.slc\n"
            "test \"lamp $V\" with V\n  row 0\n  row 1\n  set SWITCH = $V\n  scan 1\n  expect LAMP == $V\n");
  auto list = box.command(Options({"s"}).listing());
  EXPECT_EQ(list.rc, kAllPassed);
  EXPECT_EQ(list.out, "s/pass.test: lamp on\ns/pass.test: lamp off\ns/table.test: lamp 0\ns/table.test: lamp 1\n");

  auto filtered = box.command(Options({"s"}).with_filter("lamp o*"));
  EXPECT_EQ(filtered.out, "PASS s/pass.test: lamp on\nPASS s/pass.test: lamp off\n2 passed, 0 failed\n");

  auto row = box.command(Options({"s"}).with_filter("lamp 1").listing());
  EXPECT_EQ(row.out, "s/table.test: lamp 1\n");
}

// Many tests across files, some failing, some timing out, some restoring snapshots: the output
// must not depend on how many workers ran them or in which order they finished.
TEST(Command, OutputIsTheSameForAnyNumberOfJobs) {
  Sandbox box;
  for (int f = 0; f < 4; ++f) {
    std::string text = "program ../lamp.slc\n";
    text += "test \"setup\"\n  set I:1/1 = 1\n  run 200ms\n  snapshot s\n";
    for (int t = 0; t < 6; ++t) {
      const std::string n = std::to_string(f) + "." + std::to_string(t);
      text += "test \"t" + n + "\"\n  restore s\n  run " + std::to_string(50 * (t + 1)) + "ms\n";
      text += t % 3 == 0 ? "  expect DELAYED == 0\n" : "  run until DELAYED == 1 within " + std::to_string(100 * t) + "ms\n";
    }
    box.write("many/f" + std::to_string(f) + ".test", text);
  }
  auto one = box.command(Options({"many"}).with_jobs(1));
  EXPECT_EQ(one.rc, kTestsFailed);
  EXPECT_THAT(one.out, HasSubstr("FAIL many/f3.test: t3.1\n"));
  EXPECT_THAT(one.out, ::testing::EndsWith("\n24 passed, 4 failed\n"));
  for (int jobs : {2, 3, 8, 32}) {
    auto many = box.command(Options({"many"}).with_jobs(jobs));
    EXPECT_EQ(many.out, one.out) << "--jobs " << jobs;
    EXPECT_EQ(many.rc, one.rc);
  }

  // The command entry point (host times on, the runtime's own scan-time model) differs between
  // job counts only in the milliseconds of PASS lines.
  std::ostringstream out1, err1, out2, err2;
  const std::string dir = (box.dir() / "many").string();
  EXPECT_EQ(run_test_command(command_options(dir, 1), out1, err1), kTestsFailed);
  EXPECT_EQ(run_test_command(command_options(dir, 2), out2, err2), kTestsFailed);
  EXPECT_EQ(test::strip_host_ms(out1.str()), test::strip_host_ms(out2.str()));
}

TEST(JUnit, ReportParsesBackWithTheRightStructure) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  box.write("s/fail.test", kFailing);
  box.write("report.xml", "stale");
  auto r = box.command(Options({"s"}).with_junit("report.xml").with_jobs(2).timed());
  ASSERT_EQ(r.rc, kTestsFailed);
  ASSERT_EQ(r.err, "");

  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile((box.dir() / "report.xml").string().c_str()), tinyxml2::XML_SUCCESS);
  const auto* root = doc.FirstChildElement("testsuites");
  ASSERT_NE(root, nullptr);
  EXPECT_EQ(root->IntAttribute("tests"), 5);
  EXPECT_EQ(root->IntAttribute("failures"), 2);
  EXPECT_EQ(root->IntAttribute("errors"), 0);

  std::vector<std::string> suites;
  for (const auto* s = root->FirstChildElement("testsuite"); s; s = s->NextSiblingElement("testsuite"))
    suites.push_back(box.strip(s->Attribute("name")));
  EXPECT_EQ(suites, (std::vector<std::string>{"s/fail.test", "s/pass.test"}));

  const auto* fail_suite = root->FirstChildElement("testsuite");
  EXPECT_EQ(fail_suite->IntAttribute("tests"), 3);
  EXPECT_EQ(fail_suite->IntAttribute("failures"), 2);
  std::vector<std::string> cases;
  int failures = 0;
  for (const auto* c = fail_suite->FirstChildElement("testcase"); c; c = c->NextSiblingElement("testcase")) {
    cases.push_back(c->Attribute("name"));
    EXPECT_NE(c->Attribute("time"), nullptr);
    EXPECT_NE(c->Attribute("classname"), nullptr);
    const auto* props = c->FirstChildElement("properties");
    ASSERT_NE(props, nullptr);
    EXPECT_STREQ(props->FirstChildElement("property")->Attribute("name"), "virtual_time");
    if (const auto* f = c->FirstChildElement("failure")) {
      ++failures;
      EXPECT_STREQ(f->Attribute("type"), "expectation");
      if (std::string(c->Attribute("name")) == "wrong") {
        EXPECT_EQ(c->IntAttribute("line"), 2);
        EXPECT_EQ(box.strip(f->Attribute("message")), "s/fail.test:4: expect LAMP == 1");
        EXPECT_EQ(box.strip(f->GetText()),
                  "s/fail.test:4: expect LAMP == 1\n"
                  "  expected: LAMP == 1\n"
                  "  actual:   LAMP (O:2.0/0) = 0\n"
                  "  at virtual time 1.014ms, scan 1\n");
      }
    }
  }
  EXPECT_EQ(cases, (std::vector<std::string>{"wrong", "slow", "fine"}));
  EXPECT_EQ(failures, 2);

  // Written atomically: no temporary file is left beside the report.
  for (const auto& e : std::filesystem::directory_iterator(box.dir()))
    EXPECT_EQ(e.path().filename().string().find(".report.xml."), std::string::npos) << e.path();
}

TEST(JUnit, NamesAndMessagesAreEscapedByTheLibrary) {
  JUnitCase c;
  c.file = "a&b.test";
  c.name = "<quoted> \"name\" & more";
  c.line = 3;
  Failure f;
  f.file = "a&b.test";
  f.loc = {4, 3};
  f.step = "expect N7:0 < 5";
  f.expected = "N7:0 < 5";
  f.actual = "N7:0 = 7";
  c.failure = f;
  tinyxml2::XMLDocument doc;
  const std::string xml = junit_document({c});
  ASSERT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;
  const auto* tc = doc.FirstChildElement("testsuites")->FirstChildElement("testsuite")->FirstChildElement("testcase");
  EXPECT_STREQ(tc->Attribute("name"), "<quoted> \"name\" & more");
  EXPECT_STREQ(tc->FirstChildElement("failure")->Attribute("message"), "a&b.test:4: expect N7:0 < 5");
}

TEST(JUnit, AnUnwritableReportIsAnError) {
  Sandbox box;
  box.write("s/pass.test", kPassing);
  auto r = box.command(Options({"s"}).with_junit("no/such/dir/report.xml").timed());
  EXPECT_EQ(r.rc, kUsageError);
  EXPECT_THAT(r.out, ::testing::EndsWith("2 passed, 0 failed\n"));
  EXPECT_THAT(r.err, ::testing::StartsWith("error: cannot write the JUnit report: cannot create a temporary file"));
}

}  // namespace
}  // namespace softslc::testing
