// The tolerant XML reader: element paths, comments, BOM, text before the declaration, and
// syntax errors with their line.

#include "scene/xml.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace s2sim::scene {
namespace {

using ::testing::HasSubstr;

TEST(Xml, ElementPathsIndexOnlyRepeatedNames) {
  const Element root = parse_xml(R"(<robot>
    <solids>
      <cuboid><ID value=' a '/></cuboid>
      <!-- a comment is no element -->
      <cylinder/>
      <cuboid><ID value='b'/><pos x='1'/></cuboid>
    </solids>
  </robot>)",
                                 "r.xml");
  EXPECT_EQ(root.name, "robot");
  EXPECT_EQ(root.path, "robot");
  const Element& solids = root.children.at(0);
  EXPECT_EQ(solids.path, "robot/solids");
  ASSERT_EQ(solids.children.size(), 3u);
  EXPECT_EQ(solids.children[0].path, "robot/solids/cuboid[1]");
  EXPECT_EQ(solids.children[1].path, "robot/solids/cylinder");
  EXPECT_EQ(solids.children[2].path, "robot/solids/cuboid[2]");
  EXPECT_EQ(solids.children[2].children[1].path, "robot/solids/cuboid[2]/pos");
  ASSERT_NE(solids.children[0].child("ID"), nullptr);
  EXPECT_EQ(*solids.children[0].child("ID")->attribute("value"), "a");  // trimmed
  EXPECT_EQ(solids.children[0].child("nothing"), nullptr);
}

TEST(Xml, EveryTopLevelElementInDocumentOrder) {
  const std::vector<Element> top = parse_xml_elements(R"(<?xml version="1.0" ?>
<defines><const name='L' value='1'/></defines>
<!-- between -->
<things><cuboid/></things>
<things/>)",
                                                      "t.xml");
  ASSERT_EQ(top.size(), 3u);
  EXPECT_EQ(top[0].path, "defines");
  EXPECT_EQ(top[1].path, "things[1]");
  EXPECT_EQ(top[1].children.at(0).path, "things[1]/cuboid");
  EXPECT_EQ(top[2].path, "things[2]");
  // parse_xml keeps returning the first one.
  EXPECT_EQ(parse_xml("<a/><b/>", "t.xml").name, "a");
}

TEST(Xml, AttributesInDocumentOrder) {
  const Element e = parse_xml("<size z='3' x='1' y='2'/>", "s.xml");
  ASSERT_EQ(e.attributes.size(), 3u);
  EXPECT_EQ(e.attributes[0].first, "z");
  EXPECT_EQ(e.attributes[2].first, "y");
  EXPECT_EQ(e.attribute("w"), nullptr);
}

TEST(Xml, ToleratesBomLeadingTextAndOddComments) {
  const Element e = parse_xml(
      "\xEF\xBB\xBF \n\n  <?xml version=\"1.0\" ?>\n<!---->\n<scene><!--------><a/></scene>",
      "scene.xml");
  EXPECT_EQ(e.name, "scene");
  ASSERT_EQ(e.children.size(), 1u);
  EXPECT_EQ(e.children[0].name, "a");
}

TEST(Xml, SyntaxErrorNamesFileAndLine) {
  try {
    parse_xml(" \n\n<scene>\n  <a x='1'\n  <b/>\n</scene>", "scene.xml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_EQ(e.where().file, "scene.xml:5");  // leading lines are counted
    EXPECT_THAT(std::string(e.what()), HasSubstr("scene.xml:5: expected"));
  }
}

// 40 000 nested elements once overflowed the stack of the runner and the viewer (the
// parsers recurse). Deeper than 256 levels is a located scene error; 256 itself still parses,
// and comments, CDATA, quoted '>' and self-closing tags do not count as levels.
TEST(Xml, NestingBeyondTheLimitIsALocatedErrorNotACrash) {
  std::string deep = "<?xml version='1.0'?>\n<scene>\n";
  for (int i = 0; i < 40000; ++i)
    deep += "<a>";
  for (int i = 0; i < 40000; ++i)
    deep += "</a>";
  deep += "</scene>";
  try {
    parse_xml(deep, "scene.xml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_EQ(e.where().file, "scene.xml:3");
    EXPECT_THAT(e.message(), HasSubstr("nested deeper than 256 levels"));
  }
  std::string fine = "<scene>";
  for (int i = 1; i < 256; ++i)
    fine += "<a t='>'><!-- <b> --><![CDATA[<c>]]><d/>";
  for (int i = 1; i < 256; ++i)
    fine += "</a>";
  fine += "</scene>";
  EXPECT_NO_THROW(parse_xml(fine, "fine.xml"));
}

// A million things in a 109 MB file once needed 36 times its size in memory. A file of
// more elements than the limit is refused, at the line of the first one over, before a tree is
// built; a file at the limit loads.
TEST(Xml, MoreElementsThanTheLimitAreALocatedErrorBeforeAnyTreeIsBuilt) {
  std::string many = "<things>\n";
  for (int i = 1; i < 500000; ++i)
    many += "<a/>\n";
  std::string at_limit = many + "</things>";
  EXPECT_NO_THROW(parse_xml(at_limit, "things.xml"));
  many += "<a/>\n</things>";
  try {
    parse_xml(many, "things.xml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_EQ(e.where().file, "things.xml:500001");
    EXPECT_THAT(e.message(), HasSubstr("more than 500000 elements in one file"));
  }
}

TEST(Xml, EmptyFileIsAnError) {
  EXPECT_THROW(parse_xml("  \n ", "x.xml"), Error);
  EXPECT_THROW(read_xml_file("/nonexistent/file.xml", "file.xml"), Error);
}

}  // namespace
}  // namespace s2sim::scene

TEST(Xml, MismatchedClosingTagIsAnErrorWithItsLine) {
  try {
    s2sim::scene::parse_xml("<robot>\n  <solids>\n  </solid>\n</robot>\n", "bot.xml");
    FAIL() << "a mismatched closing tag loaded";
  } catch (const s2sim::Error& e) {
    EXPECT_EQ(e.kind(), s2sim::ErrorKind::scene);
    EXPECT_THAT(e.what(), ::testing::HasSubstr("bot.xml:3"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("closing tag"));
  }
}
