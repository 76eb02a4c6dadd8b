// Counters of PairOverlap::certainly_overlapping's work (session 70, growth70), for tests and
// measurements; implemented in src/oracle/overlap.cpp. Process-wide, relaxed atomics.
#pragma once

#include <cstdint>

namespace hipair::cspace {

/// The first part's edges whose interval geometry certainly_overlapping made on its lazy route
/// (posed_edge), over the process: with the blocks windowed by the second part's block boxes
/// they stay about constant per call as the tooth count grows.
std::uint64_t overlap_filter_posed_edges();

/// set_lazy_placement's switch (oracle/overlap.hpp), read by the algebraic oracle too (session
/// 74): off, its curved relation pairs every edge of one part with every edge of the other (the
/// route before the grid of box pairs); tests compare the two.
bool lazy_placement();

}  // namespace hipair::cspace
