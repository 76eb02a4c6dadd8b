// A slice of a pair's C-space around one coordinate (session 21): what a consumer needs that
// follows one point along a path (the tolerance analysis's channel), located only as far as it
// needs. Beside CSpace::slice, which locates every interval of the slice.
#pragma once

#include <hipair/cspace.hpp>

#include <cstddef>
#include <optional>

namespace hipair {

/// The part of chart `chart`'s slice (as CSpace::slice gives it) around the coordinate `at`
/// along the free axis: the `boundaries` (>= 1) nearest points below `at`, the point at `at` if
/// there is one, the `boundaries` nearest above (fewer where the chart's box ends first), and
/// the intervals between and beyond them. Points are CSpace::slice's points exactly (values and
/// features), consecutive in it; each interval has the cell and kind of CSpace::slice's interval
/// there (its sample is a coordinate inside it, not necessarily the same one). Only the
/// intervals up to those boundaries are located (exact point location), which makes it cheaper
/// than CSpace::slice when one point's neighbourhood is needed. `lower` and `upper` are the
/// chart box's, as in CSpace::slice. nullopt when `value` or `at` lies outside the chart's box.
/// \throws GeometryError for a 1-D space, a chart out of range, or 0 boundaries.
std::optional<Slice> slice_near(const CSpace& space, std::size_t chart, SliceAxis axis, const Rational& value,
                                const Rational& at, std::size_t boundaries = 2);

}  // namespace hipair
