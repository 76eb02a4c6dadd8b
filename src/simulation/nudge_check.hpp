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
struct CertifiedNudgesTag;
inline std::size_t& certified_nudges() { return thread_counter<CertifiedNudgesTag>(); }
struct NudgeWalkGapsTag;
inline std::size_t& nudge_walk_gaps() { return thread_counter<NudgeWalkGapsTag>(); }

// The allowance, in units of the first trial's displacement: a move may pass through anything
// within 2^10 first (about 2e-13 of the coordinates' scale) of its start.
inline constexpr double nudge_allowance = 1024;

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
  // inside, the Geneva drive's held pin one 1e-10 rad inside the corner of slot 1 at 0.6347 s):
  // the stretch between the allowance of the start (the contact it leaves, near which a walk
  // cannot certify) and the allowance of the crossing must lie in one blocked cell, certified by
  // a blocked walk (hipair/blocked_walk.hpp) at configurations 4/3 of the way farther from the
  // start each up to the stretch's middle, then 3/4 of the way closer to the crossing each. Each
  // axis's chart coordinate is monotone along the move, so the move between two configurations
  // lies in the hull of their boxes, which the walk certifies. Where the walk cannot certify (a
  // 1-D space, a translating axis, a free or a second cell on the way), no.
  const double near = c.u_upper.get_d(), a = allowance / length, middle = (1 - near) / 2;
  if (!(middle > a)) return true;   // within the allowance of the start or of the crossing
  MotionPath at = back;
  auto step = [&](BlockedWalk& walk, double u) {
    at.u_begin = at.u_end = Rational(u);
    return certainly_blocked(space, at, walk);
  };
  // From the walk's last configuration `from` on to `to`: one step, or halves of it; where a
  // stretch no longer than the allowance cannot be walked (a curve crosses it that the walk's
  // test cannot exclude: the carrier of a real edge vanishing on its blocked continuation, as at
  // the corner of a Geneva slot where the start lies inside both walls), a new walk is placed
  // beyond it by the exact location of `to` (blocked, or the move is refused).
  BlockedWalk walk;
  auto reach = [&](auto& self, double from, double to) -> bool {
    BlockedWalk tried = walk;
    if (step(tried, to)) {
      walk = tried;
      return true;
    }
    if (std::abs(from - to) <= a) {
      walk = BlockedWalk{};
      ++nudge_walk_gaps();
      return step(walk, to);
    }
    const double halfway = (from + to) / 2;
    return self(self, from, halfway) && self(self, halfway, to);
  };
  double last = 1 - a;
  if (!step(walk, last)) return false;
  auto next = [&](double u) {
    bool ok = reach(reach, last, u);
    last = u;
    return ok;
  };
  for (double from_start = a * 8 / 7; from_start < middle; from_start *= 8.0 / 7)
    if (!next(1 - from_start)) return false;
  for (double gap = middle; gap > a; gap *= 7.0 / 8)
    if (!next(near + gap)) return false;
  return next(near + a);
}

}  // namespace hipair::simulation
