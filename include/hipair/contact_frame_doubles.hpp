// HIPAIR — CSpace::contact_frame at a configuration given by doubles, without rationals: what the
// simulator's Coulomb rows take from a frame (src/simulation, friction_of).
//
// contact_frame_ranges(space, f, x, y) is CSpace::contact_frame(f, X, Y) with X, Y the part
// coordinates whose exact values are the doubles (PartCoordinate{kind, Rational(value)}): the
// same chart (the first that holds the configuration), the same double enclosures of the chart
// values (KInterval::enclose of the exact chart value: the double itself, or -1/value on a
// half-turn chart, whose enclosure is found from the correctly rounded quotient and the sign of
// its exact residual fma(q, value, 1)), the same kernels' frame, so the same point_range and
// normal bit for bit, and the same GeometryError where contact_frame throws. A chart-bound test
// the doubles do not decide (the value within the bound's enclosure), a quotient outside
// 2^±500, or a coordinate kind its axis does not take, is answered by contact_frame itself.
#pragma once

#include <hipair/cspace.hpp>

#include <array>
#include <optional>

namespace hipair {

/// A part coordinate whose exact value is a double (PartCoordinate{kind, Rational(value)};
/// value ignored for half_turn).
struct DoubleCoordinate {
  PartCoordinate::Kind kind = PartCoordinate::Kind::half_angle_tangent;
  double value = 0;
};

/// The certified enclosures of a contact frame (Contact::point_range, Contact::normal).
struct FrameRanges {
  std::array<CertifiedRange, 2> point_range;
  std::array<CertifiedRange, 2> normal;
};

/// CSpace::contact_frame(feature, x, y)'s point_range and normal (nullopt where it has none),
/// bit for bit; throws where it throws.
std::optional<FrameRanges> contact_frame_ranges(const CSpace& space, FeatureId feature, const DoubleCoordinate& x,
                                                const DoubleCoordinate& y = {});

/// How many contact_frame_ranges calls on this thread were answered by CSpace::contact_frame
/// (the doubles did not decide; tests).
std::size_t& contact_frame_ranges_fallbacks();

}  // namespace hipair
