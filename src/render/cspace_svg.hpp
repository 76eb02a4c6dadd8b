// A C-space as an SVG picture in the style of Joskowicz & Sacks (1997), Figure 2: blocked
// space shaded, free space white, contact curves coloured by kind of contact (vertex-segment,
// arc-arc, ...) with a legend listing the curves in view (a few feature pairs per kind, "+N
// more"; the canvas is sized to hold it), axes in degrees (rotation) or mm (translation),
// chart seams dashed. With a motion path the view zooms to the path's bounding box plus a
// margin (within the charts' range), everything clipped to it. A picture only: edges are
// drawn by sampling their certified double evaluation.
#pragma once

#include <hipair/cspace.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace hipair::render {

/// A configuration to mark with a dot, in part coordinates (rad or mm).
struct CSpaceMark {
  double x = 0;
  double y = 0;
  std::string label;
};

/// A point of a motion path in part coordinates (rad or mm), and whether the parts touch.
struct CSpacePathPoint {
  double x = 0;
  double y = 0;
  bool contact = false;
  bool break_before = false;   ///< start a new piece here (not joined to the previous point)
};

struct CSpaceSvgOptions {
  double pixel_width = 1100;
  std::vector<CSpaceMark> marks;
  /// A motion path drawn over the space (Figures 2 and 6b): blue where the parts are apart,
  /// red in contact; angles wrapped into the charts' range. The plotted window is the path's
  /// (and the marks') bounding box plus a margin.
  std::vector<CSpacePathPoint> path;
  bool show_spurious = false;     ///< also draw spurious edges (thin, grey)
  std::string title;
  /// Axis names replacing "<part> offset (mm)" / "<part> angle (deg)" (empty: those).
  std::string x_axis_label, y_axis_label;
  /// A plotted window in display units (deg or mm): x_lo, x_hi, y_lo, y_hi (within the charts'
  /// range); a motion path's zoom applies when absent.
  std::optional<std::array<double, 4>> window;
  /// Legend: feature pairs listed per kind of contact (0: the kinds only), and its text size.
  std::size_t legend_pairs_per_kind = 3;
  double legend_text_size = 6;
  /// Edge samples from certified double enclosures where they give the same drawing as the
  /// exact ordinates (render/edge_ordinates.hpp); false: every sample exact (tests compare).
  bool certified_samples = true;
};

/// The SVG document of the C-space.
std::string cspace_svg(const CSpace& space, const CSpaceSvgOptions& options = {});

}  // namespace hipair::render
