// The contact table as one dispatch (kernels/contact_table.hpp): the same function in exact
// polynomials of the chart coordinates and in rationals at a configuration, the
// exact-versus-squared policy (the squared form is the product of the two tangency branches),
// the existence rule against the table of docs/contact-kernels.md, the reflex rule, and the
// (1 + t^2) normalisation (kernels/weights.hpp).
#include "algebra/polynomial.hpp"
#include "kernels/contact_table.hpp"
#include "kernels/weights.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace hipair::cspace
