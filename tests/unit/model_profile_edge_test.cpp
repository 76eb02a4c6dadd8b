// A profile tolerance on one segment of a loop ("edge": the wheel's slot flank, a follower's
// face): the segment's line is offset by δ outward from the material and its two vertices slide
// along the neighbouring segments to it; nothing else moves (docs/model-format.md "Profile
// tolerances"). Oracle: the offset line intersected with each neighbour's line by Cramer's rule
// in exact rationals; and the tolerance analysis of a cam under a flat face whose face carries
// the band: the follower's worst case gains exactly the half band (a linear mechanism).
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>

namespace hipair {
namespace {

Rational q(long n, long d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

// A quadrilateral (0,0) (w,0) (w+s,h) (0,h), counter-clockwise, material inside; edge `edge`
// banded by t.
std::string quad(long w, long h, long s, int edge, const std::string& t) {
  auto str = [](long v) { return std::to_string(v); };
  return R"({"hipair": 1, "name": "quad", "parts": [{"name": "p", "motion": "fixed", "loops": [{"start": [0, 0], "edges": [
    {"line_to": [)" + str(w) + R"(, 0]}, {"line_to": [)" + str(w + s) + ", " + str(h) + R"(]},
    {"line_to": [0, )" + str(h) + R"(]}, {"line_to": [0, 0]}]}],
    "profile_tolerances": [{"loop": 0, "edge": )" + std::to_string(edge) + R"(, "tolerance": )" + t + R"(, "parameter": "d"}]}]})";
}

// Intersection of the line through p with direction u and the line {x : n.x = c}.
Point meet(const Point& p, const Point& u, const Point& n, const Rational& c) {
  Rational t = (c - (n.x * p.x + n.y * p.y)) / (n.x * u.x + n.y * u.y);
  return Point{Rational(p.x + t * u.x), Rational(p.y + t * u.y)};
}

TEST(ModelProfileEdge, OneSegmentMovesAlongItsNeighboursExactly) {
  std::mt19937 random(812);
  std::uniform_int_distribution<long> size(3, 40), slant(-2, 9), numerator(-100, 100);
  int cases = 0;
  while (cases < 60) {
    long w = size(random), h = size(random), s = slant(random);
    if (w + s <= 0) continue;
    // the edges with rational outward unit normals: 0 (bottom), 2 (top), 3 (left)
    int edge = std::array<int, 3>{0, 2, 3}[static_cast<std::size_t>(cases % 3)];
    std::string text = quad(w, h, s, edge, "\"1/5\"");   // band 0.2: d in [-1/10, 1/10]
    Rational d = q(numerator(random), 1000);
    ReadOptions options;
    options.parameter_values["d"] = d;
    Model m = read_model(text, "<test>", options);
    Model nominal = read_model(text);
    ++cases;
    SCOPED_TRACE("w " + std::to_string(w) + " h " + std::to_string(h) + " s " + std::to_string(s) + " edge " +
                 std::to_string(edge) + " d " + d.get_str());
    EXPECT_TRUE(m.roundings.empty());
    std::vector<Point> v0, v;
    for (const Edge& e : nominal.parts[0].loops[0].edges) v0.push_back(e.source);
    for (const Edge& e : m.parts[0].loops[0].edges) v.push_back(e.source);
    ASSERT_EQ(v.size(), 4u);
    ASSERT_EQ(v0.size(), 4u);
    // the reader keeps the written (counter-clockwise) order here
    ASSERT_EQ(v0[1], (Point{Rational(w), Rational(0)}));
    Point n = edge == 0 ? Point{0, -1} : edge == 2 ? Point{0, 1} : Point{-1, 0};
    std::size_t a = static_cast<std::size_t>(edge), b = (a + 1) % 4, prev = (a + 3) % 4, after = (a + 2) % 4;
    Rational c = n.x * v0[a].x + n.y * v0[a].y + d;   // the offset line
    Point expect_a = meet(v0[prev], Point{Rational(v0[a].x - v0[prev].x), Rational(v0[a].y - v0[prev].y)}, n, c);
    Point expect_b = meet(v0[b], Point{Rational(v0[after].x - v0[b].x), Rational(v0[after].y - v0[b].y)}, n, c);
    EXPECT_EQ(v[a], expect_a);
    EXPECT_EQ(v[b], expect_b);
    EXPECT_EQ(v[prev], v0[prev]);
    EXPECT_EQ(v[after], v0[after]);
  }
}

const char* cam_with_face_band = R"({
  "hipair": 1, "name": "eccentric-cam-face-band",
  "units": {"length": "mm", "angle": "rad"},
  "parameters": {"R": {"nominal": 20, "tolerance": 0.03}, "e": {"nominal": 5, "tolerance": 0.01}, "face": {"nominal": 30}},
  "parts": [
    {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
     "loops": [{"circle": {"center": ["e", 0], "radius": "R"}}]},
    {"name": "follower", "motion": {"translation": {"direction": [0, 1], "limits": [-20, 20]}},
     "initial": {"offset": -10},
     "loops": [{"start": [-40, "face"], "edges": [
        {"line_to": [40, "face"], "label": "face"}, {"line_to": [30, "face + 10"]},
        {"line_to": [-40, "face + 10"]}, {"line_to": [-40, "face"]}]}],
     "profile_tolerances": [{"loop": 0, "edge": 0, "tolerance": 0.04, "parameter": "face-profile"}],
     "dynamics": {"mass": 0.1, "force": [0, -10]}}
  ],
  "pairs": [{"parts": ["cam", "follower"]}]
})";

// s = R + e sin(theta) - face + delta: the band on the face adds its half width (0.02) to the
// worst case, exactly, with sensitivity 1.
TEST(ModelProfileEdge, FaceBandReachesTheFollowerAsTheClosedForm) {
  ToleranceOptions options;
  options.driver = "cam";
  options.positions = 48;
  options.relative_accuracy = 0.01;
  options.monte_carlo = 200;
  options.threads = 2;
  ToleranceResult result = analyze_tolerances_text(cam_with_face_band, options);
  std::size_t checked = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    double sine = std::sin(s.driver);
    double half = 0.03 + 0.01 * std::fabs(sine) + 0.02;
    EXPECT_NEAR(s.nominal, 20 + 5 * sine - 30, 1e-9);
    EXPECT_NEAR(s.linear_upper - s.nominal, half, 1e-12) << s.driver;
    EXPECT_NEAR(s.nominal - s.linear_lower, half, 1e-12) << s.driver;
    EXPECT_LE(s.certified.lower, s.nominal - half + 1e-12);
    EXPECT_GE(s.certified.upper, s.nominal + half - 1e-12);
    ++checked;
  }
  EXPECT_GE(checked, 40u);
  bool found = false;
  for (const ParameterContribution& c : result.regions.front().ranked)
    if (c.parameter == "face-profile") {
      found = true;
      EXPECT_NEAR(c.sensitivity, 1.0, 1e-12);
    }
  EXPECT_TRUE(found);
  ASSERT_TRUE(result.monte_carlo);
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
}

TEST(ModelProfileEdge, BadEdgesNameWhere) {
  auto message = [](const std::string& text) {
    try {
      read_model(text);
    } catch (const ModelError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  std::string base = quad(10, 5, 2, 0, "0.1");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  EXPECT_NE(message(with("\"edge\": 0", "\"edge\": 4")).find("/parts/0/profile_tolerances/0/edge"), std::string::npos);
  EXPECT_NE(message(with("\"edge\": 0", "\"edge\": 4")).find("has no edge"), std::string::npos);
  EXPECT_NE(message(with("\"edge\": 0", "\"edge\": -1")).find("/parts/0/profile_tolerances/0/edge"), std::string::npos);
  EXPECT_NE(message(with("\"loop\": 0, \"edge\": 0", "\"feature\": 0, \"edge\": 0")).find("profile_tolerances/0"),
            std::string::npos);
  // an arc neighbour
  std::string arc = R"({"hipair": 1, "name": "stadium", "parts": [{"name": "p", "motion": "fixed", "loops": [{"start": [0, 0], "edges": [
    {"line_to": [10, 0]}, {"arc_to": [10, 4], "center": [10, 2], "dir": "ccw"}, {"line_to": [0, 4]},
    {"arc_to": [0, 0], "center": [0, 2], "dir": "ccw"}]}],
    "profile_tolerances": [{"loop": 0, "edge": 0, "tolerance": 0.1}]}]})";
  std::string m = message(arc);
  EXPECT_NE(m.find("/parts/0/profile_tolerances/0/edge"), std::string::npos) << m;
  EXPECT_NE(m.find("neighbour is an arc"), std::string::npos) << m;
  std::string on_arc = arc;
  on_arc.replace(on_arc.find("\"edge\": 0"), 9, "\"edge\": 1");
  EXPECT_NE(message(on_arc).find("is an arc"), std::string::npos) << message(on_arc);
  // the band's extremes are checked as for whole loops: a band wider than the quad
  EXPECT_NE(message(quad(10, 5, 2, 0, "20")).find("too wide"), std::string::npos) << message(quad(10, 5, 2, 0, "20"));
}

}  // namespace
}  // namespace hipair
