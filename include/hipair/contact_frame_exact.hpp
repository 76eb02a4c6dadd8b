// HIPAIR — CSpace::contact_frame evaluated exactly at a rational configuration (session 70,
// stop70): the kernels' contact point and normal (kernels/contact_geometry.hpp) in rationals, at
// a configuration on or next to the feature pair's contact curve (the features need not touch
// there exactly). What the fixed-axis simulator's jam test takes to decide a lock exactly at the
// rational configuration of its state (src/simulation/simulation.cpp, `exact_jam_row`).
#pragma once

#include <hipair/cspace.hpp>

#include <optional>

namespace hipair {

/// The contact frame of feature pair `feature` at the rational configuration (x, y): `exact`
/// true, `point` the world contact point (mm) and `normal_direction` the normal (not normalised,
/// the orientation of CSpace::contact_frame's unit normal), exactly; the ranges their enclosures.
/// nullopt where the frame is undefined (a degenerate configuration, a vertex–vertex pair).
/// \throws GeometryError when the configuration is outside every chart.
std::optional<Contact> exact_contact_frame(const CSpace& space, FeatureId feature, const PartCoordinate& x,
                                           const PartCoordinate& y = {});

}  // namespace hipair
