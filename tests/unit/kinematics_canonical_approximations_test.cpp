// Session 27: the kinematic engine's approximations of exact positions are functions of the
// number, not of its isolating interval, so a slicer may isolate roots however it likes without
// changing a printed digit:
//   - truncated_double(x) is the double nearest x towards zero (mpq_get_d's truncation of x);
//   - rational_near(x, bits) is x when x is an exact Real or lies on a cell edge k 2^-bits, else
//     the midpoint of the cell [k, k + 1) 2^-bits holding x (a rational off the grid given by an
//     isolating interval is not recognised as rational: its cell's midpoint).
// Oracle: exact comparisons of x with the returned double and its neighbour, and with the cell's
// edges; every number is given by several different isolating intervals (roots isolated on
// different ranges, by Sturm and by Descartes, refined copies), which must give the same answers.
// The numbers: roots of (b x - a)(x^2 - c) and of (x - d)^2 - e with d a double and e tiny (roots
// within 2^-60 of a double or of a grid edge), doubles themselves as roots of higher-degree
// polynomials (not exact Reals), and grid edges k 2^-bits as such roots.
#include "kinematics/axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;
using algebra::Polynomial;

Polynomial times(const Polynomial& a, const Polynomial& b) {
  Polynomial c(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

// (den x - num) for a rational
Polynomial linear(const Rational& r) { return Polynomial{-r.get_num(), r.get_den()}; }

// The roots of p in [lo, hi] by three isolations: Sturm on [lo, hi], Sturm on a wider range,
// Descartes, each also refined; grouped by number (each group: the same root, several intervals).
std::vector<std::vector<Real>> isolations(const Polynomial& p, const Rational& lo, const Rational& hi) {
  std::vector<std::vector<Real>> sets{algebra::real_roots(p, lo, hi), algebra::real_roots(p, lo - 3, hi + 5),
                                      algebra::descartes_real_roots(p, lo, hi)};
  std::vector<std::vector<Real>> groups;
  for (const std::vector<Real>& set : sets)
    for (const Real& root : set) {
      if (root.compare(lo) < 0 || root.compare(hi) > 0) continue;
      std::vector<Real> versions{root};
      Real refined = root;
      refined.refine_to(Rational(1, mpz_class(1) << 30));
      versions.push_back(refined);
      refined.refine();
      versions.push_back(refined);
      bool placed = false;
      for (auto& group : groups)
        if (algebra::compare(group.front(), root) == 0) {
          group.insert(group.end(), versions.begin(), versions.end());
          placed = true;
          break;
        }
      if (!placed) groups.push_back(versions);
    }
  return groups;
}

// The oracle of truncated_double: x between the double and its neighbour away from zero.
void expect_truncated(const Real& x, double d, const std::string& where) {
  ASSERT_TRUE(std::isfinite(d)) << where;
  int sign = x.compare(Rational(0));
  if (sign >= 0) {
    EXPECT_GE(x.compare(Rational(d)), 0) << where;
    EXPECT_LT(x.compare(Rational(std::nextafter(d, std::numeric_limits<double>::infinity()))), 0) << where;
  } else {
    EXPECT_LE(x.compare(Rational(d)), 0) << where;
    EXPECT_GT(x.compare(Rational(std::nextafter(d, -std::numeric_limits<double>::infinity()))), 0) << where;
  }
}

// The oracle of rational_near: the number itself when exact or on a cell edge, else the midpoint
// of the grid cell holding it.
void expect_near(const Real& x, const Rational& r, int bits, const std::string& where) {
  Rational scale(mpz_class(1) << bits);
  if (x.exact) {
    EXPECT_EQ(r, x.lower) << where;
    return;
  }
  if (x.compare(r) == 0) {
    Rational scaled = r * scale;
    EXPECT_EQ(scaled.get_den(), 1) << where << ": a rational off the grid";
    return;
  }
  Rational k = r * scale - Rational(1, 2);
  ASSERT_EQ(k.get_den(), 1) << where << ": not a cell midpoint";
  EXPECT_GT(x.compare(k / scale), 0) << where;
  EXPECT_LT(x.compare((k + 1) / scale), 0) << where;
}

TEST(KinematicCanonicalApproximations, TruncatedDoubleAndRationalNearAreFunctionsOfTheNumber) {
  std::mt19937_64 random(27);
  std::size_t numbers = 0, versions = 0, near_boundary = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int bits = trial % 2 ? 64 : 60;
    Polynomial p;
    const int kind = trial % 4;
    double d = std::ldexp(static_cast<double>(random() % (1ull << 53)), -53) * ((random() % 2) ? 1 : -1) *
               std::ldexp(1.0, static_cast<int>(random() % 9) - 4);
    if (kind == 0) {
      // (b x - a)(x^2 - c): a rational and two square roots
      Rational a(static_cast<long>(random() % 2001) - 1000, static_cast<long>(1 + random() % 997));
      a.canonicalize();
      Polynomial quadratic{-mpz_class(static_cast<unsigned long>(1 + random() % 50)), 0, 1};
      p = times(linear(a), quadratic);
    } else if (kind == 1) {
      // (x - d)^2 - e: roots d +- sqrt(e) within about 2^-(65 + j) of the double d
      Rational e(mpz_class(1), mpz_class(1) << (130 + 2 * static_cast<int>(random() % 8)));
      Polynomial square = times(linear(Rational(d)), linear(Rational(d)));
      for (auto& c : square) c *= e.get_den();
      square[0] -= e.get_num();
      p = square;
      ++near_boundary;
    } else if (kind == 2) {
      // the double d itself as a root of a cubic (not an exact Real after isolation)
      p = times(linear(Rational(d)), Polynomial{-mpz_class(static_cast<unsigned long>(2 + random() % 30)), 0, 1});
    } else {
      // a grid edge k 2^-bits and a number within 2^-(bits + 10) of one
      mpz_class k = mpz_class(static_cast<unsigned long>(random() % (1ull << 40))) << (bits - 40);
      Rational edge(k, mpz_class(1) << bits);
      edge.canonicalize();
      Rational e(mpz_class(1), mpz_class(1) << (2 * bits + 20));
      Polynomial square = times(linear(edge), linear(edge));
      for (auto& c : square) c *= e.get_den();
      square[0] -= e.get_num();
      p = times(linear(edge), Polynomial{-mpz_class(3), 0, 1});
      p = times(p, square);
      ++near_boundary;
    }
    for (const std::vector<Real>& group : isolations(p, Rational(-40), Rational(40))) {
      ++numbers;
      const std::string where = "trial " + std::to_string(trial) + " root " + group.front().description();
      const double first_double = truncated_double(group.front());
      expect_truncated(group.front(), first_double, where);
      std::optional<Rational> first_near;   // of the first version given by an isolating interval
      for (const Real& version : group) {
        ++versions;
        EXPECT_EQ(truncated_double(version), first_double) << where << " interval " << version.description();
        Rational near = rational_near(version, bits);
        expect_near(version, near, bits, where + " interval " + version.description());
        if (version.exact) continue;
        if (!first_near) first_near = near;
        EXPECT_EQ(near, *first_near) << where << " interval " << version.description();
      }
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(numbers, 800u);
  EXPECT_GT(near_boundary, 150u);
  std::cout << numbers << " numbers, " << versions << " isolating intervals\n";
}

}  // namespace
}  // namespace hipair::kinematics_detail
