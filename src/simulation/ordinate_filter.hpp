// The ordinate test of a held contact on a vertical C-space edge in doubles first
// (simulation.cpp, Simulation::Impl::on_vertical_edge): whether the contact's chart ordinate ty
// lies beyond an end vertex of the edge starts with the rational comparisons of ty with the
// vertex's isolating interval [y_lower, y_upper]. With doubles lo <= y_lower and y_upper <= hi
// (double_below, double_above: rounded toward the outside, exactly), ty < lo proves ty < y_lower
// and ty > hi proves ty > y_upper — a double is a rational — so those answers are the rational
// comparisons' without making the rational; inside [lo, hi] the rational comparisons (and the
// exact compare_ordinate) decide as before.
//
// Switch simulation::ordinate_filter() (on by default; tests turn it off on their thread to
// compare, SimulationOrdinateFilter.*); counter ordinate_filter_decided().
#pragma once

#include "core/thread_switch.hpp"

#include <hipair/rational.hpp>

#include <cmath>
#include <cstddef>
#include <limits>

namespace hipair::simulation {

struct OrdinateFilterTag;
inline bool& ordinate_filter() { return thread_switch<OrdinateFilterTag>(); }
// How many vertex comparisons the doubles decided (tests, profiling).
struct OrdinateFilterDecidedTag;
inline std::size_t& ordinate_filter_decided() { return thread_counter<OrdinateFilterDecidedTag>(); }

// A double <= r: the largest (in the normal range; -infinity or the largest double beyond it).
inline double double_below(const Rational& r) {
  double d = r.get_d();
  if (std::isinf(d)) return d > 0 ? std::numeric_limits<double>::max() : d;
  if (Rational(d) > r) d = std::nextafter(d, -std::numeric_limits<double>::infinity());
  return d;
}

// A double >= r: the smallest (in the normal range; +infinity or the lowest double beyond it).
inline double double_above(const Rational& r) {
  double d = r.get_d();
  if (std::isinf(d)) return d < 0 ? std::numeric_limits<double>::lowest() : d;
  if (Rational(d) < r) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

}  // namespace hipair::simulation
