// HIPAIR — which contacts an impact leaves held (docs/simulation.md, "A held set the velocities
// cannot keep" and "Why held_at_resolution's thresholds are what they are"). Shared by both planar
// simulators' `hold` (src/simulation/planar.cpp). Internal to src/simulation (uses Eigen).
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace hipair::simulation {

/// The fraction of the rest speed to which the projection onto the held contacts must bring their
/// normal speeds (and below which a contact counts as not separating). A speed r left on a held
/// contact moves it by r t; in the time t = sqrt(2 delta / a) = rest speed / a in which the loads
/// turn a motion at the rest speed, that is within the held positions' own projection tolerance
/// (10^-3 of the hold gap 3/4 delta) when r <= 3.75e-4 of the rest speed: the largest fraction
/// the accuracy allows. The double solve leaves, on rows it keeps independent, about
/// 2^-52 kappa of the normal speeds (kappa the rows' condition, <= about 1e10 before the
/// decomposition merges them), and on rows it merges the rows' speed difference (of the order of
/// the speeds themselves). 1e-6 lies between the two with two orders of magnitude to spare on the
/// accuracy's side; tests/unit/simulation_impact_resolution_test.cpp checks on generated cases
/// (rows 1e-5 of the reach apart and more) that no decision changes for fractions 1e-9 ... 1e-4.
inline constexpr double held_solve_fraction = 1e-6;

/// A projection is a plastic remainder when it changes no body's point velocity by more than
/// (1 + e_max) rest speeds, e_max = 1: the most an impact at the rest speed (the speeds the hold
/// stands for) could change it, at any restitution. A larger change is not the remainder of
/// impacts below the resolution but a change of the motion (session 52: a turning of 55 rad/s
/// removed for a normal speed of 5e-3 mm/s).
inline constexpr double held_change_factor = 2;

/// Which of the contacts an impact left without separating speed (keep[r]: normal speed
/// after(r) <= the rest speed, a contact of its own) are held. Holding them projects the
/// velocity v onto J v = 0 (mass-weighted, inverse masses minv): a plastic remainder, by the rest
/// speed's definition, moves no point of a part by more than about the rest speed. Where two
/// contacts' rows are nearly dependent (two fixed vertices 1e-8 mm apart under one turning face
/// of the part: their rows differ by the moment arm 1e-8 only) the projection is not a remainder:
/// it either stops the part's turning (a rotation of 55 rad/s removed for a normal speed of
/// 5e-3 mm/s) or, where the decomposition takes the rows as one, leaves one contact approaching
/// while held — the next step's force problem lifts it off and the chord strikes it again at
/// once, with no end (session 52). Then the contact the impact left separating fastest is not held
/// (the exact chords watch it like any free feature pair), until the projection of the rest
/// removes their normal speeds (to held_solve_fraction of the rest speed) and changes no body's
/// point velocity (|dv| + |domega| reach, reach(b) per body of 3 coordinates) by more than
/// held_change_factor rest speeds. A single contact is always held. row(r): contact r's row of J;
/// `solve_fraction` and `change_factor` are the constants above (the tests vary them).
template <class Row, class After, class Reach>
std::vector<bool> held_at_resolution(std::vector<bool> keep, Row row, After after, const Eigen::VectorXd& minv,
                                     const Eigen::VectorXd& v, Reach reach, double rest_speed,
                                     double solve_fraction = held_solve_fraction,
                                     double change_factor = held_change_factor) {
  const Eigen::Index n = minv.size();
  for (;;) {
    std::vector<std::size_t> kept;
    for (std::size_t r = 0; r < keep.size(); ++r)
      if (keep[r]) kept.push_back(r);
    if (kept.size() <= 1) return keep;
    Eigen::MatrixXd A(static_cast<Eigen::Index>(kept.size()), n);
    for (std::size_t i = 0; i < kept.size(); ++i) A.row(static_cast<Eigen::Index>(i)) = row(kept[i]).transpose();
    const Eigen::MatrixXd MAt = minv.asDiagonal() * A.transpose();
    const Eigen::VectorXd dv = -MAt * (A * MAt).completeOrthogonalDecomposition().solve(A * v);
    const double residual = (A * (v + dv)).cwiseAbs().maxCoeff();
    double change = 0;
    for (Eigen::Index b = 0; b + 2 < n; b += 3)
      change = std::max(change, std::hypot(dv(b), dv(b + 1)) + std::abs(dv(b + 2)) * reach(static_cast<std::size_t>(b / 3)));
    if (residual <= solve_fraction * rest_speed && change <= change_factor * rest_speed) return keep;
    std::size_t fastest = kept.front();
    for (std::size_t r : kept)
      if (after(r) > after(fastest)) fastest = r;
    if (!(after(fastest) > solve_fraction * rest_speed)) return keep;   // none separating: the projection stands
    keep[fastest] = false;
  }
}

}  // namespace hipair::simulation
