#pragma once
// The operating region of a pair along an analysed motion (docs/cspace.md, "Operating region").

#include <hipair/cspace.hpp>

#include <array>
#include <string_view>
#include <vector>

namespace hipair {

/// Builds the operating region of the pair (first_part, second_part) — the flooded channel of
/// CSpaceBuildOptions::operating_region, seeded at path.front() unless options.region_seed is
/// set — and of its tiles only those holding a configuration of `path`, or next to such a tile
/// in the same chart. `path` holds configurations as coordinates of the x and y parts (rad or
/// mm, as region_seed), e.g. the motion path of an analysis: a full turn of a gear pair whose
/// channel closes only after several turns builds only the part of the channel it runs through.
/// Everything built is exact, as in any operating region; complete() is false and
/// statistics().region_tiles counts the tiles built. A path none of whose configurations lies
/// in a flooded tile builds the whole flooded region.
/// \throws what CSpace::build throws (a 1-D pair is built whole, as there).
CSpace build_operating_region_along(const Model& model, std::string_view first_part, std::string_view second_part,
                                    const std::vector<std::array<double, 2>>& path, CSpaceBuildOptions options = {});

}  // namespace hipair
