// Planted ties of two-contact impacts, shared by the exact impact LCP tests
// (simulation_impact_lcp_exact_test.cpp: diagonal masses; simulation_impact_lcp_full_test.cpp:
// the pin-slot part's coupled mass matrix): the two-contact LCP's oracle in rationals, and the
// generator step that orients the two rows and puts v_1 where contact 2's speed after contact 1's
// impulse alone is exactly 0 or +-2^-(s+k).
#pragma once

#include <hipair/rational.hpp>

#include "held_oracle_support.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <optional>

namespace hipair::impact_tie {

// the two-contact LCP lambda >= 0, w = A lambda + b >= 0, lambda w = 0 in rationals, by its four
// held sets (A positive definite: exactly one is consistent; `found` false if none is)
struct Lcp2 {
  Rational lambda[2], w[2];
  bool found = false;
};

inline Lcp2 lcp2(const Rational (&A)[2][2], const Rational (&b)[2]) {
  for (int set = 3; set >= 0; --set) {
    Lcp2 o;
    const bool h0 = set & 1, h1 = set & 2;
    o.lambda[0] = o.lambda[1] = 0;
    if (h0 && h1) {
      const Rational d = A[0][0] * A[1][1] - A[0][1] * A[1][0];
      o.lambda[0] = (-b[0] * A[1][1] + b[1] * A[0][1]) / d;
      o.lambda[1] = (-b[1] * A[0][0] + b[0] * A[1][0]) / d;
    } else if (h0) {
      o.lambda[0] = -b[0] / A[0][0];
    } else if (h1) {
      o.lambda[1] = -b[1] / A[1][1];
    }
    bool ok = true;
    for (int k = 0; k < 2; ++k) {
      o.w[k] = A[k][0] * o.lambda[0] + A[k][1] * o.lambda[1] + b[k];
      ok = ok && sgn(o.lambda[k]) >= 0 && sgn(o.w[k]) >= 0;
    }
    if (ok) {
      o.found = true;
      return o;
    }
  }
  return {};
}

struct Plant {
  bool planted = false;
  int k = 0, side = 0;
};

// Orients rows 0 and 1 of G (contact 1 approaching; A_21 > 0, so that contact 2 approaches where
// it is planted), then with probability 3/4 plants the tie: g2 v = (A21 / A11) g1 v + delta,
// delta = side 2^-(s+k) (side in {-1, 0, 1}, k = 1..60), solved for v_1 (g2_1 = +-1; the coordinates
// 0..n-1 carry the two rows). `form_A()` recomputes A from G; `dot(row, v)` is g_row v exactly.
// Returns nothing where the case is to be skipped (A_21 = 0, A singular, g1 v = 0, v_1 beyond a
// double, or contact 1 no longer approaching).
template <class FormA, class Dot>
std::optional<Plant> orient_and_plant(Eigen::MatrixXd& G, Eigen::VectorXd& v, const Rational (&A)[2][2], int n, int s,
                                      held_oracle::Rng& rng, FormA form_A, Dot dot) {
  form_A();
  if (sgn(A[0][1]) == 0 || sgn(A[0][0] * A[1][1] - A[0][1] * A[1][0]) <= 0 || sgn(dot(0, v)) == 0) return std::nullopt;
  if (sgn(dot(0, v)) > 0) G.row(0) = -G.row(0);   // contact 1 approaching
  form_A();
  if (sgn(A[0][1]) < 0) G.row(1) = -G.row(1);   // contact 2 approaching where it is planted (r > 0)
  form_A();
  Plant p;
  p.planted = rng.below(4) != 0;
  if (!p.planted) return p;
  p.k = 1 + rng.below(60);
  p.side = rng.below(3) - 1;
  const Rational delta = p.side * Rational(std::ldexp(1.0, -(s + p.k)));
  const Rational target = A[1][0] / A[0][0] * dot(0, v) + delta;
  Rational rest = 0;
  for (int i = 0; i < n; ++i)
    if (i != 1) rest += Rational(G(1, i)) * Rational(v(i));
  const Rational v1 = (target - rest) / Rational(G(1, 1));
  const double d = to_double(v1);
  if (!std::isfinite(d) || Rational(d) != v1) return std::nullopt;   // beyond a double's precision
  v(1) = d;
  if (sgn(dot(0, v)) >= 0) return std::nullopt;
  return p;
}

}  // namespace hipair::impact_tie
