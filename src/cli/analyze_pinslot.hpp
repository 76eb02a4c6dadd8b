// `hipair analyze` on a model with a pin-in-slot follower (the film advance): the work cycle of
// driver, follower and pushed part (hipair::pin_slot_cycle), printed phase by phase with the
// contacts, and written as cycle.json into --out.
#pragma once

#include <hipair/model.hpp>

#include <string>

namespace hipair::cli {

/// A pin_slot part is paired with a rotating part: analyze runs the work cycle.
bool has_pin_slot_part(const Model& model);

struct PinSlotCycleRequest {
  std::string driver;
  std::string direction;   ///< "", "cw", "ccw", "+", "-"
  unsigned steps = 72;
  std::string out;
  bool quiet = false;
};

int run_pin_slot_cycle(const Model& model, const PinSlotCycleRequest& request);

}  // namespace hipair::cli
