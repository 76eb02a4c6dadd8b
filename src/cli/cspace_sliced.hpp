// `hipair cspace` on 3-DOF pairs (a planar part against a fixed part): the sliced C-space
// (include/hipair/sliced.hpp) as JSON of its cell structure and statistics.
#pragma once

#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hipair::cli {

/// The parts (fixed, planar) when `first`:`second` names a 3-DOF pair, in either order;
/// nothing when either part is unknown or the pair is not one.
std::optional<std::pair<std::string, std::string>> sliced_pair(const Model& model, const std::string& first,
                                                               const std::string& second);

/// The refusal of a planar part against a part that moves (rotating, translating or planar: a
/// C-space of 4 or more dimensions, not built), naming the pair, its JSON pointer when the
/// model lists it, and both parts' motions; nothing for any other pair (a pin_slot part's pair
/// is refused by pin_slot_pair).
std::optional<std::string> planar_pair_not_built(const Model& model, std::size_t first, std::size_t second);

/// The model's 3-DOF pairs among its pairs (fixed part, planar part).
std::vector<std::pair<std::string, std::string>> sliced_pairs(const Model& model);

/// Builds the sliced C-space, with a progress line on stderr when `progress`.
SlicedSpace build_sliced(const Model& model, const std::string& fixed, const std::string& free, bool progress);

/// JSON of the cell structure: critical angles (isolating intervals, decimals), slices with
/// their representative angle and free cells, connections across critical angles (with their
/// exact witnesses: `witnesses`, parallel to `connections`), components.
std::string sliced_json(const SlicedSpace& space, bool with_times);

/// Counts and times, as `--stats` prints them.
void print_sliced_statistics(const SlicedSpace& space);

}  // namespace hipair::cli
