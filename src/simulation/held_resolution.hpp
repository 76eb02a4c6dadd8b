// HIPAIR — which contacts an impact leaves held (docs/simulation.md, "A held set the velocities
// cannot keep", "Why held_at_resolution's thresholds are what they are" and "Held contacts decided
// exactly"). Shared by both planar simulators' `hold` (src/simulation/planar.cpp). Internal to
// src/simulation. Every decision here is exact: the contacts' rows are exact rationals (the
// kernels' contact frames at the exact configuration), the velocities, masses and speeds are the
// doubles they are, read as exact rationals.
#pragma once

#include <hipair/rational.hpp>

#include "simulation/exact_elimination.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace hipair::simulation {

/// The fraction of the rest speed above which a contact counts as separating in the choice of
/// the contact to free (below: the projection stands). A speed r left on a held contact moves it
/// by r t; in the time t = sqrt(2 delta / a) = rest speed / a in which the loads turn a motion at
/// the rest speed, that is within the held positions' own projection tolerance (10^-3 of the hold
/// gap 3/4 delta) when r <= 3.75e-4 of the rest speed: the largest fraction the accuracy allows.
/// The exact projection leaves no normal speed at all (session 56: before, the double solve left
/// about 2^-52 kappa of the speeds and this fraction bounded that residual as well).
inline constexpr double held_solve_fraction = 1e-6;

/// A projection is a plastic remainder when it changes no body's point velocity by more than
/// (1 + e_max) rest speeds, e_max = 1: the most an impact at the rest speed (the speeds the hold
/// stands for) could change it, at any restitution. A larger change is not the remainder of
/// impacts below the resolution but a change of the motion (session 52: a turning of 55 rad/s
/// removed for a normal speed of 5e-3 mm/s).
inline constexpr double held_change_factor = 2;

/// One contact's row of J in exact rationals, over every coordinate (x, y, theta per body):
/// [n_x, n_y, r x n] for the body the normal points into, minus that for the other body, with a
/// normal n that need not be a unit vector; norm2 = |n|^2. The contact's normal speed is
/// a . v / |n|.
struct ExactRow {
  std::vector<Rational> a;
  Rational norm2;
};

/// sign(s1 / sqrt(N1) - s2 / sqrt(N2)) for N1, N2 > 0, exactly.
inline int compare_normal_speeds(const Rational& s1, const Rational& N1, const Rational& s2, const Rational& N2) {
  const int a = sgn(s1), b = sgn(s2);
  if (a != b) return a < b ? -1 : 1;
  if (a == 0) return 0;
  const int magnitude = cmp(s1 * s1 * N2, s2 * s2 * N1);   // |s1| / sqrt(N1) against |s2| / sqrt(N2)
  return a > 0 ? (magnitude > 0) - (magnitude < 0) : (magnitude < 0) - (magnitude > 0);
}

/// Whether the contact of `row` moves apart faster than `speed` (>= 0) at velocity v: a . v > speed |n|.
inline bool separating_faster_than(const ExactRow& row, const std::vector<Rational>& v, const Rational& speed) {
  Rational s = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (sgn(row.a[i]) != 0) s += row.a[i] * v[i];
  if (sgn(s) <= 0) return false;
  return cmp(s * s, speed * speed * row.norm2) > 0;
}

/// The velocity change of the mass-weighted projection of v onto J v = 0 (rows `rows`, inverse
/// masses minv), exactly: dv = -M^-1 J^T lambda with (J M^-1 J^T) lambda = J v. The projection is
/// unique whatever lambda solves the system when the rows are dependent (J v lies in the range
/// of J M^-1 J^T); Gaussian elimination with exact pivots takes the free multipliers as 0.
inline std::vector<Rational> exact_projection_change(const std::vector<const ExactRow*>& rows,
                                                     const std::vector<Rational>& minv, const std::vector<Rational>& v) {
  const std::size_t k = rows.size(), n = minv.size();
  std::vector<std::vector<Rational>> G(k, std::vector<Rational>(k + 1));
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = i; j < k; ++j) {
      Rational g = 0;
      for (std::size_t c = 0; c < n; ++c)
        if (sgn(rows[i]->a[c]) != 0 && sgn(rows[j]->a[c]) != 0) g += rows[i]->a[c] * minv[c] * rows[j]->a[c];
      G[i][j] = g;
      G[j][i] = g;
    }
    Rational s = 0;
    for (std::size_t c = 0; c < n; ++c)
      if (sgn(rows[i]->a[c]) != 0) s += rows[i]->a[c] * v[c];
    G[i][k] = s;
  }
  // forward elimination (exact: a pivot is any non-zero entry)
  const std::vector<std::size_t> pivot_column = row_echelon(G, k);
  const std::size_t r = pivot_column.size();
  std::vector<Rational> lambda(k, Rational(0));
  for (std::size_t i = r; i-- > 0;) {
    const std::size_t c = pivot_column[i];
    Rational s = G[i][k];
    for (std::size_t j = c + 1; j < k; ++j)
      if (sgn(G[i][j]) != 0) s -= G[i][j] * lambda[j];
    lambda[c] = s / G[i][c];
  }
  std::vector<Rational> dv(n, Rational(0));
  for (std::size_t i = 0; i < k; ++i) {
    if (sgn(lambda[i]) == 0) continue;
    for (std::size_t c = 0; c < n; ++c)
      if (sgn(rows[i]->a[c]) != 0) dv[c] -= minv[c] * rows[i]->a[c] * lambda[i];
  }
  return dv;
}

/// Whether a velocity change dv moves no body's point by more than `limit`: per body b (3
/// coordinates), |(dv_x, dv_y)| + |dv_theta| reach(b) <= limit, exactly.
template <class Reach>
bool change_within(const std::vector<Rational>& dv, Reach reach, const Rational& limit) {
  for (std::size_t b = 0; b + 2 < dv.size(); b += 3) {
    const Rational turn = abs(dv[b + 2]) * reach(b / 3);
    if (cmp(turn, limit) > 0) return false;
    const Rational left = limit - turn;
    if (cmp(dv[b] * dv[b] + dv[b + 1] * dv[b + 1], left * left) > 0) return false;
  }
  return true;
}

/// Which of the contacts an impact left without separating speed (keep[r]: normal speed
/// after the impact <= the rest speed, a contact of its own) are held. Holding them projects the
/// velocity v onto J v = 0 (mass-weighted, inverse masses minv): a plastic remainder, by the rest
/// speed's definition, moves no point of a part by more than about the rest speed. Where two
/// contacts' rows are nearly dependent (two fixed vertices 1e-8 mm apart under one turning face
/// of the part: their rows differ by the moment arm 1e-8 only) the projection is not a remainder:
/// it stops the part's turning (a rotation of 55 rad/s removed for a normal speed of 5e-3 mm/s).
/// Then the contact the impact left separating fastest is not held (the exact chords watch it
/// like any free feature pair), until the projection onto the rest changes no body's point
/// velocity (|dv| + |domega| reach, reach(b) per body of 3 coordinates) by more than
/// change_factor rest speeds. A single contact is always held; a set none of whose contacts
/// separates faster than solve_fraction rest speeds is held whole. Exact throughout (the
/// projection, the change's comparison, the fastest contact): rows any distance apart, 0
/// included, and numbers of any size decide as their values do. `solve_fraction` and
/// `change_factor` are the constants above (the tests vary them).
template <class Reach>
std::vector<bool> held_at_resolution(std::vector<bool> keep, const std::vector<ExactRow>& rows,
                                     const std::vector<Rational>& minv, const std::vector<Rational>& v, Reach reach,
                                     const Rational& rest_speed, double solve_fraction = held_solve_fraction,
                                     double change_factor = held_change_factor) {
  const Rational separating = Rational(solve_fraction) * rest_speed, limit = Rational(change_factor) * rest_speed;
  for (;;) {
    std::vector<std::size_t> kept;
    std::vector<const ExactRow*> kept_rows;
    for (std::size_t r = 0; r < keep.size(); ++r)
      if (keep[r]) {
        kept.push_back(r);
        kept_rows.push_back(&rows[r]);
      }
    if (kept.size() <= 1) return keep;
    if (change_within(exact_projection_change(kept_rows, minv, v), reach, limit)) return keep;
    std::vector<Rational> speed(kept.size(), Rational(0));
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (std::size_t c = 0; c < v.size(); ++c)
        if (sgn(rows[kept[i]].a[c]) != 0) speed[i] += rows[kept[i]].a[c] * v[c];
    std::size_t fastest = 0;
    for (std::size_t i = 1; i < kept.size(); ++i)
      if (compare_normal_speeds(speed[i], rows[kept[i]].norm2, speed[fastest], rows[kept[fastest]].norm2) > 0) fastest = i;
    if (!separating_faster_than(rows[kept[fastest]], v, separating)) return keep;   // none separating: the projection stands
    keep[kept[fastest]] = false;
  }
}

}  // namespace hipair::simulation
