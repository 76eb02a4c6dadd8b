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
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <random>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>

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

// ------------------------------------------------------------------ exact vertex comparison

// Univariate helpers on algebra::Polynomial (coefficients by ascending power).
algebra::Polynomial padd(const algebra::Polynomial& a, const algebra::Polynomial& b) {
  algebra::Polynomial r(std::max(a.size(), b.size()));
  for (std::size_t i = 0; i < a.size(); ++i) r[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) r[i] += b[i];
  algebra::trim(r);
  return r;
}
algebra::Polynomial pmul(const algebra::Polynomial& a, const algebra::Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  algebra::Polynomial r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  algebra::trim(r);
  return r;
}
algebra::Polynomial pscale(const algebra::Polynomial& a, const mpz_class& k) {
  algebra::Polynomial r(a);
  for (auto& c : r) c *= k;
  algebra::trim(r);
  return r;
}
// f = col[0] + col[1] y + col[2] y^2 (degree <= 2 in y)
std::array<algebra::Polynomial, 3> columns_of(const IntegerPolynomial2& f) {
  std::array<algebra::Polynomial, 3> col;
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j) {
      if (sgn(f.coefficients[i][j]) == 0) continue;
      if (j > 2) throw std::runtime_error("test: degree > 2 in y");
      col[j].resize(std::max(col[j].size(), i + 1));
      col[j][i] = f.coefficients[i][j];
    }
  for (auto& c : col) algebra::trim(c);
  return col;
}
int sign_of(const algebra::Polynomial& p, const algebra::Real& x) { return p.empty() ? 0 : algebra::sign_at(p, x); }

// Are two vertices at the same exact x (x already compared equal) at the same y? Exact:
//  - rational x: both y are exact algebraic numbers, compared exactly;
//  - the same curve up to a constant factor: the same branch (index among the fibre's roots);
//  - otherwise (x irrational, different curves g1, g2 of degree <= 2 in y): with
//    r = a1 g2 - a2 g1 = r1 y + r0 (a_k leading in y), y1 is a root of g2 iff y1 = y* =
//    -r0/r1 (r1(x) != 0) and g1(x, y*) = 0 (a1 r0^2 - b1 r0 r1 + c1 r1^2 at x), and then
//    y1 = y* iff y* lies in y1's isolating bounds; equal iff y* is in both vertices' bounds.
//    Fibres proportional at x (r1 = r0 = 0): the same branch. Linear fibres: c1 b2 = c2 b1.
bool same_y(const raw::Vertex& p, const raw::Vertex& q) {
  if (p.y_exact && q.y_exact) return algebra::compare(p.y, q.y) == 0;
  auto normal = [](const IntegerPolynomial2& f) {
    std::string key = algebra::to_string(f, "x", "y");
    return key;
  };
  auto negated = [](IntegerPolynomial2 f) {
    for (auto& row : f.coefficients)
      for (auto& c : row) c = -c;
    return f;
  };
  if (normal(p.y_curve) == normal(q.y_curve) || normal(negated(p.y_curve)) == normal(q.y_curve))
    return p.y_branch == q.y_branch;
  const algebra::Real& x = p.x;
  auto g1 = columns_of(p.y_curve), g2 = columns_of(q.y_curve);
  const raw::Vertex* first = &p;
  const raw::Vertex* second = &q;
  if (sign_of(g1[2], x) == 0 && sign_of(g2[2], x) != 0) {
    std::swap(g1, g2);
    std::swap(first, second);
  }
  auto in_bounds = [&](const algebra::Polynomial& r0, const algebra::Polynomial& r1, const raw::Vertex& v) {
    // -r0/r1 in [v.y_lower, v.y_upper] at x (r1(x) != 0)
    const int s1 = sign_of(r1, x);
    auto minus = [&](const Rational& bound) {   // sign of (-r0/r1 - bound)
      algebra::Polynomial t = padd(pscale(r0, bound.get_den()), pscale(r1, bound.get_num()));
      return -sign_of(t, x) * s1;
    };
    return minus(v.y_lower) >= 0 && minus(v.y_upper) <= 0;
  };
  if (sign_of(g1[2], x) != 0) {
    algebra::Polynomial r1 = padd(pmul(g1[2], g2[1]), pscale(pmul(g2[2], g1[1]), -1));
    algebra::Polynomial r0 = padd(pmul(g1[2], g2[0]), pscale(pmul(g2[2], g1[0]), -1));
    if (sign_of(r1, x) == 0) return sign_of(r0, x) == 0 && p.y_branch == q.y_branch;
    algebra::Polynomial h = padd(padd(pmul(g1[2], pmul(r0, r0)), pscale(pmul(g1[1], pmul(r0, r1)), -1)),
                                 pmul(g1[0], pmul(r1, r1)));
    if (sign_of(h, x) != 0) return false;
    return in_bounds(r0, r1, *first) && in_bounds(r0, r1, *second);
  }
  // both fibres have degree <= 1 at x
  if (sign_of(g1[1], x) == 0 || sign_of(g2[1], x) == 0)
    throw std::runtime_error("test: vertex on a vertical line at an irrational x");
  return sign_of(padd(pmul(g1[0], g2[1]), pscale(pmul(g2[0], g1[1]), -1)), x) == 0;
}

// Are two vertices the same point? x compared exactly, y exactly when the certified bounds
// overlap (disjoint bounds: different points).
bool same_point(const raw::Vertex& p, const raw::Vertex& q) {
  if (p.x.upper_bound() < q.x.lower_bound() || q.x.upper_bound() < p.x.lower_bound()) return false;
  if (p.y_upper < q.y_lower || q.y_upper < p.y_lower) return false;
  if (algebra::compare(p.x, q.x) != 0) return false;
  return same_y(p, q);
}

// Two vertices of one arrangement at the same point. (CGAL 5.5.1's incremental insertion
// produced such duplicates, docs/cspace.md "A CGAL failure and its guard"; the algebraic stage
// now checks for them and rebuilds.)
bool has_duplicate_vertices(const raw::Arrangement& a) {
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    for (std::size_t j = i + 1; j < a.vertices.size(); ++j)
      if (same_point(a.vertices[i], a.vertices[j])) return true;
  return false;
}

// Every vertex of `a` has a distinct vertex of `b` at the same point (exact) with the same
// degree and isolation.
void expect_same_vertices(const raw::Arrangement& a, const raw::Arrangement& b, const std::string& what) {
  std::vector<char> used(b.vertices.size(), 0);
  for (const auto& p : a.vertices) {
    bool found = false;
    for (std::size_t j = 0; j < b.vertices.size() && !found; ++j) {
      const auto& q = b.vertices[j];
      if (used[j] || p.around.size() != q.around.size() || p.isolated != q.isolated) continue;
      if (!same_point(p, q)) continue;
      used[j] = 1;
      found = true;
    }
    EXPECT_TRUE(found) << what << ": no vertex at x ~ " << p.x.approximate() << ", y ~ " << p.y_lower_bound();
  }
}

// Both stages on the same input: the quadratic stage must apply (unless `may_decline`), and
// the two arrangements must be the same (counts, degrees, every vertex at the same exact
// point), neither with a point as two vertices. Returns whether the quadratic stage applied.
bool compare_stages(const raw::Box& box, const std::vector<IntegerPolynomial2>& curves, const std::string& what,
                    const std::vector<std::vector<cspace::ValidityClause>>& validity = {},
                    bool may_decline = false) {
  std::vector<std::vector<std::pair<Rational, Rational>>> windows;
  raw::Options options;
  raw::Arrangement reference = raw::build_arrangement(box, curves, validity, windows, options);
  std::optional<raw::Arrangement> fast = raw::build_quadratic_arrangement(box, curves, validity, windows, options);
  if (!may_decline) EXPECT_TRUE(fast.has_value()) << what << ": the quadratic stage declined";
  EXPECT_FALSE(has_duplicate_vertices(reference)) << what;
  if (!fast) return false;
  EXPECT_FALSE(has_duplicate_vertices(*fast)) << what;
  Counts p = counts(*fast), q = counts(reference);
  EXPECT_EQ(p.vertices, q.vertices) << what;
  EXPECT_EQ(p.edges, q.edges) << what;
  EXPECT_EQ(p.faces, q.faces) << what;
  EXPECT_EQ(p.isolated, q.isolated) << what;
  EXPECT_EQ(p.degrees, q.degrees) << what;
  expect_same_vertices(*fast, reference, what);
  return true;
}

const raw::Box unit_box{Rational(-2), Rational(2), Rational(-2), Rational(2)};

std::vector<IntegerPolynomial2> random_curves(unsigned seed) {
  std::mt19937 random(seed);
  std::vector<IntegerPolynomial2> curves;
  const int n = 2 + static_cast<int>(random() % 4);
  for (int k = 0; k < n; ++k) {
    std::vector<std::vector<long>> c(3, std::vector<long>(3));
    for (auto& row : c)
      for (auto& v : row) v = static_cast<long>(random() % 7) - 3;
    curves.push_back(poly(c));
  }
  return curves;
}

// Every seed must agree (no tolerance). Until session 9 up to 10 % of seeds were excused as
// "CGAL wrong on tangential inputs"; the one such seed (47) was CGAL 5.5.1's incremental
// insertion recording (0, 0) as two vertices, now caught and rebuilt by the algebraic stage.
TEST(QuadraticTraitsGenerated, RandomSmallCoefficientBiquadraticCurves) {
  std::size_t applied = 0, total = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    ++total;
    // the quadratic stage declines only curve sets with common components
    applied += compare_stages(unit_box, random_curves(seed), "seed " + std::to_string(seed), {}, true);
  }
  EXPECT_GE(applied, total * 9 / 10);
}

// Pinned reproductions of the disagreement once excused: generated seed 47 (five curves; CGAL's
// incremental insertion put (0, 0) in twice, left curve 3 with a gap at x ~ 0.2873 and missed
// its transversal crossing with curve 2 at x ~ 0.12932; checked independently with
// tests/arrangement/exact_seed_check.py), and its minimal core: curve 0 (a vertical tangent at
// (0, 0)) inserted before curve 3 (cut at x = 0, where its other branch has a horizontal
// tangent). The quadratic stage's counts are the exact ones.
TEST(QuadraticTraitsGenerated, CgalDuplicateVertexReproductions) {
  const auto curves = random_curves(47);
  const auto f0 = poly({{0, 0, -3}, {3, 3, -1}, {3, -3, -1}});
  const auto f3 = poly({{0, -1, 1}, {2, 0, -2}, {-3, -1, 3}});
  ASSERT_EQ(curves.size(), 5u);
  EXPECT_EQ(algebra::to_string(curves[0], "x", "y"), algebra::to_string(f0, "x", "y"));
  EXPECT_EQ(algebra::to_string(curves[3], "x", "y"), algebra::to_string(f3, "x", "y"));
  for (bool aggregated : {false, true}) {
    raw::Options options;
    options.aggregated_insertion = aggregated;
    const std::string how = aggregated ? " (sweep)" : " (incremental)";
    for (const auto& [what, set, vertices] :
         {std::tuple{"seed 47", curves, std::size_t{78}}, std::tuple{"curves 0 and 3 of seed 47", std::vector{f0, f3}, std::size_t{22}}}) {
      raw::Arrangement a = raw::build_arrangement(unit_box, set, {}, {}, options);
      EXPECT_EQ(a.vertices.size(), vertices) << what << how;
      EXPECT_FALSE(has_duplicate_vertices(a)) << what << how;
      // the crossing of curves 2 and 3 at x ~ 0.129322885556, y ~ 0.256105727582
      if (set.size() == 5) {
        bool crossing = false;
        for (const auto& v : a.vertices)
          crossing |= std::abs(v.x.approximate() - 0.129322885556) < 1e-9 && v.around.size() == 4;
        EXPECT_TRUE(crossing) << what << how;
      }
    }
    compare_stages(unit_box, curves, "seed 47");
    compare_stages(unit_box, {f0, f3}, "curves 0 and 3 of seed 47");
  }
  // the smallest reproduction: two whole curves tangent at (0, 0), both with a vertical tangent
  // there (zero-clearance set 1 below); CGAL's incremental insertion alone gives two vertices at
  // (0, 0) (Arrangement_2::is_valid: are_vertices_unique), with a third and fourth curve through
  // (0, 0) a precondition failure, and the box pieces a corrupt face boundary
  const auto g1 = poly({{0, 0, -3}, {2, 2, 2}, {-2, -1, -1}});   // -(x^2y^2 + x^2y + 2x^2 - 2xy^2 - 2xy - 2x + 3y^2)
  const auto g2 = poly({{0, 0, 24}, {2, 38, 2}, {10, -1, -1}});
  for (const auto& [what, set] : {std::pair{"two curves tangent at a vertical tangent", std::vector{g1, g2}},
                                   std::pair{"with the tangent line and a crossing curve",
                                             std::vector{g1, g2, poly({{0}, {2}}),
                                                         poly({{0, 3, 1}, {-1, 3, -2}, {2, -3}})}}}) {
    raw::Arrangement a = raw::build_arrangement(unit_box, set, {}, {}, raw::Options{});
    std::size_t at_origin = 0;
    for (const auto& v : a.vertices) at_origin += v.x.exact && sgn(v.x.lower) == 0 && v.y_exact && v.y.exact && sgn(v.y.lower) == 0;
    EXPECT_EQ(at_origin, 1u) << what;
    compare_stages(unit_box, set, what);
  }
}

Rational random_rational(std::mt19937& random) {
  return Rational(static_cast<long>(random() % 13) - 6, static_cast<long>(1 + random() % 4));
}

// Clears denominators of a polynomial with rational coefficients c[i][j] (x^i y^j).
IntegerPolynomial2 integer_polynomial(const std::vector<std::vector<Rational>>& c) {
  mpz_class l = 1;
  for (const auto& row : c)
    for (const auto& v : row) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), v.get_den_mpz_t());
  IntegerPolynomial2 f;
  for (const auto& row : c) {
    std::vector<mpz_class> r;
    for (const auto& v : row) r.push_back(mpz_class(v * l));
    f.coefficients.push_back(std::move(r));
  }
  return f;
}

Rational evaluate(const std::vector<std::vector<Rational>>& c, const Rational& x, const Rational& y) {
  Rational sum = 0, xi = 1;
  for (const auto& row : c) {
    Rational yj = 1;
    for (const auto& v : row) {
      sum += v * xi * yj;
      yj *= y;
    }
    xi *= x;
  }
  return sum;
}

// Zero clearance by construction: curves through a rational point P with exactly the same
// tangent there (g2 = g1 + k L^2 with L a line through P: g2(P) = g1(P) = 0 and equal
// gradients), the common tangent line itself, and a curve crossing through P; tangencies of
// same and opposite curvature. Exact rational tangency, no rounding.
TEST(QuadraticTraitsGenerated, ZeroClearanceTangentCurves) {
  std::size_t tangent_sets = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::mt19937 random(1000 + seed);
    const Rational px(static_cast<long>(random() % 5) - 2, 2), py(static_cast<long>(random() % 5) - 2, 3);
    auto random_through_p = [&]() {
      std::vector<std::vector<Rational>> c(3, std::vector<Rational>(3));
      for (auto& row : c)
        for (auto& v : row) v = Rational(static_cast<long>(random() % 7) - 3);
      c[0][0] -= evaluate(c, px, py);   // through P
      return c;
    };
    auto g1 = random_through_p();
    // gradient at P
    Rational gx = 0, gy = 0;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) {
        Rational xi = 1, yj = 1;
        for (std::size_t k = 0; k + 1 < i; ++k) xi *= px;
        for (std::size_t k = 0; k + 1 < j; ++k) yj *= py;
        if (i > 0) {
          Rational yj_full = 1;
          for (std::size_t k = 0; k < j; ++k) yj_full *= py;
          gx += g1[i][j] * Rational(static_cast<long>(i)) * xi * yj_full;
        }
        if (j > 0) {
          Rational xi_full = 1;
          for (std::size_t k = 0; k < i; ++k) xi_full *= px;
          gy += g1[i][j] * Rational(static_cast<long>(j)) * xi_full * yj;
        }
      }
    if (gx == 0 && gy == 0) continue;   // P singular: no tangent line
    ++tangent_sets;
    // L = a (x - px) + b (y - py), random direction; g2 = g1 + k L^2
    const Rational a(static_cast<long>(random() % 5) - 2), b(static_cast<long>(random() % 3) + 1);
    const Rational k = (random() % 2 ? 1 : -1) * Rational(static_cast<long>(1 + random() % 3));
    auto g2 = g1;
    g2[0][0] += k * (a * px + b * py) * (a * px + b * py);
    g2[1][0] += k * (-2 * a * (a * px + b * py));
    g2[0][1] += k * (-2 * b * (a * px + b * py));
    g2[2][0] += k * a * a;
    g2[0][2] += k * b * b;
    g2[1][1] += k * 2 * a * b;
    // the common tangent line gx (x - px) + gy (y - py) = 0
    std::vector<std::vector<Rational>> tangent(3, std::vector<Rational>(3));
    tangent[0][0] = -gx * px - gy * py;
    tangent[1][0] = gx;
    tangent[0][1] = gy;
    // a curve through P, generically transversal
    auto g3 = random_through_p();
    std::vector<IntegerPolynomial2> set = {integer_polynomial(g1), integer_polynomial(g2), integer_polynomial(tangent),
                                           integer_polynomial(g3)};
    // sanity: P is on every curve (exact)
    for (const auto& f : set) ASSERT_EQ(algebra::sign_at(f, px, py), 0) << "seed " << seed;
    compare_stages(unit_box, set, "zero-clearance seed " + std::to_string(seed), {}, true);
    compare_stages(unit_box, {set[0], set[1]}, "tangent pair seed " + std::to_string(seed), {}, true);
  }
  EXPECT_GE(tangent_sets, 25u);
}

// Generated validity clauses: every curve valid only where one of two random linear atoms
// (and, for some curves, a second clause) is >= 0. The stages' spurious stretches past a
// validity end stop at points of their own choice, so what is compared is: the quadratic
// stage applies, neither arrangement has a point as two vertices, and every vertex where two
// different input curves meet inside the box in both is found in the other.
TEST(QuadraticTraitsGenerated, RandomValidityClauses) {
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::vector<IntegerPolynomial2> curves = random_curves(seed);
    std::mt19937 random(500 + seed);
    std::vector<std::vector<cspace::ValidityClause>> validity(curves.size());
    for (auto& clauses : validity) {
      const int count = 1 + static_cast<int>(random() % 2);
      for (int c = 0; c < count; ++c) {
        cspace::ValidityClause clause;
        for (int atom = 0; atom < 2; ++atom)
          clause.atoms.push_back(poly({{static_cast<long>(random() % 5) - 2, static_cast<long>(random() % 5) - 2},
                                       {static_cast<long>(random() % 5) - 2}}));
        clauses.push_back(std::move(clause));
      }
    }
    std::vector<std::vector<std::pair<Rational, Rational>>> windows;
    raw::Options options;
    const std::string what = "validity seed " + std::to_string(seed);
    raw::Arrangement reference = raw::build_arrangement(unit_box, curves, validity, windows, options);
    std::optional<raw::Arrangement> fast = raw::build_quadratic_arrangement(unit_box, curves, validity, windows, options);
    EXPECT_FALSE(has_duplicate_vertices(reference)) << what;
    if (!fast) continue;   // common components: declined
    EXPECT_FALSE(has_duplicate_vertices(*fast)) << what;
    // vertices of degree >= 3 not on the box: crossings and branchings of the valid pieces;
    // a spurious stretch may add a crossing to one side only, so only degree >= 4 vertices
    // (two valid pieces crossing) of the quadratic build are required in the reference
    for (const auto& p : fast->vertices) {
      if (p.around.size() < 4) continue;
      bool found = false;
      for (const auto& q : reference.vertices) found = found || (q.around.size() >= 4 && same_point(p, q));
      EXPECT_TRUE(found) << what << ": crossing at x ~ " << p.x.approximate() << " only in the quadratic build";
    }
  }
}

// A clip's cut abscissae are the roots of several polynomials (box sides, each validity atom's
// resultant with the curve, the horizontal tangents); one irrational root of two of them is one
// cut (clip's CutOrder: such pairs decided equal by the gcd, each pair's order kept for the
// merge of equal cuts). Atoms that hold everywhere in the box (squares, times x^2 + 1 or
// y^2 + 1) but whose resultants share the roots +-sqrt(2), +-sqrt(3), +-1/sqrt(5) with each
// other: the pieces are those of the curves without validity, so both stages must build the
// same arrangement (compare_stages) with and without the clauses.
TEST(QuadraticTraitsGenerated, CutsSharedByValidityAtomsAreOneCut) {
  auto product = [](const std::vector<std::vector<long>>& x_factors, const std::vector<long>& y_factor) {
    algebra::Polynomial px{mpz_class(1)};
    for (const auto& factor : x_factors) {
      algebra::Polynomial q;
      for (long c : factor) q.emplace_back(c);
      px = pmul(px, q);
    }
    IntegerPolynomial2 f;
    for (const auto& cx : px) {
      std::vector<mpz_class> row;
      for (long cy : y_factor) row.emplace_back(cx * cy);
      f.coefficients.push_back(std::move(row));
    }
    return f;
  };
  const std::vector<long> s2{-2, 0, 1}, s3{-3, 0, 1}, s5{-1, 0, 5}, half{-1, 2}, plus1{1, 0, 1}, plus4{4, 0, 1};
  const std::vector<IntegerPolynomial2> atoms = {
      product({s2, s2}, {1}),           product({s2, s2, plus1}, {1}),     product({s2, half, s2, half}, {1}),
      product({s2, s3, s2, s3}, {1}),   product({s3, s3}, {1, 0, 1}),      product({s3, s5, s3, s5}, {1}),
      product({s5, s5, plus4}, {1}),    product({s2, s2}, {1, 0, 1}),      product({s5, s2, s5, s2}, {1, 0, 1})};
  std::size_t applied = 0;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    std::vector<IntegerPolynomial2> curves = random_curves(seed);
    std::mt19937 random(900 + seed);
    std::vector<std::vector<cspace::ValidityClause>> validity(curves.size());
    for (auto& clauses : validity)
      for (int c = 0; c < 3; ++c) clauses.push_back(cspace::ValidityClause{{atoms[random() % atoms.size()]}});
    const std::string what = "shared cuts seed " + std::to_string(seed);
    if (compare_stages(unit_box, curves, what, validity, true)) {
      ++applied;
      std::optional<raw::Arrangement> with = raw::build_quadratic_arrangement(unit_box, curves, validity, {}, {});
      std::optional<raw::Arrangement> without = raw::build_quadratic_arrangement(unit_box, curves, {}, {}, {});
      ASSERT_TRUE(with && without) << what;
      Counts p = counts(*with), q = counts(*without);
      EXPECT_EQ(p.vertices, q.vertices) << what;
      EXPECT_EQ(p.edges, q.edges) << what;
      EXPECT_EQ(p.faces, q.faces) << what;
      EXPECT_EQ(p.degrees, q.degrees) << what;
      expect_same_vertices(*with, *without, what);
    }
  }
  EXPECT_GE(applied, 20u);
}

void expect_identical_reals(const algebra::Real& a, const algebra::Real& b, const std::string& what) {
  EXPECT_EQ(a.polynomial, b.polynomial) << what;
  EXPECT_EQ(a.lower, b.lower) << what;
  EXPECT_EQ(a.upper, b.upper) << what;
  EXPECT_EQ(a.exact, b.exact) << what;
}

// Two arrangements equal field for field: the same numbers (defining polynomials, isolating
// intervals, y bounds), the same numbering of vertices, edges and faces.
void expect_identical(const raw::Arrangement& a, const raw::Arrangement& b, const std::string& what) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size()) << what;
  ASSERT_EQ(a.edges.size(), b.edges.size()) << what;
  ASSERT_EQ(a.faces.size(), b.faces.size()) << what;
  EXPECT_EQ(a.unbounded_face, b.unbounded_face) << what;
  EXPECT_EQ(a.pieces_inserted, b.pieces_inserted) << what;
  for (std::size_t v = 0; v < a.vertices.size(); ++v) {
    const raw::Vertex &p = a.vertices[v], &q = b.vertices[v];
    const std::string where = what + " vertex " + std::to_string(v);
    expect_identical_reals(p.x, q.x, where);
    EXPECT_EQ(p.y_exact, q.y_exact) << where;
    if (p.y_exact) expect_identical_reals(p.y, q.y, where);
    EXPECT_EQ(p.y_lower, q.y_lower) << where;
    EXPECT_EQ(p.y_upper, q.y_upper) << where;
    EXPECT_EQ(p.y_curve.coefficients, q.y_curve.coefficients) << where;
    EXPECT_EQ(p.y_branch, q.y_branch) << where;
    EXPECT_EQ(p.isolated, q.isolated) << where;
    EXPECT_EQ(p.face_below, q.face_below) << where;
    EXPECT_EQ(p.face_above, q.face_above) << where;
    ASSERT_EQ(p.around.size(), q.around.size()) << where;
    for (std::size_t k = 0; k < p.around.size(); ++k) {
      EXPECT_EQ(p.around[k].edge, q.around[k].edge) << where;
      EXPECT_EQ(p.around[k].direction, q.around[k].direction) << where;
      EXPECT_EQ(p.around[k].wedge_face, q.around[k].wedge_face) << where;
    }
  }
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    const raw::Edge &p = a.edges[e], &q = b.edges[e];
    const std::string where = what + " edge " + std::to_string(e);
    EXPECT_EQ(p.min_vertex, q.min_vertex) << where;
    EXPECT_EQ(p.max_vertex, q.max_vertex) << where;
    EXPECT_EQ(p.vertical, q.vertical) << where;
    EXPECT_EQ(p.support.coefficients, q.support.coefficients) << where;
    EXPECT_EQ(p.left_face, q.left_face) << where;
    EXPECT_EQ(p.right_face, q.right_face) << where;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(p.box[k], q.box[k]) << where;
    EXPECT_EQ(p.box_side, q.box_side) << where;
    ASSERT_EQ(p.arc_numbers.events.size(), q.arc_numbers.events.size()) << where;
    for (std::size_t k = 0; k < p.arc_numbers.events.size(); ++k)
      expect_identical_reals(p.arc_numbers.events[k], q.arc_numbers.events[k], where);
    EXPECT_EQ(p.arc_numbers.between, q.arc_numbers.between) << where;
    EXPECT_EQ(p.arc_numbers.at_event, q.arc_numbers.at_event) << where;
  }
  for (std::size_t f = 0; f < a.faces.size(); ++f) {
    const raw::Face &p = a.faces[f], &q = b.faces[f];
    const std::string where = what + " face " + std::to_string(f);
    EXPECT_EQ(p.unbounded, q.unbounded) << where;
    EXPECT_EQ(p.boundary, q.boundary) << where;
    EXPECT_EQ(p.component_starts, q.component_starts) << where;
    EXPECT_EQ(p.isolated_vertices, q.isolated_vertices) << where;
  }
}

// The quadratic traits remembers per thread what does not depend on a tile's box — resultants,
// supports without their events, the square-free tests of what it isolates — because the tiles
// of one chart share their curves. Every tile of a 4 x 4 tiling, for 30 generated curve sets
// with validity clauses, built one after the other in this thread (the memos warm, shared by
// the tiles and the seeds) is, field for field, the tile built alone in a fresh thread (whose
// memos are empty).
TEST(QuadraticTraitsGenerated, TilesBuiltAfterEachOtherAreTheTilesBuiltAlone) {
  std::size_t built = 0, with_vertices = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    std::vector<IntegerPolynomial2> curves = random_curves(seed);
    std::mt19937 random(900 + seed);
    std::vector<std::vector<cspace::ValidityClause>> validity(curves.size());
    for (auto& clauses : validity) {
      if (random() % 3 == 0) continue;
      cspace::ValidityClause clause;
      for (int atom = 0; atom < 1 + static_cast<int>(random() % 2); ++atom)
        clause.atoms.push_back(poly({{static_cast<long>(random() % 5) - 2, static_cast<long>(random() % 5) - 2},
                                     {static_cast<long>(random() % 5) - 2}}));
      clauses.push_back(std::move(clause));
    }
    const std::vector<std::vector<std::pair<Rational, Rational>>> windows;
    const raw::Options options;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const raw::Box tile{Rational(i - 2), Rational(i - 1), Rational(j - 2), Rational(j - 1)};
        const std::string what = "seed " + std::to_string(seed) + " tile " + std::to_string(i) + "," + std::to_string(j);
        std::optional<raw::Arrangement> alone;
        std::string alone_error, warm_error;
        std::thread([&] {
          try {
            alone = raw::build_quadratic_arrangement(tile, curves, validity, windows, options);
          } catch (const std::exception& e) {
            alone_error = e.what();
          }
        }).join();
        std::optional<raw::Arrangement> warm;
        try {
          warm = raw::build_quadratic_arrangement(tile, curves, validity, windows, options);
        } catch (const std::exception& e) {
          warm_error = e.what();
        }
        EXPECT_EQ(alone_error, warm_error) << what;
        ASSERT_EQ(alone.has_value(), warm.has_value()) << what;
        if (!alone) continue;
        ++built;
        with_vertices += alone->vertices.size() > 4 ? 1 : 0;
        expect_identical(*warm, *alone, what);
      }
  }
  EXPECT_GT(built, 300u);
  EXPECT_GT(with_vertices, 150u);
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
      {"tangency at the origin (CGAL's incremental insertion: a duplicate vertex)", {vertical, with_line, circle}},
  };
  for (const auto& [name, curves] : cases) compare_stages(unit_box, curves, name);
  // curves with a common component: declined (the algebraic traits takes them)
  std::vector<IntegerPolynomial2> common = {poly({{-1, 1}, {-1, 1}}), poly({{-1, 1}, {1, -1}})};   // (y-1)(x+1), (y-1)(1-x)
  std::vector<std::vector<cspace::ValidityClause>> no_validity;
  std::vector<std::vector<std::pair<Rational, Rational>>> no_windows;
  EXPECT_FALSE(raw::build_quadratic_arrangement(unit_box, common, no_validity, no_windows, raw::Options{}));
}

// ------------------------------------------------------------------ examples

// ------------------------------------------------------------------ culled vertical lines, windowed roots

IntegerPolynomial2 times(const IntegerPolynomial2& f, const IntegerPolynomial2& g) {
  IntegerPolynomial2 out;
  out.coefficients.assign(f.coefficients.size() + g.coefficients.size() - 1, {});
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j)
      for (std::size_t k = 0; k < g.coefficients.size(); ++k)
        for (std::size_t l = 0; l < g.coefficients[k].size(); ++l) {
          auto& row = out.coefficients[i + k];
          if (row.size() < j + l + 1) row.resize(j + l + 1);
          row[j + l] += f.coefficients[i][j] * g.coefficients[k][l];
        }
  return out;
}

// Random dyadic boxes {x_lo, x_hi, y_lo, y_hi} inside the unit box, sorted by x_lo, some
// sharing a column (the culling's cells: merged along columns, several per column).
std::vector<std::array<double, 4>> random_cells(std::mt19937& random) {
  std::vector<std::array<double, 4>> cells;
  const int columns = 1 + static_cast<int>(random() % 4);
  for (int c = 0; c < columns; ++c) {
    const double x0 = -2 + static_cast<double>(random() % 64) / 16;
    const double x1 = x0 + static_cast<double>(1 + random() % 24) / 16;
    const int stacked = 1 + static_cast<int>(random() % 3);
    for (int k = 0; k < stacked; ++k) {
      const double y0 = -2 + static_cast<double>(random() % 64) / 16;
      cells.push_back({x0, std::min(x1, 2.0), y0, std::min(y0 + static_cast<double>(1 + random() % 24) / 16, 2.0)});
    }
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

// A vertical line of the quadratic stage ends where the culling's surviving cells end: built
// with the cells (every curve the same boxes), its vertical edges lie inside the union of the
// boxes over their x, and every stretch of the unculled build's vertical lines strictly inside
// a box is on a vertical edge of the culled build. Curves: random ones times a factor in x
// alone (lines x = p/q, pairs of lines 4x^2 - k), pure vertical lines, random curves.
TEST(QuadraticTraitsGenerated, VerticalLinesEndWithTheCulledCells) {
  std::size_t vertical_checked = 0, inside_checked = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 random(900 + seed);
    std::vector<IntegerPolynomial2> curves = random_curves(seed);
    const long p = static_cast<long>(random() % 7) - 3, q = 1 + static_cast<long>(random() % 3);
    curves[0] = times(poly({{-p}, {q}}), curves[0]);                      // (q x - p) g
    curves.push_back(poly({{-static_cast<long>(1 + random() % 12)}, {0}, {4}}));   // 4x^2 - k
    if (seed % 2 == 0) curves[1] = times(poly({{-static_cast<long>(random() % 9)}, {0}, {4}}), curves[1]);
    const std::vector<std::array<double, 4>> boxes = random_cells(random);
    std::vector<std::vector<std::array<double, 4>>> cells(curves.size(), boxes);
    raw::Options culled, whole;
    culled.cells = &cells;
    const std::string what = "vertical seed " + std::to_string(seed);
    std::optional<raw::Arrangement> a = raw::build_quadratic_arrangement(unit_box, curves, {}, {}, culled);
    std::optional<raw::Arrangement> b = raw::build_quadratic_arrangement(unit_box, curves, {}, {}, whole);
    ASSERT_EQ(a.has_value(), b.has_value()) << what;
    if (!a) continue;   // common components: declined
    EXPECT_FALSE(has_duplicate_vertices(*a)) << what;
    // the y-ranges (closed, merged) of the boxes whose closed x-range may hold x
    auto covered = [&](const algebra::Real& x) {
      std::vector<std::pair<Rational, Rational>> ys;
      for (const auto& c : boxes)
        if (Rational(c[0]) <= x.upper && x.lower <= Rational(c[1])) ys.emplace_back(Rational(c[2]), Rational(c[3]));
      std::sort(ys.begin(), ys.end());
      std::vector<std::pair<Rational, Rational>> merged;
      for (const auto& y : ys)
        if (!merged.empty() && y.first <= merged.back().second)
          merged.back().second = std::max(merged.back().second, y.second);
        else
          merged.push_back(y);
      return merged;
    };
    for (const auto& e : a->edges) {
      if (!e.vertical || e.box_side >= 0) continue;
      const raw::Vertex &low = a->vertices[e.min_vertex], &high = a->vertices[e.max_vertex];
      bool inside = false;
      // (an end at a cell's side y = c over an irrational x has certified bounds around c)
      for (const auto& [y0, y1] : covered(low.x)) inside = inside || (y0 <= low.y_upper && high.y_lower <= y1);
      EXPECT_TRUE(inside) << what << ": a vertical edge at x ~ " << low.x.approximate() << ", y ~ ["
                          << low.y_lower_bound() << ", " << high.y_upper_bound() << "] outside the cells";
      ++vertical_checked;
    }
    for (const auto& e : b->edges) {
      if (!e.vertical || e.box_side >= 0) continue;
      const raw::Vertex &low = b->vertices[e.min_vertex], &high = b->vertices[e.max_vertex];
      const Rational y = (low.y_upper + high.y_lower) / 2;   // strictly inside the edge
      const algebra::Real& x = low.x;
      bool in_a_box = false;
      for (const auto& c : boxes)
        in_a_box = in_a_box || (Rational(c[0]) < x.lower && x.upper < Rational(c[1]) && Rational(c[2]) < y && y < Rational(c[3]));
      if (!in_a_box) continue;
      ++inside_checked;
      bool found = false;
      for (const auto& f : a->edges) {
        if (!f.vertical || f.box_side >= 0) continue;
        const raw::Vertex &fl = a->vertices[f.min_vertex], &fh = a->vertices[f.max_vertex];
        if (fl.y_upper <= y && y <= fh.y_lower && algebra::compare(fl.x, x) == 0) found = true;
      }
      EXPECT_TRUE(found) << what << ": the line x ~ " << x.approximate() << " at y = " << y.get_d()
                         << " lies in a cell but is not built";
    }
  }
  EXPECT_GT(vertical_checked, 40u);
  EXPECT_GT(inside_checked, 20u);
}

// Windows restrict where a curve's cuts and the resultant roots of two curves are isolated
// (only inside the windows, and over the common x-range of two curves' pieces): every crossing
// of two pieces strictly inside a window is a vertex of both the quadratic and the algebraic
// build (which isolates every root over the whole box), with the same windows for every curve.
TEST(QuadraticTraitsGenerated, CrossingsInsideWindowsAgreeWithTheAlgebraicStage) {
  std::size_t crossings = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::vector<IntegerPolynomial2> curves = random_curves(seed);
    std::mt19937 random(1300 + seed);
    std::vector<std::pair<Rational, Rational>> w;
    Rational at(-2);
    const int count = 1 + static_cast<int>(random() % 3);
    for (int k = 0; k < count; ++k) {
      Rational lo = at + Rational(static_cast<long>(random() % 16), 16);
      Rational hi = lo + Rational(static_cast<long>(1 + random() % 24), 16);
      if (hi > Rational(2)) hi = Rational(2);
      if (!(lo < hi)) break;
      w.emplace_back(lo, hi);
      at = hi + Rational(1, 16);
    }
    std::vector<std::vector<std::pair<Rational, Rational>>> windows(curves.size(), w);
    const std::string what = "windows seed " + std::to_string(seed);
    raw::Options options;
    std::optional<raw::Arrangement> fast = raw::build_quadratic_arrangement(unit_box, curves, {}, windows, options);
    if (!fast) continue;   // common components: declined
    raw::Arrangement reference = raw::build_arrangement(unit_box, curves, {}, windows, options);
    EXPECT_FALSE(has_duplicate_vertices(*fast)) << what;
    auto strictly_inside = [&](const raw::Vertex& v) {
      for (const auto& [lo, hi] : w)
        if (lo < v.x.lower && v.x.upper < hi && Rational(-2) < v.y_lower && v.y_upper < Rational(2)) return true;
      return false;
    };
    auto expect_in = [&](const raw::Arrangement& from, const raw::Arrangement& in, const char* side) {
      for (const auto& p : from.vertices) {
        if (p.around.size() < 4 || !strictly_inside(p)) continue;
        ++crossings;
        bool found = false;
        for (const auto& q : in.vertices) found = found || (q.around.size() >= 4 && same_point(p, q));
        EXPECT_TRUE(found) << what << ": crossing at x ~ " << p.x.approximate() << ", y ~ " << p.y_lower_bound()
                           << " only in the " << side << " build";
      }
    };
    expect_in(*fast, reference, "quadratic");
    expect_in(reference, *fast, "algebraic");
  }
  EXPECT_GT(crossings, 20u);
}

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

// Gears have coefficients of hundreds of bits: the multiple-precision filter and the subresultant
// equality test decide their predicates. A 10 x 10 tooth pair's operating region. (Its largest
// coefficients were 400-650 bits while the flanks' radial segments had irrational lengths: the
// squared arc-segment curves of degree 4 then went to the algebraic traits. Since the segments
// have rational lengths (model-format.md, spur_gear) every curve is of degree 2 and the largest
// coefficients are about 320 bits, still far beyond the double filter's reach.)
TEST(QuadraticTraitsExamples, SameGearCSpaceAsAlgebraicTraits) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(10);
  read.parameter_values["teeth-2"] = Rational(10);
  read.allow_out_of_tolerance = true;
  Model model = read_model_file((std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json").string(), read);
  CSpaceBuildOptions fast_options, reference_options;
  fast_options.operating_region = reference_options.operating_region = true;
  fast_options.quadratic_max_coefficient_bits = 1024;
  reference_options.quadratic_traits = false;
  CSpace fast = CSpace::build(model, "pinion", "gear", fast_options);
  CSpace reference = CSpace::build(model, "pinion", "gear", reference_options);
  EXPECT_EQ(reference.statistics().quadratic_charts, 0u);
  // no chart on the algebraic traits (the quadratic one, or lines and circles only)
  EXPECT_EQ(fast.statistics().quadratic_charts + fast.statistics().circle_segment_charts, fast.statistics().charts);
  // the coefficients are big (the class this test is about)
  std::size_t max_bits = 0;
  for (std::size_t e = 0; e < fast.edges().size(); ++e)
    for (const auto& row : fast.edge_polynomial_coefficients(e))
      for (const auto& c : row) max_bits = std::max<std::size_t>(max_bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  EXPECT_GT(max_bits, 300u);
  expect_same_space(fast, reference, "spur gears 10x10 pinion:gear");
}

}  // namespace
}  // namespace hipair
