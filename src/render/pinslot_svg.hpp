// A pin-in-slot pair's C-space as a stack of slices (Joskowicz & Sacks 1997, Figure 3b): one
// panel per slice of the stack, each the exact slice at a rational follower angle drawn by the
// fixed-axis renderer (cspace_svg), labelled with its angle, free cells and groups, laid out as
// small multiples. A picture only.
#pragma once

#include <hipair/pin_slot.hpp>

#include <string>

namespace hipair::render {

struct PinSlotSvgOptions {
  double panel_pixel_width = 360;
  std::size_t columns = 0;   ///< 0: about the square root of the number of panels (at most 6)
  std::string title;
  /// A path through the stack (PinSlotSpace::path), drawn on the panels: its motions inside a
  /// slice as a polyline on that slice's panel, its waypoints where it leaves a slice ("-> k":
  /// to slice k, or to an end between slices) and arrives ("<- k") marked, its ends marked
  /// "start" / "end" (on the panel of the slice they lie on).
  const PinSlotPath* path = nullptr;
};

/// The SVG document of the stack (2-D slices; a pair against a fixed part has 1-D slices, drawn
/// as strips by the same renderer).
std::string pin_slot_stack_svg(const PinSlotSpace& space, const PinSlotSvgOptions& options = {});

}  // namespace hipair::render
