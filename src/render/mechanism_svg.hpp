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

}  // namespace hipair::render
