// The words hipair's messages use for a part's kind of motion, in one place.
#pragma once

#include <hipair/model.hpp>

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

}  // namespace hipair
