#include "core/vrml_field_filter.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace palpate::detail {
namespace {

std::string squeeze(const std::string& text) {  // collapse runs of spaces, to compare what is left
  std::string out;
  for (char c : text) {
    if (c == ' ' && !out.empty() && out.back() == ' ') continue;
    out.push_back(c);
  }
  return out;
}

TEST(RemoveVrmlField, RemovesNumbersNodesStringsAndArraysKeepingLines) {
  std::string text =
      "Material { diffuseColor 1 0 0 mirror 0.9 }\n"
      "Appearance { material Material { mirror 1 2 3 } blendMode BlendMode {\n destFactor \"ONE\" } }\n"
      "Material { mirror [ 1, 2,\n 3 ] shininess 0.2 }  # mirror 5 in a comment stays\n"
      "DEF mirror Material { }\n"
      "WorldInfo { info \"mirror 4\" }\n";
  const auto lines_before = std::count(text.begin(), text.end(), '\n');
  EXPECT_EQ(remove_vrml_field(text, "mirror", {"Material"}), 3u);
  EXPECT_EQ(remove_vrml_field(text, "blendMode", {"VRMLAppearance", "Appearance"}), 1u);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), lines_before);
  EXPECT_EQ(squeeze(text),
            "Material { diffuseColor 1 0 0 }\n"
            "Appearance { material Material { } \n }\n"
            "Material { \n shininess 0.2 } # mirror 5 in a comment stays\n"
            "DEF mirror Material { }\n"
            "WorldInfo { info \"mirror 4\" }\n");
}

TEST(RemoveVrmlField, LeavesOtherNodeTypesAlone) {
  std::string text = "Transform { mirror 1 } Material { mirror 2 }";
  EXPECT_EQ(remove_vrml_field(text, "mirror", {"Material"}), 1u);
  EXPECT_EQ(squeeze(text), "Transform { mirror 1 } Material { }");
}

TEST(RemoveVrmlField, EnumValueIsOneToken) {
  std::string text = "Material { reflMode FANCY ambientColor 0 0 0 }";
  EXPECT_EQ(remove_vrml_field(text, "reflMode", {"Material"}), 1u);
  EXPECT_EQ(squeeze(text), "Material { ambientColor 0 0 0 }");
}

}  // namespace
}  // namespace palpate::detail
