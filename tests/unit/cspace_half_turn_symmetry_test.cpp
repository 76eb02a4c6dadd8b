// Session 66 (geneva66): the exact half-turn symmetry of a rotating part (src/cspace/
// half_turn_symmetry.hpp) and what it means for a pair's charts. A wheel that maps onto itself
// under q -> 2 p - q turns its chart at theta + pi into the chart at theta with its features
// permuted: the exact contact structure of the two charts (every real edge's curve and its
// feature pairs, mapped by the permutation) must then be the same. Generated star wheels of 3-8
// arms (odd counts have no half turn), near-symmetric ones (one corner moved by 2^-k), the
// symmetric examples (geneva-template, ratchet) and Geneva as shipped (exactly symmetric since
// session 67's half-turn reduction of the model's angles before their rounding) are decided and
// compared; a wrong permutation (every image one edge further, or the identity) is caught.
// Printed, not asserted: whether the twin charts also agree in their spurious pieces, vertices
// and faces as sets, and in order (the numbering every output uses) - mostly they do not
// (docs/performance.md "Session 66 (geneva66)"), which is why no chart is built by the map.
#include "cspace/half_turn_symmetry.hpp"
#include "model/exact_trig.hpp"
#include "star_wheel_support.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test::geneva;
using test::part_index;
using test::star_wheel;
using test::with_wheel;

std::string feature_text(const FeatureIdentity& f) {
  return std::to_string(f.part) + ":" + std::to_string(f.loop) + ":" + std::to_string(f.edge) + ":" +
         std::to_string(static_cast<int>(f.kind));
}

std::string vertex_text(const CSpaceVertex& v) {
  std::ostringstream out;
  out << v.x.to_string("x") << " | ";
  if (v.y_exact) {
    out << v.y.to_string("y");
  } else {
    for (const auto& row : v.y_curve) {
      out << "[";
      for (const mpz_class& c : row) out << c.get_str() << " ";
      out << "]";
    }
    out << " branch " << v.y_branch << " in [" << v.y_lower.get_str() << ", " << v.y_upper.get_str() << "]";
  }
  out << " | " << v.on_chart_boundary << v.contact_change << v.touching;
  return out.str();
}

// What one chart of `space` is, with the wheel's features mapped by `image` (identity: nullptr):
// vertices, edges (ends, polynomial, role, realness, mapped feature pairs), faces' classes.
struct ChartText {
  std::vector<std::string> vertices, edges, faces;
  std::vector<std::string> contacts;   // per real edge: its polynomial and (mapped) feature pairs
  std::vector<std::string> skeleton;   // per edge: polynomial, role, realness, (mapped) pairs; no vertex text
};

ChartText chart_text(const CSpace& space, std::size_t chart, std::size_t wheel,
                     const std::vector<std::vector<cspace::HalfTurnImage>>* image) {
  ChartText text;
  auto mapped = [&](FeatureIdentity f) {
    if (image && f.part == wheel) {
      const cspace::HalfTurnImage to = (*image)[f.loop][f.edge];
      f.loop = to.loop;
      f.edge = to.edge;
    }
    return feature_text(f);
  };
  for (const CSpaceVertex& v : space.vertices())
    if (v.chart == chart) text.vertices.push_back(vertex_text(v));
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (edge.chart != chart) continue;
    std::ostringstream out;
    out << vertex_text(space.vertices()[edge.source]) << " -> " << vertex_text(space.vertices()[edge.target]) << " |";
    for (const auto& row : space.edge_polynomial_coefficients(e)) {
      out << "[";
      for (const mpz_class& c : row) out << c.get_str() << " ";
      out << "]";
    }
    out << " role " << static_cast<int>(edge.role) << " real " << edge.real << " vertical " << edge.vertical << " |";
    std::vector<std::string> pairs;
    for (std::size_t p : edge.curves) {
      const FeaturePair& pair = space.feature_pairs()[p];
      pairs.push_back(mapped(pair.first) + "/" + mapped(pair.second) + ":" + std::to_string(static_cast<int>(pair.kind)));
    }
    std::sort(pairs.begin(), pairs.end());
    for (const auto& p : pairs) out << " " << p;
    text.edges.push_back(out.str());
    {
      std::ostringstream bare;
      for (const auto& row : space.edge_polynomial_coefficients(e)) {
        bare << "[";
        for (const mpz_class& c : row) bare << c.get_str() << " ";
        bare << "]";
      }
      bare << " role " << static_cast<int>(edge.role) << " real " << edge.real << " vertical " << edge.vertical << " |";
      for (const auto& p : pairs) bare << " " << p;
      text.skeleton.push_back(bare.str());
    }
    if (edge.real) {
      std::ostringstream contact;
      for (const auto& row : space.edge_polynomial_coefficients(e)) {
        contact << "[";
        for (const mpz_class& c : row) contact << c.get_str() << " ";
        contact << "]";
      }
      for (const auto& p : pairs) contact << " " << p;
      text.contacts.push_back(contact.str());
    }
  }
  for (const CSpaceFace& face : space.faces(chart)) {
    std::ostringstream out;
    // (the cycles' order is the arrangement's: as a set)
    std::vector<std::size_t> cycles;
    for (const auto& cycle : face.boundary) cycles.push_back(cycle.size());
    std::sort(cycles.begin(), cycles.end());
    out << static_cast<int>(face.kind) << " with " << face.boundary.size() << " boundary cycles of";
    for (std::size_t n : cycles) out << " " << n;
    text.faces.push_back(out.str());
  }
  return text;
}

std::vector<std::string> sorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// The (chart at the wheel's 0, chart at its pi) pairs of the same chart of the other part.
std::vector<std::pair<std::size_t, std::size_t>> half_turn_twins(const CSpace& space, bool wheel_is_x) {
  std::vector<std::pair<std::size_t, std::size_t>> twins;
  const auto& charts = space.charts();
  for (std::size_t a = 0; a < charts.size(); ++a)
    for (std::size_t b = 0; b < charts.size(); ++b) {
      const CSpaceChart &ca = charts[a], &cb = charts[b];
      const bool other_same = wheel_is_x ? ca.y_half_turn == cb.y_half_turn : ca.x_half_turn == cb.x_half_turn;
      const bool wheel_twin = wheel_is_x ? !ca.x_half_turn && cb.x_half_turn : !ca.y_half_turn && cb.y_half_turn;
      if (other_same && wheel_twin && ca.x_lo == cb.x_lo && ca.x_hi == cb.x_hi && ca.y_lo == cb.y_lo && ca.y_hi == cb.y_hi)
        twins.emplace_back(a, b);
    }
  return twins;
}

struct Agreement {
  bool contacts = true;     // the same real edges' curves and (mapped) feature pairs, as a set
  bool as_sets = true;      // the same vertices, edges and faces (mapped)
  bool in_order = true;     // ... in the same order (the outputs' numbering)
  bool skeleton = true;     // the same edges (polynomial, role, pairs) as multisets, vertices' text aside
  bool skeleton_in_order = true;   // ... and in the same order
};

Agreement twins_agree(const CSpace& space, std::size_t wheel, const std::vector<std::vector<cspace::HalfTurnImage>>* image,
                      bool wheel_is_x = false) {
  Agreement agreement;
  const auto twins = half_turn_twins(space, wheel_is_x);
  EXPECT_FALSE(twins.empty());
  for (auto [a, b] : twins) {
    // chart b (wheel at pi) read with the wheel's features mapped onto those of chart a
    const ChartText ta = chart_text(space, a, wheel, nullptr), tb = chart_text(space, b, wheel, image);
    auto as_set = [](std::vector<std::string> v) {
      v = sorted(std::move(v));
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    };
    if (as_set(ta.contacts) != as_set(tb.contacts)) agreement.contacts = false;
    if (sorted(ta.skeleton) != sorted(tb.skeleton)) agreement.skeleton = false;
    if (ta.skeleton != tb.skeleton) agreement.skeleton_in_order = false;
    // HIPAIR_HALF_TURN_DEBUG=1: print what differs between the twin charts (the evidence of
    // docs/performance.md "Session 67 (geneva67)")
    if (std::getenv("HIPAIR_HALF_TURN_DEBUG")) {
      auto show = [](const char* what, std::vector<std::string> x, std::vector<std::string> y) {
        x = sorted(x); y = sorted(y);
        std::vector<std::string> only_x, only_y;
        std::set_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(only_x));
        std::set_difference(y.begin(), y.end(), x.begin(), x.end(), std::back_inserter(only_y));
        for (auto& v : only_x) std::cout << "DBG " << what << " only a: " << v.substr(0, 400) << "\n";
        for (auto& v : only_y) std::cout << "DBG " << what << " only b: " << v.substr(0, 400) << "\n";
      };
      show("vertex", ta.vertices, tb.vertices);
      show("edge", ta.edges, tb.edges);
      show("face", ta.faces, tb.faces);
      show("skeleton", ta.skeleton, tb.skeleton);
    }
    if (sorted(ta.vertices) != sorted(tb.vertices) || sorted(ta.edges) != sorted(tb.edges) ||
        sorted(ta.faces) != sorted(tb.faces)) {
      agreement.as_sets = false;
    }
    if (ta.vertices != tb.vertices || ta.edges != tb.edges || ta.faces != tb.faces) agreement.in_order = false;
  }
  return agreement;
}

TEST(HalfTurnSymmetry, GenevaAsShippedIsExactlySymmetric) {
  // Session 67: the wheel's lock arcs start at angles k pi/2 + pi + span/2; the model reader takes
  // the whole half turns out of rational + p pi exactly before its one rounding (expression.cpp
  // unit_vector), so the arcs of k and k + 2 are exact half turns of each other and so are the
  // charts at the wheel's 0 and pi. (Until session 66 each angle was rounded on its own: lock arc
  // 1's half turn started 1.8e-11 mm off lock arc 3 and this decision refused.)
  const Model model = geneva();
  const std::size_t wheel = part_index(model, "wheel");
  std::string why;
  const auto image = cspace::half_turn_symmetry(model.parts[wheel], &why);
  ASSERT_TRUE(image) << why;
  ASSERT_EQ(model.parts[wheel].loops.size(), 1u);
  const std::size_t n = model.parts[wheel].loops[0].edges.size();
  ASSERT_EQ(n, 24u);
  for (std::size_t e = 0; e < n; ++e) EXPECT_EQ((*image)[0][e], (cspace::HalfTurnImage{0, (e + 12) % 24}));
  {
    const Part& part = model.parts[wheel];
    const Edge turned = cspace::half_turned(part.loops[0].edges[0], part.motion.pivot);
    const Edge& twin = part.loops[0].edges[12];
    EXPECT_EQ(turned.source, twin.source);
    EXPECT_EQ(turned.target, twin.target);
    EXPECT_EQ(turned.center, twin.center);
  }
  // near-symmetric: one lock arc's start moved by 2^-k (k in [30, 200]): refused (its half turn is
  // no edge of the part); the driver (pin + lock segment) has no half turn at all
  std::mt19937_64 random(test::test_seed(67));
  for (int trial = 0; trial < 8; ++trial) {
    Model near = model;
    Loop& loop = near.parts[wheel].loops[0];
    const std::size_t arc = 6 * (random() % 4);  // lock arcs are edges 0, 6, 12, 18
    const int k = std::uniform_int_distribution<int>(30, 200)(random);
    Point& p = loop.edges[arc].source;
    (random() % 2 ? p.x : p.y) += Rational(mpz_class(1), mpz_class(1) << k);
    loop.edges[(arc + n - 1) % n].target = p;
    EXPECT_FALSE(cspace::half_turn_symmetry(near.parts[wheel])) << "lock arc edge " << arc << " moved by 2^-" << k;
  }
  EXPECT_FALSE(cspace::half_turn_symmetry(model.parts[part_index(model, "driver")]));
  const CSpace space = CSpace::build(model, "driver", "wheel");
  // the twin charts (wheel at 0 and pi) carry the same contact structure under e -> e + 12;
  // the identity and the map shifted one edge further are caught
  const Agreement agreement = twins_agree(space, wheel, &*image);
  EXPECT_TRUE(agreement.contacts);
  std::cout << "geneva: twin charts the same as sets " << agreement.as_sets << ", in the same order " << agreement.in_order
            << ", the same edges as multisets (vertices' text aside) " << agreement.skeleton << ", in order "
            << agreement.skeleton_in_order << "\n";
  std::vector<std::vector<cspace::HalfTurnImage>> shifted(1);
  for (std::size_t e = 0; e < n; ++e) shifted[0].push_back({0, (e + 13) % n});
  EXPECT_FALSE(twins_agree(space, wheel, &shifted).contacts);
  EXPECT_FALSE(twins_agree(space, wheel, nullptr).contacts);
}

TEST(HalfTurnSymmetry, GeneratedWheelsAreDecidedExactlyAndSymmetricChartsAgree) {
  const std::uint64_t seed = test::test_seed(66);
  std::mt19937_64 random(seed);
  std::size_t symmetric_built = 0, same_sets = 0, same_order = 0, same_skeleton = 0;
  for (int arms = 3; arms <= 8; ++arms) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", " + std::to_string(arms) + " arms");
    const Loop wheel = star_wheel(random, arms, true);
    Model model = with_wheel(wheel);
    const std::size_t w = part_index(model, "wheel");
    std::string why;
    const auto image = cspace::half_turn_symmetry(model.parts[w], &why);
    ASSERT_EQ(static_cast<bool>(image), arms % 2 == 0) << why;
    if (image) {
      // an involution moving every edge by half the arms
      for (std::size_t e = 0; e < wheel.edges.size(); ++e) {
        EXPECT_EQ((*image)[0][e].edge, (e + wheel.edges.size() / 2) % wheel.edges.size());
        EXPECT_EQ((*image)[0][(*image)[0][e].edge].edge, e);
      }
    }
    // near-symmetric: one corner moved by 2^-k in x or y (both its edges): no longer symmetric
    {
      Model near = model;
      Loop& loop = near.parts[w].loops[0];
      const std::size_t i = random() % loop.edges.size();
      const int k = std::uniform_int_distribution<int>(8, 200)(random);
      Rational delta(mpz_class(1), mpz_class(1) << k);
      Point& p = loop.edges[i].source;
      (random() % 2 ? p.x : p.y) += delta;
      loop.edges[(i + loop.edges.size() - 1) % loop.edges.size()].target = p;
      EXPECT_FALSE(cspace::half_turn_symmetry(near.parts[w])) << "corner " << i << " moved by 2^-" << k;
    }
    if (!image) continue;
    const CSpace space = CSpace::build(model, "driver", "wheel");
    const Agreement agreement = twins_agree(space, w, &*image);
    // the exact contact structure (real edges' curves and their mapped feature pairs) of the
    // twin charts is the same: what a chart mapped from its twin could carry exactly
    EXPECT_TRUE(agreement.contacts);
    ++symmetric_built;
    same_sets += agreement.as_sets ? 1 : 0;
    same_order += agreement.in_order ? 1 : 0;
    same_skeleton += agreement.skeleton ? 1 : 0;
    // the map mutated (the identity, or every edge one further): caught
    std::vector<std::vector<cspace::HalfTurnImage>> shifted = *image;
    for (auto& to : shifted[0]) to.edge = (to.edge + 1) % wheel.edges.size();
    EXPECT_FALSE(twins_agree(space, w, &shifted).contacts);
    EXPECT_FALSE(twins_agree(space, w, nullptr).contacts);
  }
  EXPECT_EQ(symmetric_built, 3u);
  // Not asserted (the evidence of docs/performance.md "Session 66 (geneva66)"): the direct
  // builds of twin charts need not agree in their spurious pieces (the culling's windows end at
  // the quadtree's dyadic cells, found by interval poses of each chart's own angles) nor in
  // their numbering, so a mapped chart cannot be written as the direct build writes it.
  std::cout << "symmetric wheels built: " << symmetric_built << ", twin charts the same as sets: " << same_sets
            << ", in the same order: " << same_order << ", the same edges as multisets (vertices' text aside): "
            << same_skeleton << "\n";
}

// The examples whose wheel is exactly symmetric (a template's geometry, not rounded angle by
// angle): the twin charts' contact structure agrees under the map; how much of the rest agrees
// is printed (the evidence of docs/performance.md "Session 66 (geneva66)").
TEST(HalfTurnSymmetry, SymmetricExamplesTwinChartsCarryTheSameContacts) {
  struct Case {
    const char* file;
    const char* first;
    const char* second;
    const char* wheel;
  };
  for (const Case& c : {Case{"geneva-template.json", "driver", "wheel", "wheel"}, Case{"ratchet.json", "wheel", "pawl", "wheel"}}) {
    SCOPED_TRACE(c.file);
    const Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.file);
    const std::size_t w = part_index(model, c.wheel);
    const auto image = cspace::half_turn_symmetry(model.parts[w]);
    ASSERT_TRUE(image);
    const CSpace space = CSpace::build(model, c.first, c.second);
    const bool wheel_is_x = space.x_part() == c.wheel;
    ASSERT_FALSE(half_turn_twins(space, wheel_is_x).empty());
    const Agreement agreement = twins_agree(space, w, &*image, wheel_is_x);
    EXPECT_TRUE(agreement.contacts);
    std::cout << c.file << ": twin charts " << half_turn_twins(space, wheel_is_x).size() << ", the same as sets "
              << agreement.as_sets << ", in the same order " << agreement.in_order
              << ", the same edges as multisets (vertices' text aside) " << agreement.skeleton << "\n";
    // the map mutated: every image one edge further
    auto shifted = *image;
    for (auto& loop : shifted)
      for (auto& to : loop) to.edge = (to.edge + 1) % model.parts[w].loops[to.loop].edges.size();
    EXPECT_FALSE(twins_agree(space, w, &shifted, wheel_is_x).contacts);
  }
}

TEST(HalfTurnSymmetry, PartsWithoutAHalfTurnChartAreRefused) {
  Model model = geneva();
  Part part = model.parts[part_index(model, "wheel")];
  std::mt19937_64 random(test::test_seed(66));
  part.loops = {star_wheel(random, 4, true)};
  EXPECT_TRUE(cspace::half_turn_symmetry(part));
  Part limited = part;
  limited.motion.angle_limits = RationalInterval{Rational(-1), Rational(1)};
  EXPECT_FALSE(cspace::half_turn_symmetry(limited));
  Part sliding = part;
  sliding.motion.kind = Motion::Kind::translation;
  EXPECT_FALSE(cspace::half_turn_symmetry(sliding));
  // an arc's half turn: same radius and orientation, centre and ends reflected
  Edge arc;
  arc.kind = Edge::Kind::arc;
  arc.center = Point{Rational(3), Rational(4)};
  arc.source = Point{Rational(8), Rational(4)};
  arc.target = Point{Rational(3), Rational(9)};
  arc.radius_squared = Rational(25);
  const Edge turned = cspace::half_turned(arc, Point{Rational(1), Rational(1)});
  EXPECT_EQ(turned.center, (Point{Rational(-1), Rational(-2)}));
  EXPECT_EQ(turned.source, (Point{Rational(-6), Rational(-2)}));
  EXPECT_EQ(turned.target, (Point{Rational(-1), Rational(-7)}));
  EXPECT_TRUE(turned.ccw);
  EXPECT_EQ(turned.radius_squared, Rational(25));
}

}  // namespace
}  // namespace hipair
