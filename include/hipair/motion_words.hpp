// The words hipair's messages use for a part's kind of motion, in one place.
#pragma once

#include <hipair/model.hpp>

#include <string>

namespace hipair {

/// The adjective a message uses for a part moving as `kind`: "fixed", "rotating", "translating",
/// "planar" or "pin-slot" (e.g. "the planar part 'peg' against the rotating part 'cam'").
inline const char* motion_adjective(Motion::Kind kind) noexcept {
  switch (kind) {
    case Motion::Kind::fixed: return "fixed";
    case Motion::Kind::rotation: return "rotating";
    case Motion::Kind::translation: return "translating";
    case Motion::Kind::planar: return "planar";
    case Motion::Kind::pin_slot: return "pin-slot";
  }
  return "?";
}

/// A part as a message names it with its motion: "rotating part 'cam' (/parts/0/motion)".
inline std::string described_part(const Part& part) {
  return std::string(motion_adjective(part.motion.kind)) + " part '" + part.name + "' (" + part.motion.pointer + ")";
}

}  // namespace hipair
