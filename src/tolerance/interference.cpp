// The producer of "never interferes" tolerance certificates (hipair/tolerance.hpp
// certify_no_interference; docs/certify.md "Tolerance", property no_interference). Interval
// branch-and-bound over the varied parameters x the driver range x the follower range: a box is
// a leaf when the verifier's own leaf check (certify/tolerance_check.hpp, apart_failure) passes;
// otherwise its centre is tested exactly (the exact model at the centre's rational parameters,
// the parts placed by rational rotations inside the box, the exact overlap predicate) and, if the
// parts do not overlap there, the box is split. The producer chooses (split dimensions, the
// doubles it uses to rank them); it decides nothing: the certificate is re-checked from its JSON
// text, and an interference is reported only with an exact witness.
#include "certify/tolerance_check.hpp"
#include "tolerance/certificate.hpp"
#include "model/parametric/parametric.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>
#include <hipair/tolerance.hpp>

#include <mpfi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

namespace hipair {
namespace {

using verify::Interval;

using tolerance_detail::seconds_since;

// x rounded down to a multiple of 10^-12 (short rationals for the exact witness's tangents).
Rational grid(double x) {
  Rational q(mpz_class(std::floor(x * 1e12)), mpz_class("1000000000000"));
  q.canonicalize();
  return q;
}

// Whether 2 atan(t) lies certainly inside [lo, hi] (MPFI).
bool angle_inside(const Rational& t, const RationalInterval& range) {
  Interval a(t);
  mpfi_atan(a.get(), a.get());
  a = Interval(Rational(2)) * a;
  return (a - verify::enclose(range.lo)).sign() > 0 && (verify::enclose(range.hi) - a).sign() > 0;
}

class InterferenceProducer {
 public:
  InterferenceProducer(std::string_view text, const InterferenceCertifyOptions& options, std::string source)
      : options_(options), text_(text), source_(std::move(source)) {
    model_ = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
    const Model& m = model_->nominal();
    auto part = [&](const std::string& name, const char* role) {
      std::optional<std::size_t> k = m.find_part(name);
      if (!k) throw ModelError("/parts", std::string("no ") + role + " part '" + name + "' in the model");
      return *k;
    };
    driver_ = part(options.driver, "driver");
    follower_ = part(options.follower, "follower");
    if (!(options.driver_range.lo < options.driver_range.hi))
      throw ModelError("", "the driver range [" + to_exact_string(options.driver_range.lo) + ", " +
                               to_exact_string(options.driver_range.hi) + "] is empty");
    if (!(options.follower_range.lo <= options.follower_range.hi))
      throw ModelError("", "the follower range [" + to_exact_string(options.follower_range.lo) + ", " +
                               to_exact_string(options.follower_range.hi) + "] is empty");
    if (!(options.scale > 0)) throw ModelError("", "the certificate's tolerance scale must be positive");
    if (options.vary.empty()) {
      for (std::size_t i = 0; i < m.parameters.size(); ++i)
        if (m.parameters[i].range.lo < m.parameters[i].range.hi) varied_.push_back(i);
    } else {
      for (const std::string& name : options.vary) {
        const Parameter* p = m.find_parameter(name);
        if (!p) throw ModelError("/parameters", "unknown parameter '" + name + "' to vary");
        if (!(p->range.lo < p->range.hi)) throw ModelError("/parameters", "parameter '" + name + "' has no tolerance to vary");
        varied_.push_back(static_cast<std::size_t>(p - m.parameters.data()));
      }
    }
    if (varied_.empty()) throw ModelError("/parameters", "no toleranced parameter to certify over");
    claim_.property = "no_interference";
    claim_.driver = m.parts[driver_].name;
    claim_.follower = m.parts[follower_].name;
    claim_.range = options.driver_range;
    claim_.follower_range = options.follower_range;
    claim_.scale = options.scale;
    for (std::size_t i : varied_) {
      const Parameter& p = m.parameters[i];
      claim_.varied.push_back(p.name);
      claim_.box.push_back({options.scale * (p.range.lo - p.nominal), options.scale * (p.range.hi - p.nominal)});
    }
    levers_ = split_levers();
  }

  ToleranceCertification run() {
    auto start = std::chrono::steady_clock::now();
    ToleranceCertification result;
    result.scale = options_.scale;
    try {
      evaluator_ = std::make_unique<verify::ToleranceEvaluator>(model_, claim_);
    } catch (const verify::Rejection& rejection) {
      throw ModelError("", "cannot certify: " + rejection.reason);
    }
    std::vector<RationalInterval> region = claim_.box;
    region.push_back(claim_.range);
    region.push_back(*claim_.follower_range);
    Status status = solve(region, 0);
    result.leaves = claim_.leaves.size();
    result.attempts = attempts_;
    result.seconds_produce = seconds_since(start);
    if (status == Status::interferes) {
      result.outcome = ToleranceCertification::Outcome::interferes;
      result.reason = reason_;
      result.witness_parameters = witness_parameters_;
      result.witness_driver = witness_driver_;
      result.witness_follower = witness_follower_;
      return result;
    }
    if (status != Status::ok) {
      result.reason = reason_;
      return result;
    }
    tolerance_detail::CheckedCertificate checked =
        tolerance_detail::checked_tolerance_certificate(model_->nominal(), claim_, text_, source_);
    result.seconds_verify = checked.seconds_verify;
    if (!checked.check.valid)
      throw GeometryError("no-interference certificate failed its own check (a producer bug): " + checked.check.reason);
    result.outcome = ToleranceCertification::Outcome::certified;
    result.certificate = std::move(checked.certificate);
    return result;
  }

 private:
  enum class Status { ok, interferes, undecided };

  // The lever of every dimension of the search (the varied parameters, the driver, the
  // follower), for ranking splits only: how far (mm, the largest coordinate change) a point of
  // the two parts moves per unit of the dimension. A rotating part's: its reach from its pivot;
  // a translating part's: 1. A varied parameter's: the largest secant slope over the parts'
  // vertices, arc centres and pivots between the nominal and the exact model at the box's end
  // (a parameter that moves nothing of the pair has lever 0 and is not split). Exact rationals,
  // so that the ranking is the same at every scale of the model (a length written "(x)*1e-300"
  // or a parameter of 1e-300 mm moves the geometry by as little, and is split as its unscaled
  // model's would be; doubles underflow there).
  std::vector<Rational> split_levers() const {
    const Model& m = model_->nominal();
    std::size_t k = varied_.size();
    std::vector<Rational> levers(k + 2, Rational(0));
    auto largest = [](const Point& a, const Point& b) {
      Rational dx = abs(Rational(a.x - b.x)), dy = abs(Rational(a.y - b.y));
      return dx < dy ? dy : dx;
    };
    auto points = [](const Part& part) {
      std::vector<Point> all{part.motion.pivot};
      for (const Loop& loop : part.loops)
        for (const Edge& e : loop.edges) {
          all.push_back(e.source);
          all.push_back(e.target);
          if (e.is_arc()) all.push_back(e.center);
        }
      return all;
    };
    for (std::size_t i = 0; i < k; ++i) {
      const RationalInterval& range = claim_.box[i];
      Rational step = range.hi != 0 ? range.hi : range.lo;
      if (step == 0) continue;
      std::vector<Rational> deviations(model_->parameter_count(), Rational(0));
      deviations[varied_[i]] = step;
      Model moved;
      try {
        moved = model_->exact_model(deviations);
      } catch (const ModelError&) {
        continue;   // the geometry is invalid at the box's end: ranked as moving nothing
      }
      Rational most(0);
      for (std::size_t part : {driver_, follower_}) {
        std::vector<Point> a = points(m.parts[part]), b = points(moved.parts[part]);
        if (a.size() != b.size()) continue;
        for (std::size_t j = 0; j < a.size(); ++j) most = std::max(most, largest(a[j], b[j]));
      }
      levers[i] = most / abs(step);
    }
    auto reach = [&](std::size_t index) {
      const Part& part = m.parts[index];
      if (part.motion.kind != Motion::Kind::rotation) return Rational(1);
      Rational most(0);
      for (const Point& q : points(part)) most = std::max(most, largest(q, part.motion.pivot));
      return most;
    };
    levers[k] = reach(driver_);
    levers[k + 1] = reach(follower_);
    return levers;
  }

  // An exact position of a part inside `range` near its middle, and its placement in the
  // exact model. False when no rational rotation was found certainly inside the range.
  bool position(const Model& exact, std::size_t part, const RationalInterval& range, ExactPosition& where,
                Placement& placement) const {
    const Motion& motion = exact.parts[part].motion;
    Rational middle = (range.lo + range.hi) / 2;
    if (motion.kind == Motion::Kind::translation) {
      where.value = middle;
      where.is_offset = true;
      placement = placement_about(motion.pivot, 1, 0, Point{middle * motion.direction.x, middle * motion.direction.y});
      return true;
    }
    double angle = middle.get_d();
    if (std::fabs(angle) >= 3.1) return false;   // half-angle tangents near +-pi: not needed here
    Rational t = grid(std::tan(angle / 2));
    if (range.lo == range.hi) {
      // A single angle: its tangent must be exact (rational) for an exact witness.
      if (!(range.lo == 0)) return false;
      t = 0;
    } else if (!angle_inside(t, range)) {
      return false;
    }
    where.value = t;
    Rational d = 1 + t * t;
    placement = placement_about(motion.pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
    return true;
  }

  // The exact check at the region's centre: overlapping parts there are a witness.
  bool interferes_at_centre(const std::vector<RationalInterval>& region) {
    std::size_t k = varied_.size();
    std::vector<Rational> deviations(model_->parameter_count(), Rational(0));
    for (std::size_t i = 0; i < k; ++i) deviations[varied_[i]] = (region[i].lo + region[i].hi) / 2;
    Model exact;
    try {
      exact = model_->exact_model(deviations);
    } catch (const ModelError&) {
      return false;   // the geometry is invalid there: no witness
    }
    ExactPosition wd, wf;
    Placement pd, pf;
    if (!position(exact, driver_, region[k], wd, pd) || !position(exact, follower_, region[k + 1], wf, pf)) return false;
    PartOverlap overlap = part_overlap(exact.parts[driver_], pd, exact.parts[follower_], pf);
    if (overlap.relation != PartRelation::overlapping) return false;
    witness_parameters_.clear();
    for (std::size_t i = 0; i < k; ++i) witness_parameters_.emplace_back(claim_.varied[i], deviations[varied_[i]]);
    witness_driver_ = wd;
    witness_follower_ = wf;
    auto text = [&](const ExactPosition& p) {
      return p.is_offset ? "offset " + to_exact_string(p.value) + " mm"
                         : "tan(angle/2) = " + to_exact_string(p.value) + " (angle " +
                               std::to_string(2 * std::atan(p.value.get_d())) + " rad)";
    };
    reason_ = "the parts overlap (exact predicate on the exact model) with '" + claim_.driver + "' at " + text(wd) +
              " and '" + claim_.follower + "' at " + text(wf) + ", at the parameter deviations";
    for (const auto& [name, value] : witness_parameters_) reason_ += " " + name + "=" + to_exact_string(value);
    return true;
  }

  Status solve(const std::vector<RationalInterval>& region, int depth) {
    if (attempts_ >= 4 * options_.max_leaves || claim_.leaves.size() >= options_.max_leaves) {
      reason_ = "the branch-and-bound gave up after " + std::to_string(attempts_) + " boxes (" +
                std::to_string(claim_.leaves.size()) + " leaves certified)";
      return Status::undecided;
    }
    ++attempts_;
    std::size_t k = varied_.size();
    ToleranceLeaf leaf;
    leaf.parameters.assign(region.begin(), region.begin() + static_cast<std::ptrdiff_t>(k));
    leaf.driver = region[k];
    leaf.follower = region[k + 1];
    std::string failure = evaluator_->apart_failure(leaf);
    if (failure.empty()) {
      ToleranceTreeNode node;
      node.leaf = true;
      node.index = claim_.leaves.size();
      claim_.tree.push_back(node);
      claim_.leaves.push_back(std::move(leaf));
      return Status::ok;
    }
    // The exact test at the centre: always where the interval check saw a loop inside the other
    // part, else at every fourth level (it costs an exact model).
    if ((failure.find("interfere") != std::string::npos || depth % 4 == 0) && interferes_at_centre(region))
      return Status::interferes;
    if (depth > 300) {
      reason_ = "the branch-and-bound reached depth 300 without certifying a box: " + failure;
      return Status::undecided;
    }
    // Split the dimension that moves the geometry most (mm): its width times its lever
    // (split_levers), compared exactly.
    std::size_t best = 0;
    std::optional<Rational> score;
    for (std::size_t d = 0; d < k + 2; ++d) {
      if (!(region[d].lo < region[d].hi)) continue;
      Rational moves = Rational(region[d].hi - region[d].lo) * levers_[d];
      if (!score || moves > *score) {
        score = moves;
        best = d;
      }
    }
    Rational cut = (region[best].lo + region[best].hi) / 2;
    ToleranceTreeNode node;
    node.dimension = best == k ? "driver" : best == k + 1 ? "follower" : claim_.varied[best];
    node.value = cut;
    claim_.tree.push_back(node);
    std::vector<RationalInterval> low = region, high = region;
    low[best].hi = cut;
    high[best].lo = cut;
    Status s = solve(low, depth + 1);
    if (s != Status::ok) return s;
    return solve(high, depth + 1);
  }

  const InterferenceCertifyOptions& options_;
  std::string text_, source_;
  std::shared_ptr<const model_detail::ParametricModel> model_;
  std::size_t driver_ = 0, follower_ = 0;
  std::vector<std::size_t> varied_;
  std::vector<Rational> levers_;   // split_levers()
  ToleranceClaim claim_;
  std::unique_ptr<verify::ToleranceEvaluator> evaluator_;
  std::size_t attempts_ = 0;
  std::string reason_;
  std::vector<std::pair<std::string, Rational>> witness_parameters_;
  std::optional<ExactPosition> witness_driver_, witness_follower_;
};

}  // namespace

ToleranceCertification certify_no_interference_text(std::string_view json_text, const InterferenceCertifyOptions& options,
                                                    const std::string& source_name) {
  return InterferenceProducer(json_text, options, source_name).run();
}

ToleranceCertification certify_no_interference(const std::filesystem::path& model_file,
                                               const InterferenceCertifyOptions& options) {
  std::error_code error;
  if (std::filesystem::is_directory(model_file, error))
    throw IoError("cannot read model file '" + model_file.string() + "': it is a directory");
  std::ifstream file(model_file, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + model_file.string() + "'");
  std::ostringstream content;
  content << file.rdbuf();
  return certify_no_interference_text(content.str(), options, model_file.filename().string());
}

}  // namespace hipair
