// HIPAIR — opt-in access to the raw CGAL arrangements behind a C-space, for users who embed
// them in their own CGAL-based tools. Including this header pulls in CGAL's algebraic
// arrangement code (tens of seconds of compile time); the rest of HIPAIR never needs it.
//
// The arrangements exist only when the C-space was built with
// CSpaceBuildOptions::keep_arrangements = true. CGAL's algebraic kernel keeps per-thread
// caches: use a kept arrangement only on the thread that built it (build_all builds on worker
// threads unless keep_arrangements is set, in which case it builds on the calling thread).
#pragma once

#include <hipair/cspace.hpp>

#include <CGAL/Arr_algebraic_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Gmpz.h>

#include <cstddef>

namespace hipair::cgal {

/// The traits class: exact algebraic curve segments with integer polynomial coefficients.
using Traits = CGAL::Arr_algebraic_segment_traits_2<CGAL::Gmpz>;
/// One chart's arrangement of clipped contact-curve segments and the chart box boundary.
using Arrangement = CGAL::Arrangement_2<Traits>;

/// The arrangement of chart `chart` (index into CSpace::charts()), or nullptr when it was not
/// kept (or the space is 1-D, or the chart's curves are all lines and circles — a translating
/// pair — and it was built on CGAL's circle–segment traits, which this accessor does not
/// expose). Edges are in chart coordinates; the chart box is its boundary.
const Arrangement* arrangement(const CSpace& space, std::size_t chart);

}  // namespace hipair::cgal
