// `hipair cspace` on pin-in-slot pairs (a pin_slot part against a rotating, translating or
// fixed part): the stack-of-slices C-space (include/hipair/pin_slot.hpp) as JSON and SVG.
#pragma once

#include <hipair/model.hpp>
#include <hipair/pin_slot.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hipair::cli {

/// (other part, pin-slot part) when `first`:`second` names a pair with a pin_slot part, in
/// either order; nothing otherwise. \throws GeometryError when both parts are pin_slot or the
/// other is planar (a pair that is not built), naming the pair.
std::optional<std::pair<std::string, std::string>> pin_slot_pair(const Model& model, const std::string& first,
                                                                  const std::string& second);

/// The model's pin-in-slot pairs among its pairs. \throws GeometryError as pin_slot_pair.
std::vector<std::pair<std::string, std::string>> pin_slot_pairs(const Model& model);

/// Builds the stack, with a progress line on stderr when `progress`.
PinSlotSpace build_pin_slot(const Model& model, const std::string& other, const std::string& pin_slot, bool progress,
                            std::size_t slices, bool plane_witnesses);

/// JSON of the stack: slices (tau exact, degrees), free cells (contacts, sample, group),
/// connections with their witnesses, changes, groups, statistics.
/// `decimal_exponent`: the space was built on the model divided by 10^E (an extreme-scale
/// mechanism, cli/cspace.cpp); its lengths are written in mm, times 10^E exactly.
std::string pin_slot_json(const PinSlotSpace& space, bool with_times, long decimal_exponent = 0);

/// Counts and times, as `--stats` prints them.
void print_pin_slot_statistics(const PinSlotSpace& space);

}  // namespace hipair::cli
