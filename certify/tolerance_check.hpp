// The verifier's check of tolerance certificates (docs/certify.md "Tolerance"): the geometry
// is re-evaluated from the model's parametric form (src/model/parametric: the formulas the
// model reader records) with the verifier's own arithmetic — MPFI enclosures at 256 bits and
// forward-mode jets over them — and each branch-and-bound leaf is re-checked: both sides of
// the follower's channel bracketed (a certain sign change of the side's contact function across
// its bracket), then either a witness follower path strictly between the sides (each side's
// function monotone from the witness to its bracket's channel-side end: the side is the root
// nearest the channel) or the play between them (each function monotone over its whole bracket)
// enclosed in mean-value form over the leaf and certainly positive. The leaves must cover the parameter
// box times the driver range (the subdivision tree is walked with exact rationals).
//
// The producer (src/tolerance/certificate.cpp) uses the same evaluator to search, so that what
// it emits is what the verifier accepts; it is not trusted: every certificate is re-checked.
#pragma once

#include "certify/exact_geometry.hpp"
#include "model/interval.hpp"
#include "model/parametric/parametric.hpp"

#include <hipair/certificate.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace hipair::verify {

using model_detail::Interval;

/// A value and its gradient with respect to the certificate's variables (the varied
/// parameters, then the driver, then the follower), every component an MPFI enclosure.
/// An empty gradient is a constant.
struct Jet {
  Interval value;
  std::vector<Interval> gradient;

  Jet() : value(Rational(0)) {}
  Jet(int v) : value(Rational(v)) {}   // NOLINT(google-explicit-constructor): formulas use T(0)
  explicit Jet(const Interval& v) : value(v) {}
  Jet(const Interval& v, std::vector<Interval> g) : value(v), gradient(std::move(g)) {}
  /// Variable `index` of `count` ranging over `v`.
  static Jet variable(const Interval& v, std::size_t index, std::size_t count);
  Interval partial(std::size_t i) const { return i < gradient.size() ? gradient[i] : Interval(Rational(0)); }
};

Jet operator+(const Jet& a, const Jet& b);
Jet operator-(const Jet& a, const Jet& b);
Jet operator-(const Jet& a);
Jet operator*(const Jet& a, const Jet& b);
Jet operator/(const Jet& a, const Jet& b);

/// [lo, hi] as an MPFI enclosure (exact ends).
Interval enclose(const RationalInterval& range);
Interval enclose(const Rational& value);

/// A value with its gradient and Hessian with respect to the dimensions of a leaf (the varied
/// parameters, then the driver), every component an MPFI enclosure; sparse: only the
/// dimensions in `index` (increasing) have non-zero derivatives. `smooth` is false when a
/// non-differentiable operation (abs, min, max of undecided order) was met: then no
/// derivative is trusted. The second-order Taylor form of the witness test uses it
/// (docs/certify.md "Tolerance", check 6).
struct Jet2 {
  Interval value;
  std::vector<std::size_t> index;
  std::vector<Interval> gradient;   ///< per entry of index
  std::vector<Interval> hessian;    ///< upper triangle, row by row: (a, b), a <= b
  bool smooth = true;

  Jet2() : value(Rational(0)) {}
  Jet2(int v) : value(Rational(v)) {}   // NOLINT(google-explicit-constructor): formulas use T(0)
  explicit Jet2(const Interval& v) : value(v) {}
  /// Dimension `dimension` ranging over `v`.
  static Jet2 variable(const Interval& v, std::size_t dimension);
  /// The Hessian entry of entries a, b of index.
  const Interval& second(std::size_t a, std::size_t b) const;
};

Jet2 operator+(const Jet2& a, const Jet2& b);
Jet2 operator-(const Jet2& a, const Jet2& b);
Jet2 operator-(const Jet2& a);
Jet2 operator*(const Jet2& a, const Jet2& b);
Jet2 operator/(const Jet2& a, const Jet2& b);

}  // namespace hipair::verify

namespace hipair::model_detail {
/// The parametric formulas over first-order jets (MPFI; tolerance_check.cpp).
template <>
struct Arithmetic<verify::Jet> {
  using J = verify::Jet;
  static J constant(const Rational& q);
  static J pi();
  static J sqrt(const J& x);
  static J sin(const J& x);
  static J cos(const J& x);
  static J tan(const J& x);
  static J atan2(const J& y, const J& x);
  static J abs(const J& x);
  static J extremum(const J& a, const J& b, bool minimum);
  static J min(const J& a, const J& b) { return extremum(a, b, true); }
  static J max(const J& a, const J& b) { return extremum(a, b, false); }
};

/// The parametric formulas over second-order jets (MPFI; tolerance_check.cpp).
template <>
struct Arithmetic<verify::Jet2> {
  using J = verify::Jet2;
  static J constant(const Rational& q);
  static J pi();
  static J sqrt(const J& x);
  static J sin(const J& x);
  static J cos(const J& x);
  static J tan(const J& x);
  static J atan2(const J& y, const J& x);
  static J abs(const J& x);
  static J extremum(const J& a, const J& b, bool minimum);
  static J min(const J& a, const J& b) { return extremum(a, b, true); }
  static J max(const J& a, const J& b) { return extremum(a, b, false); }
};
}  // namespace hipair::model_detail

namespace hipair::verify {

/// Geometry of the pair's two parts at one parameter set (edges evaluated on demand).
template <class T>
struct GeometryOf {
  std::vector<T> parameters;   ///< every parameter's value
  std::map<std::tuple<std::size_t, std::size_t, std::size_t>, model_detail::EdgeValue<T>> edges;
  kernels::Vector<T> driver_pivot, driver_direction, follower_pivot, follower_direction;
};
using ToleranceGeometry = GeometryOf<Jet>;

/// What one side of one leaf certifies: the side's root over the leaf lies in `bracket`, at
/// the leaf's centre in `centre`, and its partial derivatives (varied parameters, then the
/// driver) lie in `slope`.
struct SideEnclosure {
  Interval bracket, centre;
  std::vector<Interval> slope;
};

/// A tolerance claim resolved against the parametric model. \throws Rejection when the claim
/// does not fit the model (unknown parts or parameters, a box that is not the scaled tolerance
/// box, features that do not exist or have no contact of their own).
class ToleranceEvaluator {
 public:
  ToleranceEvaluator(std::shared_ptr<const model_detail::ParametricModel> model, const ToleranceClaim& claim);

  std::size_t varied_count() const { return varied_.size(); }
  std::size_t variables() const { return varied_.size() + 2; }
  std::size_t driver_variable() const { return varied_.size(); }
  std::size_t follower_variable() const { return varied_.size() + 1; }
  const ToleranceClaim& claim() const { return claim_; }

  /// The geometry at deviations of the varied parameters (others nominal): with `gradient`,
  /// each varied parameter is a variable.
  ToleranceGeometry geometry(const std::vector<Interval>& deviations, bool gradient) const;

  /// The contact function of side pair `pair` with the driver at `driver` and the follower at
  /// `follower` (part coordinates: rad or mm): zero where the two features touch.
  Jet contact(ToleranceGeometry& geometry, std::size_t pair, const Jet& driver, const Jet& follower) const;

  /// The certain sign (+1, -1; 0 undecided) of side `pair`'s contact function over the whole
  /// leaf with the follower at `y` (mean-value form about the leaf's centre).
  int sign_over_leaf(const ToleranceLeaf& leaf, std::size_t pair, const Rational& y, ToleranceGeometry& over_box,
                     ToleranceGeometry& at_centre) const;
  /// The sign `want` (+1 or -1) of a function over the leaf proved with monotonicity, or 0
  /// (docs/certify.md "Tolerance", check 3): `over_leaf` encloses the function with its
  /// gradient (varied parameters, then the driver) over the leaf. Every dimension whose partial
  /// derivative has a certain sign is fixed at the end of its interval where the function is
  /// nearest to 0; on that face of the leaf `evaluate(face, geometry)` (a sub-box of the leaf,
  /// the geometry evaluated over it with gradient, or at a point without) gives the function
  /// with its gradient over the face, which may fix more dimensions; the bound is the value at
  /// the face's centre plus the mean-value remainder over the face's remaining widths.
  template <class Evaluate>
  int monotone_sign(const ToleranceLeaf& leaf, const Jet& over_leaf, int want, const Evaluate& evaluate) const;

  /// Checks one side of a leaf: certain opposite signs at the bracket's ends over the whole
  /// leaf, and a sign change across the centre interval at the leaf's centre; with
  /// `monotone_in_bracket` (leaves without a witness) also a follower derivative of one sign
  /// over leaf x bracket (one root; its slopes in the result). \throws Rejection with the reason.
  SideEnclosure check_side(const ToleranceLeaf& leaf, const LeafSide& side, ToleranceGeometry& over_box,
                           ToleranceGeometry& at_centre, const std::string& where,
                           bool monotone_in_bracket = true) const;
  /// Checks one leaf (both sides and the play). \throws Rejection with the reason.
  void check_leaf(const ToleranceLeaf& leaf, std::size_t index) const;
  /// The same with the geometry over the leaf's box and at its centre already evaluated.
  void check_leaf(const ToleranceLeaf& leaf, std::size_t index, ToleranceGeometry& over_box,
                  ToleranceGeometry& at_centre) const;
  /// A certified enclosure of the play (upper side minus lower side) over the leaf, given both
  /// sides' enclosures.
  Interval play(const ToleranceLeaf& leaf, const SideEnclosure& lower, const SideEnclosure& upper) const;

  /// Checks a leaf's witness: y*(p, d) strictly between the two sides over the whole leaf
  /// (after both sides' brackets were checked): each side's function has at y* the sign of its
  /// bracket's channel-side end and is monotone between them, so the side (the root nearest
  /// the channel in its bracket) lies strictly beyond y*. \throws Rejection.
  void check_witness(const ToleranceLeaf& leaf, ToleranceGeometry& over_box, ToleranceGeometry& at_centre,
                     const std::string& where) const;

  /// The second-order Taylor form of side `lower` (or upper) 's contact function at the
  /// leaf's witness path, over the whole leaf: the value and gradient at the leaf's centre,
  /// the Hessian enclosed over the leaf (docs/certify.md "Tolerance", check 6); the plain
  /// enclosure over the leaf when the function is not smooth there.
  Interval second_order(const ToleranceLeaf& leaf, bool upper) const;

  /// A region of the subdivision tree: the part of box x range (x follower range) that leaf
  /// `leaf` is used for (inside the leaf's own box; the tree's regions partition the whole).
  struct Region {
    std::size_t leaf = 0;
    std::vector<RationalInterval> box;   ///< the varied parameters, the driver (, the follower)
  };
  /// Walks the subdivision tree: the leaves cover the box times the range (times the follower
  /// range for no_interference). Returns the regions in preorder. \throws Rejection.
  std::vector<Region> check_cover() const;

  /// no_jam, check 7 (docs/certify.md "Tolerance"): for every parameter vector of the box a
  /// free follower path crosses the whole driver range. Over every region the follower on its
  /// leaf's witness path y*(p, d), and at every driver value where one region ends and a
  /// neighbouring one continues, the follower's move between the two witness paths, keep the
  /// parts apart: apart at the region's centre (exact-rounded enclosures) and no first-contact
  /// event over it (free_path_check.cpp), the region bisected while undecided, at most
  /// `piece_budget` plus one per region times in all (session 66). Returns "" when proved,
  /// otherwise what was not proved.
  std::string free_path_failure(std::size_t piece_budget = 48) const;
  /// Check 7's test over one leaf's whole box with the follower on its witness path (for the
  /// producer, to choose leaves whose paths check 7 proves): "" when proved.
  /// `split` receives the dimension (a varied parameter's index, or the driver's: k) along which
  /// the undecided piece would have been bisected next, when the budget ran out.
  std::string free_leaf_failure(std::size_t leaf, std::size_t piece_budget,
                                std::optional<std::size_t>* split = nullptr,
                                std::optional<ContactSidePair>* event = nullptr) const;
  /// (`event`, when the undecided first-contact event is a vertex of one part on an edge of the
  /// other: that feature pair as a contact side — a candidate side for the producer to keep the
  /// witness path away from.)

  /// Whether this evaluator's check_leaf passed the witness test (checks 4 or 6) of exactly
  /// `leaf` (every field equal) at index `index`: what check 7 may then use of that leaf.
  bool witness_proved(std::size_t index, const ToleranceLeaf& leaf) const;

  /// no_interference: the claim's property.
  bool interference_claim() const { return claim_.property == "no_interference"; }
  /// no_interference: checks one leaf — every edge of the driver certainly apart from every
  /// edge of the follower over the whole leaf, and at the leaf's centre one vertex of every
  /// loop of each part certainly outside the other part. \throws Rejection with the reason.
  void check_apart(const ToleranceLeaf& leaf, std::size_t index) const;
  /// The same, returning the reason instead of throwing ("" when the leaf holds).
  std::string apart_failure(const ToleranceLeaf& leaf) const;

 private:
  template <class T>
  kernels::Vector<T> posed(const GeometryOf<T>& g, bool driver_part, const kernels::Vector<T>& point,
                           const T& coordinate) const;
  template <class T>
  const model_detail::EdgeValue<T>& edge(GeometryOf<T>& g, std::size_t part, const FeatureReference& f) const;
  template <class T>
  T contact_of(GeometryOf<T>& g, std::size_t pair, const T& driver, const T& follower) const;
  template <class T>
  void pose_pivots(GeometryOf<T>& g) const;
  // apart_failure; for a leaf that is a point (check 7's centres), `at_point` (when given) holds
  // the geometry at its varied parameters: evaluated on first use (when empty), its parametric
  // edges kept in it for the next call at the same parameters (free_path_check.cpp: every
  // region's and move's centre of a certificate whose leaves share one parameter box).
  std::string apart_failure(const ToleranceLeaf& leaf, std::optional<ToleranceGeometry>* at_point) const;
  // free_path_check.cpp
  class FreePath;
  friend class FreePath;

  std::shared_ptr<const model_detail::ParametricModel> model_;
  const ToleranceClaim& claim_;
  std::size_t driver_ = 0, follower_ = 0;
  bool driver_rotates_ = true, follower_rotates_ = true;
  std::vector<std::size_t> varied_;   ///< model parameter index per varied parameter
  /// Per leaf index: a copy of the leaf whose witness test (checks 4 or 6) this evaluator has
  /// passed, so that check 7 may use what it proved (its sides' contact functions of one certain
  /// sign along the witness path over the leaf) — only for that very leaf (every field compared).
  mutable std::vector<std::optional<ToleranceLeaf>> witness_proved_;
};

/// Checks a tolerance certificate against the model text (its hash already checked).
/// Returns the summary line. \throws Rejection.
/// A no_jam certificate whose checks 1-6 pass is proved only when check 7 (the free path) holds:
/// otherwise `not_proved` receives what was not proved (empty: proved).
std::string check_tolerance(const Certificate& certificate, const Model& model, std::string_view model_text,
                            std::string& not_proved);

/// For the verdict: the model's toleranced parameters that the claim does not vary (held at
/// their nominal values), as "; the model's other toleranced parameters (N: 'a', 'b', 'c' and K
/// more) are held at their nominal values", or empty when the claim varies every one.
std::string held_at_nominal(const Certificate& certificate, const Model& model);

}  // namespace hipair::verify
