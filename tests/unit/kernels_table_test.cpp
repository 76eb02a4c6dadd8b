// The contact table as one dispatch (kernels/contact_table.hpp): the same function in exact
// polynomials of the chart coordinates and in rationals at a configuration, the
// exact-versus-squared policy (the squared form is the product of the two tangency branches),
// the existence rule against the table of docs/contact-kernels.md, the reflex rule, and the
// (1 + t^2) normalisation (kernels/weights.hpp); a model edge as the kernels' feature geometry
// (kernels/model_features.hpp).
#include "algebra/polynomial.hpp"
#include "kernels/contact_table.hpp"
#include "kernels/model_features.hpp"
#include "kernels/weights.hpp"
#include "random_integers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

namespace hipair::cspace {
namespace {

using kernels::ContactType;
using kernels::FeatureGeometry;
using kernels::FeatureShape;
using kernels::Pose;
using kernels::Vector;
using Poly = RationalPolynomial2;

Rational frac(long n, long d) {
  Rational r(n, d);
  r.canonicalize();
  return r;
}

struct Random {
  std::mt19937_64 engine{1010};
  Rational rational(long range, long denominator = 97) {
    std::uniform_int_distribution<long> d(-range * denominator, range * denominator);
    return frac(d(engine), denominator);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine); }
  Vector<Rational> point(long range) { return {rational(range), rational(range)}; }
};

// A random feature; with `rational_roots`, radii are rational and segments have rational
// lengths (direction (3, 4) k), so every radius product has an exact root.
FeatureGeometry<Rational> random_feature(Random& random, FeatureShape shape, bool rational_roots) {
  FeatureGeometry<Rational> f;
  f.shape = shape;
  f.point = random.point(40);
  if (shape == FeatureShape::segment) {
    Rational k = random.rational(5) + 6;
    f.target = rational_roots ? Vector<Rational>{Rational(f.point.x + 3 * k), Rational(f.point.y + 4 * k)} : random.point(40);
  }
  if (shape == FeatureShape::arc) {
    f.center = random.point(40);
    Rational r = random.rational(8) + 9;
    f.radius_squared = rational_roots ? Rational(r * r) : Rational(r * r + frac(1, 3));
    f.convex = random.integer(0, 3) != 0;
    if (random.integer(0, 2) == 0) {
      f.sector.full = true;
    } else {
      f.sector.start = random.point(5);
      f.sector.end = random.point(5);
      f.sector.large = random.integer(0, 1) == 1;
    }
  }
  return f;
}

template <class T, class Convert>
Pose<T> pose_of(bool rotates, bool half_turn, const Vector<Rational>& pivot, const T& value, Convert&& convert) {
  Vector<T> p{convert(pivot.x), convert(pivot.y)};
  if (rotates) return kernels::rotation_pose_from_half_tangent(p, value, half_turn);
  return kernels::translation_pose(Vector<T>{convert(Rational(3, 5)), convert(Rational(4, 5))}, value);
}

std::optional<Rational> exact_root(const Rational& square) {
  if (sgn(square) < 0) return std::nullopt;
  mpz_class n, d;
  if (!mpz_perfect_square_p(square.get_num_mpz_t()) || !mpz_perfect_square_p(square.get_den_mpz_t())) return std::nullopt;
  mpz_sqrt(n.get_mpz_t(), square.get_num_mpz_t());
  mpz_sqrt(d.get_mpz_t(), square.get_den_mpz_t());
  return frac(0, 1) + Rational(n, d);
}

TEST(ContactTable, OneDispatchInPolynomialsAndRationalsAgreesValueAndValidity) {
  Random random;
  auto identity = [](const Rational& r) { return r; };
  auto constant = [](const Rational& r) { return Poly(r); };
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    auto shape = [&] { return static_cast<FeatureShape>(random.integer(0, 2)); };
    bool roots = random.integer(0, 1) == 1;
    FeatureGeometry<Rational> fa = random_feature(random, shape(), roots), fb = random_feature(random, shape(), roots);
    bool a_rotates = random.integer(0, 3) != 0, b_rotates = random.integer(0, 1) == 1;
    bool a_half = random.integer(0, 1) == 1, b_half = random.integer(0, 1) == 1;
    Vector<Rational> pa = random.point(30), pb = random.point(30);
    Rational ta = random.rational(1), tb = random.rational(1);
    Pose<Poly> a = pose_of(a_rotates, a_half, pa, Poly::variable(0), constant);
    Pose<Poly> b = pose_of(b_rotates, b_half, pb, Poly::variable(1), constant);
    Pose<Rational> a_at = pose_of(a_rotates, a_half, pa, ta, identity);
    Pose<Rational> b_at = pose_of(b_rotates, b_half, pb, tb, identity);
    for (bool squared : {false, true}) {
      std::optional<kernels::ContactFunction<Poly>> curve =
          squared ? kernels::contact_function(a, fa, b, fb, constant, kernels::AlwaysSquared{})
                  : kernels::contact_function(a, fa, b, fb, constant, kernels::ExactRootOrSquared{exact_root});
      std::optional<kernels::ContactFunction<Rational>> value =
          squared ? kernels::contact_function(a_at, fa, b_at, fb, identity, kernels::AlwaysSquared{})
                  : kernels::contact_function(a_at, fa, b_at, fb, identity, kernels::ExactRootOrSquared{exact_root});
      ASSERT_EQ(curve.has_value(), kernels::contact_type(fa, fb).has_value());
      ASSERT_EQ(curve.has_value(), value.has_value());
      if (!curve) continue;
      EXPECT_EQ(curve->type, *kernels::contact_type(fa, fb));
      EXPECT_EQ(curve->value.evaluate(ta, tb), value->value);
      ASSERT_EQ(curve->validity.clauses.size(), value->validity.clauses.size());
      for (std::size_t c = 0; c < curve->validity.clauses.size(); ++c)
        for (int i = 0; i < curve->validity.clauses[c].count; ++i)
          EXPECT_EQ(curve->validity.clauses[c].atoms[i].evaluate(ta, tb), value->validity.clauses[c].atoms[i]);
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

// The squared form (AlwaysSquared) is the product of the physical branch (the exact root) and
// the spurious one (the root negated), exactly, wherever the root is rational.
TEST(ContactTable, SquaredPolicyIsTheProductOfBothTangencyBranches) {
  Random random;
  auto identity = [](const Rational& r) { return r; };
  int checked = 0;
  for (int trial = 0; trial < 600; ++trial) {
    FeatureShape sa = random.integer(0, 1) ? FeatureShape::arc : FeatureShape::segment;
    FeatureShape sb = sa == FeatureShape::segment ? FeatureShape::arc : (random.integer(0, 1) ? FeatureShape::arc : FeatureShape::segment);
    FeatureGeometry<Rational> fa = random_feature(random, sa, true), fb = random_feature(random, sb, true);
    Pose<Rational> a = pose_of(true, false, random.point(30), random.rational(1), identity);
    Pose<Rational> b = pose_of(random.integer(0, 1) == 1, true, random.point(30), random.rational(1), identity);
    auto squared = kernels::contact_function(a, fa, b, fb, identity, kernels::AlwaysSquared{});
    if (!squared) continue;
    auto physical = kernels::contact_function(a, fa, b, fb, identity, kernels::ExactRootOrSquared{exact_root});
    auto spurious = kernels::contact_function(a, fa, b, fb, identity, [](const Rational& s) -> std::optional<Rational> {
      std::optional<Rational> r = exact_root(s);
      if (r) *r = -*r;
      return r;
    });
    ASSERT_TRUE(physical && spurious);
    EXPECT_EQ(squared->value, Rational(physical->value * spurious->value)) << static_cast<int>(squared->type);
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

// The existence rule is the table of docs/contact-kernels.md §3.
TEST(ContactTable, ContactTypeIsTheDocumentedTable) {
  auto feature = [](FeatureShape shape, bool convex, int radius_squared) {
    FeatureGeometry<Rational> f;
    f.shape = shape;
    f.convex = convex;
    f.radius_squared = radius_squared;
    return f;
  };
  using S = FeatureShape;
  auto type = [&](FeatureGeometry<Rational> a, FeatureGeometry<Rational> b) { return kernels::contact_type(a, b); };
  EXPECT_FALSE(type(feature(S::vertex, true, 0), feature(S::vertex, true, 0)));
  EXPECT_FALSE(type(feature(S::segment, true, 0), feature(S::segment, true, 0)));
  EXPECT_EQ(type(feature(S::vertex, true, 0), feature(S::segment, true, 0)), ContactType::vertex_segment);
  EXPECT_EQ(type(feature(S::segment, true, 0), feature(S::vertex, true, 0)), ContactType::segment_vertex);
  for (bool convex : {true, false}) {
    EXPECT_EQ(type(feature(S::vertex, true, 0), feature(S::arc, convex, 4)), ContactType::vertex_arc);
    EXPECT_EQ(type(feature(S::arc, convex, 4), feature(S::vertex, true, 0)), ContactType::arc_vertex);
    EXPECT_EQ(type(feature(S::arc, convex, 4), feature(S::segment, true, 0)).has_value(), convex);
    EXPECT_EQ(type(feature(S::segment, true, 0), feature(S::arc, convex, 4)).has_value(), convex);
  }
  EXPECT_EQ(type(feature(S::arc, true, 4), feature(S::arc, true, 9)), ContactType::arc_arc);
  EXPECT_FALSE(type(feature(S::arc, false, 4), feature(S::arc, false, 9)));
  // a convex arc inside a concave one: only into a larger (or equal) circle
  EXPECT_EQ(type(feature(S::arc, true, 4), feature(S::arc, false, 9)), ContactType::arc_arc);
  EXPECT_EQ(type(feature(S::arc, true, 9), feature(S::arc, false, 9)), ContactType::arc_arc);
  EXPECT_FALSE(type(feature(S::arc, true, 9), feature(S::arc, false, 4)));
  EXPECT_EQ(type(feature(S::arc, false, 9), feature(S::arc, true, 4)), ContactType::arc_arc);
  EXPECT_FALSE(type(feature(S::arc, false, 4), feature(S::arc, true, 9)));
  EXPECT_EQ(kernels::arc_arc_tangency(feature(S::arc, true, 4), feature(S::arc, false, 9)),
            kernels::Tangency::first_inside_second);
  EXPECT_EQ(kernels::arc_arc_tangency(feature(S::arc, false, 9), feature(S::arc, true, 4)),
            kernels::Tangency::second_inside_first);
  EXPECT_EQ(kernels::blocked_sign, -1);
}

TEST(ContactTable, StrictlyReflexIsAnInteriorAngleAboveAHalfTurn) {
  auto sign = [](const Rational& r) { return sgn(r); };
  using V = Vector<Rational>;
  // counter-clockwise square: convex corners
  EXPECT_FALSE(kernels::strictly_reflex(V{1, 0}, V{0, 1}, sign));
  // a straight continuation (interior angle pi) is not strictly reflex
  EXPECT_FALSE(kernels::strictly_reflex(V{1, 0}, V{2, 0}, sign));
  // the inner corner of an L (turning right with material on the left)
  EXPECT_TRUE(kernels::strictly_reflex(V{1, 0}, V{0, -1}, sign));
}

TEST(ContactTable, HalfAngleWeightIsDividedOutExactlyAndOnlyWhenPresent) {
  Random random;
  int divided = 0;
  for (int trial = 0; trial < 200; ++trial) {
    int rows = random.integer(1, 4), columns = random.integer(1, 4);
    std::vector<std::vector<mpz_class>> p(static_cast<std::size_t>(rows), std::vector<mpz_class>(static_cast<std::size_t>(columns)));
    for (auto& row : p)
      for (auto& c : row) c = random.integer(-9, 9);
    for (auto& c : p.back()) c = c == 0 ? mpz_class(1) : c;   // degree rows - 1 in x
    // q = (1 + x^2) p
    std::vector<std::vector<mpz_class>> q(p.size() + 2, std::vector<mpz_class>(static_cast<std::size_t>(columns)));
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = 0; j < p[i].size(); ++j) {
        q[i][j] += p[i][j];
        q[i + 2][j] += p[i][j];
      }
    ASSERT_TRUE(kernels::divide_by_half_angle_weight(q));
    EXPECT_EQ(q, p);
    ++divided;
    // p + 1 (constant changed) is not divisible when p is: nothing changes
    std::vector<std::vector<mpz_class>> r = p;
    r[0][0] += 1;
    std::vector<std::vector<mpz_class>> before = r;
    bool was = kernels::divide_by_half_angle_weight(r);
    if (!was) EXPECT_EQ(r, before);
  }
  EXPECT_EQ(divided, 200);
  // and mpq coefficients (any exact coefficient type)
  std::vector<std::vector<Rational>> half{{Rational(1, 2)}, {Rational(0)}, {Rational(1, 2)}};
  ASSERT_TRUE(kernels::divide_by_half_angle_weight(half));
  EXPECT_EQ(half, (std::vector<std::vector<Rational>>{{Rational(1, 2)}}));
}

// Session 55: divide_by_half_angle_weight tests a(i) = 0 per column before forming a quotient,
// and normalize transposes only when (1 + y^2) divides (half_angle_weight_divides_x / _y).
// Oracle: the plain long division by x^2 + 1 of every column (the remainder r_1 x + r_0 zero),
// on generated polynomials (ragged rows, 1-6 rows and columns, coefficients of 1-200 bits): the
// products (1 + x^2) p, (1 + y^2) p, (1 + x^2)^2 (1 + y^2) p, and each with one coefficient
// changed by +-1 or +-2 (an even or an odd power). normalize against the plain normalisation
// (the content divided out, every (1 + x^2) and (1 + y^2) divided out by long division).
namespace weight_oracle {

using Matrix = std::vector<std::vector<mpz_class>>;

bool long_division_divides(const std::vector<mpz_class>& a) {
  std::vector<mpz_class> r = a;   // r <- r - r_k x^(k-2) (1 + x^2), from the top
  for (std::size_t k = r.size(); k-- > 2;) r[k - 2] -= r[k];
  return (r.empty() || r[0] == 0) && (r.size() < 2 || r[1] == 0);
}

std::vector<mpz_class> column(const Matrix& c, std::size_t j) {
  std::vector<mpz_class> out(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) out[i] = j < c[i].size() ? c[i][j] : mpz_class(0);
  return out;
}

std::size_t width(const Matrix& c) {
  std::size_t w = 0;
  for (const auto& row : c) w = std::max(w, row.size());
  return w;
}

bool divides_x(const Matrix& c) {
  for (std::size_t j = 0; j < width(c); ++j)
    if (!long_division_divides(column(c, j))) return false;
  return true;
}

bool divides_y(const Matrix& c) {
  for (const auto& row : c)
    if (!long_division_divides(row)) return false;
  return true;
}

Matrix times_one_plus_x_squared(const Matrix& p) {
  Matrix q(p.size() + 2, std::vector<mpz_class>(width(p)));
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < p[i].size(); ++j) {
      q[i][j] += p[i][j];
      q[i + 2][j] += p[i][j];
    }
  return q;
}

Matrix transposed(const Matrix& c) {
  Matrix t(width(c), std::vector<mpz_class>(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) t[j][i] = c[i][j];
  return t;
}

void trim(Matrix& c) {
  for (auto& row : c)
    while (!row.empty() && row.back() == 0) row.pop_back();
  while (!c.empty() && c.back().empty()) c.pop_back();
}

// x^2 + 1 divided out of every column (the caller knows it divides)
Matrix divided_x(const Matrix& c) {
  Matrix q(c.size() - 2, std::vector<mpz_class>(width(c)));
  for (std::size_t j = 0; j < width(c); ++j) {
    std::vector<mpz_class> r = column(c, j);
    for (std::size_t k = r.size(); k-- > 2;) {
      q[k - 2][j] = r[k];
      r[k - 2] -= r[k];
    }
  }
  return q;
}

Matrix plain_normalized(Matrix c) {
  trim(c);
  if (c.empty()) return c;
  mpz_class g = 0;
  for (const auto& row : c)
    for (const auto& v : row) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v.get_mpz_t());
  for (auto& row : c)
    for (auto& v : row) v /= g;
  while (c.size() >= 3 && divides_x(c)) {
    c = divided_x(c);
    trim(c);
  }
  Matrix t = transposed(c);
  bool divided = false;
  while (t.size() >= 3 && divides_x(t)) {
    t = divided_x(t);
    trim(t);
    divided = true;
  }
  if (divided) c = transposed(t);
  trim(c);
  return c;
}

}  // namespace weight_oracle

TEST(ContactTable, HalfAngleWeightTestsAreTheLongDivisionsRemainders) {
  using namespace weight_oracle;
  std::mt19937_64 random(550055);
  auto big = [&](int bits) { return test_random::random_sign(random, test_random::whole_words(random, bits)); };
  int divisible_x = 0, divisible_y = 0, not_x = 0, not_y = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    Matrix p(1 + random() % 6);
    const int bits = 1 + static_cast<int>(random() % 200);
    for (auto& row : p) {
      row.resize(random() % 7);
      for (auto& v : row) v = random() % 4 == 0 ? mpz_class(0) : big(bits);
    }
    if (p.back().empty()) p.back().push_back(mpz_class(1));
    Matrix c = p;
    const int kind = static_cast<int>(random() % 4);
    if (kind == 1 || kind == 3) c = times_one_plus_x_squared(c);
    if (kind == 2 || kind == 3) c = transposed(times_one_plus_x_squared(transposed(c)));
    if (kind == 3) c = times_one_plus_x_squared(c);
    if (random() % 2) {   // one coefficient changed
      auto& row = c[random() % c.size()];
      if (row.empty()) row.resize(1 + random() % 4);
      row[random() % row.size()] += mpz_class(static_cast<long>(random() % 2 + 1) * (random() % 2 ? 1 : -1));
    }
    const bool x = divides_x(c), y = divides_y(c);
    ASSERT_EQ(kernels::half_angle_weight_divides_x(c), x) << "trial " << trial;
    ASSERT_EQ(kernels::half_angle_weight_divides_y(c), y) << "trial " << trial;
    Matrix d = c;
    const Matrix before = c;
    const bool divided = kernels::divide_by_half_angle_weight(d);
    ASSERT_EQ(divided, c.size() >= 3 && x) << "trial " << trial;
    if (divided) {
      EXPECT_EQ(d, divided_x(c)) << "trial " << trial;
    } else {
      EXPECT_EQ(d, before) << "trial " << trial;
    }
    IntegerPolynomial2 f;
    f.coefficients = c;
    normalize(f);
    ASSERT_EQ(f.coefficients, plain_normalized(c)) << "trial " << trial;
    divisible_x += x && c.size() >= 3;
    divisible_y += y && width(c) >= 3;
    not_x += !x;
    not_y += !y;
  }
  EXPECT_GT(divisible_x, 300);
  EXPECT_GT(divisible_y, 300);
  EXPECT_GT(not_x, 300);
  EXPECT_GT(not_y, 300);
}


// The one map from a model feature to the kernels' body geometry (kernels/model_features.hpp)
// on generated edges: an arc's sector against the closed form (its ends are the exact radii to
// the arc's ends, counter-clockwise from the source of a counter-clockwise arc and from the
// target of a clockwise one; `large` exactly when the counter-clockwise angle between them,
// from atan2 well away from pi, exceeds pi), a full circle's, segments' and vertices' points,
// the same geometry in doubles as the rationals' conversion, and the model overload's edge.
TEST(ContactTable, ModelFeatureGeometryIsTheEdgesInEveryNumberType) {
  Random random;
  auto on_circle = [](const Point& c, const Rational& r, const Rational& t) {   // c + r (cos, sin) of 2 atan t
    Rational w = 1 + t * t;
    return Point{Rational(c.x + r * (1 - t * t) / w), Rational(c.y + r * 2 * t / w)};
  };
  auto angle = [](const Point& from, const Point& to) {
    return std::atan2(Rational(to.y - from.y).get_d(), Rational(to.x - from.x).get_d());
  };
  auto to_double = [](const Rational& r) { return r.get_d(); };
  int large = 0, small = 0, full = 0;
  Model model;
  model.parts.resize(1);
  model.parts[0].loops.resize(1);
  for (int trial = 0; trial < 600; ++trial) {
    Edge edge;
    edge.kind = Edge::Kind::arc;
    edge.center = Point{random.rational(40), random.rational(40)};
    const Rational r = random.rational(8) + 9;
    edge.radius_squared = r * r;
    edge.ccw = random.integer(0, 1) == 1;
    edge.source = on_circle(edge.center, r, random.rational(4));
    edge.target = random.integer(0, 9) == 0 ? edge.source : on_circle(edge.center, r, random.rational(4));
    const kernels::ArcSector<Rational> sector = kernels::arc_sector(edge);
    const FeatureGeometry<Rational> exact = kernels::feature_geometry<Rational>(edge, FeatureKind::arc, [](const Rational& x) { return x; });
    const Point& from = edge.ccw || edge.is_full_circle() ? edge.source : edge.target;
    const Point& to = edge.ccw || edge.is_full_circle() ? edge.target : edge.source;
    EXPECT_EQ(sector.start.x, from.x - edge.center.x) << "trial " << trial;
    EXPECT_EQ(sector.start.y, from.y - edge.center.y) << "trial " << trial;
    EXPECT_EQ(sector.end.x, to.x - edge.center.x) << "trial " << trial;
    EXPECT_EQ(sector.end.y, to.y - edge.center.y) << "trial " << trial;
    EXPECT_EQ(sector.full, edge.is_full_circle()) << "trial " << trial;
    if (edge.is_full_circle()) {
      EXPECT_FALSE(sector.large) << "trial " << trial;
      ++full;
    } else {
      double sweep = angle(edge.center, to) - angle(edge.center, from);
      if (sweep < 0) sweep += 2 * std::numbers::pi;
      if (std::abs(sweep - std::numbers::pi) > 1e-6) {
        EXPECT_EQ(sector.large, sweep > std::numbers::pi) << "trial " << trial << " sweep " << sweep;
        (sector.large ? large : small) += 1;
      }
    }
    EXPECT_EQ(exact.shape, FeatureShape::arc);
    EXPECT_EQ(exact.center.x, edge.center.x);
    EXPECT_EQ(exact.center.y, edge.center.y);
    EXPECT_EQ(exact.radius_squared, edge.radius_squared);
    EXPECT_EQ(exact.convex, edge.ccw);
    EXPECT_EQ(exact.sector.start.x, sector.start.x);
    EXPECT_EQ(exact.sector.end.y, sector.end.y);
    EXPECT_EQ(exact.sector.large, sector.large);
    EXPECT_EQ(exact.sector.full, sector.full);
    // the same map in doubles: every number the rationals' conversion, every flag the same
    const FeatureGeometry<double> approx = kernels::feature_geometry<double>(edge, FeatureKind::arc, to_double);
    EXPECT_EQ(approx.center.x, exact.center.x.get_d());
    EXPECT_EQ(approx.center.y, exact.center.y.get_d());
    EXPECT_EQ(approx.radius_squared, exact.radius_squared.get_d());
    EXPECT_EQ(approx.sector.start.x, exact.sector.start.x.get_d());
    EXPECT_EQ(approx.sector.start.y, exact.sector.start.y.get_d());
    EXPECT_EQ(approx.sector.end.x, exact.sector.end.x.get_d());
    EXPECT_EQ(approx.sector.end.y, exact.sector.end.y.get_d());
    EXPECT_EQ(approx.sector.large, exact.sector.large);
    EXPECT_EQ(approx.convex, exact.convex);
    // a segment of the same ends, and its source as a vertex; through the model overload
    Edge segment = edge;
    segment.kind = Edge::Kind::segment;
    model.parts[0].loops[0].edges = {edge, segment};
    const FeatureGeometry<Rational> seg =
        kernels::feature_geometry<Rational>(model, FeatureIdentity{0, 0, 1, FeatureKind::segment}, [](const Rational& x) { return x; });
    EXPECT_EQ(seg.shape, FeatureShape::segment);
    EXPECT_EQ(seg.point.x, edge.source.x);
    EXPECT_EQ(seg.point.y, edge.source.y);
    EXPECT_EQ(seg.target.x, edge.target.x);
    EXPECT_EQ(seg.target.y, edge.target.y);
    const FeatureGeometry<double> vertex =
        kernels::feature_geometry<double>(model, FeatureIdentity{0, 0, 0, FeatureKind::vertex}, to_double);
    EXPECT_EQ(vertex.shape, FeatureShape::vertex);
    EXPECT_EQ(vertex.point.x, edge.source.x.get_d());
    EXPECT_EQ(vertex.point.y, edge.source.y.get_d());
    const FeatureGeometry<Rational> by_model =
        kernels::feature_geometry<Rational>(model, FeatureIdentity{0, 0, 0, FeatureKind::arc}, [](const Rational& x) { return x; });
    EXPECT_EQ(by_model.sector.start.x, exact.sector.start.x);
    EXPECT_EQ(by_model.sector.large, exact.sector.large);
  }
  EXPECT_GT(large, 100);
  EXPECT_GT(small, 100);
  EXPECT_GT(full, 20);
  EXPECT_THROW(kernels::feature_geometry<double>(model, FeatureIdentity{0, 0, 2, FeatureKind::vertex}, to_double),
               std::out_of_range);
}

}  // namespace
}  // namespace hipair::cspace
