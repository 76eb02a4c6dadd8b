// Feature templates: exact geometry (every arc endpoint exactly on its circle, loops closed),
// simple loops (checked exactly by the model reader), edge counts, and errors with pointers.
#include "model/templates.hpp"

#include "core/model_scale.hpp"
#include "model/parametric/parametric.hpp"
#include "model/parametric/certified_positive.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>
#include "test_seed.hpp"
#include "random_rationals.hpp"
#include <mpfi.h>

#include <cmath>
#include <algorithm>
#include <functional>
#include <optional>
#include <iostream>
#include <random>
#include <set>
#include <sstream>

namespace hipair::model_detail {
namespace {

using Arguments = std::map<std::string, TemplateValue>;

Rational q(const std::string& text) { return parse_rational(text); }
Point at(const std::string& x, const std::string& y) { return Point{q(x), q(y)}; }
Rational squared_distance(const Point& a, const Point& b) {
  return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}
Rational squared_norm(const Point& a) { return a.x * a.x + a.y * a.y; }
// A decimal approximation as an exact rational (for test arguments computed in double).
Rational decimal(double value) {
  std::ostringstream out;
  out.precision(6);
  out << std::fixed << value;
  return q(out.str());
}

// Every loop closes, every arc endpoint lies exactly on its circle, every edge is labelled.
void expect_exact_loops(const std::vector<Loop>& loops) {
  ASSERT_FALSE(loops.empty());
  for (const Loop& loop : loops) {
    ASSERT_FALSE(loop.edges.empty());
    for (std::size_t i = 0; i < loop.edges.size(); ++i) {
      const Edge& edge = loop.edges[i];
      const Edge& next = loop.edges[(i + 1) % loop.edges.size()];
      EXPECT_EQ(edge.target, next.source) << "edge " << i << " (" << edge.label << ")";
      EXPECT_FALSE(edge.label.empty()) << "edge " << i;
      if (edge.is_arc()) {
        EXPECT_GT(edge.radius_squared, 0);
        EXPECT_EQ(squared_distance(edge.source, edge.center), edge.radius_squared)
            << edge.label;
        EXPECT_EQ(squared_distance(edge.target, edge.center), edge.radius_squared)
            << edge.label;
      } else {
        EXPECT_FALSE(edge.source == edge.target) << edge.label;
      }
    }
  }
}

std::size_t edge_count(const std::vector<Loop>& loops) {
  std::size_t count = 0;
  for (const Loop& loop : loops) count += loop.edges.size();
  return count;
}

Arguments geneva_wheel_arguments(int slots) {
  // A workable wheel for `slots` slots at centre distance 80 (see docs/examples.md).
  double d = 80, half = M_PI / slots;
  double crank = d * std::sin(half), wheel = d * std::cos(half);
  double lock = crank - 6;
  double cosine = (d * d + lock * lock - wheel * wheel) / (2 * d * lock);
  double span = 2 * std::acos(cosine) * 0.95;
  return Arguments{{"center", at("0", "0")},
                   {"slots", Rational(slots)},
                   {"slot_width", q("6")},
                   {"slot_inner_radius", decimal(d - crank - 2)},
                   {"slot_outer_radius", decimal(wheel + 2)},
                   {"lock_center_radius", q("80")},
                   {"lock_radius", decimal(lock)},
                   {"lock_span", decimal(span)}};
}

Arguments spur_gear_arguments(int teeth) {
  return Arguments{{"center", at("0", "0")},
                   {"teeth", Rational(teeth)},
                   {"pitch_radius", Rational(teeth)},  // module 2
                   {"addendum", q("2")},
                   {"dedendum", q("2.5")},
                   {"tooth_thickness", q("3.09")}};
}

// Whether a non-negative rational is the square of a rational (both parts perfect squares: the
// rational is reduced).
bool is_rational_square(const Rational& square) {
  mpz_class n = square.get_num(), d = square.get_den();
  return sgn(n) >= 0 && mpz_perfect_square_p(n.get_mpz_t()) && mpz_perfect_square_p(d.get_mpz_t());
}

// JSON of a one-part model whose only feature is `feature` (a JSON object text).
std::string model_with_feature(const std::string& feature) {
  return R"({"hipair": 1, "name": "t", "parts": [{"name": "p", "motion": "fixed",
             "features": [)" + feature + "]}]}";
}

TEST(Templates, SpecsListEveryTemplateOnce) {
  std::set<std::string> names;
  for (const TemplateSpec& spec : template_specs()) {
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
    EXPECT_FALSE(spec.arguments.empty()) << spec.name;
  }
  for (const char* name : {"circle", "pin", "geneva_wheel", "geneva_driver", "spur_gear",
                           "ratchet_wheel", "escape_wheel", "anchor", "balance"})
    EXPECT_TRUE(names.count(name)) << name;
}

TEST(Templates, CircleAndPinAreFullCircles) {
  std::vector<Rounding> roundings;
  auto loops = expand_template("pin", {{"center", at("3", "-1/3")}, {"radius", q("4.5")}},
                               "/f", roundings);
  ASSERT_EQ(loops.size(), 1u);
  ASSERT_EQ(loops[0].edges.size(), 1u);
  EXPECT_TRUE(loops[0].edges[0].is_full_circle());
  EXPECT_EQ(loops[0].edges[0].label, "pin");
  EXPECT_EQ(loops[0].edges[0].radius_squared, q("4.5") * q("4.5"));
  EXPECT_TRUE(roundings.empty());
}

TEST(Templates, GenevaWheelIsExactForThreeToEightSlots) {
  for (int slots = 3; slots <= 8; ++slots) {
    SCOPED_TRACE(slots);
    std::vector<Rounding> roundings;
    auto loops = expand_template("geneva_wheel", geneva_wheel_arguments(slots), "/f", roundings);
    expect_exact_loops(loops);
    EXPECT_EQ(edge_count(loops), static_cast<std::size_t>(6 * slots));
    for (const Rounding& rounding : roundings) EXPECT_GT(rounding.bound, 0);
    // The locking arc centres lie exactly at distance 80 from the wheel centre.
    for (const Edge& edge : loops[0].edges)
      if (edge.label.rfind("lock arc", 0) == 0)
        EXPECT_EQ(squared_distance(edge.center, Point{0, 0}), Rational(6400));
  }
}

// A pin's tangency to a slot wall is a contact curve of degree 2 in each half-angle tangent only
// when the pin's radius times the wall's length is rational (kernels/contact_table.hpp); the
// walls and the mouths have rational lengths (the walls' ends within the recorded bound of
// slot_outer_radius) for generated wheel sizes; likewise the balance's impulse pin keeps its rational radius
// (the rim passes through exact points of the pin circle).
TEST(Templates, SlotWallsAndImpulsePinsGiveDegreeTwoTangencies) {
  std::mt19937_64 random(2718);
  for (int slots = 3; slots <= 8; ++slots) {
    for (int trial = 0; trial < 4; ++trial) {
      SCOPED_TRACE(std::to_string(slots) + " slots, trial " + std::to_string(trial));
      Arguments a = geneva_wheel_arguments(slots);
      // outer radius moved by a random number of thousandths (the fit stays workable)
      Rational outer = std::get<Rational>(a["slot_outer_radius"]) + decimal(static_cast<double>(static_cast<long>(random() % 2001) - 1000) / 1000);
      a["slot_outer_radius"] = outer;
      std::vector<Rounding> roundings;
      auto loops = expand_template("geneva_wheel", a, "/f", roundings);
      expect_exact_loops(loops);
      Rational bound = 0;
      for (const Rounding& rounding : roundings)
        if (rounding.expression.find(" length (rational") != std::string::npos) bound = std::max(bound, rounding.bound);
      ASSERT_GT(bound, 0);
      std::size_t walls = 0, mouths = 0;
      for (const Edge& edge : loops[0].edges) {
        if (edge.label.find(" mouth ") != std::string::npos) {
          // the mouths (wall end to locking arc) too: the pin reaches them on three-slot wheels
          ++mouths;
          EXPECT_TRUE(is_rational_square(squared_distance(edge.source, edge.target))) << edge.label;
        }
        if (edge.label.find(" wall ") == std::string::npos) continue;
        ++walls;
        ASSERT_FALSE(edge.is_arc());
        EXPECT_TRUE(is_rational_square(squared_distance(edge.source, edge.target))) << edge.label;
        // the wall's outer end within the bound of the circle slot_outer_radius
        const Point& end = squared_norm(edge.source) > squared_norm(edge.target) ? edge.source : edge.target;
        EXPECT_GE(squared_norm(end), (outer - bound) * (outer - bound)) << edge.label;
        EXPECT_LE(squared_norm(end), (outer + bound) * (outer + bound)) << edge.label;
      }
      EXPECT_EQ(walls, static_cast<std::size_t>(2 * slots));
      EXPECT_EQ(mouths, static_cast<std::size_t>(2 * slots));
    }
  }
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE("balance trial " + std::to_string(trial));
    auto eighths = [&](long n) {
      Rational r(n, 8);
      r.canonicalize();
      return r;
    };
    Rational radius = eighths(20 + static_cast<long>(random() % 21));                 // 2.5 .. 5
    Rational pin_radius = eighths(4 + static_cast<long>(random() % 9));               // 0.5 .. 1.5
    Rational pin_centre = radius + eighths(static_cast<long>(random() % 7) - 3);      // the pin sticks out
    std::vector<Rounding> roundings;
    auto balance = expand_template("balance",
                                   {{"center", at("1", "48")}, {"radius", radius}, {"pin_radius", pin_radius},
                                    {"pin_center_radius", pin_centre}, {"phase", decimal(static_cast<double>(random() % 629) / 100)}},
                                   "/f", roundings);
    expect_exact_loops(balance);
    ASSERT_EQ(edge_count(balance), 2u);
    for (const Edge& edge : balance[0].edges) {
      ASSERT_TRUE(edge.is_arc());
      if (edge.label == "impulse pin") EXPECT_EQ(edge.radius_squared, pin_radius * pin_radius);
      if (edge.label == "rim") {
        Rational slack(1, 1000000000);
        EXPECT_GE(edge.radius_squared, (radius - slack) * (radius - slack));
        EXPECT_LE(edge.radius_squared, (radius + slack) * (radius + slack));
      }
    }
  }
}

TEST(Templates, GenevaWheelLoopsAreSimpleForThreeToEightSlots) {
  // The reader checks exactly that no loop crosses itself.
  for (int slots = 3; slots <= 8; ++slots) {
    SCOPED_TRACE(slots);
    Arguments a = geneva_wheel_arguments(slots);
    auto text = [&](const std::string& key) { return to_exact_string(std::get<Rational>(a[key])); };
    std::string feature = R"({"geneva_wheel": {"center": [0, 0], "slots": )" +
                          std::to_string(slots) + R"(, "slot_width": 6, "slot_inner_radius": ")" +
                          text("slot_inner_radius") + R"(", "slot_outer_radius": ")" +
                          text("slot_outer_radius") + R"(", "lock_center_radius": 80,
                          "lock_radius": ")" + text("lock_radius") + R"(", "lock_span": ")" +
                          text("lock_span") + R"("}})";
    Model model;
    ASSERT_NO_THROW(model = read_model(model_with_feature(feature))) << feature;
    ASSERT_EQ(model.parts[0].loops.size(), 1u);
  }
}

TEST(Templates, GenevaWheelQuarterTurnsAreExact) {
  // With phase 0 and 4 slots the locking arcs sit at multiples of pi/2: no rounding there.
  std::vector<Rounding> roundings;
  auto loops = expand_template("geneva_wheel", geneva_wheel_arguments(4), "/f", roundings);
  std::set<std::pair<std::string, std::string>> centres;
  for (const Edge& edge : loops[0].edges)
    if (edge.label.rfind("lock arc", 0) == 0)
      centres.insert({to_exact_string(edge.center.x), to_exact_string(edge.center.y)});
  std::set<std::pair<std::string, std::string>> expected = {
      {"80", "0"}, {"0", "80"}, {"-80", "0"}, {"0", "-80"}};
  EXPECT_EQ(centres, expected);
}

TEST(Templates, GenevaDriverHasPinAndCrescent) {
  std::vector<Rounding> roundings;
  Arguments a{{"center", at("80", "0")},         {"pin_radius", q("4.5")},
              {"pin_center_radius", q("56.5")},  {"lock_outer_radius", q("46")},
              {"lock_inner_radius", q("36")},    {"lock_span", q("4.9416")}};
  auto loops = expand_template("geneva_driver", a, "/f", roundings);
  expect_exact_loops(loops);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].edges[0].label, "pin");
  EXPECT_EQ(loops[0].edges[0].center, at("136.5", "0"));
  EXPECT_EQ(loops[1].edges.size(), 4u);
  // Default offset -span/2: the crescent is symmetric about the direction away from the pin.
  const Edge& outer = loops[1].edges[0];
  EXPECT_EQ(outer.source.x, outer.target.x);
  EXPECT_EQ(outer.source.y, -outer.target.y);
}

TEST(Templates, SpurGearEdgeCounts) {
  std::vector<Rounding> roundings;
  // z = 18, module 2: the root circle (15.5) lies inside the base circle (16.9): each flank
  // is a radial segment and two arcs -> 8 edges per tooth.
  auto small = expand_template("spur_gear", spur_gear_arguments(18), "/f", roundings);
  expect_exact_loops(small);
  EXPECT_EQ(edge_count(small), 8u * 18);
  // z = 60: the root circle (57.5) lies outside the base circle (56.4): two arcs per flank.
  auto large = expand_template("spur_gear", spur_gear_arguments(60), "/f", roundings);
  expect_exact_loops(large);
  EXPECT_EQ(edge_count(large), 6u * 60);
  // With an explicit flank radius: one arc per flank -> 4 edges per tooth.
  Arguments single = spur_gear_arguments(25);
  single["flank_radius"] = q("8.5");
  auto one_arc = expand_template("spur_gear", single, "/f", roundings);
  expect_exact_loops(one_arc);
  EXPECT_EQ(edge_count(one_arc), 4u * 25);
}

// Session 9 (issue 14 item 3): the tip vertices are no longer exactly on the tip circle. Each
// upper flank arc's centre is on the normal at the pitch point at a rounded (small) distance,
// and its tip end is the exact point of that circle next to the involute's tip point: the
// flank's centre and squared radius drop from ~200 to ~50 bits (the gears' contact polynomials
// from 248 to 205 bits, median). What stays exact: every tip arc is centred on the gear's
// centre with both ends equidistant from it (mirror images), and each tip lies within its
// recorded displacement bound (plus the double-precision construction of the ideal point,
// 20 mm * 2^-52 * a few operations < 1e-13 mm) of the radius-20 tip circle.
TEST(Templates, SpurGearTipAndRootVerticesLieWithinTheirRecordedDisplacementsOfTheirCircles) {
  std::vector<Rounding> roundings;
  auto loops = expand_template("spur_gear", spur_gear_arguments(18), "/f", roundings);
  Rational tip_bound = 0;
  for (const Rounding& rounding : roundings)
    if (rounding.expression.find("upper tooth flank arc") != std::string::npos &&
        rounding.expression.find(" end:") != std::string::npos)
      tip_bound = std::max(tip_bound, rounding.bound);
  ASSERT_GT(tip_bound, 0);
  EXPECT_LT(tip_bound, Rational(1, 1000000000));   // a displacement of the order of 20 mm * b
  Rational slack = tip_bound + Rational(1, 10000000000000L);
  Rational root_bound = 0;
  for (const Rounding& rounding : roundings)
    if (rounding.expression.find("radial below the base circle") != std::string::npos)
      root_bound = std::max(root_bound, rounding.bound);
  ASSERT_GT(root_bound, 0);
  std::size_t tips = 0, roots = 0;
  for (const Edge& edge : loops[0].edges) {
    if (edge.label.find(" tip") != std::string::npos) {
      ++tips;
      EXPECT_EQ(edge.center, at("0", "0"));
      EXPECT_EQ(squared_distance(edge.source, edge.center), edge.radius_squared);
      EXPECT_EQ(squared_distance(edge.target, edge.center), edge.radius_squared);
      EXPECT_GE(edge.radius_squared, (20 - slack) * (20 - slack));
      EXPECT_LE(edge.radius_squared, (20 + slack) * (20 + slack));
    }
    if (edge.label.find(" root") != std::string::npos) {
      // the root arcs are exact arcs about the centre between the radial segments' feet, which
      // lie within their recorded displacement of the root circle (rational segment lengths)
      ++roots;
      EXPECT_EQ(edge.center, at("0", "0"));
      EXPECT_EQ(squared_distance(edge.source, edge.center), edge.radius_squared);
      EXPECT_EQ(squared_distance(edge.target, edge.center), edge.radius_squared);
      EXPECT_GE(edge.radius_squared, (q("15.5") - root_bound) * (q("15.5") - root_bound));
      EXPECT_LE(edge.radius_squared, (q("15.5") + root_bound) * (q("15.5") + root_bound));
    }
  }
  EXPECT_EQ(tips, 18u);
  EXPECT_EQ(roots, 18u);
}

// Below the base circle each flank is a radial segment of rational length (the foot is moved
// off the root circle by its recorded displacement instead), so that a rational arc radius times
// its length is rational and an arc's tangency to it stays a contact curve of degree 2 in each
// half-angle tangent (kernels/contact_table.hpp). Small tooth counts, whose tips reach the other
// gear's radial segments, must therefore build every chart on the quadratic traits.
TEST(Templates, SpurGearRadialSegmentsHaveRationalLengthsOnEveryToothCount) {
  for (int teeth : {5, 6, 7, 9, 12, 17, 18, 27, 40, 41, 42, 80, 151}) {
    SCOPED_TRACE("teeth " + std::to_string(teeth));
    std::vector<Rounding> roundings;
    auto loops = expand_template("spur_gear", spur_gear_arguments(teeth), "/f", roundings);
    Rational bound = 0;
    for (const Rounding& rounding : roundings)
      if (rounding.expression.find("radial below the base circle") != std::string::npos)
        bound = std::max(bound, rounding.bound);
    std::size_t radials = 0;
    for (const Edge& edge : loops[0].edges) {
      if (edge.label.find(" radial") == std::string::npos) continue;
      ++radials;
      ASSERT_FALSE(edge.is_arc());
      Rational length2 = squared_distance(edge.source, edge.target);
      EXPECT_TRUE(is_rational_square(length2)) << edge.label << ": squared length " << length2;
      // the foot (the end nearer the centre) within its recorded displacement of the root circle
      const Point& foot = squared_distance(edge.source, Point{0, 0}) < squared_distance(edge.target, Point{0, 0})
                              ? edge.source
                              : edge.target;
      Rational root = Rational(teeth) - q("2.5"), r2 = squared_distance(foot, Point{0, 0});
      EXPECT_GE(r2, (root - bound) * (root - bound)) << edge.label;
      EXPECT_LE(r2, (root + bound) * (root + bound)) << edge.label;
    }
    // a radial segment on both flanks of every tooth while the base circle (0.94 z) lies above
    // the root circle (z - 2.5), i.e. below 42 teeth
    EXPECT_EQ(radials, teeth < 42 ? static_cast<std::size_t>(2 * teeth) : 0u);
    if (radials > 0) {
      EXPECT_GT(bound, 0);
      EXPECT_LT(bound, Rational(1, 1000000000));
    }
  }
}

TEST(Templates, SpurGearFlanksAreSymmetricAndTangentAtThePitchPoint) {
  std::vector<Rounding> roundings;
  auto loops = expand_template("spur_gear", spur_gear_arguments(18), "/f", roundings);
  const auto& edges = loops[0].edges;
  // Tooth 1 (axis along +x): R lower, R upper arcs meet at the pitch point, their centres and
  // that point are collinear (a common tangent), exactly.
  const Edge* lower = nullptr;
  const Edge* upper = nullptr;
  for (const Edge& edge : edges) {
    if (edge.label == "tooth 1 flank R lower") lower = &edge;
    if (edge.label == "tooth 1 flank R upper") upper = &edge;
  }
  ASSERT_TRUE(lower && upper);
  EXPECT_EQ(lower->target, upper->source);
  EXPECT_EQ(squared_distance(upper->source, Point{0, 0}), Rational(18 * 18));
  Point p = upper->source;
  Rational cross = (lower->center.x - p.x) * (upper->center.y - p.y) -
                   (lower->center.y - p.y) * (upper->center.x - p.x);
  EXPECT_EQ(cross, 0);
}

TEST(Templates, RatchetAndEscapeWheelsAreExact) {
  std::vector<Rounding> roundings;
  auto ratchet = expand_template("ratchet_wheel",
                                 {{"center", at("1", "2")},
                                  {"teeth", Rational(12)},
                                  {"tip_radius", q("30")},
                                  {"root_radius", q("24")},
                                  {"dir", std::string("cw")}},
                                 "/f", roundings);
  expect_exact_loops(ratchet);
  EXPECT_EQ(edge_count(ratchet), 24u);
  for (const Edge& edge : ratchet[0].edges) {
    Rational r2 = squared_distance(edge.source, at("1", "2"));
    EXPECT_TRUE(r2 == 900 || r2 == 576) << edge.label;
  }
  auto escape = expand_template("escape_wheel",
                                {{"center", at("0", "0")},
                                 {"teeth", Rational(15)},
                                 {"tip_radius", q("20")},
                                 {"root_radius", q("15")},
                                 {"face_angle", q("0.07")},
                                 {"back_angle", q("0.17")},
                                 {"tip_angle", q("0.02")}},
                                "/f", roundings);
  expect_exact_loops(escape);
  EXPECT_EQ(edge_count(escape), 4u * 15);  // root arc, back, top, face
}

TEST(Templates, AnchorAndBalanceAreExactAndSimple) {
  std::vector<Rounding> roundings;
  Arguments anchor{{"center", at("0", "23.094")},  {"wheel_center", at("0", "0")},
                   {"wheel_radius", q("20")},      {"pallet_width", q("3.6")},
                   {"lift", q("0.1047")},          {"lock", q("0.0349")},
                   {"fork_length", q("21.7")},     {"fork_width", q("5")},
                   {"fork_slot_width", q("2.7")},  {"fork_slot_depth", q("2.4")}};
  auto loops = expand_template("anchor", anchor, "/f", roundings);
  expect_exact_loops(loops);
  EXPECT_EQ(edge_count(loops), 17u);
  // every side of the fork (which the balance's impulse pin touches) has a rational length, so
  // the pin's tangencies are contact curves of degree 2 (kernels/contact_table.hpp)
  std::size_t fork_sides = 0;
  for (const Edge& edge : loops[0].edges)
    if (edge.label.rfind("fork ", 0) == 0) {
      ++fork_sides;
      ASSERT_FALSE(edge.is_arc()) << edge.label;
      EXPECT_TRUE(is_rational_square(squared_distance(edge.source, edge.target))) << edge.label;
    }
  EXPECT_EQ(fork_sides, 7u);
  auto balance = expand_template("balance",
                                 {{"center", at("0", "48")},
                                  {"radius", q("3")},
                                  {"pin_radius", q("1.2")},
                                  {"pin_center_radius", q("4")}},
                                 "/f", roundings);
  expect_exact_loops(balance);
  EXPECT_EQ(edge_count(balance), 2u);
  // Both outlines pass the reader's exact simplicity checks.
  EXPECT_NO_THROW(read_model(model_with_feature(
      R"({"anchor": {"center": [0, 23.094], "wheel_center": [0, 0], "wheel_radius": 20,
          "pallet_width": 3.6, "lift": 0.1047, "lock": 0.0349, "fork_length": 21.7,
          "fork_width": 5, "fork_slot_width": 2.7, "fork_slot_depth": 2.4}},
         {"balance": {"center": [0, 48], "radius": 3, "pin_radius": 1.2,
          "pin_center_radius": 4}})")));
}

// Expects expand_template to throw a ModelError at `pointer`.
void expect_error_at(const std::string& name, const Arguments& arguments,
                     const std::string& pointer) {
  std::vector<Rounding> roundings;
  try {
    expand_template(name, arguments, "/parts/0/features/0/" + name, roundings);
    ADD_FAILURE() << "no error for " << name << ", expected one at " << pointer;
  } catch (const ModelError& error) {
    EXPECT_EQ(error.pointer(), "/parts/0/features/0/" + name + pointer) << error.what();
    EXPECT_FALSE(error.reason().empty());
  }
}

TEST(Templates, BadValuesThrowModelErrorsWithPointers) {
  expect_error_at("circle", {{"center", at("0", "0")}, {"radius", q("-1")}}, "/radius");
  expect_error_at("circle", {{"center", at("0", "0")}}, "/radius");  // missing
  Arguments wide = geneva_wheel_arguments(6);
  wide["slot_width"] = q("72");  // wider than a 60-degree sector at slot_outer_radius
  expect_error_at("geneva_wheel", wide, "/slot_width");
  Arguments three = geneva_wheel_arguments(4);
  three["slots"] = Rational(2);
  expect_error_at("geneva_wheel", three, "/slots");
  Arguments shallow = geneva_wheel_arguments(4);
  shallow["slot_inner_radius"] = q("2");
  expect_error_at("geneva_wheel", shallow, "/slot_inner_radius");
  Arguments pointed = spur_gear_arguments(18);
  pointed["addendum"] = q("6");
  expect_error_at("spur_gear", pointed, "/addendum");
  Arguments thick = spur_gear_arguments(18);
  thick["tooth_thickness"] = q("7");
  expect_error_at("spur_gear", thick, "/tooth_thickness");
  expect_error_at("ratchet_wheel",
                  {{"center", at("0", "0")},
                   {"teeth", Rational(12)},
                   {"tip_radius", q("20")},
                   {"root_radius", q("20")}},
                  "/root_radius");
  expect_error_at("ratchet_wheel",
                  {{"center", at("0", "0")},
                   {"teeth", Rational(12)},
                   {"tip_radius", q("20")},
                   {"root_radius", q("10")},
                   {"dir", std::string("up")}},
                  "/dir");
  expect_error_at("balance",
                  {{"center", at("0", "0")},
                   {"radius", q("3")},
                   {"pin_radius", q("1")},
                   {"pin_center_radius", q("5")}},
                  "/pin_center_radius");
  expect_error_at("geneva_driver",
                  {{"center", at("0", "0")},
                   {"pin_radius", q("4")},
                   {"pin_center_radius", q("40")},
                   {"lock_outer_radius", q("46")},
                   {"lock_inner_radius", q("36")},
                   {"lock_span", q("4")},
                   {"lock_offset", q("1.5")}},  // the crescent covers the pin's direction
                  "/pin_center_radius");
  std::vector<Rounding> roundings;
  try {
    expand_template("sprocket", {}, "/parts/0/features/3/sprocket", roundings);
    ADD_FAILURE() << "unknown template accepted";
  } catch (const ModelError& error) {
    EXPECT_EQ(error.pointer(), "/parts/0/features/3/sprocket");
  }
}

TEST(Templates, RoundingsCarryPointersAndBounds) {
  std::vector<Rounding> roundings;
  expand_template("spur_gear", spur_gear_arguments(18), "/parts/1/features/0/spur_gear",
                  roundings);
  ASSERT_FALSE(roundings.empty());
  for (const Rounding& rounding : roundings) {
    EXPECT_EQ(rounding.pointer.rfind("/parts/1/features/0/spur_gear", 0), 0u) << rounding.pointer;
    EXPECT_GT(rounding.bound, 0);
    EXPECT_LT(rounding.bound, q("1/1000000"));
  }
}


// Session 61 (tol61b): the templates' rules are decided exactly at their bounds. Until session
// 60 the rational rules were exact comparisons and the angle rules double comparisons; session
// 61's shared rules enclosed every margin in double intervals and refused valid vectors within
// about 1e-15 (relative) of a bound. Generated: for every rule of every template a vector exactly
// ON the bound where the bound is rational (every rule is strict: refused), 2^-k above and below
// it (k = 40 ... 200), and, where the bound is irrational (pi, sin, a square root), its MPFI
// enclosure's two ends at 4096 bits (within 2^-4000 of it) and 2^-k beyond them; lengths at
// scales 1, 1e-300 and 1e400. The oracle: the rule's closed form (the bound B exact or enclosed),
// a vector passing iff it lies on the rule's side of B. Expected: refused by that rule (its
// pointer and message) exactly when it does not pass; a passing vector may still be refused by
// a later rule or constructive check (counted, not allowed to be this rule).
struct Bound {
  Rational lo, hi;   // B in [lo, hi]; lo == hi: B exact, else lo < B < hi
};

// An MPFI enclosure at 4096 bits, as rationals (the function `f` writes it).
Bound enclosed(const std::function<void(mpfi_ptr)>& f) {
  mpfi_t x;
  mpfi_init2(x, 4096);
  f(x);
  mpfr_t end;
  mpfr_init2(end, 4096);
  Bound b;
  mpfi_get_left(end, x);
  mpfr_get_q(b.lo.get_mpq_t(), end);
  mpfi_get_right(end, x);
  mpfr_get_q(b.hi.get_mpq_t(), end);
  mpfr_clear(end);
  mpfi_clear(x);
  return b;
}

Bound exactly(const Rational& b) { return Bound{b, b}; }

// sqrt(q) enclosed.
Bound root_of(const Rational& q_value) {
  return enclosed([&](mpfi_ptr x) {
    mpfi_set_q(x, q_value.get_mpq_t());
    mpfi_sqrt(x, x);
  });
}

Rational power_of_two(int k) {   // 2^-k
  mpz_class d;
  mpz_ui_pow_ui(d.get_mpz_t(), 2, static_cast<unsigned long>(k));
  return Rational(mpz_class(1), d);
}

using test_numbers::power_of_ten;

struct RuleCase {
  std::string name, key, refusal;   // the template, the argument the rule names, its message (part)
  int side;                         // +1: the argument must exceed B; -1: stay below it
  bool length;                      // the varied argument is a length (scaled with the others)
  Bound bound;                      // B at scale 1
  std::function<Arguments(const Rational& x, const Rational& scale)> arguments;
};

// The 28 rules of the 7 templates with their bounds (at scale 1) and argument vectors.
std::vector<RuleCase> rule_cases() {
  auto L = [](const char* text, const Rational& s) { return Rational(q(text) * s); };
  auto P = [](const char* x, const char* y, const Rational& s) { return Point{Rational(q(x) * s), Rational(q(y) * s)}; };
  const Rational milli(1, 1000000000);   // the angle rules' 1e-9
  auto pi_times = [](const Rational& factor, const Rational& minus) {   // factor pi - minus
    return enclosed([=](mpfi_ptr x) {
      mpfi_const_pi(x);
      mpfi_mul_q(x, x, factor.get_mpq_t());
      mpfi_sub_q(x, x, minus.get_mpq_t());
    });
  };
  // geneva_wheel (4 slots, docs/examples.md's proportions; slot_width 6)
  auto wheel = [=](const Rational& s) {
    Arguments a = geneva_wheel_arguments(4);
    for (const char* key : {"slot_width", "slot_inner_radius", "slot_outer_radius", "lock_center_radius", "lock_radius"})
      a[key] = Rational(std::get<Rational>(a[key]) * s);
    return a;
  };
  const Rational inner4 = std::get<Rational>(geneva_wheel_arguments(4)["slot_inner_radius"]);
  auto anchor = [=](const Rational& s, const char* y) {
    return Arguments{{"center", P("0", y, s)},         {"wheel_center", P("0", "0", s)},
                     {"wheel_radius", L("20", s)},     {"pallet_width", L("3.6", s)},
                     {"lift", q("0.1047")},            {"lock", q("0.0349")},
                     {"fork_length", L("21.7", s)},    {"fork_width", L("5", s)},
                     {"fork_slot_width", L("2.7", s)}, {"fork_slot_depth", L("2.4", s)}};
  };
  const Rational tangent2 = q("23.094") * q("23.094") - 400;   // the base anchor's squared tangent length
  auto escape = [=](const Rational& s) {
    return Arguments{{"center", P("0", "0", s)}, {"teeth", Rational(15)},   {"tip_radius", L("20", s)},
                     {"root_radius", L("15", s)}, {"face_angle", q("0.07")}, {"back_angle", q("0.17")},
                     {"tip_angle", q("0.02")}};
  };
  auto driver = [=](const Rational& s) {
    return Arguments{{"center", P("80", "0", s)},          {"pin_radius", L("4.5", s)},
                     {"pin_center_radius", L("56.5", s)}, {"lock_outer_radius", L("46", s)},
                     {"lock_inner_radius", L("36", s)},   {"lock_span", q("4.9416")}};
  };
  auto balance = [=](const Rational& s) {
    return Arguments{{"center", P("0", "48", s)}, {"radius", L("3", s)}, {"pin_radius", L("1.2", s)},
                     {"pin_center_radius", L("4", s)}};
  };
  auto gear = [=](const Rational& s) {
    Arguments a = spur_gear_arguments(20);
    for (const char* key : {"pitch_radius", "addendum", "dedendum", "tooth_thickness"})
      a[key] = Rational(std::get<Rational>(a[key]) * s);
    a["pressure_angle"] = q("0.35");
    return a;
  };
  auto with = [](Arguments a, const char* key, const TemplateValue& value) {
    a[key] = value;
    return a;
  };
  return std::vector<RuleCase>{
      {"geneva_wheel", "slot_inner_radius", "would reach the wheel centre", +1, true, exactly(3),
       [=](const Rational& x, const Rational& s) { return with(wheel(s), "slot_inner_radius", x); }},
      {"geneva_wheel", "slot_outer_radius", "must reach beyond the slot bottom", +1, true, exactly(5),   // 3, 4, 5
       [=](const Rational& x, const Rational& s) {
         return with(with(wheel(s), "slot_inner_radius", Rational(4 * s)), "slot_outer_radius", x);
       }},
      {"geneva_wheel", "slot_outer_radius", "must reach beyond the slot bottom", +1, true,
       root_of(Rational(inner4 * inner4 + 9)),
       [=](const Rational& x, const Rational& s) { return with(wheel(s), "slot_outer_radius", x); }},
      {"geneva_wheel", "lock_radius", "would enclose the wheel centre", -1, true, exactly(80),
       [=](const Rational& x, const Rational& s) { return with(wheel(s), "lock_radius", x); }},
      {"geneva_wheel", "lock_span", "strictly between 0 and 180", -1, false, pi_times(1, milli),
       [=](const Rational& x, const Rational& s) { return with(wheel(s), "lock_span", x); }},
      {"geneva_wheel", "slot_width", "too wide", -1, true,   // 6 slots: 2 * 60 sin(pi/6 - 1e-9)
       enclosed([=](mpfi_ptr x) {
         mpfi_const_pi(x);
         mpfi_div_ui(x, x, 6);
         mpfi_sub_q(x, x, milli.get_mpq_t());
         mpfi_sin(x, x);
         mpfi_mul_ui(x, x, 120);
       }),
       [=](const Rational& x, const Rational& s) {
         Arguments a = geneva_wheel_arguments(6);
         for (const char* key : {"lock_center_radius", "lock_radius"}) a[key] = Rational(std::get<Rational>(a[key]) * s);
         a["slot_outer_radius"] = Rational(60 * s);
         a["slot_inner_radius"] = Rational(40 * s);
         a["slot_width"] = x;
         return a;
       }},
      {"geneva_driver", "lock_inner_radius", "must be less than lock_outer_radius", -1, true, exactly(46),
       [=](const Rational& x, const Rational& s) { return with(driver(s), "lock_inner_radius", x); }},
      {"geneva_driver", "lock_span", "strictly between 0 and 360", -1, false, pi_times(2, milli),
       [=](const Rational& x, const Rational& s) { return with(driver(s), "lock_span", x); }},
      {"escape_wheel", "root_radius", "must be less than tip_radius", -1, true, exactly(20),
       [=](const Rational& x, const Rational& s) { return with(escape(s), "root_radius", x); }},
      {"escape_wheel", "face_angle", "3/4 of the tooth pitch", -1, false, pi_times(Rational(1, 10), q("0.02")),
       [=](const Rational& x, const Rational& s) { return with(escape(s), "face_angle", x); }},
      {"escape_wheel", "back_angle", "must exceed face_angle", +1, false, exactly(q("0.07") + milli),
       [=](const Rational& x, const Rational& s) { return with(escape(s), "back_angle", x); }},
      {"escape_wheel", "back_angle", "must be less than the tooth pitch", -1, false,
       pi_times(Rational(2, 15), Rational(milli - q("0.07"))),
       [=](const Rational& x, const Rational& s) { return with(escape(s), "back_angle", x); }},
      {"anchor", "center", "outside the escape wheel", -1, true, exactly(q("23.094")),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "wheel_radius", x); }},
      {"anchor", "lift", "must stay below 1.2 rad", -1, false, exactly(q("1.2") - q("0.1047") - q("0.0349")),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "pallet_extent", x); }},
      {"anchor", "pallet_width", "wider than twice the pallet radius", -1, true, exactly(30),   // tangent 15
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "25"), "pallet_width", x); }},
      {"anchor", "pallet_width", "wider than twice the pallet radius", -1, true, root_of(Rational(4 * tangent2)),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "pallet_width", x); }},
      {"anchor", "fork_width", "wider than the anchor's pallet circle", -1, true, exactly(q("33.6")),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "25"), "fork_width", x); }},
      {"anchor", "fork_width", "wider than the anchor's pallet circle", -1, true,
       [=] {
         Bound b = root_of(Rational(4 * tangent2));
         return Bound{Rational(b.lo + q("3.6")), Rational(b.hi + q("3.6"))};
       }(),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "fork_width", x); }},
      {"anchor", "fork_slot_width", "must be less than fork_width", -1, true, exactly(5),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "fork_slot_width", x); }},
      {"anchor", "fork_slot_depth", "must end outside the pallet circle", -1, true, exactly(q("4.9")),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "25"), "fork_slot_depth", x); }},
      {"anchor", "fork_slot_depth", "must end outside the pallet circle", -1, true,
       [=] {
         Bound b = root_of(tangent2);
         return Bound{Rational(q("19.9") - b.hi), Rational(q("19.9") - b.lo)};
       }(),
       [=](const Rational& x, const Rational& s) { return with(anchor(s, "23.094"), "fork_slot_depth", x); }},
      {"balance", "pin_center_radius", "lies inside the disc", +1, true, exactly(q("1.8")),
       [=](const Rational& x, const Rational& s) { return with(balance(s), "pin_center_radius", x); }},
      {"balance", "pin_center_radius", "detached from the disc", -1, true, exactly(q("4.2")),
       [=](const Rational& x, const Rational& s) { return with(balance(s), "pin_center_radius", x); }},
      {"balance", "pin_radius", "would swallow the disc", -1, true, exactly(7),
       [=](const Rational& x, const Rational& s) { return with(balance(s), "pin_radius", x); }},
      {"spur_gear", "dedendum", "must be less than pitch_radius", -1, true, exactly(20),
       [=](const Rational& x, const Rational& s) { return with(gear(s), "dedendum", x); }},
      {"spur_gear", "pressure_angle", "between 0.01 and 0.7", +1, false, exactly(q("0.01")),
       [=](const Rational& x, const Rational& s) { return with(gear(s), "pressure_angle", x); }},
      {"spur_gear", "pressure_angle", "between 0.01 and 0.7", -1, false, exactly(q("0.7")),
       [=](const Rational& x, const Rational& s) { return with(gear(s), "pressure_angle", x); }},
      {"ratchet_wheel", "root_radius", "must be less than tip_radius", -1, true, exactly(30),
       [=](const Rational& x, const Rational& s) {
         return Arguments{{"center", P("1", "2", s)}, {"teeth", Rational(12)}, {"tip_radius", L("30", s)}, {"root_radius", x}};
       }},
  };
}

TEST(Templates, RulesAreDecidedExactlyAtTheirBounds) {
  const std::vector<RuleCase> cases = rule_cases();
  const std::vector<int> ks{40, 52, 53, 54, 64, 80, 100, 128, 160, 200};
  int refused = 0, passed = 0, expanded = 0;
  for (const RuleCase& c : cases) {
    for (const Rational& scale : {Rational(1), power_of_ten(-300), power_of_ten(400)}) {
      const Rational s = c.length ? scale : Rational(1);
      const Bound b{Rational(c.bound.lo * s), Rational(c.bound.hi * s)};
      // (x, the sign of x - B)
      std::vector<std::pair<Rational, int>> xs;
      if (b.lo == b.hi) xs.push_back({b.lo, 0});
      else {
        xs.push_back({b.lo, -1});
        xs.push_back({b.hi, +1});
      }
      for (int k : ks) {
        const Rational d = power_of_two(k) * s;
        xs.push_back({Rational(b.lo - d), -1});
        xs.push_back({Rational(b.hi + d), +1});
      }
      for (const auto& [x, relation] : xs) {
        const bool passes = c.side * relation > 0;
        SCOPED_TRACE(c.name + "/" + c.key + " (" + c.refusal + ") at " + x.get_str() + (c.length ? " scale " + scale.get_str() : "") +
                     (passes ? ": passes" : ": fails") + " the rule");
        if (x <= 0) continue;   // (none: every bound is positive and 2^-40 below it too)
        const std::string pointer = "/parts/0/features/0/" + c.name;
        bool by_rule = false;
        std::vector<Rounding> roundings;
        try {
          expand_template(c.name, c.arguments(x, scale), pointer, roundings);
          ++expanded;
        } catch (const ModelError& error) {
          by_rule = error.pointer() == pointer + "/" + c.key && error.reason().find(c.refusal) != std::string::npos;
          if (!by_rule && !passes) ADD_FAILURE() << "refused elsewhere: " << error.what();
        }
        EXPECT_EQ(by_rule, !passes);
        (passes ? passed : refused) += 1;
      }
    }
  }
  EXPECT_GE(refused, 500);
  EXPECT_GE(passed, 500);
  EXPECT_GE(expanded, 300);   // most passing vectors expand fully
  std::cout << refused << " refused by their rule, " << passed << " kept by it (" << expanded << " expanded)\n";
}

// Session 62: the tolerance box's check of the same rules (ParametricModel::check_choices) is
// exact at every scale. For each rule above, a model with the varied argument a parameter whose
// range [lo, hi] ends on the rule's bound B, 2^-k inside it or 2^-k beyond it (k = 40, 100, 200;
// irrational bounds: 2^-k beyond their 4096-bit enclosures), the other end 1/1000 of B away on
// the rule's side, lengths at scales 1, 1e-300 and 1e400. The oracle: the exact expansion at the
// range's two ends (each rule is monotone in its argument, so the ends decide the box): the box
// must be refused at the rule's argument exactly when an end is refused by the rule. Checked on
// the form as read and on the copy the analysis rescales (1e-300: lengths in units of 1e-300 mm;
// 1e400 parameters are beyond the doubles of that copy, refused by rescaled() at their slot).
// Ends refused by another rule or check, and boxes refused as a shape change (a constructive
// check in doubles), are set aside (counted).
std::string json_number(const Rational& x) { return "\"" + x.get_str() + "\""; }

std::string json_arguments(const Arguments& arguments, const std::string& varied, const std::string& as = "v") {
  std::string out;
  for (const auto& [key, value] : arguments) {
    out += (out.empty() ? "\"" : ", \"") + key + "\": ";
    if (key == varied) out += "\"" + as + "\"";
    else if (const Rational* q = std::get_if<Rational>(&value))
      out += (key == "teeth" || key == "slots") ? q->get_str() : json_number(*q);
    else if (const Point* p = std::get_if<Point>(&value))
      out += "[" + json_number(p->x) + ", " + json_number(p->y) + "]";
    else out += "\"" + std::get<std::string>(value) + "\"";
  }
  return out;
}

TEST(Templates, BoxChecksOfTheRulesAreExactAtEveryScale) {
  int kept = 0, refused = 0, aside = 0, rescaled_checks = 0;
  for (const RuleCase& c : rule_cases()) {
    for (const Rational& scale : {Rational(1), power_of_ten(-300), power_of_ten(400)}) {
      const Rational s = c.length ? scale : Rational(1);
      const Bound b{Rational(c.bound.lo * s), Rational(c.bound.hi * s)};
      // the varied argument: the key whose value moves with x
      std::string varied;
      {
        const Arguments one = c.arguments(b.lo, scale), two = c.arguments(Rational(b.lo * 2), scale);
        for (const auto& [key, value] : one)
          if (!(two.at(key) == value)) varied = key;
      }
      ASSERT_FALSE(varied.empty()) << c.name << "/" << c.key;
      // near ends: (x, whether it lies on the rule's side)
      std::vector<std::pair<Rational, bool>> nears;
      if (b.lo == b.hi) nears.push_back({b.lo, false});
      for (int k : {40, 100, 200}) {
        const Rational d = power_of_two(k) * s;
        nears.push_back({c.side > 0 ? Rational(b.hi + d) : Rational(b.lo - d), true});
        nears.push_back({c.side > 0 ? Rational(b.lo - d) : Rational(b.hi + d), false});
      }
      const Rational width = Rational(b.lo / 1000);
      for (const auto& [near, near_passes] : nears) {
        const Rational far = c.side > 0 ? Rational(near + width) : Rational(near - width);
        const Rational lo = std::min(near, far), hi = std::max(near, far), middle = (lo + hi) / 2;
        SCOPED_TRACE(c.name + "/" + c.key + " (" + c.refusal + "): " + varied + " in [" + lo.get_str() + ", " + hi.get_str() +
                     "], scale " + scale.get_str());
        // the oracle: the exact expansion at both ends
        const std::string pointer = "/parts/0/features/0/" + c.name;
        bool by_rule = false, elsewhere = false;
        for (const Rational& end : {lo, hi}) {
          std::vector<Rounding> roundings;
          try {
            expand_template(c.name, c.arguments(end, scale), pointer, roundings);
          } catch (const ModelError& error) {
            if (error.pointer() == pointer + "/" + c.key && error.reason().find(c.refusal) != std::string::npos) by_rule = true;
            else elsewhere = true;
          }
        }
        EXPECT_EQ(by_rule, !near_passes) << "the oracle disagrees with the rule's closed form";
        if (elsewhere && !by_rule) {
          ++aside;
          continue;
        }
        // the model: the parameter v the varied argument itself, and (lengths at 1e-300 and 1e400,
        // as tests/fuzz/scale_model.py writes them) v at scale 1 with the argument "(v)*S"
        std::vector<std::pair<std::string, Rational>> forms{{"v", Rational(1)}};
        if (c.length && scale != 1) forms.push_back({scale > 1 ? "(v)*(1e400)" : "(v)*(1e-300)", scale});
        for (const auto& [as, unit] : forms) {
          const std::string text =
              R"({"hipair": 1, "name": "box", "units": {"length": "mm", "angle": "rad"}, "parameters": {"v": {"nominal": )" +
              json_number(Rational(middle / unit)) + R"(, "range": [)" + json_number(Rational(lo / unit)) + ", " +
              json_number(Rational(hi / unit)) + "]" + (c.length ? "" : R"(, "angle": true)") +
              R"(}}, "parts": [{"name": "p", "motion": {"rotation": {"pivot": [0, 0]}}, "features": [{")" + c.name +
              "\": {" + json_arguments(c.arguments(middle, scale), varied, as) + R"(}}]}], "pairs": []})";
          SCOPED_TRACE(text);
          std::optional<ParametricModel> read;
          try {
            read = ParametricModel::read(text);
          } catch (const ModelError&) {   // invalid at the range's middle (the reader's loop checks)
            ++aside;
            continue;
          }
          const ParametricModel& form = *read;
          auto check = [&](const ParametricModel& checked) -> std::optional<bool> {   // refused by the rule; none: aside
            // the box of `checked`'s own parameters: a copy rescaled by the parameters' length
            // dimensions (session 67: v beyond 1e-300 mm) holds them in its units
            const Parameter& p = checked.nominal().parameters.at(0);
            const std::vector<Rational> box_lo{Rational(p.range.lo - p.nominal)}, box_hi{Rational(p.range.hi - p.nominal)};
            try {
              checked.check_choices(box_lo, box_hi);
              return false;
            } catch (const ModelError& error) {
              const std::string what = error.what();
              if (what.find("may change the shape") != std::string::npos) return std::nullopt;
              // the rule's argument, or the varied one where the same rule is written for each
              // argument it reads (the box check names the first whose parameters vary)
              EXPECT_TRUE(error.pointer() == pointer + "/" + c.key || error.pointer() == pointer + "/" + varied) << what;
              EXPECT_NE(what.find("invalid: "), std::string::npos) << what;
              EXPECT_NE(what.find("'v'"), std::string::npos) << what;
              return true;
            }
          };
          std::optional<bool> as_read = check(form);
          if (!as_read) {
            ++aside;
            continue;
          }
          EXPECT_EQ(*as_read, by_rule);
          (by_rule ? refused : kept) += 1;
          // the copy the analysis rescales (tolerance_detail::analysed_form), where its doubles hold it
          const long exponent = kinematic_decimal_exponent(form.nominal());
          if (exponent == 0) continue;
          std::optional<ParametricModel> copy;
          try {
            copy = form.rescaled(exponent);
          } catch (const ModelError& error) {   // a parameter of 1e400 mm used as a length: refused at its slot
            EXPECT_EQ(as, "v") << error.what();
            EXPECT_NE(std::string(error.what()).find("does not evaluate there in doubles"), std::string::npos) << error.what();
            continue;
          }
          std::optional<bool> on_copy = check(*copy);
          if (on_copy) {
            EXPECT_EQ(*on_copy, by_rule) << "on the copy in units of 1e" << exponent << " mm";
            ++rescaled_checks;
          }
        }
      }
    }
  }
  std::cout << kept << " boxes kept, " << refused << " refused by their rule, " << aside << " set aside, "
            << rescaled_checks << " checked again on the rescaled copy\n";
  EXPECT_GE(kept, 120);
  EXPECT_GE(refused, 180);
  EXPECT_GE(rescaled_checks, 180);
}


// Session 63 (issue 12): the shape checks of the tolerance box (ParametricModel::check_choices:
// a negative angle, a radius reaching 0, the involute's root circle against its base circle)
// are decided exactly at every scale, as the templates' rules are since session 62. For each
// check, a model whose argument is a parameter with its range ending on the check's bound B,
// 2^-k inside it or 2^-k beyond it (k = 40, 100, 200; the irrational base-circle bound 2^-k
// beyond its enclosure by multiples of 2^-320), the other end a fixed width away on the valid side, lengths at
// scales 1, 1e-300 and 1e400: the parameter itself the length (raw) and, away from 1, a factor
// of the scale. Oracle: the closed form (the sign of x - B at the near end; a non-strict bound,
// >= 0, keeps a range ending on it). Until session 63 the checks ran in doubles on the
// outward-rounded box: a range ending on 0 or 2^-100 from it was refused, and a raw involute
// gear at 1e400 mm was refused whole (its doubles overflow).
struct ShapeCase {
  std::string name, key;   // the template and the argument the check names
  bool strict;             // x > B (true) or x >= B
  int side;                // +1: x must exceed B; -1: stay below it
  bool length;
  Bound bound;             // B at scale 1
  Rational width;          // the range's width at scale 1
  std::function<Arguments(const Rational& x, const Rational& scale)> arguments;
};

std::vector<ShapeCase> shape_cases() {
  auto L = [](const char* text, const Rational& s) { return Rational(q(text) * s); };
  auto P = [](const char* x, const char* y, const Rational& s) { return Point{Rational(q(x) * s), Rational(q(y) * s)}; };
  auto with = [](Arguments a, const char* key, const TemplateValue& value) {
    a[key] = value;
    return a;
  };
  auto escape = [=](const Rational& s) {
    return Arguments{{"center", P("0", "0", s)}, {"teeth", Rational(15)},   {"tip_radius", L("20", s)},
                     {"root_radius", L("15", s)}, {"face_angle", q("0.07")}, {"back_angle", q("0.17")},
                     {"tip_angle", q("0.02")}};
  };
  auto anchor = [=](const Rational& s) {
    return Arguments{{"center", P("0", "23.094", s)},  {"wheel_center", P("0", "0", s)},
                     {"wheel_radius", L("20", s)},     {"pallet_width", L("3.6", s)},
                     {"lift", q("0.1047")},            {"lock", q("0.0349")},
                     {"pallet_extent", q("0.2")},      {"fork_length", L("21.7", s)},
                     {"fork_width", L("5", s)},        {"fork_slot_width", L("2.7", s)},
                     {"fork_slot_depth", L("2.4", s)}};
  };
  auto driver = [=](const Rational& s) {
    return Arguments{{"center", P("80", "0", s)},          {"pin_radius", L("4.5", s)},
                     {"pin_center_radius", L("56.5", s)}, {"lock_outer_radius", L("46", s)},
                     {"lock_inner_radius", L("36", s)},   {"lock_span", q("4.9416")}};
  };
  auto gear = [=](const Rational& s) {   // 8 teeth (the model texts at 1e400 are read quicker)
    Arguments a = spur_gear_arguments(8);
    for (const char* key : {"pitch_radius", "addendum", "dedendum", "tooth_thickness"})
      a[key] = Rational(std::get<Rational>(a[key]) * s);
    a["pressure_angle"] = q("0.35");
    return a;
  };
  // the base circle's bound on the dedendum: pitch (1 - cos 0.35), pitch 8, enclosed by
  // multiples of 2^-320 (the model texts at 1e400 stay within the reader's 4096 bits)
  const Bound fine = enclosed([](mpfi_ptr x) {
    mpfi_set_q(x, q("0.35").get_mpq_t());
    mpfi_cos(x, x);
    mpfi_ui_sub(x, 1, x);
    mpfi_mul_ui(x, x, 8);
  });
  const mpz_class unit = mpz_class(1) << 320;
  mpz_class lo_units, hi_units;
  mpz_fdiv_q(lo_units.get_mpz_t(), mpz_class(fine.lo.get_num() * unit).get_mpz_t(), fine.lo.get_den().get_mpz_t());
  mpz_cdiv_q(hi_units.get_mpz_t(), mpz_class(fine.hi.get_num() * unit).get_mpz_t(), fine.hi.get_den().get_mpz_t());
  Bound base{Rational(lo_units, unit), Rational(hi_units, unit)};
  base.lo.canonicalize();
  base.hi.canonicalize();
  const Rational hundredth(1, 100), tenth(1, 10);
  return std::vector<ShapeCase>{
      {"escape_wheel", "face_angle", false, +1, false, exactly(0), hundredth,
       [=](const Rational& x, const Rational& s) { return with(escape(s), "face_angle", x); }},
      {"escape_wheel", "tip_angle", true, +1, false, exactly(0), hundredth,
       [=](const Rational& x, const Rational& s) { return with(escape(s), "tip_angle", x); }},
      {"anchor", "lift", true, +1, false, exactly(0), hundredth,
       [=](const Rational& x, const Rational& s) { return with(anchor(s), "lift", x); }},
      {"anchor", "lock", false, +1, false, exactly(0), hundredth,
       [=](const Rational& x, const Rational& s) { return with(anchor(s), "lock", x); }},
      {"anchor", "pallet_extent", true, +1, false, exactly(0), hundredth,
       [=](const Rational& x, const Rational& s) { return with(anchor(s), "pallet_extent", x); }},
      {"geneva_driver", "lock_inner_radius", true, +1, true, exactly(0), Rational(1),
       [=](const Rational& x, const Rational& s) { return with(driver(s), "lock_inner_radius", x); }},
      {"spur_gear", "dedendum", true, +1, true, base, tenth,   // radial flank: the root inside the base circle
       [=](const Rational& x, const Rational& s) { return with(gear(s), "dedendum", x); }},
      {"spur_gear", "dedendum", true, -1, true, base, tenth,   // no radial segment: the root outside it
       [=](const Rational& x, const Rational& s) { return with(gear(s), "dedendum", x); }},
  };
}

// The model text of one template feature whose argument `varied` is the parameter v over [lo, hi]
// (written as `as`, divided by `unit`).
std::string box_model(const std::string& name, const Arguments& middle_arguments, const std::string& varied,
                      const std::string& as, const Rational& unit, const Rational& lo, const Rational& hi,
                      bool length) {
  return R"({"hipair": 1, "name": "box", "units": {"length": "mm", "angle": "rad"}, "parameters": {"v": {"nominal": )" +
         json_number(Rational((lo + hi) / 2 / unit)) + R"(, "range": [)" + json_number(Rational(lo / unit)) + ", " +
         json_number(Rational(hi / unit)) + "]" + (length ? "" : R"(, "angle": true)") +
         R"(}}, "parts": [{"name": "p", "motion": {"rotation": {"pivot": [0, 0]}}, "features": [{")" + name + "\": {" +
         json_arguments(middle_arguments, varied, as) + R"(}}]}], "pairs": []})";
}

TEST(Templates, ShapeChecksOfTheBoxAreExactAtEveryScale) {
  int kept = 0, refused = 0, aside = 0;
  for (const ShapeCase& c : shape_cases()) {
    for (const Rational& scale : {Rational(1), power_of_ten(-300), power_of_ten(400)}) {
      const Rational s = c.length ? scale : Rational(1);
      const Bound b{Rational(c.bound.lo * s), Rational(c.bound.hi * s)};
      const Rational inner = c.side > 0 ? b.hi : b.lo, outer = c.side > 0 ? b.lo : b.hi;
      // near ends: (x, whether the check keeps it)
      std::vector<std::pair<Rational, bool>> nears;
      if (b.lo == b.hi) nears.push_back({b.lo, !c.strict});
      for (int k : {40, 100, 200}) {
        const Rational d = power_of_two(k) * s;
        nears.push_back({Rational(inner + c.side * d), true});
        nears.push_back({Rational(outer - c.side * d), false});
      }
      for (const auto& [near, keeps] : nears) {
        const Rational far = Rational(near + c.side * c.width * s);
        const Rational lo = std::min(near, far), hi = std::max(near, far), middle = (lo + hi) / 2;
        SCOPED_TRACE(c.name + "/" + c.key + ": v in [" + lo.get_str() + ", " + hi.get_str() + "], scale " + scale.get_str() +
                     (keeps ? ": kept" : ": refused"));
        std::vector<std::pair<std::string, Rational>> forms{{"v", Rational(1)}};
        if (c.length && scale != 1) forms.push_back({scale > 1 ? "(v)*(1e400)" : "(v)*(1e-300)", scale});
        for (const auto& [as, unit] : forms) {
          const std::string text = box_model(c.name, c.arguments(middle, scale), c.key, as, unit, lo, hi, c.length);
          SCOPED_TRACE(text);
          std::optional<ParametricModel> read;
          try {
            read = ParametricModel::read(text);
          } catch (const ModelError& error) {   // invalid at the range's middle
            ADD_FAILURE() << "the middle is refused: " << error.what();
            ++aside;
            continue;
          }
          const Parameter& p = read->nominal().parameters.at(0);
          const std::vector<Rational> box_lo{Rational(p.range.lo - p.nominal)}, box_hi{Rational(p.range.hi - p.nominal)};
          const std::string pointer = "/parts/0/features/0/" + c.name + "/" + c.key;
          try {
            read->check_choices(box_lo, box_hi);
            EXPECT_TRUE(keeps) << "kept, though " << near.get_str() << " is beyond the bound";
            ++kept;
          } catch (const ModelError& error) {
            EXPECT_FALSE(keeps) << "refused: " << error.what();
            if (!keeps) {
              EXPECT_EQ(error.pointer(), pointer) << error.what();
              EXPECT_NE(std::string(error.what()).find("may change the shape"), std::string::npos) << error.what();
            }
            ++refused;
          }
        }
      }
    }
  }
  std::cout << kept << " boxes kept, " << refused << " refused, " << aside << " set aside\n";
  EXPECT_GE(kept, 60);
  EXPECT_GE(refused, 60);
}

// Session 64 (tol64, issue 12): a shape check whose argument is a formula of the parameter, not
// the parameter itself ("v - C", "K*(v - C)", "C - v", "(v - C)*v/C", C and K drawn from the test
// seed, not dyadic), over a range whose margin ends exactly on the check's bound 0, 2^-k inside or
// 2^-k beyond it, at scales 1, 1e-300 and 1e400 (lengths): the enclosures straddle 0 at the tie,
// and it is decided by the margin's monotony and its exact value at the box's corner. Oracle: the
// sign of the margin at the near end (a non-strict check keeps a range ending on 0, a strict one
// refuses it). Until session 64 every non-strict tie was refused (the enclosure of C - C holds 0).
TEST(Templates, ShapeChecksThroughAFormulaDecideExactTies) {
  const std::uint64_t seed = test::test_seed(64);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  auto draw = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  auto non_dyadic = [&](int lo, int hi) {   // p/q in [lo, hi], q odd > 1
    const int den = 2 * draw(1, 20) + 1;
    return Rational(mpz_class(draw(lo * den, hi * den)), mpz_class(den));
  };
  int kept = 0, refused = 0, ties_kept = 0;
  for (const ShapeCase& c : shape_cases()) {
    if (c.bound.lo != 0 || c.bound.hi != 0) continue;   // the ties at 0
    for (int form = 0; form < 4; ++form) {
      const Rational c0 = non_dyadic(1, 3), k = non_dyadic(1, 5);
      for (const Rational& scale : {Rational(1), power_of_ten(-300), power_of_ten(400)}) {
        if (!c.length && scale != 1) continue;
        const Rational& s = scale;
        const Rational big_c = c0 * s, width = c.width * s;
        const std::string ct = "(" + big_c.get_str() + ")", kt = "(" + k.get_str() + ")";
        std::vector<Rational> nears{Rational(0)};
        for (int e : {40, 200}) {
          nears.push_back(Rational(power_of_two(e) * s));
          nears.push_back(Rational(-power_of_two(e) * s));
        }
        for (const Rational& d : nears) {
          const bool keeps = c.strict ? d > 0 : d >= 0;
          // v at the margin's near end (d) and far end (d + width)
          std::string as;
          Rational v_near, v_far;
          switch (form) {
            case 0: as = "v - " + ct; v_near = big_c + d; v_far = big_c + d + width; break;
            case 1: as = kt + "*(v - " + ct + ")"; v_near = big_c + d / k; v_far = big_c + (d + width) / k; break;
            case 2: as = ct + " - v"; v_near = big_c - d; v_far = big_c - d - width; break;
            default: as = "(v - " + ct + ")*v/" + ct; v_near = big_c + d; v_far = big_c + d + width; break;
          }
          const Rational lo = std::min(v_near, v_far), hi = std::max(v_near, v_far);
          // the other arguments at the margin's middle value (the check's argument is replaced by `as`)
          const std::string text = box_model(c.name, c.arguments(Rational(d + width / 2), s), c.key, as, Rational(1), lo, hi, c.length);
          SCOPED_TRACE(c.name + "/" + c.key + " as " + as + ", near margin " + d.get_str() + (keeps ? ": kept" : ": refused"));
          std::optional<ParametricModel> read;
          try {
            read = ParametricModel::read(text);
          } catch (const ModelError& error) {
            ADD_FAILURE() << "the middle is refused: " << error.what() << "\n" << text;
            continue;
          }
          const Parameter& p = read->nominal().parameters.at(0);
          try {
            read->check_choices({Rational(p.range.lo - p.nominal)}, {Rational(p.range.hi - p.nominal)});
            EXPECT_TRUE(keeps) << "kept, though the margin is negative at its near end\n" << text;
            ++kept;
            if (d == 0) ++ties_kept;
          } catch (const ModelError& error) {
            EXPECT_FALSE(keeps) << "refused: " << error.what() << "\n" << text;
            if (!keeps) EXPECT_EQ(error.pointer(), "/parts/0/features/0/" + c.name + "/" + c.key) << error.what();
            ++refused;
          }
        }
      }
    }
  }
  std::cout << kept << " boxes kept (" << ties_kept << " ending exactly on a non-strict bound), " << refused << " refused\n";
  EXPECT_GE(ties_kept, 8);
  EXPECT_GE(refused, 40);
}

// Generated involute gears (teeth, module, pressure angle and tolerances drawn from the test
// seed), every dimension toleranced, at scales 1, 1e-300 and 1e400 (raw lengths and, away from 1,
// factors of the scale): the shape check is invariant under the scale (the gears are similar),
// so each scale's verdict (kept, or refused at the same pointer) equals scale 1's, which the
// doubles decide; most are kept. Until session 63 every raw gear at 1e400 was refused.
TEST(Templates, InvoluteGearShapeChecksAreTheSameAtEveryScale) {
  const std::uint64_t seed = test::test_seed(63);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  auto draw = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int kept = 0, refused = 0;
  for (int round = 0; round < 4; ++round) {
    const int teeth = draw(8, 14);
    const Rational module(draw(5, 40), 10), alpha(draw(300, 450), 1000);
    const Rational pitch = module * teeth / 2, addendum = module, dedendum = module * draw(110, 135) / 100,
                   thickness = module * draw(150, 160) / 100;
    auto tolerance = [&](const Rational& x) { return Rational(x * draw(0, 20) / 1000); };   // up to 2 %
    const std::vector<std::pair<std::string, Rational>> values{
        {"pr", pitch}, {"ad", addendum}, {"de", dedendum}, {"th", thickness}};
    const Rational alpha_tolerance(draw(0, 10), 1000);
    std::vector<Rational> tolerances;
    for (const auto& value : values) tolerances.push_back(tolerance(value.second));
    std::optional<std::pair<bool, std::string>> at_one;
    for (const Rational& scale : {Rational(1), power_of_ten(-300), power_of_ten(400)}) {
      std::vector<bool> raw_forms{true};
      if (scale != 1) raw_forms.push_back(false);
      for (bool raw : raw_forms) {
        std::string parameters, arguments;
        for (std::size_t i = 0; i < values.size(); ++i) {
          const Rational unit = raw ? scale : Rational(1);
          parameters += "\"" + values[i].first + "\": {\"nominal\": " + json_number(Rational(values[i].second * unit)) +
                        ", \"tolerance\": " + json_number(Rational(tolerances[i] * unit)) + "}, ";
          const std::string use = raw || scale == 1 ? values[i].first
                                                    : "(" + values[i].first + ")*(" + (scale > 1 ? "1e400" : "1e-300") + ")";
          arguments += std::string(", \"") + (i == 0 ? "pitch_radius" : i == 1 ? "addendum" : i == 2 ? "dedendum" : "tooth_thickness") +
                       "\": \"" + use + "\"";
        }
        parameters += "\"al\": {\"nominal\": " + json_number(alpha) + ", \"tolerance\": " + json_number(alpha_tolerance) +
                      ", \"angle\": true}";
        const std::string text =
            R"({"hipair": 1, "name": "gear", "units": {"length": "mm", "angle": "rad"}, "parameters": {)" + parameters +
            R"(}, "parts": [{"name": "g", "motion": {"rotation": {"pivot": [0, 0]}}, "features": [{"spur_gear": {"center": [0, 0], "teeth": )" +
            std::to_string(teeth) + arguments + R"(, "pressure_angle": "al"}}]}], "pairs": []})";
        SCOPED_TRACE(text);
        std::optional<ParametricModel> read;
        try {
          read = ParametricModel::read(text);
        } catch (const ModelError& error) {
          ADD_FAILURE() << "the nominal gear is refused: " << error.what();
          continue;
        }
        std::vector<Rational> lo, hi;
        for (const Parameter& p : read->nominal().parameters) {
          lo.push_back(Rational(p.range.lo - p.nominal));
          hi.push_back(Rational(p.range.hi - p.nominal));
        }
        std::pair<bool, std::string> verdict{true, ""};
        try {
          read->check_choices(lo, hi);
        } catch (const ModelError& error) {
          verdict = {false, error.pointer()};
          if (!at_one) std::cout << "refused at scale 1: " << error.what() << "\n";
        }
        if (!at_one) {
          at_one = verdict;
          (verdict.first ? kept : refused) += 1;
        } else {
          EXPECT_EQ(verdict, *at_one) << "scale " << scale.get_str() << (raw ? " (raw lengths)" : " (factors of the scale)");
        }
      }
    }
  }
  std::cout << kept << " gears kept, " << refused << " refused (at every scale alike)\n";
  EXPECT_GE(kept, 3);
}


// A non-strict shape-check margin that does not evaluate over a sub-box (it throws there: the
// integrator's session-64 fix in certified_positive) leaves that sub-box open, to be split; the
// box holds only when every sub-box is decided. Generated margins of v over its range [lo, hi],
// about a non-dyadic point z inside it (bisection never reaches z as a point):
//  (a) undefined at z (throws over every sub-box holding z, as a division by v - z would): the
//      check must not hold, strict or not (the model has no value at v = z);
//  (b) |v - z|^2, throwing over sub-boxes wider than a share of the range (too wide to enclose),
//      defined and >= 0 everywhere: a non-strict check holds, a strict one does not (0 at z);
//  (c) -|v - z|^2 - e, throwing likewise: fails.
// Until the fix (e0ff50ea) a sub-box that did not evaluate read as [0, 0], which a non-strict
// check took as holding: every (a) case held.
TEST(Templates, ShapeCheckMarginsThatDoNotEvaluateOverASubBoxAreNotHeld) {
  using MI = model_detail::Interval;
  const std::uint64_t seed = test::test_seed(65);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  auto draw = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int undefined_open = 0, held = 0, failed = 0;
  for (int round = 0; round < 12; ++round) {
    const Rational lo(draw(1, 40), 1000), width(draw(5, 40), 1000), hi = lo + width;
    const int den = 2 * draw(1, 20) + 1;   // z = lo + width * k / den, odd den > 1: never a bisection point
    const Rational z = lo + width * Rational(draw(1, den - 1), den);
    const ShapeCase face = shape_cases().at(0);   // escape_wheel face_angle >= 0: v itself
    const std::string text = box_model(face.name, face.arguments(Rational((lo + hi) / 2), Rational(1)), face.key, "v",
                                       Rational(1), lo, hi, face.length);
    SCOPED_TRACE(text + "\nz = " + z.get_str());
    const ParametricModel model = ParametricModel::read(text);
    const Parameter& p = model.nominal().parameters.at(0);
    const std::vector<Rational> dlo{Rational(p.range.lo - p.nominal)}, dhi{Rational(p.range.hi - p.nominal)};
    const std::vector<bool> derived{model.derived(0)};
    const MI zi(z);
    // v - z over the sub-box; does it hold z?
    auto offset = [&](const std::vector<MI>& q) { return MI(q.at(0) - zi); };
    auto holds_z = [&](const MI& d) { return d.sign() == 0; };
    auto too_wide = [&](const MI& v) { return !v.is_bounded() || Rational((v.upper() - v.lower()) * 8) > width; };
    auto square = [&](const MI& d) {
      MI a;
      mpfi_abs(a.get(), d.get());
      return MI(a * a);
    };
    const std::function<MI(const std::vector<MI>&)> undefined = [&](const std::vector<MI>& q) {
      const MI d = offset(q);
      if (holds_z(d)) throw NumericError("does not evaluate at v = z");
      return square(d);
    };
    const std::function<MI(const std::vector<MI>&)> nonnegative = [&](const std::vector<MI>& q) {
      if (too_wide(q.at(0))) throw NumericError("too wide to enclose");
      return square(offset(q));
    };
    const Rational e(1, 1000000);
    const std::function<MI(const std::vector<MI>&)> negative = [&](const std::vector<MI>& q) {
      if (too_wide(q.at(0))) throw NumericError("too wide to enclose");
      return MI(MI(Rational(0)) - square(offset(q)) - MI(e));
    };
    for (bool strict : {false, true}) {
      SCOPED_TRACE(strict ? "strict" : "non-strict");
      const BoxVerdict a = certified_positive(model, derived, dlo, dhi, {0}, undefined, strict);
      EXPECT_NE(a, BoxVerdict::holds) << "a margin undefined at v = z held";
      if (a != BoxVerdict::holds && !strict) ++undefined_open;
      const BoxVerdict b = certified_positive(model, derived, dlo, dhi, {0}, nonnegative, strict);
      if (strict) EXPECT_NE(b, BoxVerdict::holds) << "|v - z|^2 > 0 held, though it is 0 at z";
      else EXPECT_EQ(b, BoxVerdict::holds) << "|v - z|^2 >= 0 not held";
      if (b == BoxVerdict::holds) ++held;
      const BoxVerdict c = certified_positive(model, derived, dlo, dhi, {0}, negative, strict);
      EXPECT_EQ(c, BoxVerdict::fails) << "-|v - z|^2 - e >= 0 not refused";
      if (c == BoxVerdict::fails) ++failed;
    }
  }
  std::cout << undefined_open << " undefined margins not held (non-strict), " << held << " held, " << failed << " failed\n";
  EXPECT_EQ(undefined_open, 12);
}

}  // namespace
}  // namespace hipair::model_detail
