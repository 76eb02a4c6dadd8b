// Geometric profile tolerances translated into offset parameters (docs/model-format.md
// "Profile tolerances"): offset squares, triangles, stadiums and circles against their closed
// forms, exactly where the normals are rational; the nominal model unchanged; the parametric
// model's exact form equal to the reader's at offset values; errors naming where; and a cam
// whose profile bands reach the follower exactly as the closed form says, Monte Carlo inside
// the certified band.
#include "model/parametric/parametric.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace hipair {
namespace {

std::string with_parts(const std::string& parts, const std::string& parameters = "{}") {
  return R"({"hipair": 1, "name": "profile", "parameters": )" + parameters + R"(, "parts": [)" + parts + "]}";
}

Rational q(long n, long d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

Model at(const std::string& text, const std::string& name, const Rational& value) {
  ReadOptions options;
  options.parameter_values[name] = value;
  return read_model(text, "<test>", options);
}

// The written vertices of a loop in the reader's (counter-clockwise) order.
std::vector<Point> vertices(const Loop& loop) {
  std::vector<Point> out;
  for (const Edge& e : loop.edges) out.push_back(e.source);
  return out;
}

bool contains(const std::vector<Point>& points, const Point& p) {
  for (const Point& q : points)
    if (q == p) return true;
  return false;
}

const std::string square = R"({"name": "plate", "motion": "fixed",
  "loops": [{"start": [0, 0], "edges": [{"line_to": ["a", 0]}, {"line_to": ["a", "a"]}, {"line_to": [0, "a"]}, {"line_to": [0, 0]}]},
            {"start": [3, 3], "edges": [{"line_to": [3, 7]}, {"line_to": [7, 7]}, {"line_to": [7, 3]}, {"line_to": [3, 3]}]},
            {"circle": {"center": [15, 5], "radius": 2}}],
  "profile_tolerances": [{"loop": 0, "tolerance": 0.4, "distribution": "uniform"},
                         {"loop": 1, "tolerance": 0.2, "parameter": "hole"},
                         {"loop": 2, "tolerance": "2/10"}]})";

TEST(ModelProfileTolerance, SquareAndHoleOffsetExactlyAsTheClosedForm) {
  std::string text = with_parts(square, R"({"a": {"nominal": 10, "tolerance": 0.1}})");
  Model nominal = read_model(text);
  ASSERT_EQ(nominal.profile_tolerances.size(), 3u);
  const Parameter* p = nominal.find_parameter("profile-0-loop-0");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->nominal, 0);
  EXPECT_EQ(p->range.lo, Rational(-1, 5));
  EXPECT_EQ(p->range.hi, Rational(1, 5));
  EXPECT_EQ(p->distribution, Parameter::Distribution::uniform);
  ASSERT_NE(nominal.find_parameter("hole"), nullptr);
  EXPECT_EQ(nominal.find_parameter("profile-0-loop-2")->range.hi, Rational(1, 10));
  EXPECT_TRUE(nominal.roundings.empty());
  // Nominal: exactly the file's geometry.
  EXPECT_TRUE(contains(vertices(nominal.parts[0].loops[0]), Point{10, 10}));
  for (int k = -4; k <= 4; ++k) {
    Rational d = q(k, 20);  // inside [-0.2, 0.2]
    Model m = at(text, "profile-0-loop-0", d);
    EXPECT_TRUE(m.roundings.empty());
    auto v = vertices(m.parts[0].loops[0]);
    for (const Point& corner : {Point{-d, -d}, Point{10 + d, -d}, Point{10 + d, 10 + d}, Point{-d, 10 + d}})
      EXPECT_TRUE(contains(v, corner)) << "offset " << d;
    // the hole grows when its parameter is negative (material removed) and shrinks when positive
    Rational h = q(k, 40);
    Model mh = at(text, "hole", h);
    auto w = vertices(mh.parts[0].loops[1]);
    EXPECT_TRUE(mh.parts[0].loops[1].is_hole);
    for (const Point& corner : {Point{3 + h, 3 + h}, Point{7 - h, 3 + h}, Point{7 - h, 7 - h}, Point{3 + h, 7 - h}})
      EXPECT_TRUE(contains(w, corner)) << "hole offset " << h;
    Model mc = at(text, "profile-0-loop-2", h);
    EXPECT_EQ(mc.parts[0].loops[2].edges[0].radius_squared, (2 + h) * (2 + h));
  }
  // The square follows its other parameter too: a = 10.1, offset 0.2.
  ReadOptions both;
  both.parameter_values["a"] = Rational(101, 10);
  both.parameter_values["profile-0-loop-0"] = Rational(1, 5);
  Model m = read_model(text, "<test>", both);
  EXPECT_TRUE(contains(vertices(m.parts[0].loops[0]), Point{Rational(103, 10), Rational(103, 10)}));
}

TEST(ModelProfileTolerance, TiltedSquareWithRationalNormalsIsExact) {
  // side 10 along (3, 4)/5: unit normals are rational, so every offset vertex is exact.
  std::string part = R"({"name": "tilt", "motion": "fixed",
    "loops": [{"start": [0, 0], "edges": [{"line_to": [6, 8]}, {"line_to": [-2, 14]}, {"line_to": [-8, 6]}, {"line_to": [0, 0]}]}],
    "profile_tolerances": [{"loop": 0, "tolerance": 1}]})";
  std::string text = with_parts(part);
  for (int k = -5; k <= 5; ++k) {
    Rational d = q(k, 10);
    Model m = at(text, "profile-0-loop-0", d);
    EXPECT_TRUE(m.roundings.empty());
    // the loop as written is clockwise... outward normals of the square with centre (-1, 7)
    auto v = vertices(m.parts[0].loops[0]);
    Point centre{-1, 7};
    for (const Point& c : {Point{0, 0}, Point{6, 8}, Point{-2, 14}, Point{-8, 6}}) {
      // corner moves by d along both adjacent outward normals: (c - centre)/5 * d (diagonal = 5 sqrt2 / sqrt2)
      Point expected{c.x + d * (c.x - centre.x) / 5, c.y + d * (c.y - centre.y) / 5};
      EXPECT_TRUE(contains(v, expected)) << "offset " << d;
    }
  }
}

TEST(ModelProfileTolerance, IrrationalNormalsAreRoundedAndRecorded) {
  std::string part = R"({"name": "tri", "motion": "fixed",
    "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}],
    "profile_tolerances": [{"loop": 0, "tolerance": 1}]})";
  std::string text = with_parts(part);
  EXPECT_TRUE(read_model(text).roundings.empty());  // offset 0: exact
  Rational d(3, 10);
  Model m = at(text, "profile-0-loop-0", d);
  EXPECT_FALSE(m.roundings.empty());
  for (const Rounding& r : m.roundings) EXPECT_LE(r.bound, parse_rational("1e-12"));
  // closed form: (0,0) -> (-d, -d); (10,0) -> (10 + d(1 + sqrt2), -d); (0,10) -> (-d, 10 + d(1 + sqrt2))
  auto v = vertices(m.parts[0].loops[0]);
  double far = 10 + 0.3 * (1 + std::sqrt(2.0));
  std::vector<std::pair<double, double>> expected = {{-0.3, -0.3}, {far, -0.3}, {-0.3, far}};
  for (auto [x, y] : expected) {
    bool found = false;
    // each coordinate rounded to 1e-12 (recorded bound); double evaluation adds < 1e-14 here
    for (const Point& p : v)
      found = found || (std::fabs(p.x.get_d() - x) <= 2e-12 && std::fabs(p.y.get_d() - y) <= 2e-12);
    EXPECT_TRUE(found) << x << ", " << y;
  }
}

TEST(ModelProfileTolerance, StadiumArcsChangeRadiusAndStayTangent) {
  // a slot-shaped part: two segments joined by semicircles of radius 5 (tangent joins)
  std::string part = R"({"name": "stadium", "motion": "fixed",
    "loops": [{"start": [0, 0], "edges": [{"line_to": [20, 0]}, {"arc_to": [20, 10], "center": [20, 5], "dir": "ccw"},
                                          {"line_to": [0, 10]}, {"arc_to": [0, 0], "center": [0, 5], "dir": "ccw"}]}],
    "profile_tolerances": [{"loop": 0, "tolerance": 2}]})";
  std::string text = with_parts(part);
  for (int k = -10; k <= 10; k += 2) {
    Rational d = q(k, 10);
    Model m = at(text, "profile-0-loop-0", d);
    EXPECT_TRUE(m.roundings.empty());
    for (const Edge& e : m.parts[0].loops[0].edges) {
      if (e.is_arc()) {
        EXPECT_EQ(e.radius_squared, (5 + d) * (5 + d));
      } else {
        EXPECT_TRUE((e.source.y == -d && e.target.y == -d) || (e.source.y == 10 + d && e.target.y == 10 + d));
      }
    }
  }
}

TEST(ModelProfileTolerance, CircleFeatureAndParametricRoundTrip) {
  std::string text = with_parts(R"({"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}},
      "features": [{"circle": {"center": ["e", 0], "radius": 20}}],
      "profile_tolerances": [{"feature": 0, "tolerance": 0.04, "distribution": {"normal": {"sigma": 0.005}}}]},
    {"name": "plate", "motion": {"translation": {"direction": [0, 1]}},
      "loops": [{"start": [-30, 25], "edges": [{"line_to": [30, 25]}, {"line_to": [30, 35]}, {"line_to": [-30, 35]}, {"line_to": [-30, 25]}]}],
      "profile_tolerances": [{"loop": 0, "tolerance": 0.02}]})",
                                R"({"e": {"nominal": 5, "tolerance": 0.01}})");
  Model nominal = read_model(text);
  const Parameter* p = nominal.find_parameter("profile-0-feature-0");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->distribution, Parameter::Distribution::normal);
  EXPECT_EQ(*p->sigma, Rational(1, 200));
  auto parametric = model_detail::ParametricModel::read(text);
  ASSERT_EQ(parametric.parameter_count(), nominal.parameters.size());
  // exact_model at deviations equals read_model with the values overridden
  for (int k = -2; k <= 2; ++k) {
    std::vector<Rational> deviations(nominal.parameters.size(), Rational(0));
    ReadOptions options;
    for (std::size_t i = 0; i < nominal.parameters.size(); ++i) {
      const Parameter& par = nominal.parameters[i];
      deviations[i] = (par.range.hi - par.nominal) * q(k, 2) * (i % 2 ? 1 : -1);
      options.parameter_values[par.name] = par.nominal + deviations[i];
    }
    Model a = parametric.exact_model(deviations);
    Model b = read_model(text, "<test>", options);
    for (std::size_t part = 0; part < a.parts.size(); ++part)
      for (std::size_t l = 0; l < a.parts[part].loops.size(); ++l)
        for (std::size_t e = 0; e < a.parts[part].loops[l].edges.size(); ++e) {
          const Edge& x = a.parts[part].loops[l].edges[e];
          const Edge& y = b.parts[part].loops[l].edges[e];
          EXPECT_TRUE(x.source == y.source && x.target == y.target && x.radius_squared == y.radius_squared);
        }
    const Rational& dc = options.parameter_values["profile-0-feature-0"];
    EXPECT_EQ(b.parts[0].loops[0].edges[0].radius_squared, (20 + dc) * (20 + dc));
  }
}

TEST(ModelProfileTolerance, BandGivenByAnExpressionOfParameters) {
  std::string text = with_parts(R"({"name": "p", "motion": "fixed",
      "loops": [{"circle": {"center": [0, 0], "radius": 3}}],
      "profile_tolerances": [{"loop": 0, "tolerance": "e", "parameter": "band"}]})",
                                R"({"e": {"nominal": "1/10"}})");
  Model m = read_model(text);
  ASSERT_NE(m.find_parameter("band"), nullptr);
  EXPECT_EQ(m.find_parameter("band")->range.hi, q(1, 20));
  EXPECT_EQ(m.profile_tolerances.front().loop, "/parts/0/loops/0");
}

std::string error_pointer(const std::string& text) {
  try {
    read_model(text);
  } catch (const ModelError& error) {
    return error.pointer();
  }
  return "(no error)";
}

TEST(ModelProfileTolerance, BadInputNamesWhere) {
  auto part = [](const std::string& tolerances) {
    return with_parts(R"({"name": "p", "motion": "fixed",
      "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 10]}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}],
      "features": [{"geneva_driver": {"center": [30, 30], "pin_radius": 1, "pin_center_radius": 8, "lock_outer_radius": 5, "lock_inner_radius": 0, "lock_span": 3}}],
      "profile_tolerances": [)" + tolerances + "]}");
  };
  EXPECT_EQ(error_pointer(part(R"({"loop": 3, "tolerance": 0.1})")), "/parts/0/profile_tolerances/0/loop");
  EXPECT_EQ(error_pointer(part(R"({"loop": 0, "tolerance": -0.1})")), "/parts/0/profile_tolerances/0/tolerance");
  EXPECT_EQ(error_pointer(part(R"({"loop": 0})")), "/parts/0/profile_tolerances/0");
  EXPECT_EQ(error_pointer(part(R"({"loop": 0, "tolerance": 0.1, "color": 1})")),
            "/parts/0/profile_tolerances/0/color");
  EXPECT_EQ(error_pointer(part(R"({"feature": 0, "tolerance": 0.1})")), "/parts/0/profile_tolerances/0/feature");
  // a band so wide that the square collapses and turns inside out at -t/2
  EXPECT_EQ(error_pointer(part(R"({"loop": 0, "tolerance": 24})")), "/parts/0/profile_tolerances/0");
  // a full circle written as one arc, its radius 2 passing zero at -t/2
  std::string disc = with_parts(R"({"name": "p", "motion": "fixed",
      "loops": [{"start": [2, 0], "edges": [{"arc_to": [2, 0], "center": [0, 0], "dir": "cw"}]}],
      "profile_tolerances": [{"loop": 0, "tolerance": 6}]})");
  EXPECT_EQ(error_pointer(disc), "/parts/0/profile_tolerances/0");
  // non-tangent arc corner: refused, naming the edge
  std::string lens = with_parts(R"({"name": "p", "motion": "fixed",
      "loops": [{"start": [0, 0], "edges": [{"line_to": [6, 0]}, {"arc_to": [0, 0], "center": [3, 4], "dir": "ccw"}]}],
      "profile_tolerances": [{"loop": 0, "tolerance": 0.1}]})");
  EXPECT_EQ(error_pointer(lens).rfind("/parts/0/loops/0/edges/", 0), 0u) << error_pointer(lens);
  // a notch that closes on itself: an L-shaped loop offset inward past its narrow arm
  std::string notch = with_parts(R"({"name": "p", "motion": "fixed",
      "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 0]}, {"line_to": [10, 1]}, {"line_to": [1, 1]}, {"line_to": [1, 10]}, {"line_to": [0, 10]}, {"line_to": [0, 0]}]}],
      "profile_tolerances": [{"loop": 0, "tolerance": 3}]})");
  EXPECT_EQ(error_pointer(notch), "/parts/0/profile_tolerances/0");
  try {
    read_model(notch);
  } catch (const ModelError& error) {
    EXPECT_NE(std::string(error.what()).find("too wide"), std::string::npos) << error.what();
  }
}

TEST(ModelProfileTolerance, CamProfileBandsReachTheFollowerAsTheClosedForm) {
  // Eccentric cam (R = 20, e = 5) under a flat follower: lift s = R + e sin(theta) - 30 + dc + df
  // with dc the cam's profile offset (radius) and df the follower loop's (its face moves down).
  std::string text = R"({
    "hipair": 1, "name": "eccentric-cam-profile",
    "parameters": {"R": {"nominal": 20, "tolerance": 0.03}, "e": {"nominal": 5}},
    "parts": [
      {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
       "loops": [{"circle": {"center": ["e", 0], "radius": "R"}}],
       "profile_tolerances": [{"loop": 0, "tolerance": 0.04, "distribution": "uniform"}]},
      {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}},
       "initial": {"offset": -10},
       "loops": [{"start": [-40, 30], "edges": [{"line_to": [40, 30], "label": "face"}, {"line_to": [40, 40]},
                                               {"line_to": [-40, 40]}, {"line_to": [-40, 30]}]}],
       "profile_tolerances": [{"loop": 0, "tolerance": 0.02}],
       "dynamics": {"mass": 0.1, "force": [0, -10]}}
    ],
    "pairs": [{"parts": ["cam", "follower"]}]})";
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 24;
  options.monte_carlo = 100;
  options.seed = 5;
  ToleranceResult result = analyze_tolerances_text(text, options);
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    double sine = std::sin(s.driver);
    EXPECT_NEAR(s.nominal, 20 + 5 * sine - 30, 1e-9);
    double half = 0.03 + 0.02 + 0.01;   // R, cam band / 2, follower band / 2
    EXPECT_NEAR(s.linear_lower - s.nominal, -half, 1e-12);
    EXPECT_NEAR(s.linear_upper - s.nominal, half, 1e-12);
    EXPECT_LE(s.certified.lower, s.nominal - half + 1e-12);
    EXPECT_GE(s.certified.upper, s.nominal + half - 1e-12);
    ASSERT_TRUE(s.has_monte_carlo);
    EXPECT_GE(s.monte_carlo_min, s.certified.lower);
    EXPECT_LE(s.monte_carlo_max, s.certified.upper);
    ++checked;
  }
  EXPECT_GE(checked, 20u);
  ASSERT_TRUE(result.monte_carlo.has_value());
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  ASSERT_FALSE(result.regions.empty());
  bool cam = false, follower = false;
  for (const ParameterContribution& c : result.regions.front().ranked) {
    if (c.parameter == "profile-0-loop-0") cam = std::fabs(c.sensitivity - 1) < 1e-9;
    if (c.parameter == "profile-1-loop-0") follower = std::fabs(c.sensitivity - 1) < 1e-9;
  }
  EXPECT_TRUE(cam);
  EXPECT_TRUE(follower);
}

}  // namespace
}  // namespace hipair
