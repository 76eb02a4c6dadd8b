// The polygon front end's exact shortcut in front of the culling quadtree
// (`valid_point_in_box`, src/cspace/builder.cpp: integer signs of the meeting point's
// homogeneous coordinates, accumulated in place) against a reference in rationals on
// generated lines, validity clauses and boxes: the meeting point of the line with each linear
// atom's line by Cramer's rule as rationals, the closed box by rational comparisons, every
// clause by evaluating its atoms exactly at that point.
#include "cspace/valid_point.hpp"
#include "algebra/polynomial.hpp"
#include <hipair/rational.hpp>
#include <gtest/gtest.h>
#include <initializer_list>
#include <optional>
#include <random>
#include <utility>
#include <vector>

namespace hipair::cspace {
namespace {

// a x + b y + c, trimmed as the generator leaves its polynomials
IntegerPolynomial2 linear_of(const mpz_class& a, const mpz_class& b, const mpz_class& c) {
  IntegerPolynomial2 p;
  if (a == 0 && b == 0 && c == 0) return p;
  p.coefficients.resize(a != 0 ? 2 : 1);
  if (a != 0) p.coefficients[1].push_back(a);
  if (b != 0) p.coefficients[0] = {c, b};
  else p.coefficients[0] = {c};
  return p;
}

IntegerPolynomial2 line(long a, long b, long c) { return linear_of(mpz_class(a), mpz_class(b), mpz_class(c)); }

// x^2 + y^2 - r (a non-linear atom: the shortcut evaluates it at the rational point)
IntegerPolynomial2 circle(long r) {
  IntegerPolynomial2 p;
  p.coefficients = {{mpz_class(-r), mpz_class(0), mpz_class(1)}, {mpz_class(0)}, {mpz_class(1)}};
  return p;
}

const mpz_class& coefficient(const IntegerPolynomial2& f, std::size_t i, std::size_t j) {
  static const mpz_class zero = 0;
  if (i >= f.coefficients.size() || j >= f.coefficients[i].size()) return zero;
  return f.coefficients[i][j];
}

bool linear(const IntegerPolynomial2& p) {
  return p.degree_x() <= 1 && p.degree_y() <= 1 && sgn(coefficient(p, 1, 1)) == 0;
}

// Where the lines f = 0 and atom = 0 meet (Cramer's rule in rationals); nullopt when parallel.
std::optional<std::pair<Rational, Rational>> meeting_point(const IntegerPolynomial2& f, const IntegerPolynomial2& atom) {
  const Rational a(coefficient(f, 1, 0)), b(coefficient(f, 0, 1)), c(coefficient(f, 0, 0));
  const Rational d(coefficient(atom, 1, 0)), e(coefficient(atom, 0, 1)), g(coefficient(atom, 0, 0));
  const Rational det = a * e - b * d;
  if (det == 0) return std::nullopt;
  return std::make_pair(Rational((b * g - c * e) / det), Rational((c * d - a * g) / det));
}

// One side of `box` moved onto the meeting point of the curve's line with the first atom of its
// first clause (the right, left, top or bottom side, drawn by `random`; the box side() long that
// way), when the curve and the atom are lines that meet: the closed box's ends. False when they
// do not (nothing drawn).
template <class Side>
bool box_through_meeting_point(const ContactCurve& curve, raw::Box& box, std::mt19937_64& random, Side side) {
  if (curve.validity.empty() || curve.validity[0].atoms.empty() || !linear(curve.validity[0].atoms[0]) ||
      curve.polynomial.degree_x() > 1)
    return false;
  const std::optional<std::pair<Rational, Rational>> point = meeting_point(curve.polynomial, curve.validity[0].atoms[0]);
  if (!point) return false;
  const auto& [x, y] = *point;
  const Rational length = side();
  switch (random() % 4) {
    case 0: box.x_hi = x; box.x_lo = x - length; break;
    case 1: box.x_lo = x; box.x_hi = x + length; break;
    case 2: box.y_hi = y; box.y_lo = y - length; break;
    default: box.y_lo = y; box.y_hi = y + length; break;
  }
  return true;
}

// The reference, in rationals.
bool reference(const ContactCurve& curve, const raw::Box& box) {
  const IntegerPolynomial2& f = curve.polynomial;
  if (f.degree_x() > 1 || f.degree_y() > 1 || sgn(coefficient(f, 1, 1)) != 0 || curve.validity.empty()) return false;
  for (const auto& clause : curve.validity)
    for (const auto& atom : clause.atoms) {
      if (!linear(atom)) continue;
      const std::optional<std::pair<Rational, Rational>> point = meeting_point(f, atom);
      if (!point) continue;
      const auto& [x, y] = *point;
      if (x < box.x_lo || x > box.x_hi || y < box.y_lo || y > box.y_hi) continue;
      bool all = true;
      for (const auto& other : curve.validity) {
        bool any = false;
        for (const auto& p : other.atoms) any = any || evaluate(p, x, y) >= 0;
        all = all && any;
      }
      if (all) return true;
    }
  return false;
}

// valid_point_in_box (machine integers first) and its GMP path both give the reference's answer,
// counted in `found` or `not_found`; false once a test assertion has failed.
bool expect_both_paths_equal(const ContactCurve& curve, const raw::Box& box, int instance, int& found, int& not_found) {
  const bool expected = reference(curve, box);
  EXPECT_EQ(valid_point_in_box(curve, box), expected) << "instance " << instance;
  EXPECT_EQ(valid_point_in_box_gmp(curve, box), expected) << "instance " << instance;
  (expected ? found : not_found) += 1;
  return !::testing::Test::HasFailure();
}

TEST(CSpaceValidPoint, ShortcutEqualsTheRationalReferenceOnGeneratedLinesClausesAndBoxes) {
  std::mt19937_64 random(2026);
  auto small = [&](int range) { return static_cast<long>(random() % (2 * range + 1)) - range; };
  auto fraction = [](long n, long d) {
    Rational q{mpz_class(n), mpz_class(d)};
    q.canonicalize();
    return q;
  };
  int found = 0, not_found = 0, on_the_box = 0;
  for (int instance = 0; instance < 40000; ++instance) {
    ContactCurve curve;
    const long a = small(4), b = small(4), c = small(12);
    curve.polynomial = line(a, b, c);
    const int clauses = static_cast<int>(random() % 4);   // 0: no validity (false)
    for (int k = 0; k < clauses; ++k) {
      ValidityClause clause;
      const int atoms = 1 + static_cast<int>(random() % 2);
      for (int m = 0; m < atoms; ++m)
        clause.atoms.push_back(random() % 6 == 0 ? circle(1 + static_cast<long>(random() % 20))
                                                  : line(small(5), small(5), small(15)));
      curve.validity.push_back(std::move(clause));
    }
    raw::Box box;
    const long den = 1 + static_cast<long>(random() % 6);
    box.x_lo = fraction(small(10), den);
    box.y_lo = fraction(small(10), den);
    box.x_hi = box.x_lo + fraction(1 + static_cast<long>(random() % 12), 1 + static_cast<long>(random() % 3));
    box.y_hi = box.y_lo + fraction(1 + static_cast<long>(random() % 12), 1 + static_cast<long>(random() % 3));
    // a third of the boxes get a side exactly through a meeting point (the closed box's ends)
    if (random() % 3 == 0 && box_through_meeting_point(curve, box, random, [] { return Rational(3); })) ++on_the_box;
    if (!expect_both_paths_equal(curve, box, instance, found, not_found)) return;
  }
  EXPECT_GE(found, 2500);
  EXPECT_GE(not_found, 2000);
  EXPECT_GE(on_the_box, 4000);
}

// The machine-integer path (exact below 2^62 per integer, overflow-checked) against the
// rational reference and the GMP path where it must give up or only just fits: every line,
// atom and box integer drawn at a random scale 2^0 .. 2^70 (so that the integers read cross
// 2^62 and the products cross 2^127 in both directions), with a common factor sometimes, and
// boxes through meeting points.
TEST(CSpaceValidPoint, MachineIntegersEqualTheReferenceAcrossTheirLimits) {
  std::mt19937_64 random(58);
  auto big = [&]() {
    const int bits = static_cast<int>(random() % 71);
    mpz_class v = 0;
    for (int b = 0; b < bits; b += 32) v = (v << 32) + mpz_class(static_cast<unsigned long>(random() & 0xffffffffu));
    if (bits > 0) v = v >> (((bits + 31) / 32) * 32 - bits);
    return random() % 2 ? mpz_class(-v) : v;
  };
  auto positive = [&]() {
    mpz_class d = abs(big());
    return d == 0 ? mpz_class(1) : d;
  };
  int found = 0, not_found = 0, large = 0;
  for (int instance = 0; instance < 20000; ++instance) {
    ContactCurve curve;
    const mpz_class factor = random() % 4 == 0 ? positive() : mpz_class(1);
    const mpz_class a = big() * factor, b = big() * factor, c = big() * factor;
    curve.polynomial = linear_of(a, b, c);
    const int clauses = 1 + static_cast<int>(random() % 3);
    for (int k = 0; k < clauses; ++k) {
      ValidityClause clause;
      const int atoms = 1 + static_cast<int>(random() % 2);
      for (int m = 0; m < atoms; ++m)
        clause.atoms.push_back(random() % 8 == 0 ? circle(1 + static_cast<long>(random() % 20)) : linear_of(big(), big(), big()));
      curve.validity.push_back(std::move(clause));
    }
    raw::Box box;
    auto fraction = [&]() {
      Rational q(big(), positive());
      q.canonicalize();
      return q;
    };
    box.x_lo = fraction();
    box.y_lo = fraction();
    box.x_hi = box.x_lo + abs(fraction()) + 1;
    box.y_hi = box.y_lo + abs(fraction()) + 1;
    if (random() % 2 == 0) box_through_meeting_point(curve, box, random, [&] { return Rational(abs(fraction()) + 1); });
    for (const mpz_class* v : std::initializer_list<const mpz_class*>{&a, &b, &c, &box.x_lo.get_num(), &box.x_hi.get_den()})
      if (mpz_sizeinbase(v->get_mpz_t(), 2) > 62) {
        ++large;
        break;
      }
    if (!expect_both_paths_equal(curve, box, instance, found, not_found)) return;
  }
  EXPECT_GE(found, 1000);
  EXPECT_GE(not_found, 1000);
  EXPECT_GE(large, 2000);
}

}  // namespace
}  // namespace hipair::cspace
