// Drawing a mechanism (a Model at one configuration) as SVG. A picture: double precision.
#pragma once

#include <hipair/model.hpp>

#include <string>
#include <vector>

namespace hipair::render {

/// Options of a mechanism drawing.
struct MechanismSvgOptions {
  bool labels = false;          ///< write each edge's feature label next to it
  double pixel_width = 900;     ///< width attribute of the document
  bool legend = true;           ///< part legend with colours and motions
  std::string title;            ///< default: the model name
};

/// A point of a part's geometry moved to the part's configuration (double precision).
struct PosedPoint {
  double x = 0;
  double y = 0;
};

/// Moves the zero-configuration point `p` of a part with `motion` to `configuration`.
PosedPoint pose_point(const Motion& motion, const PartConfiguration& configuration, double x,
                      double y);

/// SVG of `model` with part i at `configurations[i]` (size must equal the part count): filled
/// parts (holes cut), fixed parts hatched, pivots, translation axes, names, scale bar, legend.
/// \throws Error when the sizes differ.
std::string mechanism_svg(const Model& model, const std::vector<PartConfiguration>& configurations,
                          const MechanismSvgOptions& options = {});

/// One frame of an animated drawing: a time (the model's time unit) and every part's
/// configuration (size = the part count).
struct MechanismFrame {
  double time = 0;
  std::vector<PartConfiguration> configurations;
};

/// A mark shown for a moment at a world point (an impact's contact point, mm).
struct MechanismMark {
  double time = 0;
  double x = 0;
  double y = 0;
  std::string title;   ///< tooltip
};

/// Options of an animated drawing.
struct MechanismAnimationOptions {
  MechanismSvgOptions drawing;     ///< as the still drawing (legend, labels, title, width)
  double duration = 0;             ///< playback time of the whole run, seconds (> 0)
  std::string time_unit = "s";     ///< unit of the frames' times, for the readout
  std::vector<MechanismMark> marks;
  double mark_seconds = 0.2;       ///< how long (playback seconds) a mark stays visible
  std::size_t max_readouts = 1000; ///< time readouts at most (every k-th frame beyond)
};

/// An SVG that plays the frames in a browser (SMIL, repeating): every part is drawn once, as in
/// mechanism_svg() (same normalisation, colours, pivots, names), and each rotating or
/// translating part's group carries one <animateTransform> (type rotate about its pivot, or
/// translate along its axis) whose keyTimes are the frames' times over the run, scaled to
/// [0, 1], with calcMode linear; its transform attribute is the first frame's, so a renderer
/// without animation shows the first frame. A time readout and a progress bar play along; marks
/// blink at their times. Planar and pin-in-slot parts are drawn still at the first frame.
/// \throws Error when there are fewer than two frames, a frame's size differs from the part
/// count, times do not increase, or the duration is not positive.
std::string mechanism_animation_svg(const Model& model, const std::vector<MechanismFrame>& frames,
                                    const MechanismAnimationOptions& options);

}  // namespace hipair::render
