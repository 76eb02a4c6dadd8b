#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// first_crossing's Newton shrink of the crossing bracket (cspace_queries.cpp): where a stretch
// that must be subdivided keeps a single contact curve whose value at the stretch's start and
// whose rate along the stretch both exclude 0, with opposite signs, the root's interval-Newton
// bounds (widened by a cell, inside the stretch) name the smallest node of the subdivision's
// binary tree holding them; the nodes between the stretch and that one are skipped (the curve
// vanishes inside each: the halving would only have halved them) and their siblings are
// evaluated in path order. Nothing is decided by a proposal: every stretch evaluated is one the
// halving evaluates, by the same tests, so the answers are the halving's. On by default; tests
// switch it off per thread to compare (CSpaceCrossingShrink.*).
struct NewtonShrinkTag;
inline bool& newton_shrink() { return thread_switch<NewtonShrinkTag>(); }
// How many proposals have replaced a halving on this thread (tests).
struct NewtonStepsTag;
inline std::size_t& newton_steps() { return thread_counter<NewtonStepsTag>(); }

// The siblings left of a proposed node skipped (not evaluated) where the one curve's certified
// mean-value bound over the stretch proves it nonzero up to the node: every other curve is
// excluded on the whole stretch, so the motion stays in its start cell there. The halving would
// evaluate them and, but for an enclosure too wide to exclude one, exclude them: the answer is
// the halving's wherever it excludes them, and otherwise a bracket the halving's lies before
// (no crossing lies in a skipped stretch). On by default; tests switch it off per thread.
struct SkipLeftTag;
inline bool& skip_left() { return thread_switch<SkipLeftTag>(); }
// How many sibling stretches were skipped on this thread (tests, profiles).
struct SkippedLeftTag;
inline std::size_t& skipped_left() { return thread_counter<SkippedLeftTag>(); }

// The proposal's bounds narrowed by Newton steps from anchors inside them before the node is
// chosen (cspace_queries.cpp, CrossingRun::refine and MotionScanner::newton_from): from the
// curve's value at a cell before the root and its rate over the proposal's cells, the root lies
// in a narrower span of cells; a deeper node holds it. As the first proposal, it only chooses
// which nodes holding the root are skipped: the stretches evaluated are the halving's, by the
// same tests. On by default; tests switch it off per thread to compare (CSpaceNewtonRefine.*).
struct NewtonRefineTag;
inline bool& newton_refine() { return thread_switch<NewtonRefineTag>(); }
// How many Newton steps from an anchor were taken on this thread (tests, profiles).
struct NewtonRefineStepsTag;
inline std::size_t& newton_refine_steps() { return thread_counter<NewtonRefineStepsTag>(); }
// What the refinement achieved, not what it tried (session 64): proposals whose cells a Newton
// step from an anchor narrowed (refine_narrowings), and left siblings skipped because the last
// anchor proved them free where the stretch's own mean-value bound could not
// (refined_free_before; refined_skips counts the proposals, refined_skipped_stretches the
// sibling stretches not evaluated). Counted on this thread (tests, profiles).
struct RefineNarrowingsTag;
inline std::size_t& refine_narrowings() { return thread_counter<RefineNarrowingsTag>(); }
struct RefinedSkipsTag;
inline std::size_t& refined_skips() { return thread_counter<RefinedSkipsTag>(); }
struct RefinedSkippedStretchesTag;
inline std::size_t& refined_skipped_stretches() { return thread_counter<RefinedSkippedStretchesTag>(); }
// The anchor's skip alone (refined_free_before), with the narrowing kept: on by default; tests
// switch it off per thread to compare (CSpaceNewtonRefine.AnchorSkips*).
struct RefinedSkipTag;
inline bool& refined_skip() { return thread_switch<RefinedSkipTag>(); }

}  // namespace hipair::cspace
