// The filtered quadratic traits (src/arrangement/quadratic_traits.hpp) against CGAL's
// algebraic traits: every example model built with both (CSpaceBuildOptions::quadratic_traits)
// gives the same C-space (feature pairs, cells and their kinds, contact edges with their
// curves, contact vertices, point location of random configurations); generated curve sets of
// degree <= 2 in y (random small coefficients, tangencies, common points, duplicated curves,
// common components, vertical lines, isolated points) give the same raw arrangement.
//
// The two stages end spurious stretches at validity boundaries at different rationals (a
// "near" point chosen by each), so raw vertex/edge counts of charts with validity clauses may
// differ by spurious pieces; what is compared on the examples is the C-space.
#include "arrangement/arrangement.hpp"
#include "arrangement/quadratic_traits.hpp"
#include "cspace/builder_impl.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <random>

namespace hipair {
namespace {

using cspace::IntegerPolynomial2;
namespace raw = cspace::raw;
namespace algebra = cspace::algebra;

IntegerPolynomial2 poly(const std::vector<std::vector<long>>& c) {
  IntegerPolynomial2 f;
  for (const auto& row : c) {
    std::vector<mpz_class> r;
    for (long v : row) r.emplace_back(v);
    f.coefficients.push_back(std::move(r));
  }
  return f;
}

struct Counts {
  std::size_t vertices = 0, edges = 0, faces = 0, isolated = 0;
  std::vector<std::size_t> degrees;   // sorted vertex degrees
};

Counts counts(const raw::Arrangement& a) {
  Counts c{a.vertices.size(), a.edges.size(), a.faces.size(), 0, {}};
  for (const auto& v : a.vertices) {
    c.isolated += v.isolated ? 1 : 0;
    c.degrees.push_back(v.around.size());
  }
  std::sort(c.degrees.begin(), c.degrees.end());
  return c;
}

// Two vertices of one arrangement at the same point: same x exactly and overlapping certified
// y bounds (bounds isolate y among the roots of the vertex's curve). CGAL's algebraic stage
// leaves such duplicates on some tangential configurations (seen on random bi-quadratic sets):
// its arrangement is then not a reference.
bool has_duplicate_vertices(const raw::Arrangement& a) {
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    for (std::size_t j = i + 1; j < a.vertices.size(); ++j) {
      const auto &p = a.vertices[i], &q = a.vertices[j];
      if (p.x.upper_bound() < q.x.lower_bound() || q.x.upper_bound() < p.x.lower_bound()) continue;
      if (algebra::compare(p.x, q.x) != 0) continue;
      if (p.y_upper < q.y_lower || q.y_upper < p.y_lower) continue;
      return true;
    }
  return false;
}

// Every vertex of `a` has a vertex of `b` at the same x (exact comparison) with overlapping
// certified y bounds, and the same degree.
void expect_same_vertices(const raw::Arrangement& a, const raw::Arrangement& b, const std::string& what,
                          bool same_degree = true) {
  std::vector<char> used(b.vertices.size(), 0);
  for (const auto& p : a.vertices) {
    bool found = false;
    for (std::size_t j = 0; j < b.vertices.size() && !found; ++j) {
      const auto& q = b.vertices[j];
      if (same_degree && (used[j] || p.around.size() != q.around.size() || p.isolated != q.isolated)) continue;
      if (p.x.upper_bound() < q.x.lower_bound() || q.x.upper_bound() < p.x.lower_bound()) continue;
      if (p.y_upper < q.y_lower || q.y_upper < p.y_lower) continue;
      if (algebra::compare(p.x, q.x) != 0) continue;
      used[j] = same_degree;
      found = true;
    }
    EXPECT_TRUE(found) << what << ": no vertex at x ~ " << p.x.approximate() << ", y ~ " << p.y_lower_bound();
  }
}

struct Comparison {
  bool applied = false;
  bool reference_inconsistent = false;
};

Comparison compare_stages(const raw::Box& box, const std::vector<IntegerPolynomial2>& curves,
                          const std::string& what) {
  std::vector<std::vector<cspace::ValidityClause>> validity;
  std::vector<std::vector<std::pair<Rational, Rational>>> windows;
  raw::Options options;
  raw::Arrangement reference = raw::build_arrangement(box, curves, validity, windows, options);
  std::optional<raw::Arrangement> fast = raw::build_quadratic_arrangement(box, curves, validity, windows, options);
  Comparison result;
  if (!fast) return result;
  result.applied = true;
  Counts p = counts(*fast), q = counts(reference);
  const bool same = p.vertices == q.vertices && p.edges == q.edges && p.faces == q.faces;
  if (!same && has_duplicate_vertices(reference)) {
    // CGAL's arrangement has one point as two vertices: every point of it is a vertex here
    result.reference_inconsistent = true;
    EXPECT_FALSE(has_duplicate_vertices(*fast)) << what;
    expect_same_vertices(reference, *fast, what, false);
    return result;
  }
  EXPECT_EQ(p.vertices, q.vertices) << what;
  EXPECT_EQ(p.edges, q.edges) << what;
  EXPECT_EQ(p.faces, q.faces) << what;
  EXPECT_EQ(p.isolated, q.isolated) << what;
  EXPECT_EQ(p.degrees, q.degrees) << what;
  expect_same_vertices(*fast, reference, what);
  return result;
}

const raw::Box unit_box{Rational(-2), Rational(2), Rational(-2), Rational(2)};

TEST(QuadraticTraitsGenerated, RandomSmallCoefficientBiquadraticCurves) {
  std::size_t applied = 0, inconsistent = 0, total = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    std::mt19937 random(seed);
    std::vector<IntegerPolynomial2> curves;
    const int n = 2 + static_cast<int>(random() % 4);
    for (int k = 0; k < n; ++k) {
      std::vector<std::vector<long>> c(3, std::vector<long>(3));
      for (auto& row : c)
        for (auto& v : row) v = static_cast<long>(random() % 7) - 3;
      curves.push_back(poly(c));
    }
    ++total;
    Comparison r = compare_stages(unit_box, curves, "seed " + std::to_string(seed));
    applied += r.applied;
    inconsistent += r.reference_inconsistent;
  }
  // the quadratic stage declines only curve sets with common components
  EXPECT_GE(applied, total * 9 / 10);
  EXPECT_LE(inconsistent, total / 10) << "CGAL's reference arrangement had duplicate vertices too often";
}

TEST(QuadraticTraitsGenerated, DegenerateConfigurations) {
  const auto circle = poly({{-1, 0, 1}, {0}, {1}});             // x^2 + y^2 - 1
  const auto shifted = poly({{3, 0, 1}, {-4}, {1}});            // (x-2)^2 + y^2 - 1: tangent at (1, 0)
  const auto tangent_line = poly({{-1, 1}});                    // y = 1: tangent at (0, 1)
  const auto diagonal = poly({{0, 1}, {-1}});                   // y = x through the centre
  const auto parabola = poly({{0, -1}, {0}, {1}});              // y = x^2: touches y = 0 at 0
  const auto horizontal = poly({{0, 1}});                       // y = 0
  const auto hyperbola = poly({{-1}, {0, 1}});                  // x y = 1 (degree 1 in y)
  const auto with_line = poly({{0, -1, 0}, {1, 0, 0}, {0, -1, 0}, {-1, 0, 1}});   // (x - y)(...)? see below
  const auto node = poly({{0, 0, -1}, {0}, {1}, {1}});          // y^2 = x^2 (x + 1): a node at 0
  const auto isolated = poly({{0, 0, 1}, {0}, {-1}, {1}});      // y^2 = x^2 (x - 1): isolated (0, 0)
  const auto vertical = poly({{0, 0, 1}, {-1, 0, -2}, {0, 0, 1}, {1}});   // contains no vertical line
  const auto with_vertical = poly({{-1, 0, 1}, {-1, 0, 1}});    // (x + 1)(y^2 - 1): line x = -1
  const auto cusp = poly({{0, 0, 1}, {0}, {0}, {-1}});          // y^2 = x^3
  const auto asymptote = poly({{-1, 0}, {0, -1}, {0, 1}});      // y (x^2 - x) = 1: asymptotes in the box
  std::vector<std::pair<std::string, std::vector<IntegerPolynomial2>>> cases = {
      {"tangent circles", {circle, shifted}},
      {"tangent line", {circle, tangent_line}},
      {"three through the centre", {circle, diagonal, horizontal, poly({{0, 1}, {1}})}},
      {"parabola touching a line", {parabola, horizontal}},
      {"duplicated curve", {circle, circle, poly({{-2, 0, 2}, {0}, {2}})}},
      {"hyperbola", {hyperbola, circle, horizontal}},
      {"node", {node, horizontal, diagonal}},
      {"isolated point", {isolated, circle}},
      {"isolated point on a line", {isolated, horizontal}},
      {"vertical line component", {with_vertical, circle, horizontal}},
      {"cusp", {cusp, horizontal, circle}},
      {"asymptotes", {asymptote, circle}},
      {"curve on the box sides", {poly({{-4, 0, 1}}), poly({{-4}, {0}, {1}}), circle}},
      {"tangency at the origin (CGAL: a duplicate vertex)", {vertical, with_line, circle}},
  };
  for (const auto& [name, curves] : cases) {
    Comparison r = compare_stages(unit_box, curves, name);
    EXPECT_TRUE(r.applied) << name;
    if (name.find("CGAL:") == std::string::npos) EXPECT_FALSE(r.reference_inconsistent) << name;
  }
  // curves with a common component: declined (the algebraic traits takes them)
  std::vector<IntegerPolynomial2> common = {poly({{-1, 1}, {-1, 1}}), poly({{-1, 1}, {1, -1}})};   // (y-1)(x+1), (y-1)(1-x)
  std::vector<std::vector<cspace::ValidityClause>> no_validity;
  std::vector<std::vector<std::pair<Rational, Rational>>> no_windows;
  EXPECT_FALSE(raw::build_quadratic_arrangement(unit_box, common, no_validity, no_windows, raw::Options{}));
}

// ------------------------------------------------------------------ examples

void expect_same_space(const CSpace& fast, const CSpace& reference, const std::string& what) {
  ASSERT_EQ(fast.feature_pairs().size(), reference.feature_pairs().size()) << what;
  for (std::size_t i = 0; i < fast.feature_pairs().size(); ++i) {
    EXPECT_EQ(fast.feature_pairs()[i].first_feature, reference.feature_pairs()[i].first_feature) << what;
    EXPECT_EQ(fast.feature_pairs()[i].second_feature, reference.feature_pairs()[i].second_feature) << what;
    EXPECT_EQ(fast.feature_pairs()[i].label, reference.feature_pairs()[i].label) << what;
  }
  // cells: the same kinds
  std::map<CellKind, int> kinds_fast, kinds_reference;
  for (const auto& c : fast.cells()) ++kinds_fast[c.kind];
  for (const auto& c : reference.cells()) ++kinds_reference[c.kind];
  EXPECT_EQ(kinds_fast, kinds_reference) << what;
  // real edges: the same feature pairs and roles (their count may differ: a spurious stretch
  // of one build may split a contact edge, see the file comment)
  auto edge_keys = [](const CSpace& space) {
    std::set<std::pair<std::vector<std::size_t>, int>> keys;
    for (const auto& e : space.edges())
      if (e.real) keys.insert({e.curves, static_cast<int>(e.role)});
    return keys;
  };
  EXPECT_EQ(edge_keys(fast), edge_keys(reference)) << what;
  const CSpaceStatistics &s = fast.statistics(), &t = reference.statistics();
  EXPECT_EQ(s.curves, t.curves) << what;
  EXPECT_EQ(s.touching_edges, t.touching_edges) << what;
  EXPECT_EQ(s.touching_vertices, t.touching_vertices) << what;
  EXPECT_EQ(s.cells, t.cells) << what;
  // vertices of real edges: for each one of the quadratic build, one of the reference in the
  // same chart at the same x (exact comparison) with overlapping certified y bounds
  // essential vertices of the contact boundary: ends of real edges where the number of real
  // edges is not two or their feature pairs differ (a vertex splitting one contact edge in
  // two is not essential)
  auto real_vertices = [](const CSpace& space) {
    std::map<std::size_t, std::vector<const CSpaceEdge*>> at;
    for (const auto& e : space.edges())
      if (e.real) {
        at[e.source].push_back(&e);
        at[e.target].push_back(&e);
      }
    std::vector<std::size_t> out;
    for (const auto& [v, edges] : at)
      if (edges.size() != 2 || edges[0]->curves != edges[1]->curves || edges[0]->role != edges[1]->role)
        out.push_back(v);
    return out;
  };
  auto to_real = [](const AlgebraicNumber& a) {
    algebra::Real r;
    r.polynomial = a.polynomial;
    r.lower = a.lower;
    r.upper = a.upper;
    r.exact = a.exact;
    return r;
  };
  std::vector<std::size_t> mine = real_vertices(fast), theirs = real_vertices(reference);
  EXPECT_EQ(mine.size(), theirs.size()) << what;
  for (std::size_t i : mine) {
    const CSpaceVertex& p = fast.vertices()[i];
    algebra::Real px = to_real(p.x);
    bool found = false;
    for (std::size_t j : theirs) {
      const CSpaceVertex& q = reference.vertices()[j];
      if (q.chart != p.chart || p.y_upper < q.y_lower || q.y_upper < p.y_lower) continue;
      algebra::Real qx = to_real(q.x);
      if (px.upper_bound() < qx.lower_bound() || qx.upper_bound() < px.lower_bound()) continue;
      if (algebra::compare(px, qx) == 0) {
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << what << ": contact vertex at x ~ " << p.x.approximate() << " only in the quadratic build";
  }
  // point location of random configurations: the same class, and a consistent cell map
  std::mt19937_64 random(7);
  std::map<std::size_t, std::size_t> cell_map;
  for (int i = 0; i < 1500; ++i) {
    ChartPoint point = test::random_tile_point(fast, random);
    Location a = fast.locate(point), b = reference.locate(point);
    ASSERT_EQ(static_cast<int>(a.kind), static_cast<int>(b.kind)) << what << " at sample " << i;
    if (a.kind == Location::Kind::free || a.kind == Location::Kind::blocked) {
      auto [it, inserted] = cell_map.emplace(a.cell, b.cell);
      EXPECT_EQ(it->second, b.cell) << what << ": one cell of the quadratic build maps to two";
    }
  }
}

TEST(QuadraticTraitsExamples, SameCSpaceAsAlgebraicTraits) {
  const std::filesystem::path directory(HIPAIR_EXAMPLES);
  std::size_t quadratic_charts = 0, checked = 0;
  for (const char* name : {"geneva.json", "geneva-drive.json", "geneva-template.json", "ratchet.json",
                           "escapement.json", "cam-follower.json", "cam-follower-lever.json", "cam-drive.json",
                           "film-advance.json", "lever-stop.json", "scotch-yoke.json", "bouncing-bar.json",
                           "peg-in-hole.json", "peg-in-slot.json"}) {
    const auto path = directory / name;
    if (!std::filesystem::exists(path)) continue;
    Model model = read_model_file(path.string());
    CSpaceBuildOptions fast_options, reference_options;
    reference_options.quadratic_traits = false;
    std::vector<CSpace> fast = CSpace::build_all(model, fast_options);
    std::vector<CSpace> reference = CSpace::build_all(model, reference_options);
    ASSERT_EQ(fast.size(), reference.size()) << name;
    for (std::size_t i = 0; i < fast.size(); ++i) {
      EXPECT_EQ(reference[i].statistics().quadratic_charts, 0u);
      if (fast[i].statistics().quadratic_charts == 0) continue;
      quadratic_charts += fast[i].statistics().quadratic_charts;
      ++checked;
      expect_same_space(fast[i], reference[i], std::string(name) + " " + fast[i].first_part() + ":" +
                                                   fast[i].second_part());
    }
  }
  EXPECT_GT(quadratic_charts, 0u);
  EXPECT_GT(checked, 0u);
}

// Gears have 250-650-bit coefficients: the multiple-precision filter and the subresultant
// equality test decide their predicates (declined by default above 200 bits, taken here). A 10 x 10 tooth
// pair's operating region (about 10 s per build on this machine).
TEST(QuadraticTraitsExamples, SameGearCSpaceAsAlgebraicTraits) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(10);
  read.parameter_values["teeth-2"] = Rational(10);
  read.allow_out_of_tolerance = true;
  Model model = read_model_file((std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json").string(), read);
  CSpaceBuildOptions fast_options, reference_options;
  fast_options.operating_region = reference_options.operating_region = true;
  fast_options.quadratic_max_coefficient_bits = 1024;   // the default (200) keeps gears algebraic
  reference_options.quadratic_traits = false;
  CSpace fast = CSpace::build(model, "pinion", "gear", fast_options);
  CSpace reference = CSpace::build(model, "pinion", "gear", reference_options);
  EXPECT_EQ(reference.statistics().quadratic_charts, 0u);
  EXPECT_GE(fast.statistics().quadratic_charts, 50u);
  // the coefficients are big (the class this test is about)
  std::size_t max_bits = 0;
  for (std::size_t e = 0; e < fast.edges().size(); ++e)
    for (const auto& row : fast.edge_polynomial_coefficients(e))
      for (const auto& c : row) max_bits = std::max<std::size_t>(max_bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  EXPECT_GT(max_bits, 400u);
  expect_same_space(fast, reference, "spur gears 10x10 pinion:gear");
}

}  // namespace
}  // namespace hipair
