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

/// The ends of a path through a pin-in-slot pair's stack (`cspace --at ... --to ...`), in the
/// model's units (mm, rad): `--at` / `--to` assignments PIN=SLIDE,ANGLE (the pin-slot part) and
/// OTHER=VALUE (a rotating other part's angle, a translating one's offset), as `certify --at`
/// takes them; the start defaults to the model's initial configuration, what --to leaves out to
/// the start's. Angles in rad or NNdeg (exact at whole quarter turns, else rounded to the 10^-18
/// rad grid: `notes` says how they were taken); psi must not be the half turn.
struct PinSlotPathEnds {
  PinSlotConfiguration from, to;
  std::string from_option, to_option;   ///< "--at follower=1,10deg --at film=2" (or "--at (the model's initial configuration)")
  std::vector<std::string> notes;
};
/// \throws ModelError naming the option for a malformed or unknown assignment.
PinSlotPathEnds pin_slot_path_ends(const Model& model, const std::string& other, const std::string& pin_slot,
                                   const std::vector<std::string>& at, const std::vector<std::string>& to);

/// The path between the ends (PinSlotSpace::path), the ends brought to the space's units
/// (`decimal_exponent` as pin_slot_json) and checked first. \throws ModelError naming the
/// option when an end is outside the limits, blocked or in contact.
PinSlotPath pin_slot_path(const PinSlotSpace& space, const PinSlotPathEnds& ends, long decimal_exponent = 0);

/// JSON of the stack: slices (tau exact, degrees), free cells (contacts, sample, group),
/// connections with their witnesses, changes, groups, statistics; with `path`, the path too
/// (status, waypoints exact and in doubles, each motion's kind).
/// `decimal_exponent`: the space was built on the model divided by 10^E (an extreme-scale
/// mechanism, cli/cspace.cpp); its lengths are written in mm, times 10^E exactly.
std::string pin_slot_json(const PinSlotSpace& space, bool with_times, long decimal_exponent = 0,
                          const PinSlotPath* path = nullptr);

/// The one-line summary `hipair cspace` prints for a path.
std::string pin_slot_path_summary(const PinSlotSpace& space, const PinSlotPath& path);

/// Counts and times, as `--stats` prints them.
void print_pin_slot_statistics(const PinSlotSpace& space);

}  // namespace hipair::cli
