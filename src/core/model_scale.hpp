// Exact rescaling of a model by a power of two (internal).
//
// A mechanism whose parts only rotate (or are fixed) has the same configuration space, in
// half-angle tangent charts, and the same kinematics (angles) when every length is multiplied
// by one positive factor: contact equations are homogeneous in lengths and overlap does not
// depend on the unit. The builder's and the kinematic slicer's double filters (culling,
// interval boxes, inscribed disks) are only meaningful for coordinates well inside the range
// of doubles, while the model format admits 1e-300 mm features and 1e400 mm plates. Such a
// model is analysed on a copy scaled by an exact power of two to coordinates of about 2^6 mm.
#pragma once

#include <hipair/model.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hipair {

/// The power of two to divide the lengths of `parts` by before building or slicing: 0 when
/// a part translates (its coordinate is a length) or the coordinates already lie between about
/// 1e-9 mm and 1e18 mm; else the exponent that brings the largest coordinate near 2^6.
long normalising_shift(const Model& model, const std::vector<std::size_t>& parts);

/// Throws GeometryError when one of `parts` has a length coordinate (it translates, slides in a
/// slot or moves in the plane) and a length of those parts (a point, a pivot, a translation
/// limit, an initial offset) exceeds 2^1016 mm (about 7e305 mm) in magnitude: the pair's C-space
/// coordinates are then lengths at the end of the doubles' range, where its certified double
/// bounds (edge boxes, CertifiedRange) cannot be formed. Rotating and fixed parts are never
/// refused (they are rescaled, above). A pair with arcs whose every length lies below 2^-1000 mm
/// is refused too (its double enclosures would be subnormal); tiny polygon pairs are built exactly.
void require_length_coordinates_in_range(const Model& model, const std::vector<std::size_t>& parts);

/// 0 when require_length_coordinates_in_range accepts `parts`; else (a pair with a length
/// coordinate beyond 2^1016 mm, or with arcs and every length below 2^-1000 mm) the exponent
/// L that brings its largest length near 2^6 mm on scaled_model(model, L): a fixed-axis pair
/// is built there when asked (CSpaceBuildOptions::normalise_lengths), its lengths in units of 2^L mm.
long length_coordinate_shift(const Model& model, const std::vector<std::size_t>& parts);

/// Throws GeometryError when one of `parts` translates (or slides in a slot, or moves in the
/// plane) and the largest length of `parts` lies outside [2^-30, 2^30] mm (about 1e-9 mm to
/// 1e9 mm): the kinematic sweep's positions are then lengths, and its resolutions are absolute
/// (exactly rescaled models gave different events: a false dwell at 1e-12, spurious snaps at
/// 1e9, a false jam at 1e200 times two-pin-wedge.json). Rotation-only mechanisms are rescaled
/// instead (normalising_shift) and never refused.
void require_kinematic_length_scale(const Model& model, const std::vector<std::size_t>& parts);

/// The exponent E of the power of ten a kinematic analysis of the whole mechanism divides its
/// lengths by (decimal_scaled_model): 0 when the largest coordinate of the parts' points
/// (measured after normalising_translation, when the mechanism is far from the origin for its
/// size) lies within [2^-30, 2^30] mm, where require_kinematic_length_scale accepts it, or for a
/// rotation-only mechanism when normalising_shift is 0 (about 1e-9 .. 1e18 mm); else a
/// multiple of 10 that brings the largest coordinate within [1e-4, 1e6) mm. A multiple of 10 so
/// that a model scaled by 10^(10 j) from an ordinary one (largest coordinate 1e-4 .. 1e6 mm) is
/// analysed on exactly that ordinary model: the same events, lengths shown times 10^E
/// (core/length_display.hpp).
long kinematic_decimal_exponent(const Model& model);

/// The multiple E of 10 with magnitude / 10^E within [1e-4, 1e6) (magnitude > 0; 0 for 0): the
/// unit 10^E mm of kinematic_decimal_exponent and of the templates' construction at extreme
/// scales (src/model/template_geometry.cpp), so that both are exactly covariant with a model
/// scaled by 10^(10 j).
long decimal_unit_exponent(const Rational& magnitude);

/// 10^exponent, exactly.
Rational power_of_ten_rational(long exponent);

/// The model with every length divided by 10^exponent, exactly: points, centres and radii
/// (squared: by 100^exponent), pivots, translation limits, initial offsets and x/y, linear
/// springs' rest offsets and constant forces (their signs and directions are what the kinematic
/// analysis reads). The copy a kinematic analysis is made on (kinematic_decimal_exponent); the
/// parameters, the simulation data and the other dynamics data are not rescaled.
Model decimal_scaled_model(const Model& model, long exponent);

/// decimal_scaled_model, and the dynamics data rescaled so that the motion is the same in the
/// unit 10^exponent mm (mass and time unchanged, so a force scales with the lengths): moments of
/// inertia, torques, torsional stiffnesses and a rotating part's damping divided by
/// 100^exponent; gravity, a translating part's initial and driven speeds (and speed profiles; a planar part's
/// vx and vy),
/// couplings' points and rest lengths and centres of mass divided by 10^exponent; masses, linear
/// stiffnesses and dampings, angles and their rates, friction and restitution unchanged (the
/// inverse of tests/fuzz/scale_model.py's rules). A model scaled by 10^exponent from an ordinary
/// one becomes that one exactly: `hipair simulate` runs such a copy (session 53, scale53b).
Model decimal_scaled_dynamics_model(const Model& model, long exponent);

/// Throws ModelError at the pointer of the first dynamics value of `model` (a part's dynamics,
/// the simulation object) whose nonzero magnitude lies outside the doubles' normal range
/// [2.2250738585072014e-308, 1.7976931348623157e+308], saying that it is so in units of
/// 10^exponent mm (`unit`): the check read_model_for_simulation makes, on a rescaled copy.
void require_dynamics_in_double_range(const Model& model, const std::string& unit);

/// The largest spread between a pair's extent and its smallest edge that the commands building
/// or slicing a pair accept: 2^1330 (about 10^400). Exact arithmetic on such a pair carries both
/// sizes in every rational, and its cost grows with the square of the spread's exponent
/// (session 52: a 40 mm cam follower with a 10^-300 mm face, 10 s; 10^-999, about 110 s).
constexpr long max_feature_spread_bits = 1330;

/// Throws GeometryError, naming the part and the edge's pointer, when an edge of a part of the
/// pair (first, second) (indices into model.parts) has a nonzero size (a segment's larger
/// coordinate difference, an arc's radius) below 2^-max_feature_spread_bits of the pair's extent
/// (the larger side of the box of both parts' vertices), decided on exact binary exponents; the
/// message gives the supported range. A model scaled uniformly keeps its spread: 10^-300 and
/// 10^400 mm mechanisms pass.
void require_feature_spread(const Model& model, std::size_t first, std::size_t second);

/// require_feature_spread for every pair of the model.
void require_feature_spread(const Model& model);

/// value * 2^exponent, exactly (a length in units of 2^exponent mm, in mm).
Rational times_power_of_two(Rational value, long exponent);

/// The model with every length (points, centres, pivots, offsets, limits) divided by 2^shift,
/// exactly; radii squared by 4^shift.
Model scaled_model(const Model& model, long shift);

/// A pair whose parts lie far from the origin compared with their own size (the bounding box
/// of `parts`' points and pivots centred more than 2^20 box sizes away: a mechanism drawn at
/// 10^400 mm from the origin) has the same C-space, in every chart, when every point and pivot
/// of the model is moved by one vector: rotations turn about pivots that move with their parts,
/// translation offsets and limits, planar x and y and initial values are differences. The
/// vector to subtract: the box's centre rounded down to a multiple of 2^e, e the binary exponent
/// of the box's size (so the moved coordinates are of the box's size and short rationals);
/// nullopt when the pair is not that far (every ordinary model: built as it is).
std::optional<Point> normalising_translation(const Model& model, const std::vector<std::size_t>& parts);

/// The model with every point (loops' vertices and arc centres) and the pivot of every part
/// that turns (rotation, planar, pin-slot) minus `by`, exactly; nothing else changes.
Model translated_model(const Model& model, const Point& by);

/// The model moved by normalising_translation of the pair of parts named `first` and `second`
/// (translated_model), or nullopt when that pair is not far from the origin for its size (every
/// ordinary model). A claim that holds no world point — a clearance (planar too), a jam, a free
/// passage: angles, offsets, planar x and y, a distance, edge references — says the same of the
/// moved model; the verifier (certify/check.cpp) and the producer (src/certificates) decide such
/// a claim of a far pair on it (256-bit enclosures of points posed at 10^100 mm are about
/// 10^23 mm wide).
std::optional<Model> pair_moved_to_origin(const Model& model, std::string_view first, std::string_view second);

/// The copy of a whole mechanism (every part) that its angle- and offset-valued results are
/// computed on: moved to the origin (normalising_translation), then, when it only rotates and
/// lies outside the doubles' comfortable range, rescaled (normalising_shift). Its
/// configurations (angles, offsets) are the model's, and so are its name, content hash,
/// roundings and edge indices: the kinematic analysis and the certificates of its findings
/// are made on it; a world point of the copy is the model's point to_model(p).
struct NormalisedMechanism {
  Model model;
  Point by{Rational(0), Rational(0)};   ///< the model was moved by -by (translated_model(model, by))
  long shift = 0;                       ///< then divided by 2^shift (scaled_model)
  /// The model's world point of the copy's point p: p * 2^shift + by, exactly.
  Point to_model(const Point& p) const;
};

/// The normalised copy of `model`, or nullopt when neither move applies (every ordinary model:
/// analysed as it is).
std::optional<NormalisedMechanism> normalised_mechanism(const Model& model);

}  // namespace hipair
