#pragma once

// Exact bounds held without GMP rationals where they can be, and the subdivision's stack of
// stretches with its rationals reused: first_crossing's stretches (cspace_queries.cpp) compare
// their pieces' and boxes' bounds with the charts' sides thousands of times per query, and made
// four GMP rationals per piece and per box, and four per stretch pushed and popped, for it.

#include "core/thread_switch.hpp"

#include <hipair/rational.hpp>

#include <gmp.h>

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

namespace hipair::cspace {

// The lazy bounds below (ExactBound's doubles and borrowed sides) and StretchStack's kept slots.
// On by default; off on a thread, every bound is made an owned rational at once and every
// stretch pushed gets a new slot, as first_crossing did before them (tests compare the answers:
// CSpaceExactBound.*).
struct LazyBoundsTag;
inline bool& lazy_bounds() { return thread_switch<LazyBoundsTag>(); }

// A crossing query's working storage kept per thread between queries (cspace_queries.cpp,
// CrossingRun::Kept: the canonical path, the stretch stack's slots, the step's rationals; and
// CrossingQuery's state block): the next query on the thread takes them instead of allocating
// them again. On by default; off on a thread, every query makes and frees its own, as before
// session 50 (tests compare the answers: CSpaceKeptRuns.*). The counters count the queries on
// this thread that took kept storage and kept state blocks.
struct KeptRunsTag;
inline bool& kept_runs() { return thread_switch<KeptRunsTag>(); }
struct KeptRunReusesTag;
inline std::size_t& kept_run_reuses() { return thread_counter<KeptRunReusesTag>(); }
struct KeptBlockReusesTag;
inline std::size_t& kept_block_reuses() { return thread_counter<KeptBlockReusesTag>(); }

// An exact bound of a stretch's piece or box, held without a GMP rational where it can be:
// a finite double (the number is exactly that double: the filtered pieces' bounds), a rational
// owned, or a rational borrowed from the space (a chart's side, which outlives the scanner and
// its evaluations). The double's rational is made only when asked for (rational()): the
// subdivision's stretches compare their bounds with the charts' sides exactly (compare(), no
// allocation) and need the rationals only at an answer, a located point or an anchor.
class ExactBound {
 public:
  ExactBound() = default;   // the double 0
  ExactBound(Rational r) : owned_(std::move(r)) {}   // NOLINT: a rational is an exact bound
  static ExactBound of_double(double d) {   // \pre d finite
    if (!lazy_bounds()) return ExactBound(Rational(d));
    ExactBound b;
    b.double_ = d;
    return b;
  }
  static ExactBound borrowed(const Rational& r) {
    if (!lazy_bounds()) return ExactBound(r);
    ExactBound b;
    b.borrowed_ = &r;
    return b;
  }
  // the rational held, or nullptr for a double
  const Rational* exact() const { return owned_ ? &*owned_ : borrowed_; }
  double as_double() const { return double_; }   // \pre exact() == nullptr
  Rational rational() const {
    if (const Rational* r = exact()) return *r;
    return Rational(double_);
  }
  // the same number without a copy: the rational held, or the double written into `scratch`
  // (a caller's kept rational: its limbs reused)
  const Rational& rational(Rational& scratch) const {
    if (const Rational* r = exact()) return *r;
    scratch = double_;
    return scratch;
  }

 private:
  double double_ = 0;
  const Rational* borrowed_ = nullptr;
  std::optional<Rational> owned_;
};

// sign of a - b, exactly; a double is compared through a per-thread scratch rational
inline int compare(const ExactBound& a, const Rational& b) {
  if (const Rational* r = a.exact()) return cmp(*r, b);
  thread_local Rational scratch;
  mpq_set_d(scratch.get_mpq_t(), a.as_double());
  return cmp(scratch, b);
}
inline int compare(const ExactBound& a, const ExactBound& b) {
  if (const Rational* r = b.exact()) return compare(a, *r);
  if (!a.exact()) return a.as_double() < b.as_double() ? -1 : a.as_double() > b.as_double() ? 1 : 0;
  return -compare(b, *a.exact());
}
inline bool operator<(const Rational& a, const ExactBound& b) { return compare(b, a) > 0; }
inline bool operator>(const Rational& a, const ExactBound& b) { return compare(b, a) < 0; }
inline bool operator>(const ExactBound& a, const ExactBound& b) { return compare(a, b) > 0; }
inline bool operator==(const ExactBound& a, const ExactBound& b) { return compare(a, b) == 0; }

// A chart's side (a rational of the space) with doubles lo <= r <= hi: a double bound outside
// [lo, hi] is compared without the rational.
struct Side {
  const Rational& r;
  double lo, hi;
};
inline int compare(const ExactBound& a, const Side& b) {
  if (!a.exact()) {
    if (a.as_double() < b.lo) return -1;
    if (a.as_double() > b.hi) return 1;
  }
  return compare(a, b.r);
}
inline bool operator<(const ExactBound& a, const Side& b) { return compare(a, b) < 0; }
inline bool operator>(const ExactBound& a, const Side& b) { return compare(a, b) > 0; }
inline bool operator<=(const ExactBound& a, const Side& b) { return compare(a, b) <= 0; }
inline bool operator>=(const ExactBound& a, const Side& b) { return compare(a, b) >= 0; }

// std::max(p, side) and std::min(p, side) with the side borrowed, not copied
inline ExactBound max_with(const ExactBound& p, const Side& side) { return p < side ? ExactBound::borrowed(side.r) : p; }
inline ExactBound min_with(const ExactBound& p, const Side& side) { return p > side ? ExactBound::borrowed(side.r) : p; }

// The subdivision's stack of stretches [a, b]. A popped slot is kept, and the next push copies
// into it (mpq_set reuses its limbs): the halving pushes and pops thousands of stretches, which
// would otherwise allocate and free four GMP integers each. Slots in a deque: never moved.
class StretchStack {
 public:
  bool empty() const { return size_ == 0; }
  const std::pair<Rational, Rational>& back() const { return slots_[size_ - 1]; }
  void pop_back() {
    --size_;
    if (!lazy_bounds()) slots_.resize(size_);   // switched off: no slot kept, every push a new one
  }
  // empty again (a kept stack taken by the next query: its slots kept, none of them on the stack)
  void clear() {
    size_ = 0;
    if (!lazy_bounds()) slots_.clear();
  }
  void emplace_back(const Rational& a, const Rational& b) {
    if (size_ == slots_.size()) slots_.emplace_back();
    slots_[size_].first = a;
    slots_[size_].second = b;
    ++size_;
  }

 private:
  std::deque<std::pair<Rational, Rational>> slots_;
  std::size_t size_ = 0;
};

}  // namespace hipair::cspace
