// HIPAIR — the step's cut at a sustained contact's first violated condition (simulation.cpp's
// step): a bracket [lo, hi] of the change of a boolean predicate along the step's path, found
// with the violated condition's continuous indicator proposing the probes (docs/performance.md,
// "Session 30 (sim30)").
//
// The predicate decides every end: lo is a probe at which it holds no violation (or 0), hi one at
// which it does (or the given upper end, already found violated), and hi - lo <= width. The
// indicators (one per held condition: > 0 inside it, < 0 past it, NaN where there is none) only
// choose where to probe: regula falsi with the Illinois modification between the two ends'
// values of the condition violated at hi, never closer than width / 2 to an end, and halving
// instead whenever those values are missing or inconsistent with the predicate's answers, or the
// bracket did not halve over the last two probes. So the answer is a bracket of the predicate's
// change exactly as a bisection's, to the same width or tighter, with far fewer probes than a
// bisection's 50.
#pragma once

#include "core/thread_switch.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace hipair::simulation {

struct CutProbe {
  int kind = 0;               // 0: no condition violated; otherwise which kind (the caller's)
  std::size_t which = 0;      // the violated condition's contact (kind != 0)
  std::size_t indicator = 0;  // the violated condition's index in `margins` (kind != 0)
  std::vector<double> margins;  // every condition's indicator at the probe (NaN: none)

  double margin(std::size_t index) const {
    return index < margins.size() ? margins[index] : std::numeric_limits<double>::quiet_NaN();
  }
};

struct CutBracket {
  double lo = 0, hi = 0;
  CutProbe at_hi;             // the probe at hi (the violated condition the cut reports)
  int probes = 0;             // evaluations made (without the caller's at the upper end)
};

// How many probes the cut searches made on this thread (tests, profiling).
struct CutProbesTag;
inline std::size_t& cut_probes() { return thread_counter<CutProbesTag>(); }

// `probe(u)` evaluates the predicate at u; `upper` its answer at u = hi > 0 (violated, kind != 0).
// The search probes u = 0 first (its indicators start the interpolation); a violation there is
// bracketed by a probe at `width`: lo = 0 and hi = width when that one is violated too, as a
// bisection gives for a violation present all along.
template <class Probe>
CutBracket bracket_cut(double hi, const CutProbe& upper, double width, Probe probe) {
  CutBracket b;
  b.hi = hi;
  b.at_hi = upper;
  CutProbe at_lo = probe(0.0);
  ++b.probes;
  if (at_lo.kind != 0) {
    if (!(width < hi)) return b;
    CutProbe p = probe(width);
    ++b.probes;
    if (p.kind != 0) {
      b.hi = width;
      b.at_hi = std::move(p);
      return b;
    }
    b.lo = width;
    at_lo = std::move(p);
  }
  // ITP (interpolate, truncate, project; Oliveira and Takahashi 2020): the regula falsi point,
  // moved toward the midpoint by delta = kappa (hi - lo)^2 (so that both ends move), and kept
  // within r of the midpoint, r shrinking as a bisection would: not more than about
  // n_half + 1 probes (n_half: the bisection's halvings to the width), superlinear where the
  // indicator is smooth
  const double epsilon = 0.5 * width;
  const double kappa = 0.2 / (b.hi - b.lo);
  const int n_max = static_cast<int>(std::ceil(std::log2((b.hi - b.lo) / width))) + 1;
  for (int j = 0; b.hi - b.lo > width; ++j) {
    const double span = b.hi - b.lo;
    const double half = 0.5 * (b.lo + b.hi);
    double m = half;
    const double f_lo = at_lo.margin(b.at_hi.indicator);
    const double f_hi = b.at_hi.margin(b.at_hi.indicator);
    if (f_lo >= 0 && f_hi < 0 && std::isfinite(f_lo) && std::isfinite(f_hi)) {
      const double falsi = b.hi - f_hi * (span / (f_hi - f_lo));
      if (std::isfinite(falsi)) {
        const double sigma = half > falsi ? 1.0 : half < falsi ? -1.0 : 0.0;
        const double delta = std::max(kappa * span * span, 0.5 * width);
        const double truncated = delta <= std::abs(half - falsi) ? falsi + sigma * delta : half;
        const double r = std::ldexp(epsilon, n_max - j) - 0.5 * span;
        m = std::abs(truncated - half) <= r ? truncated : half - sigma * r;
      }
    }
    if (!(m > b.lo && m < b.hi)) m = half;
    if (!(m > b.lo && m < b.hi)) break;   // no double between the ends
    CutProbe p = probe(m);
    ++b.probes;
    if (p.kind != 0) {
      b.hi = m;
      b.at_hi = std::move(p);
    } else {
      b.lo = m;
      at_lo = std::move(p);
    }
  }
  return b;
}

}  // namespace hipair::simulation
