// The side of a new contact's C-space normal (simulation.cpp, Simulation::Impl::sustain): the
// contact g = sigma (q_y - Y(q_x)) >= 0 is oriented so that its C-space normal (-sigma Y', sigma)
// agrees with the physical normal G over the pair's two coordinates, i.e. sigma is the sign of
// dot = G_y - Y' G_x. Before session 42 Y' was the midpoint of the exact slope range
// (edge_coordinate_slope at the configuration's rational abscissa: the edge's ordinate as an
// algebraic number, rational interval arithmetic, ≈ 400 k instructions) and the sign taken of
// the double dot there.
//
// Now first a certified enclosure [lo, hi] of Y' from track_derivatives (outward-rounded double
// intervals on a fresh tracker, hipair/edge_tracker.hpp): dot is affine in Y', so over [lo, hi]
// it lies between its values at the two ends; each is computed in doubles with the error bound
// of two roundings, 4 eps (|s G_x| + |G_y|) (eps = 2^-52, twice the unit roundoff: generous).
// When both ends are certainly of one sign, that is the sign of the true dot (the exact slope's),
// so of the old rule's wherever the old rule's double was right. Otherwise (the enclosure
// meets dot = 0, the filter cannot certify, a non-finite bound) the exact slope decides as
// before. Switch simulation::normal_filter() (on by default; tests turn it off on their thread to
// compare, SimulationNormalSide.*); counter normal_filter_decided().
#pragma once

#include "core/thread_switch.hpp"

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>

namespace hipair::simulation {

struct NormalFilterTag;
inline bool& normal_filter() { return thread_switch<NormalFilterTag>(); }
// How many new contacts the filter oriented (tests, profiling).
struct NormalFilterDecidedTag;
inline std::size_t& normal_filter_decided() { return thread_counter<NormalFilterDecidedTag>(); }

/// +1 or -1: the sign of gy - s gx for every s in [lo, hi], certified; 0: not decided.
inline int certified_side(double lo, double hi, double gx, double gy) {
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(gx) || !std::isfinite(gy)) return 0;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  int side = 0;
  for (double s : {lo, hi}) {
    const double product = s * gx;
    const double dot = gy - product;
    const double error = 4 * eps * (std::abs(product) + std::abs(gy));
    if (!std::isfinite(dot) || !std::isfinite(error)) return 0;
    const int here = dot > error ? 1 : dot < -error ? -1 : 0;
    if (here == 0 || (side != 0 && here != side)) return 0;
    side = here;
  }
  return side;
}

}  // namespace hipair::simulation
