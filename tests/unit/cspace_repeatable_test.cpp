// The same build gives the same certified bounds, bit for bit: edge extents (chart and
// coordinates) and vertex y bounds of charts on CGAL's algebraic traits once depended on CGAL's
// clock-seeded default random generator (Bitstream Descartes split points), so `hipair cspace
// --json` and the C-space pictures differed between runs and between two builds in one process.
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_paths.hpp"

namespace hipair {
namespace {

void expect_same_range(const CertifiedRange& a, const CertifiedRange& b, const std::string& where) {
  EXPECT_EQ(a.lower, b.lower) << where;
  EXPECT_EQ(a.upper, b.upper) << where;
}

void expect_same_build(const char* file, const char* first, const char* second) {
  std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  Model model = read_model_file(path);
  CSpace a = CSpace::build(model, first, second);
  CSpace b = CSpace::build(model, first, second);
  ASSERT_EQ(a.edges().size(), b.edges().size()) << file;
  ASSERT_EQ(a.vertices().size(), b.vertices().size()) << file;
  for (std::size_t e = 0; e < a.edges().size(); ++e) {
    const CSpaceEdge& x = a.edges()[e];
    const CSpaceEdge& y = b.edges()[e];
    std::string where = std::string(file) + " edge " + std::to_string(e);
    EXPECT_EQ(x.source, y.source) << where;
    EXPECT_EQ(x.target, y.target) << where;
    expect_same_range(x.x_chart, y.x_chart, where + " x_chart");
    expect_same_range(x.y_chart, y.y_chart, where + " y_chart");
    expect_same_range(x.x_coordinate, y.x_coordinate, where + " x_coordinate");
    expect_same_range(x.y_coordinate, y.y_coordinate, where + " y_coordinate");
  }
  for (std::size_t v = 0; v < a.vertices().size(); ++v) {
    std::string where = std::string(file) + " vertex " + std::to_string(v);
    EXPECT_EQ(a.vertices()[v].y_lower, b.vertices()[v].y_lower) << where;
    EXPECT_EQ(a.vertices()[v].y_upper, b.vertices()[v].y_upper) << where;
  }
}

TEST(CSpaceRepeatable, EscapementAnchorBalanceTwiceInOneProcess) {
  expect_same_build("escapement.json", "anchor", "balance");
}

TEST(CSpaceRepeatable, GenevaTemplateTwiceInOneProcess) {
  expect_same_build("geneva-template.json", "driver", "wheel");
}

}  // namespace
}  // namespace hipair
