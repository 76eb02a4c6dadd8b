// The follower of one pair of an assembly chain over a box of parameters when a feature pair
// other than the one holding it at nominal may take over inside the box (another tooth pair of
// a gear mesh near a hand-over): the envelope over every candidate feature pair, candidates
// that certainly cannot hold the follower beyond the holder's enclosure excluded by certified
// tests (docs/tolerance.md "Assembly chains", step 4, "Hand-overs"; chain.cpp). Internal to
// src/tolerance/.
#pragma once

#include "tolerance/mean_value.hpp"
#include "tolerance/solver.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace hipair::tolerance_detail {

/// The envelope of one pair's follower over a box (chart units).
struct HandoverEnvelope {
  bool bounded = false;      ///< false: no enclosure (why says why); the band is then unbounded
  Interval chart;            ///< the holder's enclosure widened in the direction the follower is pushed
  bool extended = false;     ///< a feature pair other than the holder may hold the follower beyond it
  /// The side the follower is pushed to (the holder's F_v sign over the box, +1 or -1; 0 when
  /// not computed): for every parameter vector the follower is on this side of the holder's
  /// root, by at most the chart's extent beyond the holder's enclosure (chain.cpp uses it to
  /// carry the mean-value composition through a widened pair).
  int side = 0;
  std::size_t candidates = 0;   ///< feature pairs whose edges may meet in the window
  std::size_t occupying = 0;    ///< of which found possibly pushing in a leaf the walk passed
  std::string why;
};

/// Over a leaf y of the window where F_v is certainly of sign `sigma` (F increasing towards the
/// sigma side for each parameter vector and driver value): F has no zero in y when it is
/// certainly positive at y's -sigma end or certainly negative at its sigma end. `sign_at(v)`:
/// F's certain sign at the point v over the box (0 when not certain).
template <typename SignAt>
bool monotone_without_zero(int sigma, const Interval& y, SignAt&& sign_at) {
  double near = sigma > 0 ? y.lo : y.hi, far = sigma > 0 ? y.hi : y.lo;
  return sign_at(near) > 0 || sign_at(far) < 0;
}

/// The envelope's walk (handover.cpp, step 3) over `window` (of chart units, beyond the
/// holder's enclosure on its sigma side, `start` its near end): from E = start, the leaf
/// [E, E + h] (sigma-wards; h from `coarse` halved up to `levels` times) in which no candidate
/// may push (`may_push(i, leaf)` false for every i < `candidates`) ends the walk at E; a leaf
/// of the finest size where one may push moves E to its far end. The candidate found pushing
/// last is tried first.
struct WindowWalk {
  bool bounded = false;          ///< a free leaf was found before E reached the window's far end
  double edge = 0;               ///< E: the follower's bound on the sigma side
  std::size_t last = 0;          ///< the candidate found pushing last (`candidates`: none)
  std::vector<char> occupying;   ///< per candidate: found pushing in a finest leaf the walk passed
};
template <typename MayPush>
WindowWalk walk_window(double start, const Interval& window, int sigma, double coarse, int levels,
                       std::size_t candidates, MayPush&& may_push) {
  WindowWalk out;
  out.occupying.assign(candidates, 0);
  out.last = candidates;
  auto leaf = [&](double from, double h) {
    double to = sigma > 0 ? std::min(from + h, window.hi) : std::max(from - h, window.lo);
    return sigma > 0 ? Interval(from, std::max(from, to)) : Interval(std::min(from, to), from);
  };
  auto free_leaf = [&](const Interval& y) {
    if (out.last < candidates && may_push(out.last, y)) return false;
    for (std::size_t i = 0; i < candidates; ++i)
      if (i != out.last && may_push(i, y)) {
        out.last = i;
        return false;
      }
    return true;
  };
  out.edge = start;
  int level = 0;
  while (true) {
    double h = coarse;
    for (int i = 0; i < level; ++i) h *= 0.5;
    Interval y = leaf(out.edge, h);
    if (free_leaf(y)) {
      out.bounded = true;
      break;
    }
    if (level < levels) {
      ++level;
      continue;
    }
    out.occupying[out.last] = 1;
    double next = sigma > 0 ? y.hi : y.lo;
    if (next == out.edge || next == (sigma > 0 ? window.hi : window.lo)) break;
    out.edge = next;
  }
  return out;
}

/// The pair's driver (chart units) over the box as the previous pair's mean-value form carried
/// through the chart change (chain.cpp compose_over): for every parameter vector p of the box,
///   t(p) in value + sum_i gradient_i (p_i - c_i),   c the box's centre (box_offsets),
/// the product gradient_i (p_i - c_i) an interval times a number. Given to the envelope's walk,
/// it keeps the correlation of the driver with the parameters the pair's own geometry depends
/// on (an idler's tooth phase turns its body back by what it turns its teeth: the driver and
/// the contact function move together), where an interval driver would let them vary apart.
struct DriverForm {
  Interval value;
  std::vector<Interval> gradient;   ///< per parameter of the box
};

/// A DriverForm split for the Taylor models of the walk: with xi_b = (p_q - c_q) / h_q for the
/// b-th variable (q = parameter_of[b], c_q and h_q TaylorModel1::over's centre and half width
/// over the box: p_q - c_q in h_q [-1, 1]), for every p of the box some l in `lumped` has
///   t(p) in l + sum_b coefficients_b xi_b(p),
/// coefficients_b = gradient_q h_q, lumped = value + sum over the other parameters of
/// gradient_i [B_i - c_i] (those the pair's geometry does not depend on: their effect on t is
/// independent of everything else the contact function sees).
struct DriverSplit {
  std::vector<Interval> coefficients;
  Interval lumped;
};
inline DriverSplit split_driver(const DriverForm& form, const Box& box, const std::vector<std::size_t>& parameter_of) {
  std::vector<double> center;
  std::vector<Interval> offsets;
  box_offsets(box, center, offsets);
  std::vector<char> variable(offsets.size(), 0);
  DriverSplit out;
  for (std::size_t q : parameter_of) {
    variable.at(q) = 1;
    double h = TaylorModel1::over(box.lo[q], box.hi[q], 0).coefficients[0].hi;
    out.coefficients.push_back(form.gradient.at(q) * Interval::point(h));
  }
  out.lumped = form.value;
  for (std::size_t i = 0; i < offsets.size(); ++i)
    if (!variable[i] && !(offsets[i].lo == 0.0 && offsets[i].hi == 0.0)) out.lumped = out.lumped + form.gradient.at(i) * offsets[i];
  return out;
}

/// Tests only (session 47): 1 (unless changed) lets the envelope take the driver-monotone route
/// (handover.cpp, step 5) where its walk over the driver's whole range is not bounded; 0 leaves
/// it out (the envelopes of session 46).
int& handover_monotone_driver();

/// Tests only (session 47, tol47c): 1 (unless changed) anchors the walk of a box away from the
/// nominal vector (handover.cpp, 0b); 0 walks it as before (unsound: a mutant for tests).
int& handover_sub_box_anchor();

/// Tests and measurements only (session 48): 1 (unless changed) meets an undecided partial
/// derivative of a contact function (F_v, F_t) with its Taylor-model jet's (handover.cpp,
/// partials_of); 0 uses the interval jets' alone, as before (sound, wider).
int& handover_taylor_partials();

/// Session 49: the envelope's walk goes on beyond its window over this many windows' widths in
/// all (handover.cpp, step 6) where neither the walk nor the driver-monotone route bounded it;
/// 1: not at all (the envelopes of session 48).
int& handover_far_windows();

/// Session 52: where the envelope is still not bounded after the far walk (handover.cpp, step 7),
/// the driver's range is split into 4, 8, ... up to this many pieces walked outward from the one
/// holding the nominal driver; 1: not at all (the envelopes of session 51).
int& handover_driver_pieces();

/// A switch on this thread while an instance lives (one per Tag; instances nest).
template <class Tag>
class ThreadScope {
 public:
  ThreadScope() { ++count; }
  ~ThreadScope() { --count; }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;
  static bool on() { return count > 0; }

 private:
  static inline thread_local int count = 0;
};

/// While one lives on this thread, the envelope's walk may go on beyond its window
/// (handover.cpp, step 6): chain.cpp composes a position whose band is unbounded without it again
/// under one.
using FarWalk = ThreadScope<struct FarWalkTag>;

/// While one lives on this thread (with a FarWalk), the envelope may walk its driver's range in
/// pieces (handover.cpp, step 7): chain.cpp composes a position whose band is unbounded even with
/// the far walk once more under one.
using DriverPieces = ThreadScope<struct DriverPiecesTag>;

/// Session 55: 1 (unless changed) lets the pass of the driver's pieces also walk in pieces an
/// envelope that steps 0-6 bounded only widened (handover.cpp, step 7b; the envelope is then the
/// meet of the two); 0: only unbounded envelopes are walked in pieces (the envelopes of session 54).
int& handover_widened_pieces();

/// Tests and measurements only (session 54): 1 (unless changed) lets a position's driver-pieces
/// pass replay the far-walk pass's envelopes (EnvelopeMemo); 0 walks them again, as before.
int& handover_far_reuse();

/// How many envelopes were replayed from an EnvelopeMemo (tests and measurements).
std::atomic<std::size_t>& handover_envelopes_reused();

class HandoverSearch;

/// The composition's own envelopes (HandoverSearch::envelope at depth 1) walked while a FarWalk
/// lives, kept per position for its later passes (session 54; chain.cpp `position_band`). A pass
/// with the driver's pieces (step 7) first does steps 0-6, which are those of the far walk's pass
/// for the same arguments (a pure function of them: the memos they read hold pure functions of
/// their keys, and step 7 runs only at depth 1, after them), so their result, the sub-boxes they
/// counted and what step 7 needs (the holder's free side, whether it applies) are kept here and
/// replayed; step 7 alone is then walked. One per position, on the thread composing it (Scope).
class EnvelopeMemo {
 public:
  /// Steps 0-6's outcome for one call.
  struct Entry {
    HandoverEnvelope result;
    std::size_t boxes = 0;   ///< what the steps added to the caller's sub-box count
    int sigma = 0;           ///< the holder's free side (0: not certain, or not reached)
    bool pieces = false;     ///< unbounded where step 7 applies (the box and driver's range allow it)
    bool widened = false;    ///< bounded but widened (extended) where step 7 applies: 7b may narrow it
  };
  /// Every argument of the call, bit for bit (doubles by their bits: no NaN ordering), and its search.
  using Key = std::tuple<const HandoverSearch*, std::vector<std::uint64_t>, Rational>;

  const Entry* find(const Key& key) const {
    auto it = entries_.find(key);
    return it == entries_.end() ? nullptr : &it->second;
  }
  const Entry* store(Key key, Entry entry) { return &entries_.insert_or_assign(std::move(key), std::move(entry)).first->second; }
  std::size_t size() const { return entries_.size(); }

  /// While one lives, this thread's envelopes at depth 1 under a FarWalk use `memo`.
  class Scope {
   public:
    explicit Scope(EnvelopeMemo& memo) : previous_(current_) { current_ = &memo; }
    ~Scope() { current_ = previous_; }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    static EnvelopeMemo* current() { return current_; }

   private:
    EnvelopeMemo* previous_;
    static inline thread_local EnvelopeMemo* current_ = nullptr;
  };

 private:
  std::map<Key, Entry> entries_;
};

/// The candidates' search for one pair of the chain (one per pair: its parts are fixed).
class HandoverSearch {
 public:
  HandoverSearch(std::shared_ptr<const CurveSolver> solver, std::size_t fixed_part, std::size_t free_part);

  /// `curve` is the holding feature pair's (its fixed_range the driver's range when it ranges),
  /// `holder` the certified enclosure of its root over `box` (chart units). The feature pairs
  /// of the two parts whose edges may meet with the follower in the window beyond `holder`, in
  /// the direction the follower is free to move (the holder's F_v sign), are the candidates;
  /// the envelope ends at the first leaf of the window (from the holder's enclosure on) where
  /// every candidate is certainly unable to hold the follower (no zero of its contact function
  /// there, only zeros where the follower's free side is the other one, or only zeros off its
  /// features). Unbounded when the holder's free side is not certain or no such leaf is found
  /// in the window. Candidates' roots are enclosed by CurveSolver::certified_range (with
  /// `relative_accuracy`, `absolute_accuracy`; its sub-boxes counted in `boxes`). `side`: the
  /// holder's free side when the caller has proven it (F_v's sign, certain over box x the
  /// driver's range x `holder`: CurveSolver::root_partials), 0 to have it computed here.
  /// `driver`: the driver's chart coordinate as a form in the parameters (null: an interval,
  /// its fixed_range, independent of the parameters); the walk's exclusions then hold over
  /// the box with the driver given by the form, its range still met with fixed_range.
  HandoverEnvelope envelope(const CurveSlice& curve, const Box& box, const Interval& holder,
                            double relative_accuracy, double absolute_accuracy, std::size_t& boxes,
                            int side = 0, const DriverForm* driver = nullptr,
                            bool monotone = true,
                            double nominal_free = std::numeric_limits<double>::quiet_NaN()) const;

  /// `monotone` (session 47): where the walk over box x T is not bounded, the envelope may be
  /// found through the follower's monotonicity in its driver (handover.cpp, step 5; false in
  /// the route's own walks).
  /// `nominal_free` (session 47, tol47c): the holder's root at the nominal vector and driver
  /// (chart units). A box away from the nominal vector needs it: its walk is anchored by a walk
  /// from the nominal configuration to the box (handover.cpp, 0b); without it, no envelope there.
  /// Off under `--assume-nominal-contact` (ToleranceOptions::chain_assume_nominal_holder,
  /// chain.cpp): the holder's enclosure returned as the envelope, as before session 25.
  void set_disabled(bool disabled) { disabled_ = disabled; }

 private:
  /// envelope's steps 0-6 (all but the driver's pieces); `entry` receives the free side and
  /// whether step 7 applies where the result is unbounded.
  HandoverEnvelope walk_steps(const CurveSlice& curve, const Box& box, const Interval& holder,
                              double relative_accuracy, double absolute_accuracy, std::size_t& boxes, int side,
                              const DriverForm* driver, bool monotone, double nominal_free,
                              EnvelopeMemo::Entry& entry) const;
  /// Step 7 (session 52): the envelope's sigma end over box x T walked in pieces of T (none: not
  /// bounded so).
  std::optional<double> driver_pieces(const CurveSlice& curve, const Box& box, const Interval& holder, int sigma,
                                      double relative_accuracy, double absolute_accuracy, std::size_t& boxes,
                                      double nominal_free) const;

  struct BoxParts;
  std::shared_ptr<const BoxParts> box_parts(const Box& box) const;

  std::shared_ptr<const CurveSolver> solver_;
  std::size_t fixed_part_, free_part_;
  bool disabled_ = false;
  mutable std::mutex mutex_;
  mutable std::map<std::vector<double>, std::shared_ptr<const BoxParts>> memo_;
  /// memo_'s bound (cleared when full): every edge of both parts as Taylor models over a box is
  /// large, and the walk reuses a box's parts within one composition (its sub-boxes'), not across
  /// positions; 256 before session 43 (docs/performance.md "Session 43 (tol43)": the chain's
  /// memos held most of the full turn's 2.9 GB).
  static constexpr std::size_t max_box_parts = 32;
};

}  // namespace hipair::tolerance_detail
