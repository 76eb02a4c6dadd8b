#pragma once

#include <cstddef>

namespace hipair::cspace {

// first_crossing's Newton shrink of the crossing bracket (cspace_queries.cpp): where a stretch
// that must be subdivided keeps a single contact curve whose value at the stretch's start and
// whose rate along the stretch both exclude 0, with opposite signs, the root's interval-Newton
// bounds propose the next stretches (snapped to the resolution's grid) instead of the halves.
// Nothing is decided by a proposal: every stretch is still excluded or subdivided by the same
// tests, in path order. On by default; tests switch it off per thread to compare the brackets.
inline bool& newton_shrink() {
  thread_local bool on = true;
  return on;
}
// How many proposals have replaced a halving on this thread (tests).
inline std::size_t& newton_steps() {
  thread_local std::size_t count = 0;
  return count;
}

}  // namespace hipair::cspace
