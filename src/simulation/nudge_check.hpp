#pragma once

// The certified move of a nudge off contact (simulation.cpp, Simulation::Impl::nudge_free;
// docs/simulation.md, "Session 34"). A configuration computed in doubles on a contact curve
// lies on either side of it by rounding; the nudge moves it along a fixed direction by trials
// start + first (2^k - 1) dir (first = 4 eps max(1, |q|)) until the exact point query of every
// pair it moves says free. Until session 34 only that end point was checked: a trial far out
// (up to about 1 rad) could lie beyond a thin tooth or a whole blocked cell the straight move
// jumps over (a missed contact).
//
// Now the move is certified per pair it moves: the reversed straight segment trial -> start,
// with exact rational end points, is asked of the certified first-crossing query. It is in the
// trial's free cell on [0, u_lower); the rest, (1 - u_lower) of the move next to the start, must
// lie within the allowance of the start, nudge_allowance x first (the contact the move leaves:
// the rounding of a configuration on it), or, for a start deeper inside blocked space, in one
// blocked cell between the allowances of the start and of the crossing (a blocked walk). A
// move no longer than the allowance is the rounding itself and is not asked. Otherwise the move
// crosses blocked space or a free cell on the way (a tooth, a sliver): the nudge reports a jam
// instead of accepting it.
//
// Switch simulation::nudge_check() (on by default; tests turn it off on their thread to see
// main's unchecked nudge); counter certified_nudges() (queries asked).

#include "core/thread_switch.hpp"

#include <hipair/blocked_walk.hpp>
#include <hipair/cspace.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hipair::simulation {

struct NudgeCheckTag;
inline bool& nudge_check() { return thread_switch<NudgeCheckTag>(); }

// The nudge's point queries (nudge_free's free_at) read only the answer's status and grazing
// flag: they are asked in a StatusOnlyCrossings scope (hipair/crossing_before.hpp), which skips
// the contact's description (features, chart point, frame). Switch status_only_nudges() (on by
// default; SimulationStatusOnlyNudges.* compares the runs with it off).
struct StatusOnlyNudgesTag;
inline bool& status_only_nudges() { return thread_switch<StatusOnlyNudgesTag>(); }
struct CertifiedNudgesTag;
inline std::size_t& certified_nudges() { return thread_counter<CertifiedNudgesTag>(); }

// The allowance, in units of the first trial's displacement: a move may pass through anything
// within 2^16 first (about 5.8e-11 of the coordinates' scale) of its start. Session 34 had 2^10
// (9.1e-13): the lever of cam-follower-lever.json at 0.152236 s starts 4.6e-12 rad inside, where
// no walk can be placed (the carriers' interval evaluation there still holds zero), and its run
// stopped with a jam; 2^16 is still far below the integration's accuracy (1e-9).
inline constexpr double nudge_allowance = 65536;

/// Whether the straight move whose reversed path is `back` (u = 0 at the accepted trial, free
/// for the pair; u = 1 at the start), `length` long in the nudge's max-norm, stays in the trial's
/// free cell except within `allowance` (same norm) of the start, or, beyond it, in one blocked
/// cell up to within `allowance` of where it enters the trial's cell (see above). `length` <=
/// `allowance`: true without a query. The crossing is bracketed to a quarter of the allowance
/// (crossing_bits at most): the stretch near it left to the allowance is then at most 5/4 of it.
inline bool move_certified(const CSpace& space, const MotionPath& back, double length, double allowance,
                           unsigned crossing_bits) {
  if (length <= allowance) return true;
  // the bracket need be no finer than a quarter of the allowance (at most crossing_bits)
  CrossingOptions options;
  options.resolution_bits = std::min(crossing_bits, static_cast<unsigned>(std::ceil(std::log2(length / allowance))) + 2);
  const MotionCrossing c = space.first_crossing(back, options);
  ++certified_nudges();
  if (c.status == CrossingStatus::none) return true;
  if (c.status != CrossingStatus::crossing) return false;
  if ((1 - c.u_lower.get_d()) * length <= allowance) return true;
  // A start deeper inside blocked space (the ratchet's impacts at 0.0523 s leave one 2e-9 rad
  // inside, the Geneva drive's held pin one 1e-10 rad inside the corner of slot 1 at 0.6347 s
  // and 1.3947 s):
  // the stretch between the allowance of the start (the contact it leaves, near which a walk
  // cannot certify) and the allowance of the crossing must lie in one blocked cell, certified by
  // a blocked walk (hipair/blocked_walk.hpp) at configurations 4/3 of the way farther from the
  // start each up to the stretch's middle, then 3/4 of the way closer to the crossing each. Each
  // axis's chart coordinate is monotone along the move, so the move between two configurations
  // lies in the hull of their boxes, which the walk certifies. Where the walk cannot certify (a
  // 1-D space, a translating axis, a free or a second cell on the way), no.
  const double near = c.u_upper.get_d(), a = allowance / length, middle = (1 - near) / 2;
  if (!(middle > a)) return true;   // within the allowance of the start or of the crossing
  BlockedWalk walk;
  MotionPath at = back;
  auto blocked = [&](double u) {
    at.u_begin = at.u_end = Rational(u);
    return certainly_blocked(space, at, walk);
  };
  for (double from_start = a; from_start < middle; from_start *= 8.0 / 7)
    if (!blocked(1 - from_start)) return false;
  for (double gap = middle; gap > a; gap *= 7.0 / 8)
    if (!blocked(near + gap)) return false;
  return blocked(near + a);
}

}  // namespace hipair::simulation
