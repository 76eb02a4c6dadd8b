// HIPAIR — exact order of the slice points of the nominal C-space (AlgebraicNumber) against
// each other and against rationals, for the tolerance analysis' decisions: which slice point
// holds the follower (sample matching) and whether a slice has a free interval inside a channel
// (the jamming threshold's exact confirmation). No double is on these decision paths: the
// isolating intervals are refined by exact bisection (GMP) and equality of two irrational
// numbers is decided by the gcd of their polynomials.
#pragma once

#include "core/thread_switch.hpp"

#include <hipair/cspace.hpp>
#include <hipair/rational.hpp>

#include <optional>
#include <vector>

namespace hipair::tolerance_detail {

/// Sign of `polynomial` (ascending powers) at x, exact.
int sign_at(const std::vector<mpz_class>& polynomial, const Rational& x);
/// Sign of a - x, exact.
int compare(const AlgebraicNumber& a, const Rational& x);
/// Sign of a - b, exact.
int compare(const AlgebraicNumber& a, const AlgebraicNumber& b);

/// The same angle in the other half-turn chart: -1 / a (tan((theta - pi) / 2) = -1 / tan(theta / 2)),
/// exact: the polynomial's coefficients reversed with alternating signs and the isolating
/// interval refined by exact bisection until it excludes 0, then mapped by -1 / x (increasing on
/// either side of 0). nullopt when a = 0 (the angle is the other chart's infinity).
std::optional<AlgebraicNumber> other_half_turn(const AlgebraicNumber& a);
/// The rational x as an exact AlgebraicNumber (the degree-1 polynomial q x - p of x = p / q).
AlgebraicNumber exact_algebraic(const Rational& x);

/// Where a follower coordinate t lies among the ordered points of a slice (exact):
/// `below` points are < t; `at` is the point equal to t or, when `in_contact`, the neighbour
/// of t nearest to it (decided by exact rational enclosures of the two distances; a tie, which
/// exact refinement cannot break, leaves `at` empty and `ambiguous` set).
struct PointMatch {
  std::size_t below = 0;
  std::optional<std::size_t> at;
  bool ambiguous = false;
};
PointMatch match_point(const std::vector<Slice::Point>& points, const Rational& t, bool in_contact);

/// The indices (into slice.intervals) of the free intervals of `slice` that meet the open
/// channel (lower, upper), decided exactly (an interval (a, b) meets it when b > lower and
/// a < upper); a null side is unbounded.
std::vector<std::size_t> free_intervals_meeting(const Slice& slice, const AlgebraicNumber* lower,
                                                const AlgebraicNumber* upper);
/// The number of free intervals of `slice` that meet the open channel (lower, upper).
std::size_t free_intervals_in_channel(const Slice& slice, const AlgebraicNumber& lower, const AlgebraicNumber& upper);

/// Per-thread switch (core/thread_switch.hpp) of the exact confirmations of a pair of at most
/// 120 boundary edges (the jamming threshold's, its bracket's, the contact changes'): on, an
/// exact C-space built at the witness and sliced; off, the pair's exact kernel slices at the
/// witness (hipair::KernelSlicer), as a large pair's always are. Tests turn it off to compare
/// the two answers on pairs small enough to build whole.
struct WholeSpaceConfirmationsTag;
inline bool& whole_space_confirmations_switch() { return thread_switch<WholeSpaceConfirmationsTag>(); }
/// Turns the switch off on this thread for its lifetime (the kernel slices' confirmations) and
/// restores the value it found, also when the scope is left by an exception or a failed
/// ASSERT_* (session 63: the tests set and reset the switch by hand, and a test failing between
/// the two left it off for every later test of the thread).
class KernelSliceConfirmationsScope {
 public:
  KernelSliceConfirmationsScope() : previous_(whole_space_confirmations_switch()) {
    whole_space_confirmations_switch() = false;
  }
  ~KernelSliceConfirmationsScope() { whole_space_confirmations_switch() = previous_; }
  KernelSliceConfirmationsScope(const KernelSliceConfirmationsScope&) = delete;
  KernelSliceConfirmationsScope& operator=(const KernelSliceConfirmationsScope&) = delete;

 private:
  bool previous_;
};

}  // namespace hipair::tolerance_detail
