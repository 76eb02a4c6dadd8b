// Pictures of a kinematic analysis: position and velocity-ratio plots, and a pair's C-space
// with the motion path overlaid (like Figures 2 and 6b of Joskowicz & Sacks 1997). Doubles:
// pictures only.
#pragma once

#include <hipair/kinematics.hpp>

#include <string>

namespace hipair::render {

/// Plots of every driven part's position and velocity ratio against the driver, with dwell
/// periods shaded and contact changes marked.
std::string kinematics_plot_svg(const KinematicsResult& result, double pixel_width = 900);

/// The sampled C-space `raster` (blocked grey, free white) with `path` overlaid: free motion
/// blue, contact motion red, start and end marked.
std::string cspace_path_svg(const CSpaceRaster& raster, const PairPath& path, const std::string& title = "",
                            double pixel_width = 700);

}  // namespace hipair::render
