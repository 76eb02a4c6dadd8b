// Kinematic tolerance analysis of an assembly chain (ToleranceOptions::chain; docs/tolerance.md
// "Assembly chains"): driver -> pair 1 -> part -> pair 2 -> ... -> output. The nominal motion of
// every part comes from the kinematic analysis of the whole model; each pair is then analysed at
// the chain's positions like a single pair (stage.hpp: exact slices of its nominal C-space, the
// feature pair holding its follower, the parametric contact curve) or, on the kernel path
// (chains of rotations without limits: gear trains), from the kinematics sliced from the contact
// kernels and the touching feature pair the exact engine names (kernel_stage; no C-space built
// unless that feature pair is not unique), and the pairs are composed:
//   - sensitivities by the chain rule, d out/dp = df_k/dp + df_k/dx_k . d x_k/dp, where x_k (the
//     pair's driver) is the previous pair's output;
//   - the linearised and RSS bands from the composed sensitivities;
//   - the certified band by interval composition: each pair's certified enclosure over the whole
//     tolerance box, its driver ranging over the previous pair's enclosure (no linearisation;
//     the driver's range enters the pair's mean-value form like a parameter: solver.cpp box_range),
//     the box bisected along parameters that act on several pairs (certified()) so that they
//     vary together; and (session 22, ToleranceOptions::mean_value_chain) in mean-value form,
//     each pair's output at the box's centre plus its total derivatives over the box (the chain
//     rule over the pairs' -F_p/F_v and -F_t/F_v) times the box, intersected with the interval
//     composition (compose_over; a box so composed through the last pair is not bisected);
//   - Monte Carlo: at each sampled vector, each pair's follower where the actual contact puts
//     it (the first contact it meets among its nominal holder and the neighbouring holders along
//     the path: a tooth hand-over inside the box followed; monte_carlo, actual_root), certified
//     (interval bisection), its driver ranging over the previous pair's certified value there.
#include "core/model_scale.hpp"
#include "model/parametric/dimensions.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/handover.hpp"
#include "tolerance/mean_value.hpp"
#include "tolerance/progress.hpp"
#include "tolerance/root_search.hpp"
#include "tolerance/stage.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>

namespace hipair::tolerance_detail {
namespace {

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool moving(const Model& m, std::size_t k) {
  auto kind = m.parts[k].motion.kind;
  return kind == Motion::Kind::rotation || kind == Motion::Kind::translation;
}

// The chain's parts: the driver, then each part moved through a pair by the one before it, up to
// the output (options.follower, or the part furthest from the driver; breadth first over the
// pairs of two moving parts, ties in model order).
std::vector<std::size_t> chain_parts(const Model& m, const ToleranceOptions& options) {
  std::optional<std::size_t> driver;
  if (!options.driver.empty()) {
    driver = m.find_part(options.driver);
    if (!driver) throw ModelError("", "unknown driver part '" + options.driver + "' (--driver)");
    if (!moving(m, *driver)) throw ModelError("", "the driver '" + options.driver + "' neither rotates nor translates");
  } else {
    for (const PairSpec& pair : m.pairs)
      if (moving(m, pair.first) && moving(m, pair.second)) {
        driver = pair.first;
        break;
      }
    if (!driver) throw ModelError("/pairs", "no pair of two moving parts to analyse");
  }
  std::vector<std::size_t> parent(m.parts.size(), no_index);
  std::vector<bool> seen(m.parts.size(), false);
  std::deque<std::size_t> queue{*driver};
  seen[*driver] = true;
  std::size_t last = *driver;
  while (!queue.empty()) {
    std::size_t part = queue.front();
    queue.pop_front();
    last = part;
    for (const PairSpec& pair : m.pairs) {
      if (!moving(m, pair.first) || !moving(m, pair.second)) continue;
      std::size_t other = pair.first == part ? pair.second : pair.second == part ? pair.first : no_index;
      if (other == no_index || seen[other]) continue;
      seen[other] = true;
      parent[other] = part;
      queue.push_back(other);
    }
  }
  std::size_t output = last;
  if (!options.follower.empty()) {
    std::optional<std::size_t> f = m.find_part(options.follower);
    if (!f) throw ModelError("", "unknown part '" + options.follower + "' (--pair)");
    if (!seen[*f] || *f == *driver)
      throw ModelError("", "the part '" + options.follower + "' is not moved by the driver '" + m.parts[*driver].name +
                               "' through pairs of moving parts");
    output = *f;
  }
  if (output == *driver) throw ModelError("/pairs", "the driver '" + m.parts[*driver].name + "' moves no other part");
  std::vector<std::size_t> parts;
  for (std::size_t k = output; k != no_index; k = parent[k]) parts.push_back(k);
  std::reverse(parts.begin(), parts.end());
  return parts;
}

// Part coordinate enclosure -> chart enclosure (the inverse of to_part): the offset of a
// translation; tan((theta - c)/2) of a rotation, c = 0 or pi (the half-turn chart), theta
// reduced by whole turns near `nominal`. False when the range reaches the chart's pole.
bool part_to_chart(const Interval& x, bool rotates, bool half, double nominal, Interval& t) {
  if (!rotates) {
    t = x;
    return true;
  }
  using A = model_detail::Arithmetic<Interval>;
  Interval centre = half ? A::pi() : Interval(0);
  double turns = std::round((nominal - (half ? std::numbers::pi : 0.0)) / (2 * std::numbers::pi));
  Interval y = x - centre - Interval::point(turns) * (Interval(2) * A::pi());
  if (!(y.lo > -3.0 && y.hi < 3.0)) return false;   // within (-pi, pi), away from the pole
  t = A::tan(y * Interval::point(0.5));   // (Interval(0.5) would be the integer 0)
  return true;
}

// The chart value of a rotation's coordinate (rad) in the layout of a rotation without angle
// limits (two charts, t in [-1, 1] about 0 and about pi, in that order): the first chart holding
// it, as CSpace::to_chart chooses (src/cspace/cspace.cpp), and the same exact rational.
struct RotationChart {
  Rational t;
  bool half = false;
};
RotationChart rotation_chart(double coordinate) {
  double wrapped = std::remainder(coordinate, 2 * std::numbers::pi);
  if (std::fabs(wrapped) == std::numbers::pi) return {Rational(0), true};
  Rational t(std::tan(wrapped / 2));
  t.canonicalize();
  if (t >= -1 && t <= 1) return {t, false};
  Rational u = -1 / t;   // tan((theta - pi)/2) = -cot(theta/2); |t| > 1 so u is in [-1, 1]
  return {u, true};
}

// The class the kernel path handles: every part of the chain rotates without angle limits.
bool rotations_without_limits(const Model& m, const std::vector<std::size_t>& parts) {
  return std::all_of(parts.begin(), parts.end(), [&](std::size_t k) {
    return m.parts[k].motion.kind == Motion::Kind::rotation && !m.parts[k].motion.angle_limits;
  });
}

// What the hand-over envelopes did at one position (over all its sub-boxes).
struct HandoverNote {
  bool extended = false;   // some pair's band widened by another feature pair taking over
  std::string why;         // why a pair's envelope was not bounded
};

struct PositionStage {
  double fixed_slope = 0;            // dv/d(driver chart), chart units
  double driver_factor = 0;          // d follower / d driver, part units
  std::vector<double> s_part;        // d follower / dp at a fixed driver, part units
  Interval certified_chart;          // enclosure of the follower's chart coordinate over the box
};

class ChainAnalysis {
 public:
  ChainAnalysis(std::string_view text, const ToleranceOptions& options, const ChainPaths& paths,
                std::vector<long>* exponents = nullptr)
      : text_(text), options_(options), paths_(paths), exponents_(exponents) {
    if (options.threshold || options.certify || options.contact_changes)
      throw ModelError("", "the jamming threshold, tolerance certificates and contact changes are analysed per pair "
                           "(--pair), not over an assembly chain");
  }

  ToleranceResult run() {
    bar_.begin(0);
    auto t0 = std::chrono::steady_clock::now();
    // The model is read once: the kinematics, the C-spaces and the parametric form (every
    // pair's) take this one.
    model_detail::ParametricModel::Nominal nominal =
        model_detail::ParametricModel::read_nominal(text_, "<string>", design_read_options(options_));
    // a mechanism at an extreme scale: analysed in units of 10^E mm (analysed_form, stage.hpp)
    const long exponent = kinematic_decimal_exponent(*nominal.model);
    const Model scaled = exponent != 0 ? decimal_scaled_model(*nominal.model, exponent) : Model();
    const Model& model = exponent != 0 ? scaled : *nominal.model;
    length_exponent_ = exponent;
    std::vector<std::size_t> parts = chain_parts(model, options_);
    bar_.begin(1);
    KinematicsOptions k;
    k.driver = model.parts[parts.front()].name;
    k.range = range_in_unit(options_, model.parts[parts.front()].motion.kind == Motion::Kind::rotation, exponent);
    k.steps_per_cycle = static_cast<unsigned>(std::max<std::size_t>(8, options_.positions));
    k.reversal = false;
    k.progress = bar_.within();
    // Kernel path (ChainPaths::kernel_kinematics; rotations without limits): the whole model's
    // kinematics sliced from the contact kernels, exact, with no C-space built; the engine names
    // the feature pairs touching at each position exactly. Otherwise, and for a pair whose
    // touching feature pair is not unique somewhere, the exact C-space of the pair (the kinematic
    // engine's C-space slices, as for a single pair); pairs with a fixed part are sliced from the
    // contact kernels (exact too). Each C-space is built once: the pairs' analyses below slice
    // the same spaces.
    const bool kernel = paths_.kernel_kinematics && rotations_without_limits(model, parts);
    // The parametric model, recorded once for every pair from the model read (on the kernel
    // path here, and a model without the generic form refused before any slicing; otherwise
    // when the first pair is analysed).
    std::shared_ptr<const model_detail::ParametricModel> parametric;
    auto parametric_model = [&]() {
      if (parametric) return parametric;
      parametric = analysed_form(model_detail::ParametricModel::read(text_, "<string>", design_read_options(options_), nominal),
                                 options_);
      parametric->require_generic();
      return parametric;
    };
    if (kernel) parametric_model();
    k.method = kernel ? SliceMethod::kernels : SliceMethod::automatic;
    std::deque<CSpace> spaces;   // (a deque: pointers to built spaces stay valid)
    std::vector<std::pair<std::size_t, std::size_t>> space_parts;
    if (!kernel)
      for (const PairSpec& pair : model.pairs)
        if (moving(model, pair.first) && moving(model, pair.second)) {
          spaces.push_back(CSpace::build(model, model.parts[pair.first].name, model.parts[pair.second].name));
          space_parts.emplace_back(pair.first, pair.second);
        }
    auto space_of = [&](std::size_t a, std::size_t b) -> const CSpace* {
      for (std::size_t k = 0; k < spaces.size(); ++k)
        if (space_parts[k] == std::pair(a, b) || space_parts[k] == std::pair(b, a)) return &spaces[k];
      if (!kernel) return nullptr;
      for (const PairSpec& pair : model.pairs)
        if ((pair.first == a && pair.second == b) || (pair.first == b && pair.second == a)) {
          spaces.push_back(CSpace::build(model, model.parts[pair.first].name, model.parts[pair.second].name));
          space_parts.emplace_back(pair.first, pair.second);
          return &spaces.back();
        }
      return nullptr;
    };
    KinematicsResult kinematics =
        analyze_kinematics(model, k, kernel ? std::vector<CSpace>{} : std::vector<CSpace>(spaces.begin(), spaces.end()));

    if (kinematics.jam) notes_.push_back("the nominal mechanism jams: " + kinematics.jam->description);
    auto follower_index = [&](std::size_t part) {
      auto it = std::find(kinematics.followers.begin(), kinematics.followers.end(), model.parts[part].name);
      if (it == kinematics.followers.end())
        throw GeometryError("the part '" + model.parts[part].name + "' is not moved by the driver over the range");
      return static_cast<std::size_t>(it - kinematics.followers.begin());
    };
    bar_.begin(2);
    // Each pair at the chain's positions.
    for (std::size_t s = 1; s < parts.size(); ++s) {
      bar_.units(s - 1, parts.size() - 1);
      const std::string& a = model.parts[parts[s - 1]].name;
      const std::string& b = model.parts[parts[s]].name;
      std::size_t fi = follower_index(parts[s]);
      std::optional<std::size_t> di;
      if (s > 1) di = follower_index(parts[s - 1]);
      std::vector<StagePosition> path;
      std::vector<const ContactLabel*> touching;   // kernel path: the one feature pair holding the follower
      std::vector<double> play;
      std::size_t not_unique = 0;
      for (const KinematicSample& ks : kinematics.samples) {
        StagePosition p;
        p.driver = di ? ks.positions[*di] : ks.driver;
        p.follower = ks.positions[fi];
        const ContactLabel* found = nullptr;
        std::size_t count = 0;
        for (const ContactLabel& c : ks.contacts[fi])
          if (!c.limit && (c.pair == a + ":" + b || c.pair == b + ":" + a)) {
            found = &c;
            ++count;
          }
        p.contact = count > 0;
        if (p.contact && (count > 1 || found->first.part == no_index || found->second.part == no_index)) ++not_unique;
        touching.push_back(count == 1 ? found : nullptr);
        play.push_back(std::isfinite(ks.play[fi]) ? ks.play[fi] : -1.0);
        path.push_back(p);
      }
      // The Monte Carlo's start (monte_carlo): an unloaded follower keeps its position while
      // free, so where the train starts with it free (the backlash not yet taken up) it waits
      // there until a contact meets it.
      bool unloaded = fi < kinematics.loads.size() && kinematics.loads[fi].kind == FollowerLoad::Kind::none;
      free_start_.push_back(unloaded && !path.empty() && !path.front().contact ? std::optional<double>(path.front().follower)
                                                                                 : std::nullopt);
      unloaded_.push_back(unloaded);
      ToleranceOptions stage_options = options_;
      stage_options.driver = a;
      stage_options.follower = b;
      stage_options.chain = false;
      stage_options.progress = nullptr;
      if (kernel && not_unique == 0 && !paths_.cspace_lookup) {
        stages_.push_back(kernel_stage(parametric, parts[s - 1], parts[s], path, touching, play, s - 1));
      } else {
        if (kernel && not_unique > 0)
          notes_.push_back("pair " + a + ":" + b + ": the touching feature pair is not unique at " +
                           std::to_string(not_unique) + " position(s): the pair's C-space was built");
        stages_.push_back(
            analyze_stage(text_, parametric_model(), stage_options, path, space_of(parts[s - 1], parts[s])));
      }
      // One solver per pair, each memoising its sub-boxes' geometry at every position: bounded
      // small (pure memos: the same results; docs/performance.md "Session 43 (tol43)").
      stages_.back().solver->limit_memos(chain_memo_entries());
      ChainStage summary;
      summary.driver = a;
      summary.follower = b;
      summary.driver_rotates = stages_.back().result.driver_rotates;
      summary.follower_rotates = stages_.back().result.follower_rotates;
      for (const StageContact& c : stages_.back().contacts) summary.contact_positions += c.contact ? 1 : 0;
      result_.chain.push_back(summary);
      for (const std::string& note : stages_.back().result.notes) notes_.push_back("pair " + a + ":" + b + ": " + note);
    }
    for (std::size_t s = 1; s < parts.size(); ++s) {
      handovers_.push_back(std::make_unique<HandoverSearch>(stages_[s - 1].solver, parts[s - 1], parts[s]));
      handovers_.back()->set_disabled(!envelope_on());
    }
    const StageAnalysis& first = stages_.front();
    const StageAnalysis& last = stages_.back();
    result_.model_name = first.result.model_name;
    result_.length_exponent = length_exponent_;
    result_.driver = first.result.driver;
    result_.follower = last.result.follower;
    result_.driver_rotates = first.result.driver_rotates;
    result_.follower_rotates = last.result.follower_rotates;
    result_.parameters = first.result.parameters;
    result_.sigma = first.result.sigma;
    result_.mean_shift = first.result.mean_shift;
    // the parameters' scale exponents of the form the pairs ran on, for the reports (session 70:
    // analyze() read and rescaled the model a second time for them)
    if (exponent != 0 && exponents_) *exponents_ = model_detail::parameter_scale_exponents(*parametric_model());
    compose();
    result_.seconds_sensitivity = wall_since(t0);
    bar_.begin(3);
    auto t1 = std::chrono::steady_clock::now();
    double c1 = cpu_now();
    if (paths_.certified_band) certified();
    result_.seconds_certified = wall_since(t1);
    result_.cpu_seconds_certified = cpu_now() - c1;
    bar_.begin(4);
    if (options_.monte_carlo > 0 && paths_.certified_band) monte_carlo();
    result_.notes.insert(result_.notes.end(), notes_.begin(), notes_.end());
    // the certified band's budgets (tolerance.json `budgets`, session 72)
    result_.budgets.emplace_back("chain_failure_boxes", static_cast<double>(std::max<std::size_t>(options_.chain_failure_boxes, 1)));
    result_.budgets.emplace_back("chain_shared_boxes", static_cast<double>(max_shared_boxes));
    result_.budgets.emplace_back("chain_held_pieces", static_cast<double>(max_held_pieces));
    if (envelope_on()) {   // the hand-over walks' reach
      result_.budgets.emplace_back("handover_far_windows", static_cast<double>(handover_far_windows()));
      result_.budgets.emplace_back("handover_driver_pieces", static_cast<double>(handover_driver_pieces()));
    }
    bar_.finish();
    return std::move(result_);
  }

 private:

  // A pair of the chain on the kernel path (rotations without limits; every touching feature
  // pair unique): what analyze_stage computes from the pair's C-space slices, from the exact
  // kinematics instead. At each position where the engine found the follower touching, the
  // feature pair it named holds the follower (exact: the kernel slicer's slice point at the
  // follower's exact position, the only feature pair vanishing there); the charts are the ones
  // CSpace::to_chart chooses, the chart values the same rationals, so the contact curve, its
  // root and sensitivities are the C-space path's. `play`: the follower's free channel in the
  // whole model (the kinematics'), -1 where unbounded.
  StageAnalysis kernel_stage(const std::shared_ptr<const model_detail::ParametricModel>& parametric, std::size_t driver,
                             std::size_t follower, const std::vector<StagePosition>& path,
                             const std::vector<const ContactLabel*>& touching, const std::vector<double>& play,
                             std::size_t stage) const {
    const Model& m = parametric->nominal();
    StageAnalysis out;
    ToleranceResult& result = out.result;
    result.model_name = m.name;
    result.parameters = m.parameters;
    result.driver = m.parts[driver].name;
    result.follower = m.parts[follower].name;
    result.driver_rotates = result.follower_rotates = true;
    out.distributions = distributions(m);
    for (const Distribution& d : out.distributions) {
      out.box.lo.push_back(d.box_lo);
      out.box.hi.push_back(d.box_hi);
      result.sigma.push_back(d.sigma);
      result.mean_shift.push_back(d.mean);
    }
    // the templates' nominal shapes kept over the box (as a single pair's analysis checks, over
    // the exact box)
    {
      std::vector<Rational> lo, hi;
      for (const Parameter& p : m.parameters) {
        lo.emplace_back(p.range.lo - p.nominal);
        hi.emplace_back(p.range.hi - p.nominal);
      }
      parametric->check_choices(lo, hi);
    }
    auto solver = std::make_shared<CurveSolver>(parametric);
    solver->set_compact_jets(options_.fast_paths);
    solver->set_second_order(false);
    solver->set_taylor_partials(options_.taylor_partials);
    for (std::size_t i = 0; i < path.size(); ++i) {
      VariationSample sample;
      sample.driver = path[i].driver;
      sample.nominal = path[i].follower;
      sample.play = play[i];
      sample.linear_lower = sample.linear_upper = sample.rss_lower = sample.rss_upper = sample.nominal;
      sample.certified = CertifiedRange{sample.nominal, sample.nominal};
      StageContact c;
      if (path[i].contact && touching[i]) {
        RotationChart d = rotation_chart(path[i].driver), f = rotation_chart(path[i].follower);
        c.curve.first = touching[i]->first;
        c.curve.second = touching[i]->second;
        c.curve.fixed_part = driver;
        c.curve.free_part = follower;
        c.curve.fixed_half_turn = d.half;
        c.curve.free_half_turn = f.half;
        c.curve.fixed_value = d.t;
        if (paths_.mutate_lookup) paths_.mutate_lookup(stage, i, c.curve);
        c.v = f.t.get_d();
        c.follower_half = f.half;
        try {
          c.s_chart = solver->sensitivities(c.curve, c.v);
          c.contact = true;
          c.label = touching[i]->label;
        } catch (const Error&) {
          c = StageContact{};
        }
      }
      sample.contact = c.contact;
      if (c.contact) {
        double slope = chart_slope(c.v, true);
        std::vector<double> sp(c.s_chart.size());
        for (std::size_t p = 0; p < sp.size(); ++p) sp[p] = c.s_chart[p] * slope;
        linear_bands(sample, sp, out.distributions);
      }
      result.samples.push_back(std::move(sample));
      out.contacts.push_back(std::move(c));
    }
    out.solver = std::move(solver);
    return out;
  }

  std::size_t positions() const { return stages_.front().contacts.size(); }
  bool held(std::size_t i) const {
    return std::all_of(stages_.begin(), stages_.end(), [&](const StageAnalysis& s) { return s.contacts[i].contact; });
  }

  // The chain rule at every position where every pair holds its follower; bands and regions.
  void compose() {
    std::size_t n = result_.parameters.size();
    const std::vector<Distribution>& dist = stages_.front().distributions;
    per_.assign(positions(), std::vector<PositionStage>(stages_.size()));
    for (std::size_t i = 0; i < positions(); ++i) {
      VariationSample sample = stages_.back().result.samples[i];
      sample.driver = stages_.front().result.samples[i].driver;
      sample.region = no_index;
      sample.contact = held(i);
      if (!sample.contact) {
        sample.linear_lower = sample.linear_upper = sample.rss_lower = sample.rss_upper = sample.nominal;
        sample.certified = CertifiedRange{sample.nominal, sample.nominal};
        result_.samples.push_back(sample);
        continue;
      }
      std::vector<double> total(n, 0.0);
      std::string label;
      for (std::size_t s = 0; s < stages_.size(); ++s) {
        const StageAnalysis& stage = stages_[s];
        const StageContact& c = stage.contacts[i];
        PositionStage& ps = per_[i][s];
        double v = c.v;
        std::vector<double> s_chart = stage.solver->sensitivities(c.curve, v, &ps.fixed_slope);
        double follower_slope = chart_slope(c.v, stage.result.follower_rotates);
        double t = c.curve.fixed_value.get_d();
        ps.driver_factor = follower_slope * ps.fixed_slope / chart_slope(t, stage.result.driver_rotates);
        ps.s_part.resize(n);
        for (std::size_t p = 0; p < n; ++p) {
          ps.s_part[p] = follower_slope * s_chart[p];
          total[p] = ps.s_part[p] + (s == 0 ? 0.0 : ps.driver_factor * total[p]);
        }
        label += (s == 0 ? "" : " -> ") + c.label;
      }
      std::pair<double, double> band = linear_bands(sample, total, dist);
      const CurveSlice& curve = stages_.back().contacts[i].curve;
      result_.samples.push_back(sample);
      extend_regions(result_, i, label, curve.first, curve.second, total, dist, 0.5 * (band.second - band.first));
    }
    rank_regions(result_);
  }

  // One composition over the sub-box `box` (a part of the tolerance box): each pair's certified
  // enclosure over it, its driver ranging over the previous pair's enclosure (interval
  // composition). `charts` receives each pair's enclosure (chart units). False where a pair
  // cannot be certified.
  //
  // With ToleranceOptions::mean_value_chain, also in mean-value form (session 22): V_k(p), pair
  // k's follower chart coordinate as a function of the parameters alone (its driver moved by
  // pair k-1), is enclosed over the box as V_k(c) + sum_i D_k,i [box_i - c_i], where V_k(c) is
  // the chain's certified root at the box's centre c (pair by pair, each driver ranging over
  // the previous pair's root there, each root bracketed by the pair's interval enclosure Y_k)
  // and D_k,i encloses dV_k/dp_i over the box by the chain rule,
  //   D_k,i = G_k,i + G_k,t . phi_k' . D_k-1,i,
  // G_k,i and G_k,t enclosing -F_i/F_v and -F_t/F_v over box x Y_k x T_k (T_k: the driver's
  // chart range; CurveSolver::root_partials, which also checks F_v's sign there: one root in Y_k
  // for every (p, t), a differentiable function of them) and phi_k' = (1 + t^2)/(1 + v^2) the
  // derivative of the driver's chart coordinate t with respect to the previous follower's v (1
  // for a translation). By the mean-value theorem on the segment from c to p (V_k(xi) in Y_k and
  // its driver in T_k for every xi in the box) V_k(p) lies in that form for every p in the box;
  // it is intersected with Y_k, and the intersection is the next pair's driver range. Where the
  // form is not available (F_v's sign uncertain, a parameter left out of the jets not proven
  // inert, no certified root at the centre) the pair and those after it keep the interval
  // composition.
  //
  // Through a widened pair (session 27; its follower y_k possibly held by another feature pair:
  // handover.cpp) the form carries a remainder R_k: V_k(p) in H_k(c) + sum_i D_k,i [box_i - c_i]
  // + R_k, where H_k(p) is the value the pairs' nominal holders would give (each pair's holder
  // driven by the previous pair's H: differentiable, D_k encloses its gradient as above) and
  // R_k encloses V_k(p) - H_k(p) (0 until a pair widens). At a widened pair the follower is on
  // the pushed side sigma of its holder's root h_k(p) (handover.hpp `side`) and within the
  // envelope C_k, h_k(p) in the holder's enclosure Y_k; so y_k(p) - h_k(p) lies in
  // [0, C_k.hi - Y_k.lo] (sigma = +1) or [C_k.lo - Y_k.hi, 0] (sigma = -1), added to R_k. At the
  // pair after it, V_k+1(p) - H_k+1(p) = f(p, phi(V_k(p))) - f(p, phi(H_k(p))) = G_t phi' R_k by
  // the mean-value theorem in the driver alone (H_k(p) and V_k(p) both in C_k, the driver's
  // values between them in T_k+1, the roots there in Y_k+1): R_k+1 = G_k+1,t phi_k+1' R_k
  // (+ its own widening). The form then encloses V_k+1(p), and H_k+1 at every point of the box
  // and every root between them, so intersecting Y_k+1 with it keeps G valid over the narrower
  // Y_k+1. H_k(c) is enclosed as before (the holders' roots at c, each driven by the previous
  // one's), so the composition stays in mean-value form through the chain.
  //
  // `failed` (when given) receives the pair at which the composition failed (stages_.size() on
  // success): certified() bisects the box along the parameters that spread that pair's
  // follower most (session 42).
  //
  // The case split at a widened middle pair (session 45; docs/tolerance.md "Assembly chains",
  // "The case split at a widened mesh"). Let k < L (L the last pair) be the last pair before L
  // whose envelope widened, on side sigma = +1 (-1 alike): for every p of the box its follower
  // y_k(p) lies in [h_k(p), C_k.hi] (h_k(p) its holder's root, C_k the envelope), and pairs
  // k+1 .. L-1 did not widen over this composition's regions (which hold every driver value
  // reached from y_k in C_k): their followers are their holders' roots. The output's holder
  // part is h_L(p, t_L(p)) = g(p, y_k(p)), g the holders of pairs k+1 .. L composed. Two more
  // compositions: pair k's widening ignored (its holder's enclosure and form: `override` mode
  // 1) and pair k's follower the point C_k.hi (D = 0, R = 0: mode 2), both with the last pair's
  // widening ignored (its holder's enclosure). monotone_between proves each g's pair monotone in
  // its driver over box x (the hull of the two cases' driver ranges) x its roots there, so, by
  // induction along the chain, g(p, .) is monotone between the cases and h_L(p, t_L(p)) lies in
  // the hull of the cases' last enclosures. If L did not widen, the output is that holder;
  // if it widened on side sigma_L, the output lies beyond the holder on side sigma_L, within this
  // composition's envelope and within the last pair's envelope over box x the hull of the cases'
  // driver ranges (`bridge`: the actual driver lies there). The band is the meet of those with
  // this composition's (all enclose the output).
  struct CaseOverride {
    std::size_t stage = std::numeric_limits<std::size_t>::max();
    int mode = 0;     // 1: pair `stage`'s widening ignored; 2: its follower the point `end`
    double end = 0;   // chart units
    mutable std::vector<Interval> drivers;   // receives each pair's driver range (chart units; s > 0)
  };
  // The last pair before the last one whose envelope widened in a composition (its side when
  // certain and the form carried through it, else 0; the envelope's far end on that side).
  struct Widened {
    std::size_t stage = std::numeric_limits<std::size_t>::max();
    int side = 0;
    double end = 0;   // chart units
  };
  // compose_once's state at the widened pair, just before its widening is applied (session 67):
  // the case split's two cases compute pairs 0 .. `stage` exactly as the composition before them
  // did (the same box, driver ranges, forms and envelopes: compose_once is a pure function of its
  // arguments, the memos it reads hold pure functions of their keys), so they resume from here.
  // A case differs from the composition only from that pair's override on.
  struct Prefix {
    std::size_t stage = std::numeric_limits<std::size_t>::max();
    bool mean_value = false;
    Interval xc, r;
    std::vector<Interval> d, charts, drivers;   // charts and drivers of pairs 0 .. stage
    std::vector<std::size_t> boxes;             // what pairs 0 .. stage added to each pair's sub-box count
    HandoverEnvelope envelope;                  // the widened pair's
  };
  bool compose_over(std::size_t i, const Box& box, std::vector<Interval>& charts, Interval& out, std::size_t* boxes,
                    bool* mean_value_through = nullptr, HandoverNote* handover = nullptr,
                    std::size_t* failed = nullptr) const {
    Widened widened;
    Prefix prefix;
    bool composed =
        compose_once(i, box, charts, out, boxes, mean_value_through, handover, failed, nullptr, &widened, &prefix);
    if (chain_case_split() == 0 || widened.stage >= stages_.size() || widened.side == 0) return composed;
    const Prefix* resume = prefix.stage == widened.stage && chain_case_resume() != 0 ? &prefix : nullptr;
    const std::size_t l = stages_.size() - 1;
    std::vector<Interval> lower(stages_.size()), upper(stages_.size()), between, slopes;
    Interval unused;
    HandoverEnvelope bridge;
    CaseOverride holder{widened.stage, 1, 0.0, std::vector<Interval>(stages_.size())};
    CaseOverride end{widened.stage, 2, widened.end, std::vector<Interval>(stages_.size())};
    if (!compose_once(i, box, lower, unused, boxes, nullptr, nullptr, nullptr, &holder, nullptr, nullptr, resume) ||
        !compose_once(i, box, upper, unused, boxes, nullptr, nullptr, nullptr, &end, nullptr, nullptr, resume) ||
        !monotone_between(i, box, widened.stage, holder.drivers, end.drivers, boxes, between, slopes, bridge))
      return composed;
    // The last pair's holder lies between the cases' (chart units) when every later pair is
    // certainly monotone in its driver (mean_value.hpp case_split_bound); where the last pair
    // may widen over the bridge's region (on side bridge.side), the follower is beyond its
    // holder, within the bridge's envelope.
    Interval met;
    if (!case_split_bound(slopes, lower[l], upper[l], bridge.chart, bridge.extended, bridge.side, met)) return composed;
    if (composed) {   // both enclose the output: meet them
      met = Interval(std::max(met.lo, charts[l].lo), std::min(met.hi, charts[l].hi));
      if (!(met.lo <= met.hi) || !(met.lo > charts[l].lo || met.hi < charts[l].hi)) return true;   // (not empty)
    } else {
      // the composition failed after the widened pair: the pairs after it hold their followers
      // at their holders' roots, in the enclosures over the bridge's regions
      if (!(met.lo <= met.hi)) return false;
      for (std::size_t s = widened.stage + 1; s < l; ++s) charts[s] = between[s];
      if (handover) handover->extended = true;
      if (mean_value_through) *mean_value_through = false;
      if (failed) *failed = stages_.size();
    }
    charts[l] = met;
    const StageAnalysis& stage = stages_[l];
    out = to_part(met, stage.result.follower_rotates, stage.contacts[i].follower_half, stage.result.samples[i].nominal);
    return true;
  }

  // One composition (compose_over without the case split); `override`: one of the case
  // split's cases; `widened` (when given) receives the last widened pair before the last one,
  // and `record` (when given) the state there (Prefix). `resume` (a case, with the state its
  // composition recorded at the case's pair): pairs 0 .. resume->stage replayed from it, their
  // sub-box counts added to `boxes`, instead of computed again.
  bool compose_once(std::size_t i, const Box& box, std::vector<Interval>& charts, Interval& out, std::size_t* boxes,
                    bool* mean_value_through, HandoverNote* handover, std::size_t* failed,
                    const CaseOverride* override, Widened* widened, Prefix* record = nullptr,
                    const Prefix* resume = nullptr) const {
    if (resume && (!override || override->stage != resume->stage)) resume = nullptr;
    bool mean_value = options_.mean_value_chain;
    std::vector<double> center;
    std::vector<Interval> offsets, d;   // B - c; D of the last pair
    Interval r(0);   // R of the last pair (chart units)
    std::vector<Interval> center_parameters;
    if (mean_value) {
      box_offsets(box, center, offsets);
      center_parameters = stages_.front().solver->point_parameters(center);
    }
    Interval x;    // the previous pair's output over the box, part units
    Interval xc;   // the same at the box's centre
    std::vector<std::size_t> boxes_before;   // (record) the sub-box counts on entry
    std::vector<Interval> drivers_seen;      // (record) each pair's driver range
    if (record) {
      boxes_before.assign(boxes, boxes + stages_.size());
      drivers_seen.assign(stages_.size(), Interval());
    }
    for (std::size_t s = resume ? resume->stage : 0; s < stages_.size(); ++s) {
      if (failed) *failed = s;
      const StageAnalysis& stage = stages_[s];
      const StageContact& c = stage.contacts[i];
      const bool last = s + 1 == stages_.size();
      HandoverEnvelope envelope;
      if (resume && s == resume->stage) {
        // pairs 0 .. s as the composition computed them (Prefix)
        mean_value = resume->mean_value;
        xc = resume->xc;
        r = resume->r;
        d = resume->d;
        for (std::size_t k = 0; k <= s; ++k) {
          charts[k] = resume->charts[k];
          boxes[k] += resume->boxes[k];
          if (k > 0) override->drivers[k] = resume->drivers[k];
        }
        envelope = resume->envelope;
        chain_cases_resumed().fetch_add(1, std::memory_order_relaxed);
      } else {
      const PositionStage& ps = per_[i][s];
      CurveSlice curve = c.curve;
      double previous_nominal = s > 0 ? stages_[s - 1].result.samples[i].nominal : 0.0;
      if (s > 0) {
        Interval t;
        if (!part_to_chart(x, stage.result.driver_rotates, curve.fixed_half_turn, previous_nominal, t)) return false;
        curve.fixed_range = t;
        curve.fixed_spread = std::fabs(ps.fixed_slope) * t.width();
        if (override) override->drivers[s] = t;
        if (record) drivers_seen[s] = t;
      }
      int proven_side = 0;   // the holder's free side as the enclosure's certification proves it
      try {
        charts[s] = stage.solver->certified_range(curve, box, c.v, c.s_chart, options_.relative_accuracy,
                                                  options_.absolute_accuracy, boxes[s], &proven_side);
        // Session 73: in the passes that compose a failed position again (a FarWalk lives), the
        // enclosure over box x T narrowed to the hull of T's pieces' (held_pieces: the driver
        // lies in some piece, so the hull holds the holder's root for every vector of the box; a
        // narrower enclosure of the same root keeps the certification's uniqueness and free side). Over the whole of a wide T the enclosure
        // can be far wider than its pieces' hull: gear-train.json at 4.9742 rad (120 per turn),
        // mesh G:H, T 0.130 chart units wide: Y 0.410 over the whole T, 0.115 over 2 pieces,
        // 0.095 over 8; H:I could then not be certified over a driver range spanning gear H's
        // tooth pitch. Only in those passes: every band bounded by the first pass is unchanged.
        // Session 74: with switch 1, not tried where the whole-T enclosure already meets
        // certified_range's own accuracy target (the linearised width over box x T, times 1 + the
        // relative accuracy, plus the absolute one: review73 M3). Session 75: the default is 2
        // again (tried at every pair): the skip saved no measurable CPU and gave up narrower bands
        // (docs/tolerance.md, Session 75).
        if (s > 0 && FarWalk::on() && chain_driver_piece_meet() != 0 && curve.fixed_range &&
            curve.fixed_range->lo < curve.fixed_range->hi &&
            (chain_driver_piece_meet() == 2 || !within_linearised_target(charts[s], box, c.s_chart, curve))) {
          Interval hull;
          std::size_t piece_boxes = 0;   // the pieces' sub-boxes, counted only when the meet is taken (review73 L1)
          // (taken only when the hull lies inside the whole-range enclosure, review73 H1: the
          // pieces' certified roots then lie where the whole-range certification put the holder's
          // root, not at another root a piece's bracket might have caught; the band narrows to
          // the hull)
          if (held_pieces(i, s, box, curve, hull, piece_boxes, nullptr) && charts[s].lo <= hull.lo &&
              hull.hi <= charts[s].hi) {
            if (hull.lo > charts[s].lo || hull.hi < charts[s].hi)
              chain_driver_piece_meets().fetch_add(1, std::memory_order_relaxed);
            charts[s] = hull;
            boxes[s] += piece_boxes;
          }
        }
      } catch (const NumericError&) {
        // the driver's range too wide for one enclosure: split it (held_pieces)
        if (s == 0 || !held_pieces(i, s, box, curve, charts[s], boxes[s], &proven_side)) return false;
      }
      // The driver as the previous pair's form (before the step below replaces D, R and H(c)):
      // the envelope's walk keeps its correlation with the parameters (handover.hpp DriverForm).
      std::optional<DriverForm> driver;
      if (mean_value && s > 0) {
        DriverForm form;
        Interval factor;
        if (driver_chart(s, curve, charts, xc, previous_nominal, form.value, factor)) {
          form.gradient = d;
          for (Interval& g : form.gradient) g = factor * g;
          if (!(r.lo == 0.0 && r.hi == 0.0)) form.value = form.value + factor * r;
          driver = std::move(form);
        }
      }
      int side = 0;   // the holder's free side, where the mean-value step proves it
      if (mean_value)
        mean_value = mean_value_step(i, s, box, curve, center_parameters, offsets, previous_nominal, charts, xc, d, r, side);
      // Else where the enclosure's certification proved it (session 51): F_v of one sign at the
      // holder's root for every (p, t) of box x T, each sub-box's (and driver piece's) bracket
      // holding that root, which is what the envelope's argument needs of the holder; F_v over
      // the whole box x T x Y (the envelope's own test, step 0) is often not of one sign where
      // the driver's range T is wide, only because Y x T is a rectangle about the root's graph.
      if (side == 0) side = proven_side;
      // Another feature pair may take over inside the box (handover.cpp): the envelope. The
      // holder's mean-value form above stays sound for the holder's root; where another feature
      // pair may hold the follower, the follower's distance beyond the holder's root joins the
      // remainder R (above).
      // (the case split's cases: no envelope after the widened pair, whose followers are their
      // holders' roots over the regions monotone_between certifies)
      if (override && s > override->stage) {
        envelope.bounded = true;
      } else {
        envelope = handovers_[s]->envelope(curve, box, charts[s], options_.relative_accuracy,
                                           options_.absolute_accuracy, boxes[s], side, driver ? &*driver : nullptr,
                                           true, c.v);
      }
      if (!envelope.bounded) {
        if (handover) handover->why = "pair " + stage.result.driver + ":" + stage.result.follower + ": " + envelope.why;
        return false;
      }
      if (record && !override && envelope.extended && !last) {   // a widened pair: where a case may resume
        record->stage = s;
        record->mean_value = mean_value;
        record->xc = xc;
        record->r = r;
        record->d = d;
        record->charts.assign(charts.begin(), charts.begin() + static_cast<std::ptrdiff_t>(s + 1));
        record->drivers.assign(drivers_seen.begin(), drivers_seen.begin() + static_cast<std::ptrdiff_t>(s + 1));
        record->boxes.assign(s + 1, 0);
        for (std::size_t k = 0; k <= s; ++k) record->boxes[k] = boxes[k] - boxes_before[k];
        record->envelope = envelope;
      }
      }
      if (override && override->stage == s) {
        // the case split's cases (above): pair s's follower at its holder's root (its widening
        // ignored), or at the widened envelope's far end, a point
        if (override->mode == 2) {
          charts[s] = Interval(override->end, override->end);
          if (mean_value) {
            for (Interval& g : d) g = Interval(0);
            r = Interval(0);
            xc = to_part(charts[s], stage.result.follower_rotates, c.follower_half, stage.result.samples[i].nominal);
          }
        }
      } else if (envelope.extended) {
        if (mean_value) {
          if (envelope.side == 1 || envelope.side == -1)
            r = widened_remainder(r, envelope.chart, charts[s], envelope.side);
          else
            mean_value = false;
        }
        if (!last && widened) {
          widened->stage = s;
          widened->side = mean_value ? envelope.side : 0;
          widened->end = widened->side > 0 ? envelope.chart.hi : envelope.chart.lo;
        }
        charts[s] = envelope.chart;
        if (handover) handover->extended = true;
      }
      x = to_part(charts[s], stage.result.follower_rotates, c.follower_half, stage.result.samples[i].nominal);
    }
    out = x;
    if (failed) *failed = stages_.size();
    // (through a widened pair the remainder R shrinks with the sub-box, so bisection may still
    // pay: not counted as through)
    if (mean_value_through) *mean_value_through = mean_value && r.lo == 0.0 && r.hi == 0.0;
    return true;
  }

  // The case split's monotonicity (compose_over, session 45): `slopes` receives, for every pair
  // s after `widened`, the enclosure of dy_s/dt_s (CurveSolver::root_partials' dt) over
  // box x hull(lower[s], upper[s]) x Y_s, the hull of the two cases' driver ranges and Y_s the
  // pair's certified enclosure over it; case_split_bound (mean_value.hpp) requires each to
  // exclude 0 (F_v's and F_t's signs certain). By induction along the chain: with
  // pairs widened+1 .. s-1 monotone, pair s's driver for the widened pair's follower anywhere
  // between the cases lies between its values in the cases (phi, the chart change, is
  // increasing), so in that hull; so pair s's holder is monotone in the widened pair's follower
  // over everything the split needs.
  //
  // Each pair's envelope (handover.cpp) over the same region (its driver an interval there):
  // for a pair before the last, certainly not widened (so its follower is its holder's root
  // there, the induction's premise), else false; the last pair's into `bridge` (bounded, else
  // false). `between` receives each pair's enclosure Y_s over its region (s > widened).
  bool monotone_between(std::size_t i, const Box& box, std::size_t widened, const std::vector<Interval>& lower,
                        const std::vector<Interval>& upper, std::size_t* boxes, std::vector<Interval>& between,
                        std::vector<Interval>& slopes, HandoverEnvelope& bridge) const {
    between.assign(stages_.size(), Interval());
    slopes.clear();
    for (std::size_t s = widened + 1; s < stages_.size(); ++s) {
      const StageAnalysis& stage = stages_[s];
      const StageContact& c = stage.contacts[i];
      CurveSlice curve = c.curve;
      Interval t = kernels::hull(lower[s], upper[s]);
      curve.fixed_range = t;
      curve.fixed_spread = std::fabs(per_[i][s].fixed_slope) * t.width();
      Interval y;
      try {
        y = stage.solver->certified_range(curve, box, c.v, c.s_chart, options_.relative_accuracy,
                                          options_.absolute_accuracy, boxes[s]);
      } catch (const NumericError&) {
        return false;
      }
      std::vector<Interval> dp;
      Interval dt;
      int side = 0;
      if (!stage.solver->root_partials(curve, box, stage.box, y, dp, dt, false, &side) &&
          !stage.solver->root_partials(curve, box, stage.box, y, dp, dt, true, &side))
        return false;
      slopes.push_back(dt);
      between[s] = y;
      HandoverEnvelope envelope = handovers_[s]->envelope(curve, box, y, options_.relative_accuracy,
                                                          options_.absolute_accuracy, boxes[s], side, nullptr,
                                                          true, c.v);
      if (!envelope.bounded) return false;
      if (s + 1 == stages_.size())
        bridge = envelope;
      else if (envelope.extended)
        return false;
    }
    return true;
  }

  // Whether enclosure `y` of a pair's follower over box x T (curve.fixed_range) is already within
  // certified_range's accuracy target for it: the linearised width (the chart sensitivities
  // `s_chart` times the box's widths, plus the driver's sweep over T, curve.fixed_spread) times
  // 1 + the relative accuracy, plus the absolute accuracy.
  bool within_linearised_target(const Interval& y, const Box& box, const std::vector<double>& s_chart,
                                const CurveSlice& curve) const {
    double linear = curve.fixed_spread;
    for (std::size_t k = 0; k < s_chart.size() && k < box.lo.size(); ++k)
      linear += std::fabs(s_chart[k]) * (box.hi[k] - box.lo[k]);
    return y.width() <= linear * (1 + options_.relative_accuracy) + options_.absolute_accuracy;
  }

  // Pair s's enclosure over `box` when certified_range cannot certify it with the driver over
  // its whole range T (curve.fixed_range: the previous pair's enclosure): T split into 2, 4, ...
  // up to max_held_pieces equal pieces (adjacent pieces share their double end, the first starts
  // at T.lo and the last ends at T.hi, so they cover T), each piece's enclosure over the box
  // certified on its own (its root bracketed about the nominal root moved by the chart slope to
  // the piece's middle), the hull of the pieces. The driver's value over the box lies in T, so in
  // some piece: the hull holds pair s's follower for every parameter vector of the box. False
  // when some piece of the finest split is not certified either.
  bool held_pieces(std::size_t i, std::size_t s, const Box& box, const CurveSlice& curve, Interval& chart,
                   std::size_t& boxes, int* free_side) const {
    const StageAnalysis& stage = stages_[s];
    const StageContact& c = stage.contacts[i];
    const Interval whole = *curve.fixed_range;
    const double slope = per_[i][s].fixed_slope;
    const double nominal_t = c.curve.fixed_value.get_d();
    for (std::size_t pieces = 2; pieces <= max_held_pieces; pieces *= 2) {
      bool all = true;
      Interval hull;
      int common_side = 2;   // the pieces' free sides (certified_range's; 0: not all the same)
      double lo = whole.lo;
      for (std::size_t j = 0; j < pieces && all; ++j) {
        double hi = j + 1 == pieces ? whole.hi : whole.lo + (whole.hi - whole.lo) * static_cast<double>(j + 1) / static_cast<double>(pieces);
        hi = std::max(hi, lo);
        CurveSlice piece = curve;
        piece.fixed_range = Interval(lo, hi);
        piece.fixed_spread = std::fabs(slope) * (hi - lo);
        double guess = c.v + slope * (0.5 * (lo + hi) - nominal_t);
        try {
          int side = 0;
          Interval y = stage.solver->certified_range(piece, box, guess, c.s_chart, options_.relative_accuracy,
                                                     options_.absolute_accuracy, boxes, &side);
          hull = j == 0 ? y : kernels::hull(hull, y);
          common_side = common_side == 2 || common_side == side ? side : 0;
        } catch (const NumericError&) {
          all = false;
        }
        lo = hi;
      }
      if (all) {
        chart = hull;
        if (free_side) *free_side = common_side == 2 ? 0 : common_side;
        return true;
      }
    }
    return false;
  }

  // Pair s's driver chart at the box's centre (`xc`, H_s-1(c) in part units, through the chart
  // change, into `tc`) and phi_s' over the region (`factor`: (1 + t^2)/(1 + v^2) with t over
  // the driver's range and v over the previous pair's enclosure; 1 for a translation). False
  // when the centre's value reaches the chart's pole.
  bool driver_chart(std::size_t s, const CurveSlice& curve, const std::vector<Interval>& charts, const Interval& xc,
                    double previous_nominal, Interval& tc, Interval& factor) const {
    const StageAnalysis& stage = stages_[s];
    if (stage.result.driver_rotates) {
      const Interval& t = *curve.fixed_range;
      const Interval& v = charts[s - 1];
      factor = (Interval(1) + t * t) / (Interval(1) + v * v);
    } else {
      factor = Interval(1);
    }
    return part_to_chart(xc, stage.result.driver_rotates, curve.fixed_half_turn, previous_nominal, tc);
  }

  // Pair s's step of compose_over's mean-value form: D_s from D_s-1 (in `d`, replaced), R_s from
  // R_s-1 (in `r`, replaced), H_s(c) (its part coordinate into `xc`, replacing pair s-1's),
  // charts[s] intersected with the form. False when the form is not available from this pair on.
  // `side` receives F_v's sign over box x T_s x Y_s once root_partials has made it certain (over
  // the enclosure before the form narrows it: so over the narrower one too), else stays 0.
  bool mean_value_step(std::size_t i, std::size_t s, const Box& box, const CurveSlice& curve,
                       const std::vector<Interval>& center_parameters, const std::vector<Interval>& offsets,
                       double previous_nominal, std::vector<Interval>& charts, Interval& xc,
                       std::vector<Interval>& d, Interval& r, int& side) const {
    const StageAnalysis& stage = stages_[s];
    const StageContact& c = stage.contacts[i];
    std::vector<Interval> dp;
    Interval dt;
    // Interval jets first; the Taylor models (dearer: the geometry over the box as Taylor models)
    // where F_v's sign is not certain without them or the form misses the accuracy asked for.
    bool taylor = false;
    if (!stage.solver->root_partials(curve, box, stage.box, charts[s], dp, dt, taylor, &side)) {
      taylor = true;
      if (!stage.solver->root_partials(curve, box, stage.box, charts[s], dp, dt, taylor, &side)) return false;
    }
    CurveSlice at_center = c.curve;
    Interval factor(0);   // phi_s' over the region
    if (s > 0) {
      Interval tc;
      if (!driver_chart(s, curve, charts, xc, previous_nominal, tc, factor)) return false;
      at_center.fixed_range = tc;
    }
    Interval vc;
    if (!stage.solver->certified_point_root(at_center, stage.solver->point_geometry(at_center, center_parameters), charts[s], vc))
      return false;
    // The form, then contracted: the partials again over the narrower Y_s (it still holds V_s
    // over the box), while that narrows Y_s by a tenth or more.
    std::vector<Interval> next;
    Interval next_r(0);
    // R_s = G_s,t phi_s' R_s-1, exactly 0 while no pair before has widened (then not added: an
    // outward-rounded sum would widen the form by an ulp)
    const bool carried = s > 0 && !(r.lo == 0.0 && r.hi == 0.0);
    auto remainder = [&](const Interval& g_t) { return carried ? g_t * factor * r : Interval(0); };
    auto plus_remainder = [&](const Interval& form, const Interval& trial_r) { return carried ? form + trial_r : form; };
    for (int contraction = 0; contraction < 3; ++contraction) {
      if (contraction > 0 && !stage.solver->root_partials(curve, box, stage.box, charts[s], dp, dt, taylor)) break;
      std::vector<Interval> trial = chain_rule(dp, dt, factor, s > 0 ? &d : nullptr);
      Interval trial_r = remainder(dt);
      Interval form = plus_remainder(mean_value_form(vc, trial, offsets), trial_r);
      if (!taylor && options_.taylor_partials) {
        double linear = carried ? trial_r.width() : 0.0;   // the form's width with every D at its midpoint (and R)
        for (std::size_t p = 0; p < trial.size(); ++p) linear += std::fabs(trial[p].middle()) * offsets[p].width();
        if (!(form.width() <= linear * (1 + options_.relative_accuracy) + options_.absolute_accuracy)) {
          taylor = true;
          std::vector<Interval> dp_t;
          Interval dt_t;
          if (stage.solver->root_partials(curve, box, stage.box, charts[s], dp_t, dt_t, taylor)) {
            dp.swap(dp_t);
            dt = dt_t;
            trial = chain_rule(dp, dt, factor, s > 0 ? &d : nullptr);
            trial_r = remainder(dt);
            form = plus_remainder(mean_value_form(vc, trial, offsets), trial_r);
          }
        }
      }
      if (!std::isfinite(form.lo) || !std::isfinite(form.hi)) {
        if (contraction == 0) return false;
        break;
      }
      next.swap(trial);
      next_r = trial_r;
      Interval narrower(std::max(charts[s].lo, form.lo), std::min(charts[s].hi, form.hi));
      if (!(narrower.lo <= narrower.hi)) return false;   // (both enclose V_s over the box: cannot happen)
      bool progress = narrower.width() < 0.9 * charts[s].width();
      charts[s] = narrower;
      if (!progress) break;
    }
    d.swap(next);
    r = next_r;
    xc = to_part(vc, stage.result.follower_rotates, c.follower_half, stage.result.samples[i].nominal);
    return true;
  }

  // Per position, the certified band of the output over the whole tolerance box. A parameter
  // acting on several pairs (a shared dimension, or one that others are defined from) would enter
  // the interval composition once per pair, independently (too wide, still sound); so the box is
  // bisected along such parameters (branch and bound, up to `max_shared_boxes` sub-boxes per
  // position) until each sub-box's composition is within the requested accuracy of the composed
  // linearised width over it, and the band is the hull of the sub-boxes' compositions. Any
  // partition of the box is sound; the choice of the shared parameters only steers the splits:
  // those on which at least two pairs' outputs depend at the position (their share of the
  // composed sensitivity, |d out / dp| summed over the pairs, exceeds |total d out / dp|: the
  // independence loss), split where that loss times the sub-box's width is largest.
  // ChainBandMemo's keys: the run (band_run: the text, the options and switches a band depends on,
  // each pair's tolerance box and solver switches) and a position's inputs (band_key: every value
  // certified() and the compositions read at position i, bit for bit). An option or switch that
  // changes a band, added later, must be added to band_run (else a memo would replay a band of
  // another setting; tests only: ChainPaths::band_memo).
  static void put(std::string& out, double value) {
    auto bits = std::bit_cast<std::uint64_t>(value);
    out.append(reinterpret_cast<const char*>(&bits), sizeof bits);
  }
  static void put(std::string& out, std::size_t value) {
    auto bits = static_cast<std::uint64_t>(value);
    out.append(reinterpret_cast<const char*>(&bits), sizeof bits);
  }
  static void put(std::string& out, const std::string& text) {
    put(out, text.size());
    out += text;
  }
  static void put(std::string& out, const Rational& value) { put(out, value.get_str()); }
  static void put(std::string& out, const std::vector<double>& values) {
    put(out, values.size());
    for (double v : values) put(out, v);
  }
  static void put(std::string& out, const FeatureIdentity& f) {
    put(out, f.part);
    put(out, f.loop);
    put(out, f.edge);
    put(out, static_cast<std::size_t>(f.kind));
  }
  std::string band_run() const {
    std::string out;
    put(out, std::string(text_));
    put(out, options_.parameter_values.size());
    for (const auto& [name, value] : options_.parameter_values) {
      put(out, name);
      put(out, value);
    }
    put(out, options_.driver);
    put(out, options_.follower);
    put(out, static_cast<std::size_t>(options_.range.has_value()));
    if (options_.range) {
      put(out, options_.range->first);
      put(out, options_.range->second);
    }
    for (std::size_t v : {options_.positions, std::size_t(options_.allow_out_of_tolerance), std::size_t(options_.fast_paths),
                          std::size_t(options_.taylor_partials), std::size_t(options_.mean_value_chain),
                          std::size_t(options_.chain_assume_nominal_holder), options_.chain_failure_boxes})
      put(out, v);
    put(out, options_.relative_accuracy);
    put(out, options_.absolute_accuracy);
    put(out, static_cast<std::size_t>(length_exponent_));
    for (int v : {chain_case_split(), chain_widened_split(), handover_monotone_driver(), handover_sub_box_anchor(),
                  handover_taylor_partials(), handover_far_windows(), handover_driver_pieces(), handover_widened_pieces(),
                  handover_far_reuse(), chain_driver_piece_meet()})
      put(out, static_cast<std::size_t>(static_cast<unsigned>(v)));
    put(out, stages_.size());
    for (const StageAnalysis& stage : stages_) {
      put(out, stage.box.lo);
      put(out, stage.box.hi);
      put(out, static_cast<std::size_t>(stage.solver->switches()));
      put(out, static_cast<std::size_t>(stage.result.driver_rotates) * 2 + static_cast<std::size_t>(stage.result.follower_rotates));
    }
    return out;
  }
  std::string band_key(std::size_t i) const {
    std::string out;
    put(out, i);
    const VariationSample& sample = result_.samples[i];
    put(out, sample.driver);
    put(out, sample.nominal);
    put(out, sample.sensitivities);
    for (std::size_t s = 0; s < stages_.size(); ++s) {
      const StageContact& c = stages_[s].contacts[i];
      put(out, static_cast<std::size_t>(c.contact) * 2 + static_cast<std::size_t>(c.follower_half));
      put(out, c.curve.first);
      put(out, c.curve.second);
      put(out, c.curve.fixed_part);
      put(out, c.curve.free_part);
      put(out, static_cast<std::size_t>(c.curve.fixed_half_turn) * 2 + static_cast<std::size_t>(c.curve.free_half_turn));
      put(out, c.curve.fixed_value);
      put(out, static_cast<std::size_t>(c.curve.fixed_range.has_value()));
      if (c.curve.fixed_range) {
        put(out, c.curve.fixed_range->lo);
        put(out, c.curve.fixed_range->hi);
      }
      put(out, c.curve.fixed_spread);
      put(out, c.v);
      put(out, c.s_chart);
      put(out, stages_[s].result.samples[i].nominal);
      const PositionStage& ps = per_[i][s];
      put(out, ps.fixed_slope);
      put(out, ps.driver_factor);
      put(out, ps.s_part);
    }
    return out;
  }

  void certified() {
    std::vector<std::size_t> boxes(positions() * stages_.size(), 0);
    std::vector<std::size_t> shared_boxes(positions(), 0);
    std::vector<std::size_t> failure_boxes(positions(), 0);   // sub-boxes where a composition failed and was bisected
    std::vector<char> ok(positions(), 0);
    // positions whose last pass ran out of the failure split's budget (ToleranceOptions::chain_failure_boxes)
    std::vector<char> exhausted(positions(), 0);
    const std::size_t max_failure_boxes = std::max<std::size_t>(options_.chain_failure_boxes, 1);
    std::vector<HandoverNote> handover(positions());
    std::size_t n = result_.parameters.size();
    // ChainPaths::band_memo (tests only): positions whose inputs another analysis of the same run
    // met, replayed
    ChainBandMemo* memo = paths_.band_memo.get();
    if (memo) {
      std::string run = band_run();
      std::lock_guard<std::mutex> lock(memo->mutex);
      if (memo->run != run) {
        memo->run = std::move(run);
        memo->positions.clear();
      }
    }
    parallel_for(options_.threads, positions(), [&](std::size_t i) {
      if (!result_.samples[i].contact) return;
      std::string key;
      if (memo) {
        key = band_key(i);
        std::lock_guard<std::mutex> lock(memo->mutex);
        auto it = memo->positions.find(key);
        if (it != memo->positions.end()) {
          const ChainBandMemo::Position& kept = it->second;
          ok[i] = kept.ok ? 1 : 0;
          exhausted[i] = kept.exhausted ? 1 : 0;
          if (kept.ok) {
            result_.samples[i].certified = CertifiedRange{kept.lower, kept.upper};
            for (std::size_t s = 0; s < stages_.size(); ++s) per_[i][s].certified_chart = kept.charts[s];
          }
          for (std::size_t s = 0; s < stages_.size(); ++s) boxes[i * stages_.size() + s] = kept.boxes[s];
          shared_boxes[i] = kept.shared_boxes;
          failure_boxes[i] = kept.failure_boxes;
          handover[i].extended = kept.extended;
          handover[i].why = kept.why;
          ++memo->replayed;
          return;
        }
      }
      const std::vector<double>& total = result_.samples[i].sensitivities;
      // each pair's share of d out / dp (output units): its own s_part times the later pairs' driver factors
      std::vector<double> spread(n, 0.0);
      double factor = 1;
      for (std::size_t s = stages_.size(); s-- > 0;) {
        for (std::size_t p = 0; p < n; ++p) spread[p] += std::fabs(factor * per_[i][s].s_part[p]);
        factor *= per_[i][s].driver_factor;
      }
      std::vector<double> loss(n, 0.0);
      for (std::size_t p = 0; p < n && p < total.size(); ++p) loss[p] = spread[p] - std::fabs(total[p]);
      // Per pair k and parameter p: the share of pair k's follower spread (part units) that p
      // accounts for, sum over j <= k of |pair j's s_part_p times the driver factors of pairs
      // j+1 .. k| (both the pair's own geometry and its driver's). Where a sub-box's composition
      // fails at pair k (session 42), it is bisected along the parameter whose share times the
      // sub-box's width is largest: pair k's driver range and its own blur shrink most there.
      // (A nominal, linearised steer only: any partition of the box is sound.)
      std::vector<std::vector<double>> share(stages_.size(), std::vector<double>(n, 0.0));
      for (std::size_t k = 0; k < stages_.size(); ++k)
        for (std::size_t j = 0; j <= k; ++j) {
          double through = 1;
          for (std::size_t m = j + 1; m <= k; ++m) through *= per_[i][m].driver_factor;
          for (std::size_t p = 0; p < n; ++p) share[k][p] += std::fabs(through * per_[i][j].s_part[p]);
        }
      // The position's compositions (the whole box, then its splits); false where the band is
      // unbounded. Run again where it is (`far`), each sub-box whose composition fails composed
      // once more with the hand-over walks carried on beyond their windows (handover.cpp step 6,
      // session 49): every band bounded without them stays as it was, and a sub-box that composes
      // without them keeps that composition (carried on, a walk that failed before may end far
      // out and change which pair the case split takes as the widened one).
      // Where it is still unbounded (`far` 2), composed once more with the envelopes' driver ranges
      // walked in pieces too (handover.cpp step 7, session 52), likewise.
      // The plain compositions (no far walk, no driver pieces) of the position's sub-boxes, kept
      // for its later passes (session 53): a pass that runs again (`far` 1, 2) first composes
      // each sub-box without the far walks, which is what the pass before did for the same box
      // (compose_over is a pure function of the box: the memos it reads hold pure functions of
      // their keys), so the kept result and its side effects (each pair's sub-box count, the
      // hand-over note's fields, the failing pair) are replayed instead of recomputed.
      struct Plain {
        bool composed = false, mean_value_through = false, extended = false;
        std::vector<Interval> charts;
        Interval out;
        std::vector<std::size_t> counts;   // what the composition added to each pair's sub-box count
        std::string why;
        std::size_t failed = 0;
      };
      std::map<std::vector<double>, Plain> plain;
      // The envelopes walked in the far walk's pass (session 54; handover.hpp EnvelopeMemo): the
      // pass of the driver's pieces makes the same calls of the sub-boxes it composes again, whose
      // steps 0-6 are the far walk's; replayed, only their step 7 is walked.
      EnvelopeMemo far_envelopes;
      auto compose_plain = [&](const Box& b, std::vector<Interval>& charts, Interval& out, bool& mean_value_through,
                               std::size_t& failed) {
        // (kept only where a later pass may run: the far walk on)
        const bool keep = chain_plain_reuse() != 0 && handover_far_windows() > 1;
        std::vector<double> key;
        const Plain* p = nullptr;
        std::optional<Plain> fresh;
        if (keep) {
          key = b.lo;
          key.insert(key.end(), b.hi.begin(), b.hi.end());
          auto it = plain.find(key);
          if (it != plain.end()) p = &it->second;
        }
        if (!p) {
          Plain made;
          made.charts = charts;
          made.counts.assign(stages_.size(), 0);
          HandoverNote note;   // compose_over only sets a note's fields (extended to true, why)
          made.failed = failed;
          made.composed = compose_over(i, b, made.charts, made.out, made.counts.data(), &made.mean_value_through, &note,
                                       &made.failed);
          made.extended = note.extended;
          made.why = std::move(note.why);
          chain_compositions_made().fetch_add(1, std::memory_order_relaxed);
          if (keep)
            p = &plain.emplace(std::move(key), std::move(made)).first->second;
          else
            p = &fresh.emplace(std::move(made));
        }
        charts = p->charts;
        out = p->out;
        for (std::size_t s = 0; s < stages_.size(); ++s) boxes[i * stages_.size() + s] += p->counts[s];
        mean_value_through = p->mean_value_through;
        if (p->extended) handover[i].extended = true;
        if (!p->why.empty()) handover[i].why = p->why;
        failed = p->failed;
        return p->composed;
      };
      auto position_band = [&](int far) -> bool {
        std::size_t failure_splits = 0, shared_splits = 0;
        exhausted[i] = 0;
        // The parameter of sub-box b whose weight times its width is largest and above `floor`
        // (n if none): where a sub-box is bisected (both halves queued, breadth first).
        auto widest = [n](const Box& b, const std::vector<double>& weight, double floor) {
          std::size_t split = n;
          for (std::size_t p = 0; p < n; ++p) {
            double score = weight[p] * (b.hi[p] - b.lo[p]);
            if (b.hi[p] > b.lo[p] && score > floor) {
              floor = score;
              split = p;
            }
          }
          return split;
        };
        std::vector<Interval> hull_charts(stages_.size());
        std::vector<Interval> charts(stages_.size());
        // breadth first: when the budget runs out, the sub-boxes left are the narrowest ones
        // (depth first would leave the first halves whole)
        std::deque<Box> pending{stages_.front().box};
        bool have = false;
        Interval band;
        std::size_t used = 0;
        // A whole box composed only through a widened envelope (a hand-over candidate's spread, far
        // beyond the linearised width): its band, kept while its halves are composed as for a failed
        // composition (session 48); both enclose the output over the box, so the band is their meet,
        // or the whole box's alone where a half fails.
        std::optional<Interval> whole;
        std::vector<Interval> whole_charts;
        // both halves of a sub-box, along parameter `split`, queued for composition
        auto bisect = [&pending](const Box& box, std::size_t split) {
          auto [left, right] = halves(box, split);
          pending.push_back(std::move(left));
          pending.push_back(std::move(right));
        };
        while (!pending.empty()) {
          Box b = std::move(pending.front());
          pending.pop_front();
          ++used;
          Interval out;
          bool mean_value_through = false;
          std::size_t failed = stages_.size();
          bool composed = compose_plain(b, charts, out, mean_value_through, failed);
          if (!composed && far > 0) {   // (a sub-box composed without the far walks keeps that composition)
            FarWalk on;
            EnvelopeMemo::Scope reuse(far_envelopes);
            std::optional<DriverPieces> pieces;
            if (far > 1) pieces.emplace();
            composed =
                compose_over(i, b, charts, out, &boxes[i * stages_.size()], &mean_value_through, &handover[i], &failed);
            chain_compositions_made().fetch_add(1, std::memory_order_relaxed);
          }
          double linear = 0;
          for (std::size_t p = 0; p < n && p < total.size(); ++p) linear += std::fabs(total[p]) * (b.hi[p] - b.lo[p]);
          bool accurate = composed && out.width() <= linear * (1 + options_.relative_accuracy) + options_.absolute_accuracy;
          // A composition in mean-value form through the last pair loses no independence (the chain
          // rule carries each parameter through every pair): bisecting for it would spend the budget
          // for nothing (a 4-gear train: 248 -> 4 634 sub-boxes, 10 x the CPU).
          // (not in a box split for a failed composition: its sub-boxes, up to max_failure_boxes,
          // are hulled as they come, which keeps the failure splits' cost bounded)
          if (composed && !accurate && !mean_value_through && failure_splits == 0 &&
              used + pending.size() + 2 <= max_shared_boxes) {
            // Bisection removes at most the independence loss, sum_p loss_p x width_p: split only
            // when that explains at least half the excess over the linearised width (otherwise the
            // excess is the pairs' own, e.g. gear meshes over a wide box, and splitting would cost
            // up to max_shared_boxes compositions for nothing), along the largest term when it is
            // at least a tenth of the excess.
            double excess = out.width() - linear, explained = 0;
            for (std::size_t p = 0; p < n; ++p) explained += loss[p] * (b.hi[p] - b.lo[p]);
            std::size_t split = explained >= 0.5 * excess ? widest(b, loss, 0.1 * excess) : n;
            if (split < n) {
              bisect(b, split);
              ++shared_splits;
              continue;
            }
          }
          if (composed && !accurate && used == 1 && handover[i].extended && chain_widened_split() != 0) {
            std::size_t split = widest(b, share[stages_.size() - 1], 0);
            if (split < n && used + pending.size() + 2 <= max_failure_boxes) {
              whole = out;
              whole_charts = charts;
              bisect(b, split);
              ++failure_splits;
              continue;
            }
          }
          if (!composed) {
            // A sub-box that cannot be certified (a pair's root not certified over its driver
            // range, its free side not certain, or a competitor possibly holding its follower
            // beyond the window: at the last meshes of a long gear train the driver's range,
            // composed over the whole box, is too wide): bisected along the parameter that
            // spreads the failing pair's follower most, within max_failure_boxes sub-boxes; the
            // band is the hull of the halves' compositions. Otherwise unbounded.
            if (failed < stages_.size()) {
              std::size_t split = widest(b, share[failed], 0);
              if (split < n && used + pending.size() + 2 <= max_failure_boxes) {
                bisect(b, split);
                ++failure_splits;
                continue;
              }
              if (split < n) exhausted[i] = 1;   // a split was left for want of budget
            }
            if (!whole) return false;   // the band is unbounded
            have = false;   // the whole box's band stands
            break;
          }
          band = have ? kernels::hull(band, out) : out;
          for (std::size_t s = 0; s < stages_.size(); ++s) hull_charts[s] = have ? kernels::hull(hull_charts[s], charts[s]) : charts[s];
          have = true;
        }
        if (whole) {
          auto meet = [have](const Interval& kept, const Interval& halves) {
            Interval both(std::max(kept.lo, halves.lo), std::min(kept.hi, halves.hi));
            return have && both.lo <= both.hi ? both : kept;
          };
          band = meet(*whole, band);
          for (std::size_t s = 0; s < stages_.size(); ++s) hull_charts[s] = meet(whole_charts[s], hull_charts[s]);
        }
        for (std::size_t s = 0; s < stages_.size(); ++s) per_[i][s].certified_chart = hull_charts[s];
        shared_boxes[i] = shared_splits > 0 ? used : 1;
        if (failure_splits > 0) failure_boxes[i] = used;
        result_.samples[i].certified = CertifiedRange{band.lo, band.hi};
        ok[i] = 1;
        return true;
      };
      if (!position_band(0) && handover_far_windows() > 1 && !position_band(1) && handover_driver_pieces() > 1)
        position_band(2);
      if (memo) {
        ChainBandMemo::Position kept;
        kept.ok = ok[i] != 0;
        kept.exhausted = exhausted[i] != 0;
        if (kept.ok) {
          kept.lower = result_.samples[i].certified.lower;
          kept.upper = result_.samples[i].certified.upper;
          for (std::size_t s = 0; s < stages_.size(); ++s) kept.charts.push_back(per_[i][s].certified_chart);
        }
        for (std::size_t s = 0; s < stages_.size(); ++s) kept.boxes.push_back(boxes[i * stages_.size() + s]);
        kept.shared_boxes = shared_boxes[i];
        kept.failure_boxes = failure_boxes[i];
        kept.extended = handover[i].extended;
        kept.why = handover[i].why;
        std::lock_guard<std::mutex> lock(memo->mutex);
        memo->positions.insert_or_assign(std::move(key), std::move(kept));
      }
    }, [&](std::size_t done) { bar_.units(done, positions()); });
    std::size_t uncertified = 0, split_positions = 0, most = 0;
    for (std::size_t i = 0; i < positions(); ++i) {
      for (std::size_t s = 0; s < stages_.size(); ++s) {
        result_.chain[s].certified_boxes += boxes[i * stages_.size() + s];
        result_.certified_boxes += boxes[i * stages_.size() + s];
      }
      split_positions += shared_boxes[i] > 1;
      most = std::max(most, shared_boxes[i]);
      VariationSample& sample = result_.samples[i];
      if (!sample.contact) continue;
      if (!ok[i]) {
        ++uncertified;
        result_.chain_budget_exhausted += exhausted[i] != 0;
        constexpr double inf = std::numeric_limits<double>::infinity();
        sample.certified = CertifiedRange{-inf, inf};
        for (PositionStage& ps : per_[i]) ps.certified_chart = Interval(-inf, inf);
        continue;
      }
      double excess = (sample.certified.upper - sample.certified.lower) - (sample.linear_upper - sample.linear_lower);
      result_.certified_excess = std::max(result_.certified_excess, excess);
    }
    if (split_positions > 0)
      notes_.push_back("the certified band was bisected along parameters acting on several pairs at " +
                       std::to_string(split_positions) + " position(s) (at most " + std::to_string(most) +
                       " sub-boxes of the tolerance box at one position)");
    std::size_t failure_positions = 0, most_failure = 0;
    for (std::size_t i = 0; i < positions(); ++i)
      if (failure_boxes[i] > 0) {
        ++failure_positions;
        most_failure = std::max(most_failure, failure_boxes[i]);
      }
    if (failure_positions > 0)
      notes_.push_back("the certified band was bounded by bisecting the tolerance box where its composition could not be "
                       "certified over the whole box at " + std::to_string(failure_positions) + " position(s) (at most " +
                       std::to_string(most_failure) + " sub-boxes at one position)");
    if (uncertified > 0)
      notes_.push_back("the certified band could not be computed at " + std::to_string(uncertified) +
                       " driver position(s) (shown unbounded)");
    if (result_.chain_budget_exhausted > 0)
      notes_.push_back("the certified band is unbounded at " + std::to_string(result_.chain_budget_exhausted) +
                       " position(s) where the tolerance box's bisection for a failed composition used its whole budget (" +
                       std::to_string(max_failure_boxes) + " sub-boxes a position): a larger --chain-split-budget may bound them");
    // Hand-overs (docs/tolerance.md "Assembly chains" step 4, "Hand-overs"), said where the band is read.
    std::size_t widened = 0;
    std::map<std::string, std::size_t> reasons;
    for (std::size_t i = 0; i < positions(); ++i) {
      if (!result_.samples[i].contact) continue;
      widened += ok[i] && handover[i].extended;
      if (!ok[i] && !handover[i].why.empty()) ++reasons[handover[i].why];
    }
    if (envelope_on())
      notes_.push_back("the certified band encloses a change of the touching feature pair inside the tolerance box "
                       "(another tooth or flank taking over): widened for it at " + std::to_string(widened) +
                       " position(s)");
    else
      notes_.push_back("the band assumes (as asked: --assume-nominal-contact) that each pair's follower is held by the "
                       "feature pair touching at the nominal position over the whole tolerance box; a change of the "
                       "touching feature pair inside the box (another tooth or flank taking over near a contact "
                       "change) is not enclosed, so the band is certified only under that assumption");
    for (const auto& [why, count] : reasons)
      notes_.push_back("the certified band is unbounded at " + std::to_string(count) + " position(s): " + why);
  }

  // The feature pairs that may hold pair s's follower at position i at a sampled vector (the
  // Monte Carlo's candidates; docs/tolerance.md "Assembly chains", step 5): the nominal holder first, then the nearest other feature pair
  // holding the follower along the nominal path before position i and the nearest after it (the
  // tooth pairs handing over there), each as a slice at position i (its charts and driver).
  std::vector<CurveSlice> holders_near(std::size_t s, std::size_t i) const {
    const std::vector<StageContact>& contacts = stages_[s].contacts;
    const CurveSlice& own = contacts[i].curve;
    std::vector<CurveSlice> out{own};
    auto differs = [&](const CurveSlice& c) {
      return std::none_of(out.begin(), out.end(), [&](const CurveSlice& o) { return o.first == c.first && o.second == c.second; });
    };
    auto add = [&](std::size_t j) {
      if (!contacts[j].contact || !differs(contacts[j].curve)) return false;
      CurveSlice c = own;
      c.first = contacts[j].curve.first;
      c.second = contacts[j].curve.second;
      out.push_back(c);
      return true;
    };
    for (std::size_t j = i; j-- > 0;)
      if (add(j)) break;
    for (std::size_t j = i + 1; j < contacts.size(); ++j)
      if (add(j)) break;
    return out;
  }

  // Pair s's follower at one sampled vector and position (the Monte Carlo's value, chart
  // units): the first contact it meets among the candidates (holders_near), as the kinematic
  // engine places a pushed follower (src/kinematics/engine.cpp: at the end of the blocked range
  // its old position fell into). The holder's root is bracketed about its linearised value;
  // sigma, the side its contact function is positive on, is the side the follower is free to
  // move to. A candidate whose features penetrate certainly at the current value's sigma end
  // (its contact function negative there) holds the follower beyond it: the follower moves to
  // that candidate's root on the sigma side (where its function turns positive), and the
  // candidates are tried again there; one whose sign is undecided there touches within the
  // enclosure's rounding: the value becomes the sigma-most of both enclosures. Every enclosure
  // is certified (interval bisection with certain end signs); each candidate carries its
  // geometry at the vector. False when a root cannot be bracketed.
  struct Candidate {
    CurveSlice curve;
    std::optional<PairGeometry<Interval>> geometry;
  };
  // With `wider` (the retry after a failure, docs/tolerance.md "Assembly chains", step 5), a
  // bracket that fails is searched again on grids of points over the same windows: the certain
  // sign change nearest to its centre (root_search.hpp).
  bool actual_root(const CurveSolver& solver, std::vector<Candidate>& candidates, double guess, double width,
                   Interval& value, bool& handed_over, int& sigma, bool wider = false) const {
    handed_over = false;
    auto sign_at = [&](Candidate& c, double v) { return solver.point_sign(c.curve, *c.geometry, v); };
    // A root of candidate c with certain end signs in a bracket about `at` (widened up to 12
    // times by 4); `sigma` receives the sign at its upper end.
    // The wider search only for the holder (`may_widen`): another candidate's nearest sign
    // change up to a chart unit away is no proof that it pushes the follower there.
    auto bracket = [&](Candidate& c, double at, double w, Interval& root, int& sigma, bool may_widen) {
      const double w0 = w;
      for (int k = 0; k < 12 && w < 1; ++k, w *= 4) {
        int lo = sign_at(c, at - w), hi = sign_at(c, at + w);
        if ((lo == 1 || lo == -1) && (hi == 1 || hi == -1) && lo != hi) {
          sigma = hi;
          if (solver.certified_point_root(c.curve, *c.geometry, Interval(at - w, at + w), root)) return true;
          break;
        }
      }
      if (!may_widen) return false;
      std::optional<SignChange> near = nearest_sign_change([&](double v) { return sign_at(c, v); }, at, w0, 1.0);
      if (!near) return false;
      sigma = near->upper;
      return solver.certified_point_root(c.curve, *c.geometry, Interval(near->lo, near->hi), root);
    };
    sigma = 0;
    if (!bracket(candidates.front(), guess, width, value, sigma, wider)) return false;
    auto further_end = [&](const Interval& y) { return sigma > 0 ? y.hi : y.lo; };
    std::size_t holder = 0;
    for (std::size_t round = 0; round <= candidates.size(); ++round) {
      bool moved = false;
      for (std::size_t k = 0; k < candidates.size() && !moved; ++k) {
        if (k == holder) continue;
        Candidate& c = candidates[k];
        const double x = further_end(value);
        int here = sign_at(c, x);
        if (here == 1) continue;   // apart at the value: it does not push the follower beyond it
        if (here == -1) {
          // it penetrates: its root on the sigma side (its function turning positive), bracketed
          // by doubling steps from the last point where it certainly still penetrates
          double w = std::max(value.width(), 1e-9 * (1 + std::fabs(x)));
          double inside = 0;   // offset of that point from x
          int there = -1;
          for (int step = 0; step < 60 && w < 1 && there != 1; ++step) {
            there = sign_at(c, x + sigma * w);
            if (there == -1) inside = w;
            if (there != 1) w *= 2;
          }
          if (there != 1) return false;
          Interval root;
          Interval range = sigma > 0 ? Interval(x + inside, x + w) : Interval(x - w, x - inside);
          if (!solver.certified_point_root(c.curve, *c.geometry, range, root)) return false;
          value = root;
          holder = k;
          handed_over = true;
          moved = true;
          continue;
        }
        // undecided: it touches within the rounding; the sigma-most of both when it pushes
        Interval root;
        int side = 0;
        if (!bracket(c, x, std::max(value.width(), 1e-12 * (1 + std::fabs(x))), root, side, false)) return false;
        if (side != sigma) continue;   // a contact blocking the follower from ahead, not a push
        value = sigma > 0 ? Interval(std::max(value.lo, root.lo), std::max(value.hi, root.hi))
                          : Interval(std::min(value.lo, root.lo), std::min(value.hi, root.hi));
      }
      if (!moved) return true;
    }
    return false;   // the candidates did not settle
  }

  // Monte Carlo (docs/tolerance.md "Assembly chains", step 5): at each sampled vector, pair by pair, the
  // follower's actual position (actual_root, its driver the previous pair's value there), the
  // output's enclosure against the bands. Positions where every pair holds its follower at
  // nominal are evaluated, with or without a bounded certified band.
  void monte_carlo() {
    auto start = std::chrono::steady_clock::now();
    double cpu_start = cpu_now();
    MonteCarloSummary summary;
    summary.samples = options_.monte_carlo;
    summary.seed = options_.seed;
    std::vector<MonteCarloOutcome> outcomes(options_.monte_carlo);
    std::vector<std::size_t> handed(outcomes.size(), 0), failed(outcomes.size(), 0);   // failed: not certified where the band is bounded
    std::vector<std::vector<std::size_t>> left(outcomes.size());   // positions outside the certified band
    const std::vector<Distribution>& dist = stages_.front().distributions;
    // per pair and position: the candidates (the same for every vector)
    std::vector<std::vector<std::vector<CurveSlice>>> near(stages_.size());
    for (std::size_t s = 0; s < stages_.size(); ++s) {
      near[s].resize(positions());
      for (std::size_t i = 0; i < positions(); ++i)
        if (result_.samples[i].contact)
          near[s][i] = envelope_on() ? holders_near(s, i) : std::vector<CurveSlice>{stages_[s].contacts[i].curve};
    }
    auto evaluate = [&](std::size_t index) {
      MonteCarloOutcome& outcome = outcomes[index];
      outcome.value.assign(positions(), std::nan(""));
      std::vector<double> deviations =
          paths_.monte_carlo_vector ? paths_.monte_carlo_vector(index) : draw(dist, options_.seed, index);
      std::vector<Interval> parameters = stages_.front().solver->point_parameters(deviations);
      // Per pair: each feature pair's geometry at this vector (it does not depend on the position).
      struct Cached {
        FeatureIdentity first, second;
        PairGeometry<Interval> geometry;
      };
      std::vector<std::vector<Cached>> geometry(stages_.size());
      // Per pair: where its follower is (part units; an unloaded follower stays there while no
      // contact meets it), from its free start.
      std::vector<std::optional<Interval>> where(stages_.size());
      for (std::size_t s = 0; s < stages_.size(); ++s)
        if (free_start_[s]) where[s] = Interval::point(*free_start_[s]);
      for (std::size_t i = 0; i < positions(); ++i) {
        const VariationSample& sample = result_.samples[i];
        if (!sample.contact) continue;
        ++outcome.evaluations;
        Interval x;
        bool ok = true;
        bool retried = false;   // a pair's value found by the wider search
        for (std::size_t s = 0; s < stages_.size() && ok; ++s) {
          const StageAnalysis& stage = stages_[s];
          const StageContact& c = stage.contacts[i];
          std::vector<Candidate> candidates;
          for (const CurveSlice& slice : near[s][i]) {
            Candidate candidate{slice, std::nullopt};
            auto it = std::find_if(geometry[s].begin(), geometry[s].end(),
                                   [&](const Cached& g) { return g.first == slice.first && g.second == slice.second; });
            if (it == geometry[s].end()) {
              geometry[s].push_back(Cached{slice.first, slice.second, stage.solver->point_geometry(slice, parameters)});
              it = geometry[s].end() - 1;
            }
            candidate.geometry = it->geometry;
            candidates.push_back(std::move(candidate));
          }
          // the holder's linearised value: its driver moved to the previous pair's value
          double guess = c.v, linear = 0;
          for (std::size_t p = 0; p < deviations.size() && p < c.s_chart.size(); ++p) {
            guess += c.s_chart[p] * deviations[p];
            linear += std::fabs(c.s_chart[p] * deviations[p]);
          }
          if (s > 0) {
            Interval t;
            if (!part_to_chart(x, stage.result.driver_rotates, c.curve.fixed_half_turn,
                               stages_[s - 1].result.samples[i].nominal, t)) {
              ok = false;
              break;
            }
            for (Candidate& candidate : candidates) candidate.curve.fixed_range = t;
            double shift = per_[i][s].fixed_slope * (t.middle() - c.curve.fixed_value.get_d());
            guess += shift;
            linear += std::fabs(shift) + std::fabs(per_[i][s].fixed_slope) * t.width();
          }
          Interval root;
          bool handed_over = false;
          int sigma = 0;
          const double width = 0.25 * linear + 1e-9 * (1 + std::fabs(guess));
          if (!actual_root(*stage.solver, candidates, guess, width, root, handed_over, sigma)) {
            if (!actual_root(*stage.solver, candidates, guess, width, root, handed_over, sigma, true)) {
              ok = false;
              break;
            }
            retried = true;
          }
          handed[index] += handed_over;
          x = to_part(root, stage.result.follower_rotates, c.follower_half, stage.result.samples[i].nominal);
          // An unloaded follower not yet met (still beyond the contact on its free side, e.g. in
          // the backlash at the train's start) stays where it is: the sigma-further of both.
          if (unloaded_[s] && where[s])
            x = sigma > 0 ? Interval(std::max(x.lo, where[s]->lo), std::max(x.hi, where[s]->hi))
                          : Interval(std::min(x.lo, where[s]->lo), std::min(x.hi, where[s]->hi));
          if (unloaded_[s]) where[s] = x;
        }
        if (!ok) {
          // no certified value, even by the wider search: not certified (neither inside nor
          // outside the band), not an evaluation
          --outcome.evaluations;
          ++outcome.not_certified;
          if (std::isfinite(sample.certified.upper - sample.certified.lower)) ++failed[index];
          continue;
        }
        // A value the wider search found is the holder's nearest certified root, not proved to be
        // the follower's position (another root may lie nearer the nominal one, between the
        // grid's points): outside the band it is not certified rather than a defect of the band
        // (session 29's review).
        if (retried && (x.lo < sample.certified.lower || x.hi > sample.certified.upper)) {
          --outcome.evaluations;
          ++outcome.not_certified;
          if (std::isfinite(sample.certified.upper - sample.certified.lower)) ++failed[index];
          continue;
        }
        std::size_t before = outcome.outside_certified;
        outcome.record(i, x, sample);
        if (outcome.outside_certified > before) left[index].push_back(i);
        if (paths_.monte_carlo_value) paths_.monte_carlo_value(index, i, x);
      }
    };
    // in chunks, the progress bar advanced between them (each vector writes its own slot)
    const std::size_t chunk = std::max<std::size_t>(1, outcomes.size() / 20);
    for (std::size_t from = 0; from < outcomes.size(); from += chunk) {
      std::size_t count = std::min(chunk, outcomes.size() - from);
      parallel_for(options_.threads, count, [&](std::size_t k) { evaluate(from + k); },
                   [&](std::size_t done) { bar_.units(from + done, outcomes.size()); });
    }
    merge_monte_carlo(outcomes, summary, result_);
    summary.seconds = wall_since(start);
    summary.cpu_seconds = cpu_now() - cpu_start;
    result_.monte_carlo = summary;
    monte_carlo_notes(outcomes, handed, failed, left);
  }

  // What the Monte Carlo found, said where the report is read: hand-overs it followed, values
  // outside the certified band (where, and what that means), beyond the linearised band.
  void monte_carlo_notes(const std::vector<MonteCarloOutcome>& outcomes, const std::vector<std::size_t>& handed,
                         const std::vector<std::size_t>& failed, const std::vector<std::vector<std::size_t>>& left) {
    std::size_t handed_total = 0, failed_total = 0, unbounded = 0, evaluations = 0, not_certified = 0;
    for (std::size_t k = 0; k < outcomes.size(); ++k) {
      handed_total += handed[k];
      failed_total += failed[k];
      evaluations += outcomes[k].evaluations;
      not_certified += outcomes[k].not_certified;
    }
    std::vector<std::size_t> where;
    for (const auto& l : left) where.insert(where.end(), l.begin(), l.end());
    std::sort(where.begin(), where.end());
    where.erase(std::unique(where.begin(), where.end()), where.end());
    for (const VariationSample& sample : result_.samples)
      unbounded += sample.contact && !std::isfinite(sample.certified.upper - sample.certified.lower);
    notes_.push_back(
        (envelope_on()
             ? "Monte Carlo: each pair's follower placed by the first contact it meets among the feature pairs holding "
               "it along the nominal path next to the position (its nominal holder and the nearest other holder before "
               "and after it), each value certified; another feature pair than the nominal holder held a follower " +
                   std::to_string(handed_total) + " time(s) over "
             : std::string("Monte Carlo under --assume-nominal-contact: each pair's follower on its nominal holder, as the "
                           "band assumes (hand-overs inside the tolerance box not followed), each value certified; ")) +
        std::to_string(evaluations) + " evaluated output position(s)" +
                     (unbounded > 0 ? " (" + std::to_string(unbounded) +
                                          " position(s) without a certified band: compared with the linearised band only)"
                                    : std::string()));
    if (not_certified > 0)
      notes_.push_back("Monte Carlo: no value certified at " + std::to_string(not_certified) + " output position(s), " +
                       std::to_string(failed_total) +
                       " of them with a bounded certified band (a follower's root bracketed neither about its "
                       "linearised value nor by the wider search over grids of points: no certain sign change found); "
                       "counted as not certified, neither inside nor outside the band");
    if (!where.empty()) {
      std::string drivers;
      for (std::size_t k = 0; k < where.size() && k < 8; ++k)
        drivers += (k ? ", " : "") + std::to_string(result_.samples[where[k]].driver);
      if (where.size() > 8) drivers += ", ...";
      notes_.push_back(
          "Monte Carlo values outside the certified band at " + std::to_string(where.size()) +
          " driver position(s) (" + drivers + ")" +
          (envelope_on() ? ": a defect of the band (it must never happen)"
                         : ": where the nominal holder assumed by --assume-nominal-contact is not the actual one for the "
                           "sampled parameters (another tooth or flank taking over)"));
    }
    if (result_.monte_carlo && result_.monte_carlo->outside_linear > 0)
      notes_.push_back("Monte Carlo values beyond the linearised band: " +
                       std::to_string(result_.monte_carlo->outside_linear) + " of " + std::to_string(evaluations) +
                       ", by up to " + std::to_string(result_.monte_carlo->linearisation_error) +
                       " (rad or mm): the linearisation error, hand-overs inside the tolerance box included");
  }

  static constexpr std::size_t max_shared_boxes = 128;   // sub-boxes of the tolerance box per position
  static constexpr std::size_t max_held_pieces = 16;     // pieces of a held driver range (held_pieces)
  // (the sub-boxes of the tolerance box per position where a composition fails, session 42:
  // ToleranceOptions::chain_failure_boxes since session 72)

  std::string text_;
  ToleranceOptions options_;
  // The bar's stages: reading, the chain's kinematics, each pair at the positions, the certified
  // band, the Monte Carlo.
  StagedProgress bar_{options_.progress, {0, 0.05, 0.2, 0.4, 0.6, 1}};
  ChainPaths paths_;
  std::vector<long>* exponents_ = nullptr;   ///< analyze_chain's: the parameters' scale exponents
  // The hand-over envelope (handover.cpp): on unless the caller assumes the nominal holders.
  bool envelope_on() const { return !options_.chain_assume_nominal_holder; }
  std::vector<StageAnalysis> stages_;
  std::vector<char> unloaded_;                       // per pair: its follower has no load
  std::vector<std::optional<double>> free_start_;    // per pair: an unloaded follower's free start (part units)
  std::vector<std::unique_ptr<HandoverSearch>> handovers_;   // per pair
  std::vector<std::vector<PositionStage>> per_;   // [position][pair]
  ToleranceResult result_;
  long length_exponent_ = 0;   // the chain analysed in units of 10^E mm (analysed_form)
  std::vector<std::string> notes_;
};

}  // namespace

int& chain_case_split() {
  static int on = 1;
  return on;
}

int& chain_widened_split() {
  static int on = 1;
  return on;
}

int& chain_plain_reuse() {
  static int on = 1;
  return on;
}

int& chain_case_resume() {
  static int on = 1;
  return on;
}

std::atomic<std::size_t>& chain_cases_resumed() {
  static std::atomic<std::size_t> resumed{0};
  return resumed;
}

int& chain_driver_piece_meet() {
  static int on = 2;
  return on;
}

std::atomic<std::size_t>& chain_driver_piece_meets() {
  static std::atomic<std::size_t> narrowed{0};
  return narrowed;
}

std::atomic<std::size_t>& chain_compositions_made() {
  static std::atomic<std::size_t> made{0};
  return made;
}

std::size_t& chain_memo_entries() {
  // session 43 (tol43): gear-train.json 0..1.53 rad at 60 per turn 1.28 GB -> 0.32 GB, the
  // same output
  static std::size_t entries = 1000;
  return entries;
}

ToleranceResult analyze_chain(std::string_view text, const ToleranceOptions& options, const ChainPaths& paths,
                              std::vector<long>* exponents) {
  if (exponents) exponents->clear();
  return ChainAnalysis(text, options, paths, exponents).run();
}

}  // namespace hipair::tolerance_detail
