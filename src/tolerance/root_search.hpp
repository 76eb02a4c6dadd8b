#pragma once
// The Monte Carlo's wider root search (docs/tolerance.md "Monte Carlo"): where the first
// bracket of a follower's contact function fails (an end sign undecided or both ends of one
// sign: a band narrower than the function's rounding, a second root or a tangency next to the
// band), certain sign changes are looked for on grids of points, so that a value is either
// certified (a root with certain end signs) or honestly not certified. The function is known
// only through certified signs: sign(v) is +1 or -1 when certain, 0 for an exact zero at v,
// 2 when undecided.

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "kernels/interval.hpp"

namespace hipair::tolerance_detail {

/// A certain sign change of the function between `lo` and `hi` (lo < hi, certain signs of
/// opposite sense at both, `upper` the sign at hi), or an exact zero (lo == hi, upper 0).
struct SignChange {
  double lo = 0, hi = 0;
  int upper = 0;
};

/// The certain sign changes (and exact zeros) between consecutive points of certain sign of
/// the grid lo + (hi - lo) j / points, j = 0 .. points (undecided points skipped: a change
/// across them is between the nearest certain ones), in increasing order.
inline std::vector<SignChange> sign_changes(const std::function<int(double)>& sign, double lo, double hi,
                                            std::size_t points) {
  std::vector<SignChange> out;
  double last = 0;
  int last_sign = 2;
  for (std::size_t j = 0; j <= points; ++j) {
    double v = j == points ? hi : lo + (hi - lo) * static_cast<double>(j) / static_cast<double>(points);
    int s = sign(v);
    if (s == 0) {
      out.push_back(SignChange{v, v, 0});
      last_sign = 2;
      continue;
    }
    if (s != 1 && s != -1) continue;
    if ((last_sign == 1 || last_sign == -1) && s != last_sign && last < v) out.push_back(SignChange{last, v, s});
    last = v;
    last_sign = s;
  }
  return out;
}

/// The certain sign change nearest to `at` (by the distance from `at` to its bracket) on the
/// grid of `points` + 1 points over [at - w, at + w], for w = start, 4 x start, ... while
/// w < cap: the first window that has one (an assembly chain's follower, chain.cpp, after its
/// bracket about the linearised value failed). Exact zeros are not returned (they tell no free side).
inline std::optional<SignChange> nearest_sign_change(const std::function<int(double)>& sign, double at, double start,
                                                     double cap, std::size_t points = 32) {
  for (double w = start; w < cap; w *= 4) {
    std::optional<SignChange> best;
    double best_distance = 0;
    for (const SignChange& change : sign_changes(sign, at - w, at + w, points)) {
      if (change.upper == 0) continue;
      double distance = std::max(0.0, std::max(change.lo - at, at - change.hi));
      if (!best || distance < best_distance) {
        best = change;
        best_distance = distance;
      }
    }
    if (best) return best;
  }
  return std::nullopt;
}

/// What the wider search made of one Monte Carlo value.
enum class BandedRootKind {
  in_band,         ///< a root certified inside the band
  outside,         ///< certain equal signs at both ends of the band, a root certified beyond it
  not_certified,   ///< neither: no value is claimed
};
struct BandedRoot {
  BandedRootKind kind = BandedRootKind::not_certified;
  kernels::Interval root;
};

/// Whether the function certainly has no zero on [band.lo, band.hi]: `range_sign` (the sign of
/// an interval enclosure of the function over an interval: +1 or -1 when certain, else 0 or 2)
/// equal to `expected` on every piece of a bisection of the band, at most 2^depth pieces.
inline bool certainly_no_zero(const std::function<int(kernels::Interval)>& range_sign, kernels::Interval band,
                              int expected, int depth = 8) {
  int s = range_sign(band);
  if (s == expected) return true;
  if ((s == 1 || s == -1) || depth == 0) return false;   // the other sign: impossible if the ends agree
  double m = 0.5 * (band.lo + band.hi);
  if (!(m > band.lo && m < band.hi)) return false;
  return certainly_no_zero(range_sign, kernels::Interval(band.lo, m), expected, depth - 1) &&
         certainly_no_zero(range_sign, kernels::Interval(m, band.hi), expected, depth - 1);
}

/// A single pair's value at one vector after its first bracket failed (analysis.cpp): the
/// holder's contact function (`sign`; `range_sign` its sign over an interval; `refine` encloses
/// its root in a bracket with certain opposite end signs, false if it cannot) against the
/// certified band `band` (chart units).
/// In the band: a certain sign change (or an exact zero) among `points` + 1 points of the band.
/// Outside: the function certainly without a zero on the whole band (one certain sign over
/// every piece of a bisection of it: equal end signs alone leave two roots, or a double one,
/// possible between the grid's points) and a certain sign change beyond an end, the nearest one
/// found in windows of `start`, 4 x `start`, ... up to `cap` on either side. Else not certified
/// (session 29's review: with end signs alone a sound band with two roots inside was reported
/// as a defect).
inline BandedRoot search_band_root(const std::function<int(double)>& sign,
                                   const std::function<int(kernels::Interval)>& range_sign,
                                   const std::function<bool(kernels::Interval, kernels::Interval&)>& refine,
                                   kernels::Interval band, double start, double cap, std::size_t points = 16) {
  using kernels::Interval;
  BandedRoot result;
  auto settle = [&](const SignChange& change, BandedRootKind kind) {
    if (change.lo == change.hi) {
      result.kind = kind;
      result.root = Interval::point(change.lo);
      return true;
    }
    Interval root;
    if (!refine(Interval(change.lo, change.hi), root)) return false;
    result.kind = kind;
    result.root = root;
    return true;
  };
  for (const SignChange& change : sign_changes(sign, band.lo, band.hi, points))
    if (settle(change, BandedRootKind::in_band)) return result;
  int s_lo = sign(band.lo), s_hi = sign(band.hi);
  if (!((s_lo == 1 || s_lo == -1) && s_lo == s_hi)) return result;
  if (!certainly_no_zero(range_sign, band, s_lo)) return result;
  for (double w = start; w <= cap; w *= 4) {
    std::vector<SignChange> above = sign_changes(sign, band.hi, band.hi + w, points);
    std::vector<SignChange> below = sign_changes(sign, band.lo - w, band.lo, points);
    // the nearest to the band first
    std::optional<SignChange> up, down;
    if (!above.empty()) up = above.front();
    if (!below.empty()) down = below.back();
    if (up && down && band.lo - down->hi < up->lo - band.hi) std::swap(up, down);
    for (const std::optional<SignChange>& c : {up, down})
      if (c && settle(*c, BandedRootKind::outside)) return result;
  }
  return result;
}

}  // namespace hipair::tolerance_detail
