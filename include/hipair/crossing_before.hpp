// HIPAIR — the certified first-crossing query for a caller that needs a crossing only when it
// comes no later than a known parameter (the simulator: once one pair's motion is known to
// reach contact space at u in [u_lower, u_upper], another pair's crossing matters only where its
// bracket could start at or before that u_upper; a later one is discarded by the step).
//
// first_crossing_before runs CSpace::first_crossing's own query — the same start, the same
// subdivision tree in the same (path) order, the same exclusions — and stops at the first
// stretch [a, b] the subdivision would evaluate with a > u_stop. Why the answers are the query's:
// the subdivision evaluates its stretches in path order, and a stretch is evaluated only after
// every stretch before it was excluded (certified in the starting free cell) or subdivided, and
// the query returns at the first stretch within the resolution that may meet a contact curve or
// leave the built space. So:
//   - not stopped: every step taken was first_crossing's, and so is the answer (bit for bit);
//   - stopped at a: the motion is certified in its starting free cell on [u_begin, a], and
//     first_crossing's answer is `none`, or a crossing (or outside_region) whose u_lower is the
//     start of a later stretch, so u_lower >= a > u_stop.
// A query that stops leaves no start anchor (first_crossing remembers one after a motion that
// stays free to u_end; anchors only spare later point locations their exact work).
//
// CrossingQuery is the same query as an object that can be stopped and resumed: it takes the
// query's steps one at a time (the start's point query, then one stretch of the subdivision
// each), tells the start a of the next stretch, and goes on from where it stopped. Run to the
// end it has taken first_crossing's every step in first_crossing's order and gives its answer bit
// for bit, however often it was stopped on the way (the stretches left on its stack are exactly
// those the uninterrupted query would evaluate next). The simulator runs its free pairs' queries
// side by side this way, always the one whose next stretch starts first
// (src/simulation/crossing_sweep.hpp).
#pragma once

#include <hipair/cspace.hpp>

#include <cstddef>
#include <memory>

namespace hipair {

/// What first_crossing_before found.
struct CrossingBefore {
  /// stopped == false: first_crossing's answer. stopped == true: status none, and
  /// u_lower == u_upper == the stretch start a > u_stop where the query stopped; the motion is in
  /// its starting free cell on [u_begin, a] (first_crossing's u_lower, if any, is >= a).
  MotionCrossing crossing;
  bool stopped = false;
};

/// CSpace::first_crossing's query, one step at a time (see above). The space must outlive it.
class CrossingQuery {
 public:
  /// Checks the path as first_crossing does (the same throws); evaluates nothing yet.
  CrossingQuery(const CSpace& space, const MotionPath& path, const CrossingOptions& options);
  CrossingQuery(CrossingQuery&&) noexcept;
  CrossingQuery& operator=(CrossingQuery&&) noexcept;
  ~CrossingQuery();

  /// The answer is known (first_crossing's).
  bool finished() const;
  /// Where the query goes on: u_begin before the start's point query, then the start a of the
  /// next stretch its subdivision evaluates; the motion is certified in its starting free cell on
  /// [u_begin, next()] once the start is done. Finished: the answer's u_lower.
  const Rational& next() const;
  /// One step: the start's point query, or one stretch (excluded, split or answered); nothing
  /// once finished.
  void step();
  /// Steps until finished or, with `stop` and the start done, next() > *stop.
  void run(const Rational* stop = nullptr);
  /// Finished: first_crossing's answer. Not finished (after the start): status none,
  /// u_lower == u_upper == next(), the starting cell (first_crossing's u_lower, if any, >= next()).
  MotionCrossing answer() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// While one lives on a thread, the first-crossing answers made there (CSpace::first_crossing,
/// CrossingQuery, first_crossing_before) are status-only: the same status, grazing, u_lower,
/// u_upper, cell_left and cell_entered as without it (the query takes the same steps), but the
/// description of a contact — features, chart, chart_point, point, normal, and the edge where
/// only the description would name it — is not made. For a caller that asks only whether a
/// configuration is free (the simulator's nudge). Scopes nest; each restores what it found.
class StatusOnlyCrossings {
 public:
  StatusOnlyCrossings();
  ~StatusOnlyCrossings();
  StatusOnlyCrossings(const StatusOnlyCrossings&) = delete;
  StatusOnlyCrossings& operator=(const StatusOnlyCrossings&) = delete;

 private:
  bool previous_;
};
/// Whether a StatusOnlyCrossings scope is open on this thread.
bool status_only_crossings();
/// How many descriptions status-only answers skipped on this thread (tests).
std::size_t& skipped_descriptions();

/// CSpace::first_crossing(path, options), stopped where its subdivision passes u_stop (see above).
CrossingBefore first_crossing_before(const CSpace& space, const MotionPath& path, const CrossingOptions& options,
                                     const Rational& u_stop);

}  // namespace hipair
