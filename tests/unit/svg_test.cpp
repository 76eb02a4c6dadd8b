// SVG writer and mechanism drawings: well-formed documents, y-up coordinates, arc flags,
// atomic output.
#include "core/length_display.hpp"
#include "io/atomic_file.hpp"
#include "io/svg.hpp"
#include "render/cspace_svg.hpp"
#include "render/kinematics_svg.hpp"
#include "render/mechanism_svg.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <vector>

namespace hipair {
namespace {

namespace fs = std::filesystem;

// Checks that every element is closed in order (a small XML well-formedness check: tags,
// self-closing tags, the declaration, and no stray '<' or '&' in text).
::testing::AssertionResult well_formed(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = 0;
  if (xml.rfind("<?xml", 0) != 0) return ::testing::AssertionFailure() << "no XML declaration";
  while ((i = xml.find('<', i)) != std::string::npos) {
    std::size_t end = xml.find('>', i);
    if (end == std::string::npos) return ::testing::AssertionFailure() << "unclosed tag at " << i;
    std::string tag = xml.substr(i + 1, end - i - 1);
    if (tag.find('<') != std::string::npos)
      return ::testing::AssertionFailure() << "'<' inside a tag at " << i;
    if (tag[0] == '?') {
    } else if (tag[0] == '/') {
      std::string name = tag.substr(1);
      if (open.empty() || open.back() != name)
        return ::testing::AssertionFailure() << "mismatched </" << name << "> at " << i;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \n")));
    }
    std::size_t next = xml.find('<', end);
    std::string text = xml.substr(end + 1, (next == std::string::npos ? xml.size() : next) - end - 1);
    std::size_t amp = 0;
    while ((amp = text.find('&', amp)) != std::string::npos) {
      if (!std::regex_search(text.substr(amp), std::regex("^&(amp|lt|gt|quot|apos);")))
        return ::testing::AssertionFailure() << "bare '&' in text";
      ++amp;
    }
    i = end + 1;
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> not closed";
  if (xml.find("nan") != std::string::npos || xml.find("inf") != std::string::npos)
    return ::testing::AssertionFailure() << "non-finite number";
  return ::testing::AssertionSuccess();
}

TEST(Svg, EscapesText) {
  EXPECT_EQ(io::escape_xml("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
}

TEST(Svg, FormatsNumbersCompactly) {
  EXPECT_EQ(io::format_number(1.5), "1.5");
  EXPECT_EQ(io::format_number(2.0), "2");
  EXPECT_EQ(io::format_number(-0.00001), "-1e-05");  // small values are kept, not cut to 0
  EXPECT_EQ(io::format_number(-0.0), "0");
  EXPECT_EQ(io::format_number(-3.25), "-3.25");
}

TEST(Svg, FlipsTheYAxis) {
  io::SvgWriter svg(io::SvgBox{-10, -5, 10, 20});
  svg.circle(1, 5, 2, io::SvgStyle{});
  std::string out = svg.str();
  EXPECT_NE(out.find("cx=\"1\" cy=\"-5\" r=\"2\""), std::string::npos) << out;
  // viewBox: min x, -max y, width, height.
  EXPECT_NE(out.find("viewBox=\"-10 -20 20 25\""), std::string::npos) << out;
  EXPECT_TRUE(well_formed(out));
}

TEST(Svg, ArcFlagsFollowSpanAndDirection) {
  // Counter-clockwise from angle 0 to 270 degrees: 270 > 180, so large-arc = 1; a world
  // counter-clockwise arc is sweep 0 once y is flipped.
  io::SvgPath big;
  big.move_to(1, 0);
  big.arc_to(0, -1, 0, 0, true);
  EXPECT_NE(big.data().find("A1,1 0 1,0 0,1"), std::string::npos) << big.data();
  // Clockwise between the same points: 90 degrees, large-arc = 0, sweep 1.
  io::SvgPath small;
  small.move_to(1, 0);
  small.arc_to(0, -1, 0, 0, false);
  EXPECT_NE(small.data().find("A1,1 0 0,1 0,1"), std::string::npos) << small.data();
  // Just over a half turn counter-clockwise: large.
  io::SvgPath over;
  over.move_to(1, 0);
  over.arc_to(std::cos(3.2), std::sin(3.2), 0, 0, true);
  EXPECT_NE(over.data().find(" 0 1,0 "), std::string::npos) << over.data();
  // Just under a half turn: not large.
  io::SvgPath under;
  under.move_to(1, 0);
  under.arc_to(std::cos(3.1), std::sin(3.1), 0, 0, true);
  EXPECT_NE(under.data().find(" 0 0,0 "), std::string::npos) << under.data();
}

TEST(Svg, FullCircleIsTwoHalfArcs) {
  io::SvgPath circle;
  circle.move_to(3, 0);
  circle.arc_to(3, 0, 0, 0, true);
  const std::string& d = circle.data();
  std::size_t first = d.find(" A");
  ASSERT_NE(first, std::string::npos);
  EXPECT_NE(d.find(" A", first + 1), std::string::npos) << d;
  EXPECT_NE(d.find("-3,0"), std::string::npos) << d;  // through the opposite point
  // Its extent covers the whole circle.
  double min_y = 0, max_y = 0;
  for (const auto& [x, y] : circle.extent_points()) {
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  }
  EXPECT_DOUBLE_EQ(min_y, -3);
  EXPECT_DOUBLE_EQ(max_y, 3);
}

TEST(Svg, ArcExtentIncludesItsExtremes) {
  // A quarter arc through the top of the circle: extent reaches y = 2 although neither end
  // point does.
  io::SvgPath arc;
  arc.move_to(std::sqrt(2.0), std::sqrt(2.0));
  arc.arc_to(-std::sqrt(2.0), std::sqrt(2.0), 0, 0, true);
  double max_y = -1;
  for (const auto& [x, y] : arc.extent_points()) max_y = std::max(max_y, y);
  EXPECT_DOUBLE_EQ(max_y, 2);
}

TEST(Svg, DocumentWithGroupsLegendAndScaleBarIsWellFormed) {
  io::SvgWriter svg(io::SvgBox{0, 0, 100, 50}, 400);
  svg.define_hatch("hatch", "#888", 2);
  svg.define_arrow("arrow", "#333");
  svg.begin_group("part-a&b", "part", "a <b>");
  io::SvgPath path;
  path.move_to(0, 0);
  path.line_to(10, 0);
  path.arc_to(0, 10, 0, 0, true);
  path.close();
  svg.path(path, io::SvgStyle{"url(#hatch)", "black", 0.2, "evenodd", "", 0.8, ""}, "a & b");
  svg.end_group();
  svg.text(5, 5, "x < y & z", 2);
  svg.legend(60, 45, {{io::SvgStyle{}, "one"}, {io::SvgStyle{}, "two \"2\""}}, 2);
  svg.scale_bar(5, 2, io::nice_length(23), "20 mm", 2);
  std::string out = svg.str();
  EXPECT_TRUE(well_formed(out)) << out;
  EXPECT_NE(out.find("width=\"400\" height=\"200\""), std::string::npos);
  EXPECT_THROW(svg.end_group(), Error);
}

TEST(Svg, NiceLengths) {
  EXPECT_DOUBLE_EQ(io::nice_length(23), 20);
  EXPECT_DOUBLE_EQ(io::nice_length(0.04), 0.05);
  EXPECT_DOUBLE_EQ(io::nice_length(8), 10);
  EXPECT_DOUBLE_EQ(io::nice_length(1), 1);
}

TEST(MechanismSvg, PosesRotationsAndTranslations) {
  Motion rotation;
  rotation.kind = Motion::Kind::rotation;
  rotation.pivot = Point{Rational(1), Rational(0)};
  PartConfiguration quarter;
  quarter.angle = Rational(M_PI / 2);
  render::PosedPoint p = render::pose_point(rotation, quarter, 2, 0);
  EXPECT_NEAR(p.x, 1, 1e-12);
  EXPECT_NEAR(p.y, 1, 1e-12);
  Motion translation;
  translation.kind = Motion::Kind::translation;
  translation.direction = Point{Rational(3, 5), Rational(4, 5)};
  PartConfiguration moved;
  moved.offset = Rational(10);
  p = render::pose_point(translation, moved, 1, 1);
  EXPECT_DOUBLE_EQ(p.x, 7);
  EXPECT_DOUBLE_EQ(p.y, 9);
}

Model example(const std::string& name) {
  return read_model_file(fs::path(HIPAIR_EXAMPLES) / name);
}

std::vector<PartConfiguration> initial(const Model& model) {
  std::vector<PartConfiguration> configurations;
  for (const Part& part : model.parts) configurations.push_back(part.initial);
  return configurations;
}

TEST(MechanismSvg, DrawsEveryExample) {
  for (const char* name : {"geneva.json", "geneva-template.json", "cam-follower.json",
                           "scotch-yoke.json", "ratchet.json", "spur-gears.json",
                           "escapement.json"}) {
    SCOPED_TRACE(name);
    Model model = example(name);
    render::MechanismSvgOptions options;
    options.labels = true;
    std::string svg = render::mechanism_svg(model, initial(model), options);
    EXPECT_TRUE(well_formed(svg));
    for (const Part& part : model.parts) {
      EXPECT_NE(svg.find("id=\"part-" + part.name + "\""), std::string::npos) << part.name;
      EXPECT_NE(svg.find(">" + part.name + "</text>"), std::string::npos) << part.name;
    }
    EXPECT_NE(svg.find(" mm</text>"), std::string::npos);  // scale bar
  }
}

TEST(MechanismSvg, FixedPartsAreHatchedAndHolesCut) {
  Model model = example("scotch-yoke.json");
  std::string svg = render::mechanism_svg(model, initial(model));
  EXPECT_NE(svg.find("<pattern id=\"hatch\""), std::string::npos);
  EXPECT_NE(svg.find("fill=\"url(#hatch)\""), std::string::npos);
  EXPECT_NE(svg.find("fill-rule=\"evenodd\""), std::string::npos);
  EXPECT_NE(svg.find("marker-end=\"url(#arrow)\""), std::string::npos);  // translation axis
}

TEST(MechanismSvg, ConfigurationMovesTheDrawing) {
  Model model = example("geneva-template.json");
  std::vector<PartConfiguration> turned = initial(model);
  turned[1].angle = Rational(1, 2);
  EXPECT_NE(render::mechanism_svg(model, initial(model)), render::mechanism_svg(model, turned));
  turned.pop_back();
  EXPECT_THROW(render::mechanism_svg(model, turned), Error);
}

TEST(MechanismSvg, WritesAtomically) {
  fs::path directory = fs::temp_directory_path() / ("hipair_svg_test_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  fs::create_directories(directory);
  Model model = example("ratchet.json");
  std::string svg = render::mechanism_svg(model, initial(model));
  fs::path target = directory / "ratchet.svg";
  io::write_file_atomically(target, svg);
  EXPECT_EQ(io::read_file(target), svg);
  // Only the target is left behind: no temporary files.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(directory)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1u);
  // A missing directory is an IoError and creates nothing.
  EXPECT_THROW(io::write_file_atomically(directory / "missing" / "x.svg", svg), IoError);
  EXPECT_FALSE(fs::exists(directory / "missing"));
  fs::remove_all(directory);
}


// The C-space picture with a motion path zooms to the path's window (ticks chosen for it,
// drawing clipped to it), lists only a few contact curves per kind, and fits its legend.
TEST(Svg, CSpacePathPictureZoomsToThePathAndFitsItsLegend) {
  std::filesystem::path file = std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "examples/models/geneva.json missing";
  CSpace space = CSpace::build(read_model_file(file), "driver", "wheel");
  const double degree = std::acos(-1.0) / 180;
  render::CSpaceSvgOptions picture;   // the driver's dwell: wheel within +-0.5 deg of 0
  for (int i = 0; i <= 90; ++i) picture.path.push_back({(10 + i) * degree, 0.5 * std::sin(i * 0.3) * degree, false});
  picture.title = "dwell";
  std::string zoomed = render::cspace_svg(space, picture);
  std::string whole = render::cspace_svg(space, {});
  for (const std::string* out : {&zoomed, &whole}) {
    ASSERT_TRUE(well_formed(*out));
    // the legend box lies inside the canvas (the viewBox is in SVG coordinates)
    std::smatch box, legend;
    ASSERT_TRUE(std::regex_search(*out, box, std::regex(R"re(viewBox="([-0-9.e]+) ([-0-9.e]+) ([0-9.e]+) ([0-9.e]+)")re")));
    ASSERT_TRUE(std::regex_search(*out, legend, std::regex(
        R"re(class="legend">\n<rect x="([-0-9.e]+)" y="([-0-9.e]+)" width="([0-9.e]+)" height="([0-9.e]+)")re")));
    double bx = std::stod(box[1]), by = std::stod(box[2]), bw = std::stod(box[3]), bh = std::stod(box[4]);
    double lx = std::stod(legend[1]), ly = std::stod(legend[2]), lw = std::stod(legend[3]), lh = std::stod(legend[4]);
    EXPECT_GE(lx, bx);
    EXPECT_LE(lx + lw, bx + bw);
    EXPECT_GE(ly, by);
    EXPECT_LE(ly + lh, by + bh);
    // at most 3 feature pairs listed per kind of contact (7 kinds) and "+N more"
    std::size_t listed = 0;
    for (std::size_t at = out->find("\">  "); at != std::string::npos; at = out->find("\">  ", at + 1)) ++listed;
    EXPECT_LE(listed, 8u * 4);   // and the touching pairs
  }
  EXPECT_NE(zoomed.find("clip-path=\"url(#plot-window)\""), std::string::npos);
  EXPECT_NE(zoomed.find("contact curves in view"), std::string::npos);
  EXPECT_EQ(whole.find("contact curves in view"), std::string::npos);
  // y-axis tick labels (right-aligned, size 7): within the window -0.5 - 1.8 .. 0.5 + 1.8 deg
  // (margin: 0.5 % of the 360 deg range) in the zoomed picture; the whole turn otherwise
  auto y_ticks = [](const std::string& svg) {
    std::vector<double> ticks;
    std::regex tick(R"re(font-size="7" font-family="[^"]*" text-anchor="end" fill="black">([-0-9.]+)<)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tick); it != std::sregex_iterator(); ++it)
      ticks.push_back(std::stod((*it)[1]));
    return ticks;
  };
  std::vector<double> ticks = y_ticks(zoomed);
  EXPECT_GE(ticks.size(), 3u);
  for (double v : ticks) EXPECT_LE(std::fabs(v), 2.3) << v;
  std::vector<double> all = y_ticks(whole);
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(*std::max_element(all.begin(), all.end()), 270);
}

// The C-space picture is drawn from the edges the CSpace has: every contact edge (and every
// zero-clearance edge) of the built space is one path with its feature pairs as title, for a
// whole space and for an operating region (the picture `hipair analyze` draws for a large pair).
TEST(CSpaceSvg, EveryContactEdgeOfTheBuiltSpaceIsDrawn) {
  struct Case {
    const char* model;
    const char* first;
    const char* second;
    bool region;
  };
  for (const Case& test : {Case{"geneva.json", "driver", "wheel", false}, Case{"geneva.json", "driver", "wheel", true},
                           Case{"ratchet.json", "wheel", "pawl", false}}) {
    std::filesystem::path file = std::filesystem::path(HIPAIR_EXAMPLES) / test.model;
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " missing";
    CSpaceBuildOptions options;
    options.operating_region = test.region;
    CSpace space = CSpace::build(read_model_file(file), test.first, test.second, options);
    ASSERT_EQ(space.complete(), !test.region);
    std::multiset<std::string> expected;
    for (const CSpaceEdge& edge : space.edges()) {
      bool touching = edge.role == EdgeRole::touching;
      if (!touching && edge.role != EdgeRole::contact && !(edge.real && !edge.curves.empty())) continue;
      std::string title = touching ? "touching (zero clearance): " : "";
      for (std::size_t k = 0; k < edge.curves.size(); ++k)
        title += std::string(k ? "; " : "") + space.feature_pairs()[edge.curves[k]].label;
      expected.insert(io::escape_xml(title));
    }
    ASSERT_GT(expected.size(), 20u) << test.model;
    std::string svg = render::cspace_svg(space, {});
    ASSERT_TRUE(well_formed(svg));
    std::multiset<std::string> drawn;
    std::regex titled(R"re(<path d="([^"]*)"[^>]*><title>([^<]*)</title></path>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), titled); it != std::sregex_iterator(); ++it) {
      EXPECT_NE((*it)[1].str().find('L'), std::string::npos) << "an edge drawn as a single point";
      drawn.insert((*it)[2].str());
    }
    EXPECT_EQ(drawn, expected) << test.model << (test.region ? " (operating region)" : "");
    // an operating region's picture says what was built
    std::string built = "outside the " + std::to_string(space.statistics().region_tiles) + " tiles of the operating region";
    EXPECT_EQ(svg.find(built) != std::string::npos, test.region) << test.model;
  }
}


// The kinematics picture's velocity-ratio axis names the ratio's unit for every driver/follower
// combination: none for deg/deg and mm/mm, mm/deg for a translating follower of a rotating
// driver, deg/mm the other way round, and the length unit of a rescaled analysis ("1e400 mm",
// core/length_display.hpp) in it. The oracle for the plotted numbers: ratios made so that their
// largest value in the named unit is exactly 2 (mm/rad 360/pi is 2 mm/deg, rad/mm pi/90 is
// 2 deg/mm) give a ratio axis whose top tick is 2, above every position tick.
TEST(KinematicsSvg, TheVelocityRatioAxisNamesItsUnitForEveryDriverAndFollower) {
  const double pi = std::acos(-1.0);
  struct Case {
    bool driver_rotates, follower_rotates;
    long length_exponent;
    const char* label;
  };
  const Case cases[] = {{true, true, 0, "velocity ratio"},
                        {false, false, 0, "velocity ratio"},
                        {true, false, 0, "velocity ratio (mm/deg)"},
                        {false, true, 0, "velocity ratio (deg/mm)"},
                        {true, false, 400, "velocity ratio (1e400 mm/deg)"},
                        {false, true, -300, "velocity ratio (deg/1e-300 mm)"},
                        {false, false, 400, "velocity ratio"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    LengthDisplayScope unit(c.length_exponent);
    KinematicsResult result;
    result.model_name = "ratios";
    result.driver = "driver";
    result.driver_rotates = c.driver_rotates;
    result.followers = {"follower"};
    result.follower_rotates = {c.follower_rotates};
    // the largest ratio in internal units (rad or mm per rad or mm) that is 2 in the named unit
    const double top = c.driver_rotates == c.follower_rotates ? 2 : c.follower_rotates ? 2 * pi / 180 : 2 * 180 / pi;
    const double position_top = c.follower_rotates ? 0.5 * pi / 180 : 0.5;   // 0.5 deg or 0.5 mm
    for (int i = 0; i <= 20; ++i) {
      KinematicSample sample;
      sample.driver = (c.driver_rotates ? pi / 180 : 1.0) * i;   // 0 .. 20 deg or mm
      sample.positions = {position_top * i / 20};
      sample.velocity_ratios = {top * i / 20};
      result.samples.push_back(sample);
    }
    result.start = result.samples.front().driver;
    result.end = result.reached = result.samples.back().driver;
    std::string svg = render::kinematics_plot_svg(result);
    ASSERT_TRUE(well_formed(svg));
    EXPECT_NE(svg.find(">" + std::string(c.label) + "<"), std::string::npos);
    // exactly one ratio axis label (a unitless one is not followed by a unit)
    std::size_t labels = 0;
    for (std::size_t at = svg.find(">velocity ratio"); at != std::string::npos; at = svg.find(">velocity ratio", at + 1))
      if (svg.compare(at + 15, 1, "<") == 0 || svg.compare(at + 15, 2, " (") == 0) ++labels;
    EXPECT_EQ(labels, 1u);
    double largest_tick = -1;
    std::regex tick(R"re(text-anchor="end" fill="black">([-0-9.]+)<)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tick); it != std::sregex_iterator(); ++it)
      largest_tick = std::max(largest_tick, std::stod((*it)[1]));
    EXPECT_EQ(largest_tick, 2);
  }
}

}  // namespace
}  // namespace hipair
