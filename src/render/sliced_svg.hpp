// A 3-DOF pair's sliced C-space as a stack of slices (Joskowicz & Sacks 1997, Figure 3b):
// one panel per interval between consecutive critical angles, each the representative
// slice drawn by the translating-pair renderer (cspace_svg) and labelled with its angle
// interval, laid out as small multiples in a grid in order of theta; axes x, y are the shift
// of the free part's pivot (mm), all panels share one window (the blocked regions' extent
// plus a margin) and a legend of the contact kinds drawn; then chosen slices at full size,
// zoomed onto their inner free cells, with a legend of feature pairs. A picture only.
#pragma once

#include <hipair/sliced.hpp>

#include <string>
#include <vector>

namespace hipair::render {

struct SlicedSvgOptions {
  double panel_pixel_width = 420;   ///< width of one panel in the document
  std::size_t columns = 0;          ///< 0: about the square root of the number of panels (at most 6)
  std::string title;
  /// Intervals drawn again at full size below the grid (indices into intervals()); when empty
  /// and `choose_full_size`, sliced_default_full_size (the two sides of a change of structure,
  /// drawn in one shared window so that they compare).
  std::vector<std::size_t> full_size;
  bool choose_full_size = true;
  double full_pixel_width = 760;   ///< width of a full-size panel
};

/// The degrees of an interval's ends and of its representative, as display text, e.g.
/// "θ in (-45.00°, 45.00°), slice at θ = 0.00°" (angles approximate; "all θ" when there is no
/// critical angle).
std::string sliced_interval_label(const SlicedSpace& space, std::size_t interval);

/// The default full-size slices: the two intervals either side of the critical angle nearest
/// theta = 0 at which the free space changes its structure (a free cell ends, starts, splits or
/// merges there: the crossing's connections are not one-to-one); without such an angle, up to
/// two intervals with the most free cells (more than one). Ascending indices.
std::vector<std::size_t> sliced_default_full_size(const SlicedSpace& space);

/// The SVG document of the stack of slices (builds each representative slice on demand).
std::string sliced_stack_svg(const SlicedSpace& space, const SlicedSvgOptions& options = {});

}  // namespace hipair::render
