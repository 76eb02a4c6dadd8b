// A C-space as an SVG picture in the style of Joskowicz & Sacks (1997), Figure 2: blocked
// space shaded, free space white, contact curves coloured by feature pair with a legend, axes
// in degrees (rotation) or mm (translation), chart seams dashed. A picture only: edges are
// drawn by sampling their certified double evaluation.
#pragma once

#include <hipair/cspace.hpp>

#include <string>
#include <vector>

namespace hipair::render {

/// A configuration to mark with a dot, in part coordinates (rad or mm).
struct CSpaceMark {
  double x = 0;
  double y = 0;
  std::string label;
};

struct CSpaceSvgOptions {
  double pixel_width = 1100;
  std::vector<CSpaceMark> marks;
  bool show_spurious = false;     ///< also draw spurious edges (thin, grey)
  std::string title;
};

/// The SVG document of the C-space.
std::string cspace_svg(const CSpace& space, const CSpaceSvgOptions& options = {});

}  // namespace hipair::render
