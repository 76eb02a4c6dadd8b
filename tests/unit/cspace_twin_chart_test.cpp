// Session 68 (geneva68): a chart built by mapping its half-turn twin (TwinChart,
// cspace/builder_impl.hpp). Where a rotating part maps onto itself under the half turn about its
// pivot exactly (half_turn_symmetry), the chart with its axis at pi is the chart at 0 with the
// part's features read through the half turn; the build copies the chart at 0 instead of
// generating, culling, inserting and classifying the twin's curves. The mapped space must be the
// direct build's exact C-space: the same feature pairs (as identities), charts, statistics, cells
// and faces (kinds, boundary sizes), the same real edges (exact polynomial, role, feature pairs,
// exact end abscissae and the exact ordinate at a rational point inside) and the same vertices'
// exact abscissae, only written through the twin's vertices and numbered otherwise. Checked on
// Geneva and on generated exactly symmetric star wheels against the direct build
// (mapped_twin_charts() off); near-symmetric wheels (an arm's tip moved by 2^-k) are built
// directly: the same space in every piece with and without the switch (compared exactly, not as
// text: two direct builds in one process may write a vertex's number through another defining
// polynomial, the process-wide algebra caches being warmer), and not the symmetric wheel's.
#include "cspace/builder_impl.hpp"
#include "cspace/half_turn_symmetry.hpp"
#include "cli/cspace_json.hpp"
#include "algebra/exact_real.hpp"
#include "test_paths.hpp"
#include "star_wheel_support.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

namespace algebra = cspace::algebra;

using test::geneva;
using test::part_index;
using test::with_wheel;

CSpace build(const Model& model, bool mapped) {
  auto& switch_ = cspace::mapped_twin_charts();
  const bool before = switch_.load();
  switch_.store(mapped);
  CSpace space = CSpace::build(model, "driver", "wheel");
  switch_.store(before);
  return space;
}

algebra::Real real_of(const AlgebraicNumber& n) {
  algebra::Real r;
  r.polynomial = n.polynomial;
  r.lower = n.lower;
  r.upper = n.upper;
  r.exact = n.exact;
  return r;
}

std::string pair_text(const FeaturePair& p) {
  auto f = [](const FeatureIdentity& i) {
    return std::to_string(i.part) + ":" + std::to_string(i.loop) + ":" + std::to_string(i.edge) + ":" +
           std::to_string(static_cast<int>(i.kind));
  };
  return f(p.first) + "/" + f(p.second) + " " + std::to_string(static_cast<int>(p.kind)) + " " + p.label + " " +
         p.first_feature + " " + p.second_feature + " " + std::to_string(p.blocked_sign);
}

// An edge's structure without its vertices or numbers: exact polynomial, role, realness,
// verticality and its feature pairs as identities.
std::string edge_key(const CSpace& space, std::size_t e) {
  const CSpaceEdge& edge = space.edges()[e];
  // (up to its sign: the quadratic traits and the algebraic ones may write one support with
  // opposite signs, and a chart's kept curves, hence its traits, may differ from its twin's)
  std::vector<std::vector<mpz_class>> coefficients = space.edge_polynomial_coefficients(e);
  int sign = 0;
  for (const auto& row : coefficients)
    for (const mpz_class& a : row)
      if (sign == 0) sign = sgn(a);
  if (sign < 0)
    for (auto& row : coefficients)
      for (mpz_class& a : row) a = -a;
  std::string text;
  cli::append_polynomial_text(text, coefficients);
  text += " role " + std::to_string(static_cast<int>(edge.role)) + " real " + std::to_string(edge.real) + " vertical " +
          std::to_string(edge.vertical) + " chart " + std::to_string(edge.chart);
  std::vector<std::string> pairs;
  for (std::size_t p : edge.curves) pairs.push_back(pair_text(space.feature_pairs()[p]));
  std::sort(pairs.begin(), pairs.end());
  for (const auto& p : pairs) text += " | " + p;
  return text;
}

// Is edge a of space A exactly edge b of space B? The same structure, the same exact end
// abscissae, and (non-vertical) the same exact ordinate at a rational abscissa inside; vertical
// edges: the same abscissa and ends' ordinate enclosures that meet.
bool same_edge(const CSpace& A, std::size_t a, const CSpace& B, std::size_t b) {
  const CSpaceEdge& ea = A.edges()[a];
  const CSpaceEdge& eb = B.edges()[b];
  const CSpaceVertex& sa = A.vertices()[ea.source];
  const CSpaceVertex& ta = A.vertices()[ea.target];
  const CSpaceVertex& sb = B.vertices()[eb.source];
  const CSpaceVertex& tb = B.vertices()[eb.target];
  if (!algebra::equal(real_of(sa.x), real_of(sb.x)) || !algebra::equal(real_of(ta.x), real_of(tb.x))) return false;
  if (ea.vertical) {
    auto meet = [](const CSpaceVertex& u, const CSpaceVertex& v) {
      const Rational ul = u.y_exact ? u.y.lower : u.y_lower, uh = u.y_exact ? u.y.upper : u.y_upper;
      const Rational vl = v.y_exact ? v.y.lower : v.y_lower, vh = v.y_exact ? v.y.upper : v.y_upper;
      return !(uh < vl) && !(vh < ul);
    };
    return meet(sa, sb) && meet(ta, tb);
  }
  const Rational inside = algebra::rational_between(real_of(sa.x), real_of(ta.x));
  return algebra::equal(real_of(A.evaluate_exact(a, inside)), real_of(B.evaluate_exact(b, inside)));
}

struct Comparison {
  bool equal = true;
  std::string first_difference;
  std::size_t edges_matched = 0;
  void fail(const std::string& why) {
    if (first_difference.size() < 4000) first_difference += (equal ? "" : "; ") + why;
    equal = false;
  }
};

// The mapped space against the direct build: the same exact C-space (see the file's comment).
// Spurious edges: compared too when `spurious` (they bound nothing; the culling's windows of
// twin charts need not be symmetric, so a mapped chart may list other spurious pieces).
Comparison compare_spaces(const CSpace& A, const CSpace& B, bool spurious) {
  Comparison result;
  // feature pairs as identities (the mapped build registers a twin's new pairs in its source's order)
  {
    std::vector<std::string> pa, pb;
    for (const auto& p : A.feature_pairs()) pa.push_back(pair_text(p));
    for (const auto& p : B.feature_pairs()) pb.push_back(pair_text(p));
    std::sort(pa.begin(), pa.end());
    std::sort(pb.begin(), pb.end());
    if (spurious && pa != pb) result.fail("feature pairs");
  }
  if (A.charts().size() != B.charts().size()) {
    result.fail("chart count");
    return result;
  }
  for (std::size_t c = 0; c < A.charts().size(); ++c) {
    const CSpaceChart &ca = A.charts()[c], &cb = B.charts()[c];
    if (ca.x_lo != cb.x_lo || ca.x_hi != cb.x_hi || ca.y_lo != cb.y_lo || ca.y_hi != cb.y_hi ||
        ca.x_half_turn != cb.x_half_turn || ca.y_half_turn != cb.y_half_turn)
      result.fail("chart " + std::to_string(c));
  }
  const CSpaceStatistics &sa = A.statistics(), &sb = B.statistics();
  if (spurious && (sa.vertices != sb.vertices || sa.edges != sb.edges || sa.faces != sb.faces || sa.curves != sb.curves ||
                   sa.pieces_inserted != sb.pieces_inserted || sa.feature_pairs_considered != sb.feature_pairs_considered ||
                   sa.feature_pairs_culled != sb.feature_pairs_culled))
    result.fail("statistics (all pieces)");
  if (sa.cells != sb.cells || sa.contact_edges != sb.contact_edges || sa.touching_edges != sb.touching_edges ||
      sa.touching_vertices != sb.touching_vertices || sa.touching_undecided != sb.touching_undecided ||
      sa.charts != sb.charts ||
      (spurious && (sa.quadratic_charts != sb.quadratic_charts || sa.circle_segment_charts != sb.circle_segment_charts)))
    result.fail("statistics (cells and contacts): contact edges " + std::to_string(sa.contact_edges) + " / " +
                std::to_string(sb.contact_edges) + ", touching edges " + std::to_string(sa.touching_edges) + " / " +
                std::to_string(sb.touching_edges) + ", vertices " + std::to_string(sa.touching_vertices) + " / " +
                std::to_string(sb.touching_vertices) + ", undecided " + std::to_string(sa.touching_undecided) + " / " +
                std::to_string(sb.touching_undecided) + ", quadratic charts " + std::to_string(sa.quadratic_charts) + " / " +
                std::to_string(sb.quadratic_charts) + ", circle-segment charts " + std::to_string(sa.circle_segment_charts) +
                " / " + std::to_string(sb.circle_segment_charts) + ", cells " + std::to_string(sa.cells) + " / " +
                std::to_string(sb.cells));
  // cells: kind, wrapping, neighbours, real boundary edges (and faces, where every piece is
  // compared: a spurious edge splits a face), as a multiset
  {
    auto cells = [&](const CSpace& s) {
      std::vector<std::string> out;
      for (const CSpaceCell& cell : s.cells())
        out.push_back(std::to_string(static_cast<int>(cell.kind)) + " " + std::to_string(cell.wraps_x) +
                      std::to_string(cell.wraps_y) + " faces " + (spurious ? std::to_string(cell.faces) : "-") +
                      " boundary " + std::to_string(cell.boundary.size()) + " neighbours " +
                      std::to_string(cell.neighbours.size()));
      std::sort(out.begin(), out.end());
      return out;
    };
    const auto ca = cells(A), cb = cells(B);
    if (ca != cb) {
      std::string text = "cells:";
      for (const auto& c : ca) text += " [" + c + "]";
      text += " against";
      for (const auto& c : cb) text += " [" + c + "]";
      result.fail(text);
    }
  }
  for (std::size_t c = 0; c < A.charts().size(); ++c) {
    // faces: kind and boundary cycle sizes (only where every piece is compared: a spurious
    // edge splits a face)
    auto faces = [&](const CSpace& s) {
      std::vector<std::string> out;
      for (const CSpaceFace& face : s.faces(c)) {
        std::vector<std::size_t> cycles;
        for (const auto& cycle : face.boundary) cycles.push_back(cycle.size());
        std::sort(cycles.begin(), cycles.end());
        std::string text = std::to_string(static_cast<int>(face.kind));
        for (std::size_t n : cycles) text += " " + std::to_string(n);
        out.push_back(text);
      }
      std::sort(out.begin(), out.end());
      return out;
    };
    if (spurious && faces(A) != faces(B)) result.fail("faces of chart " + std::to_string(c));
    // vertices: as many per chart (each edge's ends are compared exactly below)
    if (spurious) {
      auto count = [&](const CSpace& s) {
        return std::count_if(s.vertices().begin(), s.vertices().end(), [&](const CSpaceVertex& v) { return v.chart == c; });
      };
      if (count(A) != count(B)) result.fail("vertices of chart " + std::to_string(c));
    }
    // edges: every (real, or every when `spurious`) edge of A matched one to one in B
    std::multimap<std::string, std::size_t> in_b;
    std::size_t count_a = 0;
    for (std::size_t e = 0; e < B.edges().size(); ++e)
      if (B.edges()[e].chart == c && (spurious || B.edges()[e].real)) in_b.emplace(edge_key(B, e), e);
    for (std::size_t e = 0; e < A.edges().size(); ++e) {
      if (A.edges()[e].chart != c || !(spurious || A.edges()[e].real)) continue;
      ++count_a;
      auto [lo, hi] = in_b.equal_range(edge_key(A, e));
      bool found = false;
      for (auto it = lo; it != hi; ++it)
        if (same_edge(A, e, B, it->second)) {
          in_b.erase(it);
          found = true;
          break;
        }
      if (found) {
        ++result.edges_matched;
      } else {
        std::string near;
        for (std::size_t f = 0; f < B.edges().size(); ++f)
          if (B.edges()[f].chart == c && !A.edges()[e].curves.empty() &&
              std::any_of(B.edges()[f].curves.begin(), B.edges()[f].curves.end(), [&](std::size_t p) {
                return pair_text(B.feature_pairs()[p]) == pair_text(A.feature_pairs()[A.edges()[e].curves[0]]);
              }))
            near += "\n  direct edge " + std::to_string(f) + (same_edge(A, e, B, f) ? " (same piece)" : "") + ": " +
                    edge_key(B, f).substr(0, 400);
        result.fail("chart " + std::to_string(c) + " edge " + std::to_string(e) + ": " + edge_key(A, e).substr(0, 400) + near);
      }
    }
    if (!in_b.empty()) result.fail("chart " + std::to_string(c) + ": " + std::to_string(in_b.size()) + " edges only in the direct build");
  }
  return result;
}

// The twin charts of `space` (the wheel, its y axis, at 0 and at pi) written with the same vertex
// text in the same order: what a mapped chart gives (geneva67: the direct build writes six
// vertices per pair otherwise).
bool twins_written_alike(const CSpace& space) {
  const auto& charts = space.charts();
  bool any = false;
  for (std::size_t a = 0; a < charts.size(); ++a)
    for (std::size_t b = a + 1; b < charts.size(); ++b) {
      if (charts[a].x_half_turn != charts[b].x_half_turn || charts[a].y_half_turn == charts[b].y_half_turn) continue;
      any = true;
      std::vector<std::string> va, vb;
      for (const CSpaceVertex& v : space.vertices()) {
        std::string text = v.x.to_string("x") + " " + (v.y_exact ? v.y.to_string("y") : v.y_lower.get_str() + " " + v.y_upper.get_str());
        if (v.chart == a) va.push_back(text);
        if (v.chart == b) vb.push_back(text);
      }
      if (va != vb) return false;
    }
  return any;
}

TEST(CSpaceTwinChart, GenevaMappedTwinsAreTheDirectBuildsExactCSpace) {
  const Model model = geneva();
  ASSERT_TRUE(cspace::half_turn_symmetry(model.parts[part_index(model, "wheel")]));
  const CSpace mapped = build(model, true);
  const CSpace direct = build(model, false);
  // the mapped build was taken (its twins are written alike), the direct one was not
  EXPECT_TRUE(twins_written_alike(mapped));
  EXPECT_FALSE(twins_written_alike(direct));
  // the same exact C-space, every piece included (Geneva's twin charts have the same spurious
  // edges too: docs/cspace.md "Session 67 (geneva67)")
  const Comparison all = compare_spaces(mapped, direct, true);
  EXPECT_TRUE(all.equal) << all.first_difference;
  EXPECT_EQ(all.edges_matched, direct.edges().size());
  // the feature pairs as identities and labels (the twins' new pairs are registered through the
  // half turn; left unmapped, they would name the source chart's features)
  std::set<std::string> mapped_pairs, direct_pairs;
  for (const auto& p : mapped.feature_pairs()) mapped_pairs.insert(pair_text(p));
  for (const auto& p : direct.feature_pairs()) direct_pairs.insert(pair_text(p));
  EXPECT_EQ(mapped_pairs, direct_pairs);
}

TEST(CSpaceTwinChart, GeneratedSymmetricWheelsMappedEqualDirectNearSymmetricBuiltDirectly) {
  const std::uint64_t seed = test::test_seed(68);
  std::mt19937_64 random(seed);
  int all_pieces_equal = 0, wheels = 0;
  for (int arms : {4, 6, 8}) {
    const Loop wheel = test::star_wheel(random, arms, true);
    const Model model = with_wheel(wheel);
    ASSERT_TRUE(cspace::half_turn_symmetry(model.parts[part_index(model, "wheel")])) << "seed " << seed << " arms " << arms;
    const CSpace mapped = build(model, true);
    const CSpace direct = build(model, false);
    ++wheels;
    EXPECT_TRUE(twins_written_alike(mapped)) << "seed " << seed << " arms " << arms;
    // the exact C-space: real edges, cells, contacts (the spurious pieces may differ)
    const Comparison real = compare_spaces(mapped, direct, false);
    EXPECT_TRUE(real.equal) << "seed " << seed << " arms " << arms << ": " << real.first_difference;
    EXPECT_GT(real.edges_matched, 0u);
    all_pieces_equal += compare_spaces(mapped, direct, true).equal ? 1 : 0;
    // near-symmetric: one corner moved by 2^-k: no half turn, built directly whatever the switch
    Model near = model;
    Loop& loop = near.parts[part_index(near, "wheel")].loops[0];
    // an arm's outer corner (the arms' tips meet the driver's lock disk), moved by 2^-k
    const std::size_t corner = 4 * (random() % arms) + 1 + random() % 2;
    const int k = std::uniform_int_distribution<int>(6, 14)(random);
    Point& p = loop.edges[corner].source;
    (random() % 2 ? p.x : p.y) += Rational(mpz_class(1), mpz_class(1) << k);
    loop.edges[(corner + loop.edges.size() - 1) % loop.edges.size()].target = p;
    ASSERT_FALSE(cspace::half_turn_symmetry(near.parts[part_index(near, "wheel")]));
    const CSpace near_direct = build(near, false);
    const Comparison near_same = compare_spaces(build(near, true), near_direct, true);
    EXPECT_TRUE(near_same.equal) << near_same.first_difference
        << "seed " << seed << " arms " << arms << " corner " << corner << " moved by 2^-" << k;
    // the comparison is exact: the symmetric wheel's mapped space is not the near wheel's
    const bool near_equal = compare_spaces(mapped, near_direct, false).equal;
    EXPECT_FALSE(near_equal)
        << "seed " << seed << " arms " << arms << " corner " << corner << " moved by 2^-" << k;
  }
  std::cout << "seed " << seed << ": " << all_pieces_equal << " of " << wheels
            << " mapped spaces equal to the direct build in every piece (spurious ones included)\n";
}


// Both parts symmetric (a chart mapped from a mapped chart, as in the gear trains): Geneva's
// driver replaced by a bar centred on its pivot (corners (80 -+ L, -+ h): its half turn about
// (80, 0) is itself), the wheel by a symmetric star wheel. Three of the four charts are mapped (the
// last through the driver's half turn from the chart mapped through the wheel's); the mapped space
// is the direct build's exact C-space, touching counts included.
TEST(CSpaceTwinChart, BothPartsSymmetricTwinsOfTwinsAreTheDirectBuildsExactCSpace) {
  const std::uint64_t seed = test::test_seed(68);
  std::mt19937_64 random(seed + 1);
  for (int arms : {4, 6}) {
    Model model = with_wheel(test::star_wheel(random, arms, true));
    const Rational length(std::uniform_int_distribution<long>(70, 90)(random), 2);   // 35..45
    const Rational half_width(std::uniform_int_distribution<long>(4, 10)(random), 2); // 2..5
    const Point corners[4] = {{Rational(80 - length), Rational(-half_width)},
                              {Rational(80 + length), Rational(-half_width)},
                              {Rational(80 + length), Rational(half_width)},
                              {Rational(80 - length), Rational(half_width)}};
    Loop bar;
    for (int i = 0; i < 4; ++i) {
      Edge e;
      e.kind = Edge::Kind::segment;
      e.source = corners[i];
      e.target = corners[(i + 1) % 4];
      bar.edges.push_back(e);
    }
    Part& driver = model.parts[part_index(model, "driver")];
    driver.loops = {bar};
    driver.features.clear();
    ASSERT_TRUE(cspace::half_turn_symmetry(driver)) << "seed " << seed;
    ASSERT_TRUE(cspace::half_turn_symmetry(model.parts[part_index(model, "wheel")])) << "seed " << seed;
    const CSpace mapped = build(model, true);
    const CSpace direct = build(model, false);
    ASSERT_EQ(mapped.charts().size(), 4u);
    EXPECT_TRUE(twins_written_alike(mapped)) << "seed " << seed << " arms " << arms;
    const Comparison real = compare_spaces(mapped, direct, false);
    EXPECT_TRUE(real.equal) << "seed " << seed << " arms " << arms << ": " << real.first_difference;
    EXPECT_GT(real.edges_matched, 0u) << "seed " << seed << " arms " << arms;
    // every chart of the mapped space is its chart at (0, 0) written again
    std::vector<std::size_t> per_chart(4, 0);
    for (const CSpaceEdge& edge : mapped.edges()) ++per_chart[edge.chart];
    EXPECT_EQ(per_chart[1], per_chart[0]);
    EXPECT_EQ(per_chart[2], per_chart[0]);
    EXPECT_EQ(per_chart[3], per_chart[0]);
  }
}

}  // namespace
}  // namespace hipair
