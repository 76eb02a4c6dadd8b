// Counters of PairOverlap::certainly_overlapping's work (session 70, growth70), for tests and
// measurements; implemented in src/oracle/overlap.cpp. Process-wide, relaxed atomics.
#pragma once

#include <array>
#include <cstdint>

namespace hipair::cspace {

/// The first part's edges whose interval geometry certainly_overlapping made on its lazy route
/// (posed_edge), over the process: with the blocks windowed by the second part's block boxes
/// they stay about constant per call as the tooth count grows.
std::uint64_t overlap_filter_posed_edges();

/// Session 75 (growth75): {edges posed, calls answered} by certainly_overlapping's memo of the
/// edge pairs that certified its last crossings (tried before its broad phase), over the process.
std::array<std::uint64_t, 2> overlap_filter_memo_counts();

/// set_lazy_placement's switch (oracle/overlap.hpp), read by the algebraic oracle too (session
/// 74): off, its curved relation pairs every edge of one part with every edge of the other (the
/// route before the grid of box pairs); tests compare the two.
bool lazy_placement();

}  // namespace hipair::cspace
