#pragma once

// The step's crossing queries, side by side (simulation.cpp, Simulation::Impl::step; the query
// is hipair/crossing_before.hpp's CrossingQuery; switch simulation::crossing_limits()).
//
// After every pair's start (its point query, never stopped), the queries advance one stretch at
// a time, always the one whose next stretch starts first (the first such in pair order), until
// every query has its answer or, once a crossing (or start in contact) is known, the next
// stretch of every query left starts past the limit: by default the u_upper's double, exactly as
// a rational, of the earliest bracket found so far (the smallest lower's double, the first in
// finding order). A query stopped at a stretch start a is certified free on [u_begin, a]; its own
// crossing (or exit from the built space), if any, has u_lower >= a.
//
// Then the step's earliest crossing (u_hit, u_hit_upper: the first strict minimum of the lower
// doubles in pair order, as the step takes it from complete answers, a start in contact at 0)
// is taken from the finished answers, and every stopped query whose a's double is not above
// u_hit_upper is resumed to its end — the steps first_crossing would take next, so its answer —,
// again until no stopped query is left within reach (a resumed crossing can be the earliest and
// move u_hit_upper). A query still stopped would have a crossing whose lower double is >= a's
// > u_hit_upper >= u_hit: never the earliest, never simultaneous (the step takes brackets whose
// lower double is <= u_hit_upper), and an exit from the built space there never before u_hit (a
// stopped query exists only once a crossing was found). So the step, which treats a stopped pair
// as free, takes the same crossings, rows and ends as with every query complete. The limit only
// decides the cost: any limit is sound because of the resumption (tests pass other limits to
// reach the resumption, which the default limit leaves to sub-ulp coincidences).

#include <hipair/cspace.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace hipair::simulation {

struct SweptCrossings {
  /// Per pair: first_crossing's answer, or (stopped) none at the stretch start a where the
  /// query stopped; a default answer for a pair not asked.
  std::vector<MotionCrossing> answers;
  std::vector<char> stopped;        ///< the query stopped (and was not resumed)
  std::size_t limited = 0;          ///< queries stopped at the limit before the resumption
  std::size_t resumed = 0;          ///< of those, resumed to their end
};

/// The limit from the earliest bracket found so far, in doubles: default Rational(upper).
using CrossingLimitRule = std::function<Rational(double lower, double upper)>;

/// The queries of spaces[i] (null: not asked) along paths[i], side by side with the limit (see
/// above); u_end is the step's end in path parameter (the initial u_hit, as the step's).
SweptCrossings sweep_crossings(const std::vector<const CSpace*>& spaces, const std::vector<MotionPath>& paths,
                               const CrossingOptions& options, double u_end,
                               const CrossingLimitRule& limit_rule = nullptr);

}  // namespace hipair::simulation
