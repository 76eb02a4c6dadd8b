// The sliced_connected certificate's producer (<hipair/sliced_certificate.hpp>): the sliced
// C-space's certified path between two poses of a planar part, turned into a staircase of pure
// translations and pure rotations about the part's pivot, each proved free by the verifier's own
// move check (verify::sliced_move_failure); a diagonal motion of the path (x, y and the angle
// changing together) is replaced by a translation and a rotation, in either order, and split in
// halves until both steps of each piece are proved. The finished certificate is re-checked.
#include "certificates/producer.hpp"
#include "certify/sliced_connected.hpp"
#include "core/model_scale.hpp"

#include <hipair/error.hpp>
#include <hipair/sliced.hpp>
#include <hipair/sliced_certificate.hpp>

namespace hipair {
namespace {

using namespace certify_detail;

// A pose's angle as the sliced space's exact angle: t = tan(theta/2), or the half turn.
SlicedAngle sliced_angle(const PlanarPose& pose) {
  if (!pose.half_turn) return SlicedAngle{pose.tangent, false};
  if (sgn(pose.tangent) == 0) return SlicedAngle{Rational(0), true};
  return SlicedAngle{Rational(-1 / pose.tangent), false};   // tan((theta - pi)/2) = -1 / tan(theta/2)
}

// The tangent of `angle` in the chart centred at 0 (`half_turn` false) or at pi.
Rational chart_tangent(const SlicedAngle& angle, bool half_turn) {
  if (!half_turn) {
    if (angle.half_turn) throw GeometryError("sliced_connected: the half turn lies outside the chart centred at 0");
    return angle.t;
  }
  if (angle.half_turn) return Rational(0);
  if (sgn(angle.t) == 0) throw GeometryError("sliced_connected: theta = 0 lies outside the chart centred at pi");
  return Rational(-1 / angle.t);
}

class Staircase {
 public:
  Staircase(const Part& fixed, const Part& planar, std::vector<PlanarPose>& path)
      : fixed_(fixed), planar_(planar), path_(path) {}

  // Appends moves from the last vertex to `to` (same chart as the last vertex after `rechart`).
  bool reach(const PlanarPose& to, int depth = 0) {
    const PlanarPose from = path_.back();
    const bool same_xy = from.x == to.x && from.y == to.y;
    if (same_xy || from.tangent == to.tangent) return step(to) || split(from, to, depth);
    // a diagonal move: a translation and a rotation, in either order
    PlanarPose corner = to;
    corner.tangent = from.tangent;
    if (try_steps(corner, to)) return true;
    corner = from;
    corner.tangent = to.tangent;
    if (try_steps(corner, to)) return true;
    return split(from, to, depth);
  }

  // Re-expresses the last vertex in the chart `half_turn` (a move at one pose).
  void rechart(bool half_turn) {
    const PlanarPose last = path_.back();
    if (last.half_turn == half_turn) return;
    PlanarPose p = last;
    p.half_turn = half_turn;
    p.tangent = chart_tangent(sliced_angle(last), half_turn);
    path_.push_back(p);
  }

  std::string failure;

 private:
  bool free(const PlanarPose& a, const PlanarPose& b) {
    std::string why = verify::sliced_move_failure(fixed_, planar_, a, b, trial_budget);
    if (!why.empty()) failure = why;
    return why.empty();
  }
  bool step(const PlanarPose& to) {
    if (!free(path_.back(), to)) return false;
    path_.push_back(to);
    return true;
  }
  bool try_steps(const PlanarPose& corner, const PlanarPose& to) {
    if (!free(path_.back(), corner) || !free(corner, to)) return false;
    path_.push_back(corner);
    path_.push_back(to);
    return true;
  }
  bool split(const PlanarPose& from, const PlanarPose& to, int depth) {
    if (depth >= max_depth) return false;
    PlanarPose middle = to;
    middle.x = (from.x + to.x) / 2;
    middle.y = (from.y + to.y) / 2;
    middle.tangent = (from.tangent + to.tangent) / 2;
    return reach(middle, depth + 1) && reach(to, depth + 1);
  }

  static constexpr std::size_t trial_budget = 4000;
  static constexpr int max_depth = 10;
  const Part& fixed_;
  const Part& planar_;
  std::vector<PlanarPose>& path_;
};

}  // namespace

namespace {

// The parts of a connected claim: `fixed` fixed, `planar` free in the plane without limits.
std::pair<const Part*, const Part*> connected_parts(const Model& model, const std::string& fixed, const std::string& planar) {
  const Part& fixed_part = part_of(model, fixed);
  const Part& planar_part = part_of(model, planar);
  if (fixed_part.motion.kind != Motion::Kind::fixed) throw GeometryError("sliced_connected: part '" + fixed + "' must be fixed");
  if (planar_part.motion.kind != Motion::Kind::planar)
    throw GeometryError("sliced_connected: part '" + planar + "' must be free in the plane (motion \"planar\")");
  if (planar_part.motion.angle_limits || planar_part.motion.translation_limits)
    throw GeometryError("sliced_connected: part '" + planar + "' has motion limits");
  return {&fixed_part, &planar_part};
}

// A certificate produced on the pair moved to the origin (verify::connected_pair_at_origin: the
// pivot at the origin, a pair far from it for its size first moved by pair_moved_to_origin), as
// the verifier checks it: the claim's poses are relative (moving both parts moves
// the pivot with them), so the same certificate holds of the model as given; re-checked on it.
SlicedConnectedResult checked_as_given(SlicedConnectedResult result, const Model& model) {
  if (result.certificate) {
    VerificationResult check = check_sliced_connected(*result.certificate, model);
    if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
  }
  return result;
}

}  // namespace

SlicedConnectedResult certify_sliced_path(const Model& model, const std::string& fixed, const std::string& planar,
                                          const SlicedPath& sliced, const CertifyContext& context) {
  auto [fixed_part, planar_part] = connected_parts(model, fixed, planar);
  if (std::optional<Model> moved = verify::connected_pair_at_origin(model, fixed, planar))
    return checked_as_given(certify_sliced_path(*moved, fixed, planar, sliced, context), model);
  SlicedConnectedResult result;
  result.sliced_waypoints = sliced.waypoints.size();
  if (sliced.status != SlicedPath::Status::found || sliced.waypoints.empty() ||
      sliced.through_half_turn.size() + 1 != sliced.waypoints.size())
    throw GeometryError("sliced_connected: a path needs status found and one chart flag per motion");
  auto pose_of = [&](const SlicedConfiguration& q, bool chart) {
    return PlanarPose{planar, q.x, q.y, chart_tangent(q.angle, chart), chart, std::nullopt};
  };
  const SlicedConfiguration &first = sliced.waypoints.front(), &last = sliced.waypoints.back();
  const bool first_chart = sliced.through_half_turn.empty() ? first.angle.half_turn : bool(sliced.through_half_turn.front());
  SlicedConnectedCertificate c;
  c.envelope = start_certificate(model, context, ClaimKind::planar_clearance, fixed, planar);
  c.from = pose_of(first, first.angle.half_turn);
  c.to = pose_of(last, last.angle.half_turn);
  c.path.push_back(pose_of(first, first_chart));
  Staircase staircase(*fixed_part, *planar_part, c.path);
  for (std::size_t k = 0; k + 1 < sliced.waypoints.size(); ++k) {
    const bool chart = sliced.through_half_turn[k];
    staircase.rechart(chart);
    if (!staircase.reach(pose_of(sliced.waypoints[k + 1], chart))) {
      result.failure = "motion " + std::to_string(k) + " of the sliced path: no staircase of pure translations and rotations "
                       "was proved free near it (" + staircase.failure + ")";
      return result;
    }
  }
  staircase.rechart(c.to.half_turn);
  c.envelope.statement = sliced_connected_statement(c);
  VerificationResult check = check_sliced_connected(c, model);
  if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
  result.certificate = std::move(c);
  return result;
}

SlicedConnectedResult certify_sliced_connected(const Model& model, const std::string& fixed, const PlanarPose& from,
                                               const PlanarPose& to, const CertifyContext& context) {
  if (to.part != from.part) throw ModelError("", "sliced_connected: both poses must be of one part");
  connected_parts(model, fixed, from.part);
  if (std::optional<Model> moved = verify::connected_pair_at_origin(model, fixed, from.part))
    return checked_as_given(certify_sliced_connected(*moved, fixed, from, to, context), model);
  SlicedSpace space = SlicedSpace::build(model, fixed, from.part);
  SlicedPath sliced = space.path(SlicedConfiguration{from.x, from.y, sliced_angle(from)}, SlicedConfiguration{to.x, to.y, sliced_angle(to)});
  SlicedConnectedResult result;
  result.sliced_waypoints = sliced.waypoints.size();
  switch (sliced.status) {
    case SlicedPath::Status::found: break;
    case SlicedPath::Status::not_free:
      result.failure = "an end is not a free configuration (the parts touch or overlap there)";
      return result;
    case SlicedPath::Status::not_connected:
      result.failure = "the ends lie in different components of the sliced free space (not certified here: "
                       "`--claim apart` certifies a separation)";
      return result;
    case SlicedPath::Status::not_found:
      result.failure = "the sliced C-space found no path between the ends (they are connected)";
      return result;
  }
  result = certify_sliced_path(model, fixed, from.part, sliced, context);
  if (result.certificate) {
    // the claim in the representation asked for (the same poses)
    SlicedConnectedCertificate& c = *result.certificate;
    c.from = from;
    c.to = to;
    if (c.path.front().half_turn != from.half_turn) c.path.insert(c.path.begin(), from);
    if (c.path.back().half_turn != to.half_turn) c.path.push_back(to);
    c.envelope.statement = sliced_connected_statement(c);
    VerificationResult check = check_sliced_connected(c, model);
    if (!check.valid) throw NumericError("the certificate produced does not pass its own check: " + check.reason);
  }
  return result;
}

}  // namespace hipair
