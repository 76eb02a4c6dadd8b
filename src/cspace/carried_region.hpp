#pragma once

#include "core/thread_switch.hpp"

#include <cstddef>

namespace hipair::cspace {

// first_crossing's carried region (cspace_queries.cpp, ScanMemo::Region; docs/simulation.md,
// "Session 44 (esc44)"): per space and thread, one box R of a 2-D chart, in doubles, strictly
// inside the chart's box, on which the interval value of every curve polynomial of the chart
// excludes 0, with the cell (and its kind, free or blocked) of a point of R located exactly.
// R meets no curve and no chart side, so it lies in one face of the chart's arrangement: every
// configuration in R is in that cell, off contact space. A query's box inside R (same chart) is
// then excluded without evaluating the curves (a stretch: the path stays in the cell over it)
// and a point's box inside R is located in R's cell without a point location. R is proven once,
// when it is made (from a located point's box or a query's excluded first stretch, widened), and
// is replaced when a box outside it is located or excluded: the region is a fact about the
// space, not about one motion, so it needs no other invalidation. On by default; tests switch it
// off per thread to compare (CSpaceCarriedRegion.*, SimulationCarriedRegion.*).
struct CarriedRegionsTag;
inline bool& carried_regions() { return thread_switch<CarriedRegionsTag>(); }
// boxes found inside the region (excluded or located by it) on this thread (tests)
struct CarriedRegionHitsTag;
inline std::size_t& carried_region_hits() { return thread_counter<CarriedRegionHitsTag>(); }
// regions proven (made) on this thread (tests)
struct CarriedRegionsMadeTag;
inline std::size_t& carried_regions_made() { return thread_counter<CarriedRegionsMadeTag>(); }

}  // namespace hipair::cspace
