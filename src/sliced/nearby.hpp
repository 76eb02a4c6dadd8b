// Feature pairs of a 3-DOF pair whose features lie near each other at one configuration
// (SlicedSpace::features_near): in the slice through the configuration, the distance of (x, y)
// from a feature pair's contact curve equals the world distance of the two features (the least
// translation that brings them into contact). Vertex–segment and vertex–arc distances are
// compared with the query distance exactly (squared, and signs of a + b sqrt(c)); pairs of two
// curves (segment–arc, arc–arc) get a certified lower bound (the distance of the arc's circle
// from the segment, of the two circles) and an upper bound (distances of actual points), and are reported whenever
// the lower bound does not exclude them. CGAL-free.
#pragma once

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <vector>

namespace hipair::sliced {

struct NearPair {
  FeatureIdentity fixed, free;
  Rational lower, upper;   ///< certified bounds of the features' distance (mm)
  bool exact = false;      ///< distance <= the query's distance decided exactly
};

/// Every pair whose distance may be <= `distance` at configuration `q`, nearest (by lower
/// bound) first.
std::vector<NearPair> near_features(const Model& model, std::size_t fixed, std::size_t free, const SlicedConfiguration& q,
                                    const Rational& distance);

}  // namespace hipair::sliced
