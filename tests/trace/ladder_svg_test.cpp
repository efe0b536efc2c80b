// The ladder layout's SVG form is well-formed XML and draws every instruction of every example
// program exactly once; the timing-diagram SVG is well-formed too. tinyxml2 is the independent
// XML parser; the instruction count comes from walking the program, not from the layout.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <filesystem>
#include <functional>
#include <string>

#include "parser/loader.h"
#include "tools/trace/ladder_layout.h"

namespace softslc {
namespace {

int count_instructions(const std::vector<RungElement>& elements) {
  int n = 0;
  for (const auto& e : elements) {
    if (e.kind == RungElement::Kind::Instruction) ++n;
    else
      for (const auto& leg : e.legs) n += count_instructions(leg);
  }
  return n;
}

// Counts <g class="instruction"> elements and checks each rung group names its file and rung.
void walk(const tinyxml2::XMLElement* e, int& instructions, int& rungs) {
  for (; e; e = e->NextSiblingElement()) {
    const char* cls = e->Attribute("class");
    if (cls && std::string(cls) == "instruction") ++instructions;
    if (cls && std::string(cls) == "rung") {
      ++rungs;
      EXPECT_NE(e->Attribute("data-file"), nullptr);
      EXPECT_NE(e->Attribute("data-rung"), nullptr);
    }
    walk(e->FirstChildElement(), instructions, rungs);
  }
}

TEST(LadderSvg, EveryExampleIsValidSvgWithEveryInstruction) {
  int programs = 0;
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder"))
    if (entry.path().extension() == ".slc") paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    SCOPED_TRACE(path.string());
    auto r = load_program_file(path.string());
    ASSERT_TRUE(r.ok()) << r.render_diagnostics();
    int expected = 0, expected_rungs = 0;
    for (const auto& f : r.program->files) {
      for (const auto& rung : f.rungs) expected += count_instructions(rung.elements);
      expected_rungs += static_cast<int>(f.rungs.size()) + 1;  // and the END rung
      ++expected;                                              // its <END> mark
    }
    const auto layout = ladder::layout_ladder(*r.program, {});
    const std::string svg = ladder::render_svg(layout, path.filename().string());
    tinyxml2::XMLDocument doc;
    ASSERT_EQ(doc.Parse(svg.c_str(), svg.size()), tinyxml2::XML_SUCCESS) << doc.ErrorStr();
    const auto* root = doc.RootElement();
    ASSERT_NE(root, nullptr);
    EXPECT_STREQ(root->Name(), "svg");
    EXPECT_STREQ(root->Attribute("xmlns"), "http://www.w3.org/2000/svg");
    int instructions = 0, rungs = 0;
    walk(root->FirstChildElement(), instructions, rungs);
    EXPECT_EQ(instructions, expected);
    EXPECT_EQ(rungs, expected_rungs);
    ++programs;
  }
  EXPECT_GE(programs, 30);
}

TEST(LadderSvg, RungRangeAndFileSelectOnlyThoseRungs) {
  auto r = load_program_file(std::string(SOFTSLC_SOURCE_DIR) + "/examples/ladder/seal_in/seal_in.slc");
  ASSERT_TRUE(r.ok());
  ladder::LayoutOptions o;
  o.file = 2;
  o.first_rung = 1;
  o.last_rung = 2;
  const auto layout = ladder::layout_ladder(*r.program, o);
  ASSERT_EQ(layout.files.size(), 1u);
  ASSERT_EQ(layout.files[0].rungs.size(), 2u);
  EXPECT_EQ(layout.files[0].rungs[0].number, 1);
  EXPECT_EQ(layout.files[0].rungs[1].number, 2);
  // Rung 1 is XIC OL_CONTACT TON T4:0 ...: a contact and a box, the box against the right rail.
  const auto& blocks = layout.files[0].rungs[0].blocks;
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].shape, ladder::Shape::Contact);
  EXPECT_EQ(blocks[1].shape, ladder::Shape::Box);
  EXPECT_EQ(blocks[1].x + blocks[1].w, layout.width - 1);
}

}  // namespace
}  // namespace softslc
