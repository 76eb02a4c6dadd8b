// Contact kernels: one templated source, evaluated with exact rationals, exact polynomials,
// double, certified intervals and Eigen AutoDiff; constructed contacts for every feature pair
// and motion pair checked against the exact overlap predicate; closed forms (eccentric cam,
// Scotch yoke, Geneva pin and slot); degenerate cases.
#include "curves/contact_curves.hpp"
#include "oracle/overlap.hpp"
#include "algebra/polynomial.hpp"
#include "curves/pose.hpp"
#include "kernels/contact.hpp"
#include "kernels/distance.hpp"
#include "kernels/interval.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <CGAL/Interval_nt.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_2.h>
#include <gtest/gtest.h>
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair::cspace {
namespace {

using kernels::Interval;
using kernels::Pose;
using kernels::Vector;

// gmpxx does not canonicalise mpq_class(a, b): every fraction goes through this.
Rational frac(long numerator, long denominator) {
  Rational value(numerator, denominator);
  value.canonicalize();
  return value;
}

Point pt(const Rational& x, const Rational& y) { return Point{x, y}; }

// ============================================================================ number types

// Forward-mode dual number over certified intervals: encloses value and derivative.
struct DualInterval {
  Interval value;
  Interval derivative;
  DualInterval(int v = 0) : value(v), derivative(0) {}  // NOLINT
  DualInterval(Interval v, Interval d) : value(v), derivative(d) {}
};
DualInterval operator+(const DualInterval& a, const DualInterval& b) {
  return {a.value + b.value, a.derivative + b.derivative};
}
DualInterval operator-(const DualInterval& a, const DualInterval& b) {
  return {a.value - b.value, a.derivative - b.derivative};
}
DualInterval operator-(const DualInterval& a) { return {-a.value, -a.derivative}; }
DualInterval operator*(const DualInterval& a, const DualInterval& b) {
  return {a.value * b.value, a.derivative * b.value + a.value * b.derivative};
}

using AutoDiff = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;

// Exact derivative of a polynomial in x.
RationalPolynomial2 derivative_x(const RationalPolynomial2& p) {
  RationalPolynomial2 d;
  for (int i = 1; i < p.rows(); ++i)
    for (int j = 0; j < p.columns(); ++j)
      if (sgn(p.coefficient(i, j)) != 0) d.set_coefficient(i - 1, j, p.coefficient(i, j) * i);
  return d;
}

// ============================================================================ random data

struct Random {
  std::mt19937 engine{20240611};
  // A dyadic rational k / 2^bits with |k| <= range * 2^bits: exact in double.
  Rational dyadic(int range, int bits = 6) {
    std::uniform_int_distribution<int> d(-range * (1 << bits), range * (1 << bits));
    return frac(d(engine), 1 << bits);
  }
  // A general rational (not exact in double).
  Rational general(int range) {
    std::uniform_int_distribution<int> d(-range * 997, range * 997);
    return frac(d(engine), 997);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine); }
  bool coin() { return integer(0, 1) == 1; }
  // Exact rational unit vector from a random half-angle tangent.
  Point unit() {
    Rational t = general(2);
    Rational w = 1 + t * t;
    Point u{Rational((1 - t * t) / w), Rational(2 * t / w)};
    if (coin()) u = Point{Rational(-u.x), Rational(-u.y)};
    return u;
  }
};

// One kernel evaluation recipe for any number type: builds poses from chart values and
// geometry from rationals, returns the contact function (and, for validity, an atom).
struct Scenario {
  bool a_rotates = true;
  bool b_rotates = true;
  bool a_half_turn = false;
  bool b_half_turn = false;
  Point a_pivot, b_pivot, a_direction, b_direction;
  std::vector<Point> points;        // geometry (vertices, centres, segment ends)
  std::vector<Rational> scalars;    // squared radii and the like
  int kind = 0;                     // which kernel
  Rational ta, tb;                  // chart values
};

template <class T, class Convert>
T evaluate_scenario(const Scenario& s, const T& ta, const T& tb, Convert&& convert,
                    int parameter = -1, const T* parameter_value = nullptr) {
  auto vec = [&](const Point& p) { return Vector<T>{convert(p.x), convert(p.y)}; };
  Pose<T> a = s.a_rotates ? kernels::rotation_pose_from_half_tangent(vec(s.a_pivot), ta, s.a_half_turn)
                          : kernels::translation_pose(vec(s.a_direction), ta);
  Pose<T> b = s.b_rotates ? kernels::rotation_pose_from_half_tangent(vec(s.b_pivot), tb, s.b_half_turn)
                          : kernels::translation_pose(vec(s.b_direction), tb);
  std::vector<Vector<T>> p;
  for (const Point& point : s.points) p.push_back(vec(point));
  std::vector<T> k;
  for (const Rational& value : s.scalars) k.push_back(convert(value));
  if (parameter >= 0) k[static_cast<std::size_t>(parameter)] = *parameter_value;
  kernels::ArcSector<T> sector;
  sector.start = p[3];
  sector.end = p[4];
  switch (s.kind) {
    case 0: return kernels::vertex_segment(a, p[0], b, p[1], p[2]);
    case 1: return kernels::segment_vertex(a, p[0], p[1], b, p[2]);
    case 2: return kernels::vertex_arc(a, p[0], b, p[1], k[0], true);
    case 3: return kernels::arc_vertex(a, p[0], k[0], false, b, p[1]);
    case 4: return kernels::arc_arc(a, p[0], b, p[1], k[0], kernels::Tangency::external);
    case 5: return kernels::arc_arc_squared(a, p[0], k[0], b, p[1], k[1]);
    case 6: return kernels::arc_segment(a, p[0], k[0], b, p[1], p[2]);
    case 7: return kernels::arc_segment_squared(a, p[0], k[0], b, p[1], p[2]);
    case 8: return kernels::segment_arc(a, p[0], p[1], b, p[2], k[0]);
    case 9: return kernels::vertex_segment_validity(a, p[0], b, p[1], p[2]).clauses[1].atoms[0];
    case 10: return kernels::vertex_arc_validity(a, p[0], b, p[1], sector).clauses[0].atoms[0];
    case 11: return kernels::arc_segment_validity(a, p[0], sector, b, p[1], p[2]).clauses[3].atoms[0];
    default: return kernels::arc_arc_validity(a, p[0], sector, k[0], b, p[1], sector, k[1],
                                              kernels::Tangency::first_inside_second)
                 .clauses[0].atoms[0];
  }
}

constexpr int kernel_count = 13;

Scenario random_scenario(Random& random, int kind, bool dyadic) {
  auto r = [&](int range) { return dyadic ? random.dyadic(range) : random.general(range); };
  Scenario s;
  s.kind = kind;
  s.a_rotates = random.coin();
  s.b_rotates = random.coin();
  s.a_half_turn = random.coin();
  s.b_half_turn = random.coin();
  s.a_pivot = pt(r(50), r(50));
  s.b_pivot = pt(r(50), r(50));
  s.a_direction = dyadic ? pt(frac(3, 5), frac(4, 5)) : random.unit();
  s.b_direction = dyadic ? pt(frac(-4, 5), frac(3, 5)) : random.unit();
  for (int i = 0; i < 5; ++i) s.points.push_back(pt(r(60), r(60)));
  Rational r1 = r(10), r2 = r(10);
  s.scalars = {Rational(r1 * r1 + 1), Rational(r2 * r2 + 1)};
  s.ta = dyadic ? random.dyadic(1) : random.general(1);
  s.tb = s.b_rotates ? (dyadic ? random.dyadic(1) : random.general(1)) : r(30);
  if (!s.a_rotates) s.ta = r(30);
  return s;
}

// ============================================================================ agreement

TEST(Kernels, ExactPolynomialEqualsExactEvaluation) {
  Random random;
  auto exact = [](const Rational& v) { return v; };
  auto constant = [](const Rational& v) { return RationalPolynomial2(v); };
  for (int trial = 0; trial < 40; ++trial)
    for (int kind = 0; kind < kernel_count; ++kind) {
      Scenario s = random_scenario(random, kind, false);
      Rational value = evaluate_scenario<Rational>(s, s.ta, s.tb, exact);
      RationalPolynomial2 polynomial = evaluate_scenario<RationalPolynomial2>(
          s, RationalPolynomial2::variable(0), RationalPolynomial2::variable(1), constant);
      EXPECT_EQ(polynomial.evaluate(s.ta, s.tb), value) << "kernel " << kind;
      // Degree <= 2 per rotation variable (4 for the squared forms), <= 2 per offset.
      int limit = (kind == 5 || kind == 7) ? 5 : 3;
      EXPECT_LE(polynomial.rows(), limit) << "kernel " << kind;
      EXPECT_LE(polynomial.columns(), limit) << "kernel " << kind;
      // The integer normalisation keeps the zero set and the sign at the point.
      IntegerPolynomial2 integer = normalized_integer_polynomial(polynomial);
      EXPECT_EQ(sgn(evaluate(integer, s.ta, s.tb)), sgn(value)) << "kernel " << kind;
    }
}

TEST(Kernels, DoubleAndIntervalEncloseExact) {
  Random random;
  auto exact = [](const Rational& v) { return v; };
  auto to_double = [](const Rational& v) { return v.get_d(); };
  auto to_interval = [](const Rational& v) { return Interval::enclose(v); };
  for (int trial = 0; trial < 60; ++trial)
    for (int kind = 0; kind < kernel_count; ++kind) {
      // Dyadic inputs are exact in double: the double evaluation, done with the same
      // operations in round-to-nearest, lies inside the interval evaluation, which encloses
      // the exact value. No tolerance.
      Scenario s = random_scenario(random, kind, true);
      Rational value = evaluate_scenario<Rational>(s, s.ta, s.tb, exact);
      double approximate = evaluate_scenario<double>(s, s.ta.get_d(), s.tb.get_d(), to_double);
      Interval enclosure = evaluate_scenario<Interval>(s, Interval::enclose(s.ta),
                                                       Interval::enclose(s.tb), to_interval);
      EXPECT_TRUE(enclosure.contains(value)) << "kernel " << kind;
      EXPECT_TRUE(enclosure.contains(approximate)) << "kernel " << kind;
      // General rationals: the enclosure still holds.
      Scenario g = random_scenario(random, kind, false);
      Rational general_value = evaluate_scenario<Rational>(g, g.ta, g.tb, exact);
      Interval general_enclosure = evaluate_scenario<Interval>(
          g, Interval::enclose(g.ta), Interval::enclose(g.tb), to_interval);
      EXPECT_TRUE(general_enclosure.contains(general_value)) << "kernel " << kind;
    }
}

TEST(Kernels, IntervalEnclosesOverChartBox) {
  // Interval chart coordinates: the enclosure is valid for every configuration in the box.
  Random random;
  auto exact = [](const Rational& v) { return v; };
  auto to_interval = [](const Rational& v) { return Interval::enclose(v); };
  for (int trial = 0; trial < 20; ++trial)
    for (int kind = 0; kind < kernel_count; ++kind) {
      Scenario s = random_scenario(random, kind, false);
      Rational width = frac(1, 64);
      Interval ta(Interval::enclose(s.ta).lo, Interval::enclose(Rational(s.ta + width)).hi);
      Interval tb(Interval::enclose(s.tb).lo, Interval::enclose(Rational(s.tb + width)).hi);
      Interval box = evaluate_scenario<Interval>(s, ta, tb, to_interval);
      for (int i = 0; i <= 4; ++i) {
        Rational xa = s.ta + width * frac(i, 4);
        Rational xb = s.tb + width * frac(4 - i, 4);
        EXPECT_TRUE(box.contains(evaluate_scenario<Rational>(s, xa, xb, exact))) << kind;
      }
    }
}

TEST(Kernels, AutoDiffDerivativesMatchExact) {
  Random random;
  auto exact = [](const Rational& v) { return v; };
  auto constant = [](const Rational& v) { return RationalPolynomial2(v); };
  for (int trial = 0; trial < 30; ++trial)
    for (int kind = 0; kind < kernel_count; ++kind) {
      Scenario s = random_scenario(random, kind, true);
      // d/d(ta): exact derivative of the exact polynomial.
      RationalPolynomial2 polynomial = evaluate_scenario<RationalPolynomial2>(
          s, RationalPolynomial2::variable(0), RationalPolynomial2::variable(1), constant);
      Rational exact_derivative = derivative_x(polynomial).evaluate(s.ta, s.tb);
      AutoDiff ta(s.ta.get_d(), 1, 0);
      AutoDiff tb(s.tb.get_d());
      tb.derivatives() = Eigen::Matrix<double, 1, 1>::Zero();
      auto to_autodiff = [](const Rational& v) {
        AutoDiff a(v.get_d());
        a.derivatives() = Eigen::Matrix<double, 1, 1>::Zero();
        return a;
      };
      AutoDiff value = evaluate_scenario<AutoDiff>(s, ta, tb, to_autodiff);
      // Certified bound of the rounding of this derivative computation: the width of the
      // same computation in dual intervals (which also encloses the exact derivative).
      auto to_dual = [](const Rational& v) { return DualInterval(Interval::enclose(v), Interval(0)); };
      DualInterval dual = evaluate_scenario<DualInterval>(
          s, DualInterval(Interval::enclose(s.ta), Interval(1)),
          DualInterval(Interval::enclose(s.tb), Interval(0)), to_dual);
      EXPECT_TRUE(dual.derivative.contains(exact_derivative)) << kind;
      double error = std::fabs(value.derivatives()(0) - exact_derivative.get_d());
      EXPECT_LE(error, dual.derivative.width() + std::fabs(exact_derivative.get_d()) * 1e-16)
          << "kernel " << kind;
      // Derivative with respect to a design parameter (squared radius / distance): the
      // exact central difference is exact (the kernels are at most quadratic in it).
      if (kind >= 2 && kind <= 8 && kind != 6 + 10) {
        Rational h = frac(1, 1024);
        Rational base = s.scalars[0];
        Rational plus_value = base + h;
        Rational minus_value = base - h;
        Rational plus = evaluate_scenario<Rational>(s, s.ta, s.tb, exact, 0, &plus_value);
        Rational minus = evaluate_scenario<Rational>(s, s.ta, s.tb, exact, 0, &minus_value);
        Rational difference = (plus - minus) / (2 * h);
        AutoDiff parameter(base.get_d(), 1, 0);
        AutoDiff ta_constant = to_autodiff(s.ta);
        AutoDiff tb_constant = to_autodiff(s.tb);
        AutoDiff with_parameter = evaluate_scenario<AutoDiff>(s, ta_constant, tb_constant,
                                                              to_autodiff, 0, &parameter);
        DualInterval dual_parameter(Interval::enclose(base), Interval(1));
        DualInterval dual_value = evaluate_scenario<DualInterval>(
            s, DualInterval(Interval::enclose(s.ta), Interval(0)),
            DualInterval(Interval::enclose(s.tb), Interval(0)), to_dual, 0, &dual_parameter);
        EXPECT_TRUE(dual_value.derivative.contains(difference)) << kind;
        EXPECT_LE(std::fabs(with_parameter.derivatives()(0) - difference.get_d()),
                  dual_value.derivative.width() + std::fabs(difference.get_d()) * 1e-16)
            << "kernel " << kind;
      }
    }
}

// ============================================================================ model helpers

Edge segment(const Point& a, const Point& b, std::string label = "") {
  Edge e;
  e.kind = Edge::Kind::segment;
  e.source = a;
  e.target = b;
  e.label = std::move(label);
  return e;
}

Loop polygon(const std::vector<Point>& p, bool hole = false, const std::string& label = "") {
  Loop loop;
  for (std::size_t i = 0; i < p.size(); ++i)
    loop.edges.push_back(segment(p[i], p[(i + 1) % p.size()], label));
  loop.is_hole = hole;
  return loop;
}

// Full circle of centre c through point `start` (material inside unless `hole`).
Loop circle_through(const Point& c, const Point& start, bool hole = false, std::string label = "") {
  Edge e;
  e.kind = Edge::Kind::arc;
  e.source = start;
  e.target = start;
  e.center = c;
  e.ccw = !hole;
  e.radius_squared = (start.x - c.x) * (start.x - c.x) + (start.y - c.y) * (start.y - c.y);
  e.label = std::move(label);
  Loop loop;
  loop.edges.push_back(e);
  loop.is_hole = hole;
  return loop;
}

// A part turning about `pivot`, sliding along `direction`, or fixed, made of `loops`.
Part rotating_part(std::string name, const Point& pivot, std::vector<Loop> loops) {
  Part part;
  part.name = std::move(name);
  part.motion.kind = Motion::Kind::rotation;
  part.motion.pivot = pivot;
  part.loops = std::move(loops);
  return part;
}
Part translating_part(std::string name, const Point& direction, std::vector<Loop> loops) {
  Part part;
  part.name = std::move(name);
  part.motion.kind = Motion::Kind::translation;
  part.motion.direction = direction;
  part.loops = std::move(loops);
  return part;
}
Part fixed_part(std::string name, std::vector<Loop> loops) {
  Part part;
  part.name = std::move(name);
  part.loops = std::move(loops);
  return part;
}

Point add(const Point& a, const Point& b) { return pt(a.x + b.x, a.y + b.y); }
Point scale(const Rational& k, const Point& a) { return pt(k * a.x, k * a.y); }
Point left(const Point& a) { return pt(-a.y, a.x); }

enum class MotionType { fixed, rotation, translation };

struct Placement {
  MotionType type = MotionType::fixed;
  Point pivot;
  Point direction;
  bool half_turn = false;
  Rational value;  // chart value (t or offset)
};

Motion motion_of(const Placement& placement) {
  Motion motion;
  if (placement.type == MotionType::rotation) {
    motion.kind = Motion::Kind::rotation;
    motion.pivot = placement.pivot;
  } else if (placement.type == MotionType::translation) {
    motion.kind = Motion::Kind::translation;
    motion.direction = placement.direction;
  }
  return motion;
}

ChartAxis axis_of(const Placement& placement) {
  ChartAxis axis;
  if (placement.type == MotionType::translation) {
    axis.kind = ChartAxis::Kind::translation;
    axis.lo = placement.value - 100;
    axis.hi = placement.value + 100;
  } else {
    axis.kind = ChartAxis::Kind::rotation;
    axis.half_turn = placement.half_turn;
    axis.lo = -1;
    axis.hi = 1;
  }
  return axis;
}

RigidMap inverse_of(const RigidMap& m) {
  RigidMap r;
  r.c = m.c;
  r.s = -m.s;
  r.offset = pt(-(m.c * m.offset.x + m.s * m.offset.y), -(-m.s * m.offset.x + m.c * m.offset.y));
  return r;
}

// Moves world-coordinate loops into the part's body frame for its placement.
Part body_part(const std::string& name, const Placement& placement, std::vector<Loop> loops) {
  Part part;
  part.name = name;
  part.motion = motion_of(placement);
  bool moves = placement.type != MotionType::fixed;
  RigidMap back = inverse_of(world_map(part, moves, axis_of(placement), placement.value));
  for (Loop& loop : loops)
    for (Edge& e : loop.edges) {
      e.source = back.apply(e.source);
      e.target = back.apply(e.target);
      if (e.is_arc()) e.center = back.apply(e.center);
    }
  part.loops = std::move(loops);
  return part;
}

struct PairSetup {
  Model model;
  PairAxes axes;
  ChartAxis x, y;
  ChartPoint q;
};

PairSetup setup_pair(Part a, const Placement& pa, Part b, const Placement& pb) {
  PairSetup setup;
  setup.model.name = "constructed";
  setup.model.parts = {std::move(a), std::move(b)};
  setup.model.pairs.push_back(PairSpec{0, 1, {}, {}, ""});
  setup.axes = pair_axes(setup.model, 0, 1);
  if (pa.type != MotionType::fixed) {
    setup.x = axis_of(pa);
    setup.q.x = pa.value;
    if (pb.type != MotionType::fixed) {
      setup.y = axis_of(pb);
      setup.q.y = pb.value;
    }
  } else {
    setup.x = axis_of(pb);
    setup.q.x = pb.value;
  }
  return setup;
}

Rational evaluate_at(const IntegerPolynomial2& p, const PairSetup& s, const ChartPoint& q) {
  return evaluate(p, q.x, s.axes.dimension() == 2 ? q.y : Rational(0));
}

bool validity_holds(const ContactCurve& curve, const PairSetup& s, const ChartPoint& q) {
  for (const ValidityClause& clause : curve.validity) {
    bool any = false;
    for (const IntegerPolynomial2& atom : clause.atoms)
      if (sgn(evaluate_at(atom, s, q)) >= 0) any = true;
    if (!any) return false;
  }
  return true;
}

const ContactCurve* find_curve(const std::vector<ContactCurve>& curves, const FeatureRef& first,
                               const FeatureRef& second) {
  for (const ContactCurve& c : curves)
    if (c.first == first && c.second == second) return &c;
  return nullptr;
}

// The constructed contact: the curve of (first, second) vanishes at q, is valid there, the
// parts touch, and on each side of the curve the sign of the polynomial agrees with the
// overlap predicate (negative = overlapping).
void check_contact(const PairSetup& s, const FeatureRef& first, const FeatureRef& second,
                   ContactType type, const std::string& what) {
  SCOPED_TRACE(what);
  CurveStatistics stats;
  std::vector<ContactCurve> curves = generate_contact_curves(s.model, s.axes, s.x, s.y, &stats);
  const ContactCurve* curve = find_curve(curves, first, second);
  ASSERT_NE(curve, nullptr) << "no curve emitted";
  EXPECT_EQ(curve->type, type);
  EXPECT_EQ(sgn(evaluate_at(curve->polynomial, s, s.q)), 0);
  EXPECT_TRUE(validity_holds(*curve, s, s.q));
  EXPECT_EQ(classify_overlap(s.model, s.axes, s.x, s.y, s.q), Overlap::touching);
  if (curve->blocked_sign == 0) return;
  Rational step = frac(1, 100000);
  int checked = 0;
  for (int axis = 0; axis < s.axes.dimension(); ++axis)
    for (int direction = -1; direction <= 1; direction += 2) {
      ChartPoint moved = s.q;
      (axis == 0 ? moved.x : moved.y) += step * direction;
      int sign = sgn(evaluate_at(curve->polynomial, s, moved));
      if (sign == 0) continue;
      Overlap relation = classify_overlap(s.model, s.axes, s.x, s.y, moved);
      EXPECT_EQ(relation, sign < 0 ? Overlap::overlapping : Overlap::apart)
          << "axis " << axis << " direction " << direction;
      ++checked;
    }
  EXPECT_GT(checked, 0);
}

Placement random_placement(Random& random, MotionType type) {
  Placement p;
  p.type = type;
  p.pivot = pt(random.general(30), random.general(30));
  p.direction = random.unit();
  p.half_turn = random.coin();
  p.value = type == MotionType::rotation ? random.general(1) : random.general(20);
  return p;
}

const MotionType motion_pairs[][2] = {
    {MotionType::rotation, MotionType::rotation},       {MotionType::rotation, MotionType::translation},
    {MotionType::translation, MotionType::rotation},    {MotionType::translation, MotionType::translation},
    {MotionType::fixed, MotionType::rotation},          {MotionType::rotation, MotionType::fixed},
    {MotionType::fixed, MotionType::translation},       {MotionType::translation, MotionType::fixed}};

FeatureRef vertex_ref(std::size_t part, std::size_t loop, std::size_t edge) {
  return FeatureRef{part, loop, edge, FeatureRef::Kind::vertex};
}
FeatureRef segment_ref(std::size_t part, std::size_t loop, std::size_t edge) {
  return FeatureRef{part, loop, edge, FeatureRef::Kind::segment};
}
FeatureRef arc_ref(std::size_t part, std::size_t loop, std::size_t edge) {
  return FeatureRef{part, loop, edge, FeatureRef::Kind::arc};
}

// A triangle with apex X pointing against the outward unit-ish direction `inward` (the
// triangle lies on the side of -inward), apex first so its vertex is loop 0 edge 0's source.
Loop apex_triangle(const Point& apex, const Point& away, const Point& side) {
  // vertices apex, apex + away*3 + side, apex + away*3 - side (ccw when cross(away, side) > 0)
  Point p1 = add(apex, add(scale(3, away), side));
  Point p2 = add(apex, add(scale(3, away), scale(-1, side)));
  Rational orientation = (p1.x - apex.x) * (p2.y - apex.y) - (p1.y - apex.y) * (p2.x - apex.x);
  if (sgn(orientation) > 0) return polygon({apex, p1, p2});
  return polygon({apex, p2, p1});
}

TEST(Kernels, ConstructedContactsForEveryFeatureAndMotionPair) {
  Random random;
  for (const auto& motions : motion_pairs) {
    for (int trial = 0; trial < 3; ++trial) {
      Placement pa = random_placement(random, motions[0]);
      Placement pb = random_placement(random, motions[1]);
      // A segment W1 -> W2 of a ccw triangle of B; contact point X in its interior.
      Point w1 = pt(random.general(10), random.general(10));
      Point direction = random.unit();
      Rational length = 4 + random.integer(0, 4);
      Point w2 = add(w1, scale(length, direction));
      Point inside = left(direction);  // B's material side
      Point w3 = add(add(w1, scale(length / 2, direction)), scale(3, inside));
      Rational lambda = frac(random.integer(20, 80), 100);
      Point x = add(w1, scale(lambda * length, direction));
      Point outward = scale(-1, inside);
      Point along = scale(frac(1, 2), direction);

      // vertex of A on segment of B, and the mirror case
      {
        Part a = body_part("a", pa, {apex_triangle(x, outward, along)});
        Part b = body_part("b", pb, {polygon({w1, w2, w3}, false, "wall")});
        check_contact(setup_pair(a, pa, b, pb), vertex_ref(0, 0, 0), segment_ref(1, 0, 0),
                      ContactType::vertex_segment, "vertex_segment");
        Part a2 = body_part("a", pa, {polygon({w1, w2, w3})});
        Part b2 = body_part("b", pb, {apex_triangle(x, outward, along)});
        check_contact(setup_pair(a2, pa, b2, pb), segment_ref(0, 0, 0), vertex_ref(1, 0, 0),
                      ContactType::segment_vertex, "segment_vertex");
      }
      // circle of B (radius r) with a vertex of A on it, and the mirror case
      Rational r = 2 + random.integer(0, 3);
      Point u = random.unit();
      Point k = pt(random.general(10), random.general(10));
      Point on_circle = add(k, scale(r, u));
      {
        Part a = body_part("a", pa, {apex_triangle(on_circle, u, scale(frac(1, 3), left(u)))});
        Part b = body_part("b", pb, {circle_through(k, on_circle)});
        check_contact(setup_pair(a, pa, b, pb), vertex_ref(0, 0, 0), arc_ref(1, 0, 0),
                      ContactType::vertex_arc, "vertex_arc");
        Part a2 = body_part("a", pa, {circle_through(k, on_circle)});
        Part b2 = body_part("b", pb, {apex_triangle(on_circle, u, scale(frac(1, 3), left(u)))});
        check_contact(setup_pair(a2, pa, b2, pb), arc_ref(0, 0, 0), vertex_ref(1, 0, 0),
                      ContactType::arc_vertex, "arc_vertex");
      }
      // two disks externally tangent (rational radii)
      {
        Rational ra = 1 + random.integer(0, 3);
        Point ka = add(k, scale(r + ra, u));
        Part a = body_part("a", pa, {circle_through(ka, add(ka, scale(ra, u)))});
        Part b = body_part("b", pb, {circle_through(k, on_circle)});
        check_contact(setup_pair(a, pa, b, pb), arc_ref(0, 0, 0), arc_ref(1, 0, 0),
                      ContactType::arc_arc, "arc_arc external");
      }
      // disk of A inside a hole of B, internally tangent; and B's disk in A's hole
      {
        Rational hole = r + 2;
        Rational pin = r;
        Point kb = k;
        Point ka = add(kb, scale(hole - pin, u));
        Point c = kb;
        Loop outline = polygon({add(c, pt(-20, -20)), add(c, pt(20, -20)), add(c, pt(20, 20)),
                                add(c, pt(-20, 20))});
        Loop bore = circle_through(kb, add(kb, scale(hole, u)), true, "bore");
        Part a = body_part("a", pa, {circle_through(ka, add(ka, scale(pin, u)), false, "pin")});
        Part b = body_part("b", pb, {outline, bore});
        check_contact(setup_pair(a, pa, b, pb), arc_ref(0, 0, 0), arc_ref(1, 1, 0),
                      ContactType::arc_arc, "arc_arc internal");
        Part a2 = body_part("a", pa, {outline, bore});
        Part b2 = body_part("b", pb, {circle_through(ka, add(ka, scale(pin, u)), false, "pin")});
        check_contact(setup_pair(a2, pa, b2, pb), arc_ref(0, 1, 0), arc_ref(1, 0, 0),
                      ContactType::arc_arc, "arc_arc internal mirrored");
      }
      // disk of A tangent to the segment of B (rational length: linear form) and mirror
      {
        Point ka = add(x, scale(r, outward));
        Part a = body_part("a", pa, {circle_through(ka, add(ka, scale(r, direction)))});
        Part b = body_part("b", pb, {polygon({w1, w2, w3})});
        check_contact(setup_pair(a, pa, b, pb), arc_ref(0, 0, 0), segment_ref(1, 0, 0),
                      ContactType::arc_segment, "arc_segment");
        Part a2 = body_part("a", pa, {polygon({w1, w2, w3})});
        Part b2 = body_part("b", pb, {circle_through(ka, add(ka, scale(r, direction)))});
        check_contact(setup_pair(a2, pa, b2, pb), segment_ref(0, 0, 0), arc_ref(1, 0, 0),
                      ContactType::segment_arc, "segment_arc");
      }
      // a segment of irrational length against a disk of rational radius: r |d| is
      // irrational, the squared form is used (degree 4 per rotation; its validity excludes
      // the spurious branch)
      {
        Point v1 = w1;
        Point v2 = add(w1, pt(1, 1));
        Point v3 = add(w1, pt(-2, 5));
        Point ka = add(w1, pt(1, 0));  // overlapping now: the pair cannot be culled
        Part a = body_part("a", pa, {circle_through(ka, add(ka, pt(1, 0)))});
        Part b = body_part("b", pb, {polygon({v1, v2, v3})});
        PairSetup s = setup_pair(a, pa, b, pb);
        std::vector<ContactCurve> curves = generate_contact_curves(s.model, s.axes, s.x, s.y);
        const ContactCurve* squared = find_curve(curves, arc_ref(0, 0, 0), segment_ref(1, 0, 0));
        ASSERT_NE(squared, nullptr);
        EXPECT_EQ(squared->blocked_sign, -1);
        EXPECT_EQ(squared->validity.size(), 3u);  // branch side, foot within the segment
        EXPECT_EQ(squared->type, ContactType::arc_segment);
      }
    }
  }
}

// Random configurations of two random triangles/disks posed at random rational charts: when
// the predicate says "touching", some emitted contact curve vanishes there with its validity.
TEST(Kernels, TouchingImpliesSomeCurveVanishes) {
  Random random;
  int touching = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const auto& motions = motion_pairs[trial % 8];
    Placement pa = random_placement(random, motions[0]);
    Placement pb = random_placement(random, motions[1]);
    // Construct a touching configuration by a random vertex-on-edge placement, then the
    // predicate must agree and the touch points must map to vanishing curves.
    Point w1 = pt(random.general(5), random.general(5));
    Point direction = random.unit();
    Point w2 = add(w1, scale(5, direction));
    Point w3 = add(add(w1, scale(frac(5, 2), direction)), scale(3, left(direction)));
    Point x = add(w1, scale(Rational(random.integer(0, 5)), direction));  // may be a corner
    Part a = body_part("a", pa, {apex_triangle(x, scale(-1, left(direction)), scale(frac(random.integer(1, 9), 3), direction))});
    Part b = body_part("b", pb, {polygon({w1, w2, w3})});
    PairSetup s = setup_pair(a, pa, b, pb);
    OverlapOptions options;
    options.want_touches = true;
    OverlapReport report = analyse_overlap(s.model, s.axes, s.x, s.y, s.q, options);
    if (report.relation != Overlap::touching) continue;
    ++touching;
    std::vector<ContactCurve> curves = generate_contact_curves(s.model, s.axes, s.x, s.y);
    for (const TouchPoint& touch : report.touches) {
      bool found = false;
      for (const ContactCurve& curve : curves) {
        if (sgn(evaluate_at(curve.polynomial, s, s.q)) != 0 || !validity_holds(curve, s, s.q))
          continue;
        // the curve's features must be among the edges through the touch point
        auto involves = [](const std::vector<TouchEdge>& edges, const FeatureRef& f) {
          for (const TouchEdge& e : edges)
            if (e.loop == f.loop && e.edge == f.edge) return true;
          return false;
        };
        if (involves(touch.first_edges, curve.first) || involves(touch.second_edges, curve.second))
          found = true;
      }
      EXPECT_TRUE(found) << "trial " << trial;
    }
  }
  EXPECT_GT(touching, 50);
}

// ============================================================================ closed forms

TEST(Kernels, EccentricCamWithFlatFollower) {
  // Cam: disk of radius R = 10 centred e = 3 from the pivot (origin), rotating; follower
  // translating along +x with a flat face x = s facing -x. Contact: s = R + e cos(theta).
  Rational radius = 10, eccentricity = 3;
  Part cam = rotating_part("cam", pt(0, 0), {circle_through(pt(eccentricity, 0), pt(eccentricity + radius, 0), false, "cam")});
  Part follower = translating_part("follower", pt(1, 0), {polygon({pt(0, -20), pt(10, -20), pt(10, 20), pt(0, 20)}, false, "face")});
  Model model;
  model.parts = {cam, follower};
  PairAxes axes = pair_axes(model, 0, 1);
  ChartAxis x;
  x.kind = ChartAxis::Kind::rotation;
  x.lo = -1;
  x.hi = 1;
  ChartAxis y;
  y.kind = ChartAxis::Kind::translation;
  y.lo = -30;
  y.hi = 30;
  std::vector<ContactCurve> curves = generate_contact_curves(model, axes, x, y);
  const ContactCurve* face = find_curve(curves, arc_ref(0, 0, 0), segment_ref(1, 0, 3));
  ASSERT_NE(face, nullptr);
  EXPECT_EQ(face->polynomial.degree_x(), 2);
  EXPECT_EQ(face->polynomial.degree_y(), 1);
  for (int k = -10; k <= 10; ++k) {
    Rational t = frac(k, 10);
    Rational cosine = (1 - t * t) / (1 + t * t);
    Rational s = radius + eccentricity * cosine;
    ChartPoint q{t, s};
    EXPECT_EQ(sgn(evaluate(face->polynomial, t, s)), 0) << k;
    EXPECT_EQ(classify_overlap(model, axes, x, y, q), Overlap::touching) << k;
    EXPECT_EQ(classify_overlap(model, axes, x, y, ChartPoint{t, s - frac(1, 1000000)}),
              Overlap::overlapping);
    EXPECT_EQ(classify_overlap(model, axes, x, y, ChartPoint{t, s + frac(1, 1000000)}),
              Overlap::apart);
    EXPECT_LT(sgn(evaluate(face->polynomial, t, s - frac(1, 1000000))), 0);
  }
}

TEST(Kernels, ScotchYokeZeroClearance) {
  // Crank pin (radius 2) at distance r = 15 from the pivot; yoke translating along x with a
  // vertical slot of width 4 (zero clearance) centred at x = s: s = r cos(theta).
  Rational crank = 15, pin = 2;
  Part crank_part = rotating_part("crank", pt(0, 0), {circle_through(pt(crank, 0), pt(crank + pin, 0), false, "pin")});
  Part yoke;
  yoke.name = "yoke";
  yoke.motion.kind = Motion::Kind::translation;
  yoke.motion.direction = pt(1, 0);
  // a frame around the slot: outer box and a slot hole x in [-2, 2], y in [-20, 20]
  yoke.loops = {polygon({pt(-10, -30), pt(10, -30), pt(10, 30), pt(-10, 30)}),
                polygon({pt(-2, -20), pt(-2, 20), pt(2, 20), pt(2, -20)}, true, "slot wall")};
  Model model;
  model.parts = {crank_part, yoke};
  PairAxes axes = pair_axes(model, 0, 1);
  ChartAxis x;
  x.kind = ChartAxis::Kind::rotation;
  x.lo = -1;
  x.hi = 1;
  ChartAxis y;
  y.kind = ChartAxis::Kind::translation;
  y.lo = -40;
  y.hi = 40;
  std::vector<ContactCurve> curves = generate_contact_curves(model, axes, x, y);
  const ContactCurve* left_wall = find_curve(curves, arc_ref(0, 0, 0), segment_ref(1, 1, 0));
  const ContactCurve* right_wall = find_curve(curves, arc_ref(0, 0, 0), segment_ref(1, 1, 2));
  ASSERT_NE(left_wall, nullptr);
  ASSERT_NE(right_wall, nullptr);
  for (int k = -9; k <= 9; ++k) {
    Rational t = frac(k, 10);
    Rational s = crank * (1 - t * t) / (1 + t * t);
    EXPECT_EQ(sgn(evaluate(left_wall->polynomial, t, s)), 0);
    EXPECT_EQ(sgn(evaluate(right_wall->polynomial, t, s)), 0);
    EXPECT_EQ(classify_overlap(model, axes, x, y, ChartPoint{t, s}), Overlap::touching);
    // zero clearance: any displacement of the yoke jams the pin into a wall
    EXPECT_EQ(classify_overlap(model, axes, x, y, ChartPoint{t, s + frac(1, 1000000)}),
              Overlap::overlapping);
    EXPECT_EQ(classify_overlap(model, axes, x, y, ChartPoint{t, s - frac(1, 1000000)}),
              Overlap::overlapping);
  }
}

std::string examples_dir() { return HIPAIR_EXAMPLES; }

TEST(Kernels, GenevaPinSlotWallBracketsAgreeWithOracle) {
  Model model = read_model_file(examples_dir() + "/geneva.json");
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  ASSERT_EQ(layout.x_charts.size(), 2u);
  ASSERT_EQ(layout.y_charts.size(), 2u);
  CurveStatistics stats;
  int checked = 0;
  for (const ChartAxis& x : layout.x_charts)
  for (const ChartAxis& y : layout.y_charts) {
    std::vector<ContactCurve> curves = generate_contact_curves(model, axes, x, y, &stats);
    for (const ContactCurve& curve : curves) {
      if (curve.label.find("pin / wheel slot") == std::string::npos) continue;
      if (curve.label.find("wall") == std::string::npos || curve.type != ContactType::arc_segment)
        continue;
      // For a few driver chart values, bracket each root in y of the wall curve between
      // rationals; where the contact is valid, the oracle must agree with the sign.
      for (int k = -8; k <= 8; k += 2) {
        Rational tx = frac(k, 10);
        // sample y to find sign changes
        Rational previous_y = -1;
        int previous = sgn(evaluate(curve.polynomial, tx, previous_y));
        for (int j = -99; j <= 100; ++j) {
          Rational ty = frac(j, 100);
          int sign = sgn(evaluate(curve.polynomial, tx, ty));
          if (sign != 0 && previous != 0 && sign != previous) {
            // refine the bracket to width 2^-40 by exact bisection
            Rational lo = previous_y, hi = ty;
            for (int step = 0; step < 40; ++step) {
              Rational mid = (lo + hi) / 2;
              int m = sgn(evaluate(curve.polynomial, tx, mid));
              if (m == 0) { lo = hi = mid; break; }
              if (m == previous) lo = mid; else hi = mid;
            }
            ChartPoint below{tx, lo};
            ChartPoint above{tx, hi};
            if (validity_holds(curve, {model, axes, x, y, below}, below) &&
                validity_holds(curve, {model, axes, x, y, above}, above)) {
              Overlap at_lo = classify_overlap(model, axes, x, y, below);
              Overlap at_hi = classify_overlap(model, axes, x, y, above);
              // Crossing the pin/wall curve with the contact valid changes the relation,
              // unless something else already overlaps on both sides.
              if (!(at_lo == Overlap::overlapping && at_hi == Overlap::overlapping)) {
                int lo_sign = sgn(evaluate(curve.polynomial, tx, lo));
                int hi_sign = sgn(evaluate(curve.polynomial, tx, hi));
                EXPECT_EQ(at_lo, lo_sign < 0 ? Overlap::overlapping : Overlap::apart);
                EXPECT_EQ(at_hi, hi_sign < 0 ? Overlap::overlapping : Overlap::apart);
                ++checked;
              }
            }
          }
          if (sign != 0) {
            previous = sign;
            previous_y = ty;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 4);
  EXPECT_GT(stats.curves, 0u);
}

// ============================================================================ degenerate cases

TEST(Kernels, ConcentricBearingIsIdenticallyZero) {
  // A shaft rotating about its own centre inside a fixed bearing of the same radius.
  Part shaft = rotating_part("shaft", pt(0, 0), {circle_through(pt(0, 0), pt(5, 0), false, "journal")});
  Part frame = fixed_part("frame", {polygon({pt(-10, -10), pt(10, -10), pt(10, 10), pt(-10, 10)}),
                 circle_through(pt(0, 0), pt(3, 4), true, "bore")});
  Model model;
  model.parts = {shaft, frame};
  PairAxes axes = pair_axes(model, 0, 1);
  EXPECT_EQ(axes.dimension(), 1);
  ChartLayout layout = chart_layout(model, axes);
  ASSERT_EQ(layout.x_charts.size(), 2u);
  EXPECT_TRUE(layout.y_charts.empty());
  CurveStatistics stats;
  std::vector<ContactCurve> curves =
      generate_contact_curves(model, axes, layout.x_charts[0], ChartAxis{}, &stats);
  const ContactCurve* bearing = find_curve(curves, arc_ref(0, 0, 0), arc_ref(1, 1, 0));
  ASSERT_NE(bearing, nullptr);
  EXPECT_TRUE(bearing->polynomial.is_zero());
  EXPECT_EQ(stats.identically_zero, 1u);
  EXPECT_EQ(classify_overlap(model, axes, layout.x_charts[0], ChartAxis{},
                             ChartPoint{frac(1, 3), 0}),
            Overlap::touching);
}

TEST(Kernels, ArcCentredOnPivotGivesCurveInOtherVariableOnly) {
  // The driver's locking arcs of the Geneva pair are centred on its pivot: contact with the
  // wheel does not depend on the driver angle (horizontal segments of the paper's figure).
  Model model = read_model_file(examples_dir() + "/geneva.json");
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  std::vector<ContactCurve> curves =
      generate_contact_curves(model, axes, layout.x_charts[0], layout.y_charts[0]);
  int only_y = 0;
  for (const ContactCurve& curve : curves)
    if (curve.first.kind == FeatureRef::Kind::arc &&
        curve.label.find("lock arc / wheel") != std::string::npos) {
      EXPECT_TRUE(depends_only_on_y(curve.polynomial)) << curve.label;
      ++only_y;
    }
  EXPECT_GT(only_y, 0);
}

TEST(Kernels, ParallelTranslatingSegmentsGiveCoincidentVertexCurves) {
  // Two plates translating along x and y; the horizontal bottom edge of the upper plate and
  // the top edge of the lower plate are parallel: the two vertex curves coincide.
  Part upper = translating_part("upper", pt(1, 0), {polygon({pt(0, 10), pt(4, 10), pt(4, 12), pt(0, 12)})});
  Part lower = translating_part("lower", pt(0, 1), {polygon({pt(0, 0), pt(10, 0), pt(10, 2), pt(0, 2)})});
  Model model;
  model.parts = {upper, lower};
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  ASSERT_EQ(layout.x_charts.size(), 1u);
  ASSERT_EQ(layout.y_charts.size(), 1u);
  std::vector<ContactCurve> curves =
      generate_contact_curves(model, axes, layout.x_charts[0], layout.y_charts[0]);
  // vertices (0,10) and (4,10) of the upper plate on the top edge (10,2)->(0,2) of the lower
  const ContactCurve* first = find_curve(curves, vertex_ref(0, 0, 0), segment_ref(1, 0, 2));
  const ContactCurve* second = find_curve(curves, vertex_ref(0, 0, 1), segment_ref(1, 0, 2));
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(first->polynomial.coefficients, second->polynomial.coefficients);
  // depends only on the lower plate's offset (y): s_lower = 8
  EXPECT_TRUE(depends_only_on_y(first->polynomial));
  EXPECT_EQ(sgn(evaluate(first->polynomial, 3, 8)), 0);
  EXPECT_EQ(classify_overlap(model, axes, layout.x_charts[0], layout.y_charts[0], ChartPoint{3, 8}),
            Overlap::touching);
  // the chart boxes lie in free space at their edges
  EXPECT_EQ(classify_overlap(model, axes, layout.x_charts[0], layout.y_charts[0],
                             ChartPoint{layout.x_charts[0].lo, 8}),
            Overlap::apart);
}

TEST(Kernels, NormalisationRemovesOnePlusSquareFactors) {
  RationalPolynomial2 x = RationalPolynomial2::variable(0);
  RationalPolynomial2 y = RationalPolynomial2::variable(1);
  RationalPolynomial2 core = x * y * frac(3, 2) - y + frac(1, 3);
  RationalPolynomial2 wx = RationalPolynomial2(1) + x * x;
  RationalPolynomial2 wy = RationalPolynomial2(1) + y * y;
  RationalPolynomial2 inflated = core * wx * wx * wy * frac(14, 5);
  IntegerPolynomial2 reduced = normalized_integer_polynomial(inflated);
  IntegerPolynomial2 expected = normalized_integer_polynomial(core);
  EXPECT_EQ(reduced.coefficients, expected.coefficients);
  EXPECT_EQ(reduced.degree_x(), 1);
  EXPECT_EQ(reduced.degree_y(), 1);
  // content removed and sign kept: 9xy - 6y + 2
  EXPECT_EQ(expected.coefficients[0][0], 2);
  EXPECT_EQ(expected.coefficients[0][1], -6);
  EXPECT_EQ(expected.coefficients[1][1], 9);
  EXPECT_TRUE(IntegerPolynomial2{}.is_zero());
  EXPECT_EQ(IntegerPolynomial2{}.degree_x(), -1);
}

TEST(Kernels, PairAxesRejectsPlanarParts) {
  Model model;
  Part free_part;
  free_part.name = "free";
  free_part.motion.kind = Motion::Kind::planar;
  Part fixed_part;
  fixed_part.name = "frame";
  model.parts = {free_part, fixed_part};
  EXPECT_THROW(pair_axes(model, 0, 1), GeometryError);
  Part other_fixed;
  other_fixed.name = "other";
  model.parts = {fixed_part, other_fixed};
  EXPECT_THROW(pair_axes(model, 0, 1), GeometryError);
}

TEST(Kernels, ChartLayoutForLimitedRotation) {
  Model model;
  Part arm;
  arm.name = "arm";
  arm.motion.kind = Motion::Kind::rotation;
  arm.motion.angle_limits = RationalInterval{frac(-1, 2), 2};  // rad
  arm.loops = {polygon({pt(1, 0), pt(2, 0), pt(2, 1)})};
  Part frame = fixed_part("frame", {polygon({pt(5, 5), pt(6, 5), pt(6, 6)})});
  model.parts = {arm, frame};
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  // [-0.5, 2] rad: chart around 0 from tan(-0.25) to 1, chart around pi from -1 to tan((2-pi)/2)
  ASSERT_EQ(layout.x_charts.size(), 2u);
  const ChartAxis& zero = layout.x_charts[0];
  const ChartAxis& turn = layout.x_charts[1];
  EXPECT_FALSE(zero.half_turn);
  EXPECT_TRUE(turn.half_turn);
  EXPECT_LE(zero.lo.get_d(), std::tan(-0.25));
  EXPECT_GT(zero.lo.get_d(), std::tan(-0.25) - 1e-11);
  EXPECT_EQ(zero.hi, 1);
  EXPECT_EQ(turn.lo, -1);
  EXPECT_GE(turn.hi.get_d(), std::tan((2 - M_PI) / 2));
  EXPECT_NEAR(chart_to_coordinate(turn, std::tan((2 - M_PI) / 2)), 2.0, 1e-12);
}

}  // namespace
}  // namespace hipair::cspace

namespace hipair::cspace {
namespace {

// Every curve the blocked-space cull drops lies in blocked space: where the dropped curve is
// crossed with its contact valid, the oracle says "overlapping" on both sides.
int check_dropped_curves_are_blocked(const std::string& file, int lines) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + file);
  int checked = 0;
  for (const PairSpec& spec : model.pairs) {
    if (motion_degrees_of_freedom(model.parts[spec.first].motion) > 1 ||
        motion_degrees_of_freedom(model.parts[spec.second].motion) > 1)
      continue;
    PairAxes axes = pair_axes(model, spec.first, spec.second);
    ChartLayout layout = chart_layout(model, axes);
    std::vector<ChartAxis> ys = layout.y_charts;
    if (axes.dimension() == 1) ys = {ChartAxis{ChartAxis::Kind::translation, false, 0, 0}};
    for (const ChartAxis& x : layout.x_charts)
      for (const ChartAxis& y : ys) {
        CurveOptions all;
        all.cull_blocked_space = false;
        std::vector<ContactCurve> full = generate_contact_curves(model, axes, x, y, nullptr, all);
        std::vector<ContactCurve> culled = generate_contact_curves(model, axes, x, y);
        PairSetup setup{model, axes, x, y, {}};
        for (const ContactCurve& curve : full) {
          if (find_curve(culled, curve.first, curve.second)) continue;  // kept
          int line_count = axes.dimension() == 2 ? lines : 1;
          for (int line = 0; line < line_count; ++line) {
            Rational ty = y.lo + (y.hi - y.lo) * frac(2 * line + 1, 2 * line_count);
            int previous = 0;
            Rational previous_x;
            int steps = axes.dimension() == 2 ? 64 : 1024;
            for (int step = 0; step <= steps; ++step) {
              Rational tx = x.lo + (x.hi - x.lo) * frac(step, steps);
              int sign = sgn(evaluate(curve.polynomial, tx, ty));
              if (sign != 0 && previous != 0 && sign != previous) {
                Rational lo = previous_x, hi = tx;
                for (int k = 0; k < 30; ++k) {
                  Rational mid = (lo + hi) / 2;
                  int m = sgn(evaluate(curve.polynomial, mid, ty));
                  if (m == 0) { lo = hi = mid; break; }
                  if (m == previous) lo = mid; else hi = mid;
                }
                ChartPoint a{lo, ty}, b{hi, ty};
                if (validity_holds(curve, setup, a) && validity_holds(curve, setup, b)) {
                  EXPECT_EQ(classify_overlap(model, axes, x, y, a), Overlap::overlapping) << curve.label;
                  EXPECT_EQ(classify_overlap(model, axes, x, y, b), Overlap::overlapping) << curve.label;
                  ++checked;
                }
              }
              if (sign != 0) {
                previous = sign;
                previous_x = tx;
              }
            }
          }
        }
      }
  }
  return checked;
}

TEST(Kernels, BlockedSpaceCullDropsOnlyBlockedCurvesGeneva) {
  EXPECT_GT(check_dropped_curves_are_blocked("geneva.json", 6), 0);
}

TEST(Kernels, BlockedSpaceCullDropsOnlyBlockedCurvesEscapement) {
  EXPECT_GT(check_dropped_curves_are_blocked("escapement.json", 3), 0);
}

TEST(Kernels, BlockedSpaceCullDropsOnlyBlockedCurvesRatchetAndLever) {
  // (their dropped curves may have no valid crossing at all; nothing to count then)
  check_dropped_curves_are_blocked("ratchet.json", 8);
  check_dropped_curves_are_blocked("lever-stop.json", 1);
}

TEST(Kernels, ChartLayoutRotationRangeAcrossHalfTurn) {
  // [-3, 3.2] rad spans less than a full turn but meets the chart around pi twice (on both
  // sides of the chart around 0), with disjoint t ranges.
  Model model;
  Part arm;
  arm.name = "arm";
  arm.motion.kind = Motion::Kind::rotation;
  arm.motion.angle_limits = RationalInterval{-3, frac(16, 5)};
  arm.loops = {polygon({pt(1, 0), pt(2, 0), pt(2, 1)})};
  Part frame = fixed_part("frame", {polygon({pt(5, 5), pt(6, 5), pt(6, 6)})});
  model.parts = {arm, frame};
  ChartLayout layout = chart_layout(model, pair_axes(model, 0, 1));
  int around_zero = 0, around_pi = 0;
  for (const ChartAxis& chart : layout.x_charts) {
    EXPECT_LE(chart.lo, chart.hi);
    EXPECT_GE(chart.lo, -1);
    EXPECT_LE(chart.hi, 1);
    (chart.half_turn ? around_pi : around_zero)++;
    // the chart's ends map into the limits (up to the outward 1e-12 rounding)
    double lo = chart_to_coordinate(chart, chart.lo.get_d());
    double hi = chart_to_coordinate(chart, chart.hi.get_d());
    for (double angle : {lo, hi}) {
      double wrapped = angle;
      while (wrapped > 3.2 + 1e-9) wrapped -= 2 * M_PI;
      while (wrapped < -3 - 1e-9) wrapped += 2 * M_PI;
      EXPECT_GE(wrapped, -3 - 1e-9);
      EXPECT_LE(wrapped, 3.2 + 1e-9);
    }
  }
  EXPECT_EQ(around_zero, 1);
  EXPECT_EQ(around_pi, 2);
  // a full turn or more: the two full charts
  model.parts[0].motion.angle_limits = RationalInterval{-4, 4};
  ChartLayout full = chart_layout(model, pair_axes(model, 0, 1));
  ASSERT_EQ(full.x_charts.size(), 2u);
  EXPECT_EQ(full.x_charts[0].lo, -1);
  EXPECT_EQ(full.x_charts[1].hi, 1);
}

TEST(Kernels, ChartLayoutTranslationAgainstFixedPart) {
  // A slider along x without limits against a fixed block: the chart covers every offset
  // where they can touch and its ends are in free space.
  Model model;
  Part slider = translating_part("slider", pt(1, 0), {polygon({pt(0, 0), pt(2, 0), pt(2, 1), pt(0, 1)})});
  Part block = fixed_part("block", {polygon({pt(10, 0), pt(12, 0), pt(12, 3), pt(10, 3)})});
  model.parts = {slider, block};
  PairAxes axes = pair_axes(model, 0, 1);
  ChartLayout layout = chart_layout(model, axes);
  ASSERT_EQ(layout.x_charts.size(), 1u);
  const ChartAxis& x = layout.x_charts[0];
  EXPECT_LT(x.lo, 8);   // touching at offset 8 (slider's right face on the block)
  EXPECT_GT(x.hi, 12);  // and at 12 (left face)
  ChartAxis none;
  EXPECT_EQ(classify_overlap(model, axes, x, none, ChartPoint{x.lo, 0}), Overlap::apart);
  EXPECT_EQ(classify_overlap(model, axes, x, none, ChartPoint{x.hi, 0}), Overlap::apart);
  EXPECT_EQ(classify_overlap(model, axes, x, none, ChartPoint{8, 0}), Overlap::touching);
  EXPECT_EQ(classify_overlap(model, axes, x, none, ChartPoint{12, 0}), Overlap::touching);
  EXPECT_EQ(classify_overlap(model, axes, x, none, ChartPoint{10, 0}), Overlap::overlapping);
  std::vector<ContactCurve> curves = generate_contact_curves(model, axes, x, none);
  bool at_8 = false, at_12 = false;
  for (const ContactCurve& curve : curves) {
    if (sgn(evaluate(curve.polynomial, 8, 0)) == 0) at_8 = true;
    if (sgn(evaluate(curve.polynomial, 12, 0)) == 0) at_12 = true;
    EXPECT_TRUE(depends_only_on_x(curve.polynomial));
  }
  EXPECT_TRUE(at_8);
  EXPECT_TRUE(at_12);
}

// kernels/distance.hpp against CGAL's exact squared distances (Simple_cartesian over mpq):
// generated segment pairs on a small grid (so that touching, crossing, collinear overlapping,
// collinear disjoint, parallel and degenerate segments all occur often) and with random
// 40-bit rational coordinates, each scaled by 1, 10^-300 and 10^400 (the distance scales by
// the factor squared, exactly).
TEST(Kernels, ExactSegmentDistancesMatchCgal) {
  using K = CGAL::Simple_cartesian<mpq_class>;
  std::mt19937 engine{20261205};
  std::uniform_int_distribution<int> grid(-3, 3);
  const Rational scales[] = {Rational(1), Rational(1, 1) / Rational(mpz_class("1" + std::string(300, '0'))),
                             Rational(mpz_class("1" + std::string(400, '0')))};
  int touching = 0, collinear = 0, apart = 0;
  for (int n = 0; n < 3000; ++n) {
    std::array<Point, 4> p;
    for (Point& q : p) {
      if (n < 2000) {
        const int x = grid(engine), y = grid(engine);
        q = n % 8 == 0 ? pt(x, 2 * x + 1) : pt(x, y);   // every eighth pair on one line
      } else {
        q = pt(frac(static_cast<long>(engine() % (1u << 20)) - (1 << 19), 1 + static_cast<long>(engine() % 4096)),
               frac(static_cast<long>(engine() % (1u << 20)) - (1 << 19), 1 + static_cast<long>(engine() % 4096)));
      }
    }
    for (const Rational& scale : scales) {
      std::array<Point, 4> s;
      for (int k = 0; k < 4; ++k) s[k] = pt(p[k].x * scale, p[k].y * scale);
      auto cgal_point = [](const Point& q) { return K::Point_2(q.x, q.y); };
      const Rational ours = kernels::segment_segment_squared_distance(s[0], s[1], s[2], s[3]);
      const bool a_point = s[0] == s[1], b_point = s[2] == s[3];
      mpq_class theirs;
      if (a_point && b_point) theirs = CGAL::squared_distance(cgal_point(s[0]), cgal_point(s[2]));
      else if (a_point) theirs = CGAL::squared_distance(cgal_point(s[0]), K::Segment_2(cgal_point(s[2]), cgal_point(s[3])));
      else if (b_point) theirs = CGAL::squared_distance(cgal_point(s[2]), K::Segment_2(cgal_point(s[0]), cgal_point(s[1])));
      else theirs = CGAL::squared_distance(K::Segment_2(cgal_point(s[0]), cgal_point(s[1])),
                                           K::Segment_2(cgal_point(s[2]), cgal_point(s[3])));
      ASSERT_EQ(ours, theirs) << "case " << n;
      if (!b_point)
        ASSERT_EQ(kernels::point_segment_squared_distance(s[0], s[2], s[3]),
                  mpq_class(CGAL::squared_distance(cgal_point(s[0]), K::Segment_2(cgal_point(s[2]), cgal_point(s[3])))))
            << "case " << n;
      if (scale == 1) {
        touching += sgn(ours) == 0;
        apart += sgn(ours) > 0;
        collinear += kernels::orientation(s[0], s[1], s[2]) == 0 && kernels::orientation(s[0], s[1], s[3]) == 0 &&
                     !a_point && !b_point;
      }
    }
  }
  EXPECT_GT(touching, 300);   // every kind exercised
  EXPECT_GT(apart, 300);
  EXPECT_GT(collinear, 150);
}


// Session 60: CGAL's interval filters (every filtered predicate of the arrangements) take their
// bounds from the hardware's upward rounding mode; valgrind ignores rounding modes (it rounds to
// nearest), and there `hipair cspace film-advance.json --pair film:follower` stopped at
// tau = 1/60 with "no rational strictly between 1245/3601 and 1245/3601" (a wrong CGAL answer;
// natively, and under valgrind with -DHIPAIR_CGAL_ROUND_TO_NEAREST=ON, the output is identical).
// The sum 1 + 2^-60 rounds to 1 to nearest: an enclosure's upper bound must exceed 1. This test
// fails under valgrind on a default build (the sign that CGAL's filters are not certified there)
// and passes natively; the project's own intervals (kernels::Interval: an ulp outwards per
// operation) hold in any mode.
TEST(Kernels, IntervalsEncloseASumThatRoundsAway) {
  volatile double tiny_bits = std::ldexp(1.0, -60);
  const double tiny = tiny_bits;
  const CGAL::Interval_nt<> sum = CGAL::Interval_nt<>(1.0) + CGAL::Interval_nt<>(tiny);
  EXPECT_GT(sum.sup(), 1.0) << "CGAL's intervals do not enclose 1 + 2^-60: is the rounding mode emulated (valgrind)? "
                               "configure with -DHIPAIR_CGAL_ROUND_TO_NEAREST=ON";
  EXPECT_LE(sum.inf(), 1.0);
  {
    CGAL::Protect_FPU_rounding<true> upward;   // as CGAL's filtered predicates run
    const CGAL::Interval_nt<false> unprotected = CGAL::Interval_nt<false>(1.0) + CGAL::Interval_nt<false>(tiny);
    EXPECT_GT(unprotected.sup(), 1.0);
  }
  const kernels::Interval own = kernels::Interval(1.0, 1.0) + kernels::Interval(tiny, tiny);
  EXPECT_GT(own.hi, 1.0);
  EXPECT_LE(own.lo, 1.0);
}

}  // namespace
}  // namespace hipair::cspace
