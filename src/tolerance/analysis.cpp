// Kinematic tolerance analysis of a driven pair (include/hipair/tolerance.hpp,
// docs/tolerance.md). The nominal path comes from analyze_kinematics; at each driver position
// an exact slice of the nominal C-space (the public adaptor) names the feature pair holding
// the follower and the two sides of its free channel; each is then solved over the parametric
// model (solver.hpp).
#include <hipair/tolerance.hpp>
#include <hipair/tolerance_scale.hpp>

#include "core/model_scale.hpp"
#include "model/parametric/dimensions.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/certificate.hpp"
#include "tolerance/exact_order.hpp"
#include "tolerance/progress.hpp"
#include "tolerance/root_search.hpp"
#include "tolerance/sampling.hpp"
#include "tolerance/solver.hpp"
#include "tolerance/stage.hpp"

#include <hipair/cspace_region.hpp>
#include <hipair/cspace_slice.hpp>
#include <hipair/error.hpp>
#include <hipair/kernel_slice.hpp>
#include <hipair/kinematics.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <iomanip>
#include <sstream>
#include <numbers>
#include <thread>

namespace hipair {
namespace tolerance_detail {

// Chart enclosure -> part coordinate enclosure, unwrapped near `near` (rotations).
Interval to_part(const Interval& chart, bool rotates, bool half, double near) {
  if (!rotates) return chart;
  Interval theta = tolerance_detail::chart_to_angle(chart, half);
  double turns = std::round((near - theta.middle()) / (2 * std::numbers::pi));
  if (turns != 0) {
    Interval two_pi = Interval(2) * model_detail::Arithmetic<Interval>::pi();
    theta = theta + Interval::point(turns) * two_pi;
  }
  return theta;
}

double chart_slope(double t, bool rotates) { return rotates ? 2 / (1 + t * t) : 1.0; }

std::pair<double, double> linear_bands(VariationSample& sample, const std::vector<double>& s,
                                       const std::vector<Distribution>& dist) {
  double lower = 0, upper = 0, mean = 0, variance = 0, largest = 0;
  bool ordinary = true;   // every factor within 1e-75 .. 1e75 (or 0): s^2 sigma^2 neither overflows nor underflows
  auto moderate = [](double x) { return x == 0 || (std::fabs(x) >= 1e-75 && std::fabs(x) <= 1e75); };
  for (std::size_t i = 0; i < s.size(); ++i) {
    lower += std::min(s[i] * dist[i].lo, s[i] * dist[i].hi);
    upper += std::max(s[i] * dist[i].lo, s[i] * dist[i].hi);
    mean += s[i] * dist[i].mean;
    if (s[i] == 0 || dist[i].sigma == 0) continue;   // (an infinite square times 0 was NaN)
    variance += s[i] * s[i] * dist[i].sigma * dist[i].sigma;
    largest = std::max(largest, std::fabs(s[i] * dist[i].sigma));
    ordinary = ordinary && moderate(s[i]) && moderate(dist[i].sigma);
  }
  double deviation = std::sqrt(variance);
  // Elsewhere (session 64, tol64) the standard deviation sqrt(sum (s_i sigma_i)^2) with each term
  // divided by the largest before it is squared: s_i^2 sigma_i^2 as a product of squares overflowed
  // or underflowed where a sensitivity and a sigma lie at opposite extremes (a model whose
  // parameters are lengths of 1e-300 mm: s ~ 1e300 per mm, sigma ~ 1e-302 mm: the band was +-0).
  if (!ordinary && largest > 0 && std::isfinite(largest)) {
    double sum = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] == 0 || dist[i].sigma == 0) continue;
      const double term = s[i] * dist[i].sigma / largest;
      sum += term * term;
    }
    deviation = largest * std::sqrt(sum);
  }
  sample.linear_lower = sample.nominal + lower;
  sample.linear_upper = sample.nominal + upper;
  sample.rss_lower = sample.nominal + mean - 3 * deviation;
  sample.rss_upper = sample.nominal + mean + 3 * deviation;
  sample.sensitivities = s;
  return {lower, upper};
}

void extend_regions(ToleranceResult& result, std::size_t k, const std::string& label, const FeatureIdentity& first,
                    const FeatureIdentity& second, const std::vector<double>& s, const std::vector<Distribution>& dist,
                    double half_width) {
  VariationSample& sample = result.samples[k];
  bool extend = !result.regions.empty() && result.regions.back().last_sample + 1 == k &&
                result.regions.back().contact == label && result.regions.back().first == first &&
                result.regions.back().second == second;
  if (!extend) {
    ContactRegion region;
    region.contact = label;
    region.first = first;
    region.second = second;
    region.driver_start = sample.driver;
    region.first_sample = k;
    region.ranked.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) region.ranked[i].parameter = result.parameters[i].name;
    result.regions.push_back(region);
  }
  ContactRegion& region = result.regions.back();
  region.driver_end = sample.driver;
  region.last_sample = k;
  region.linear_half_width = std::max(region.linear_half_width, half_width);
  sample.region = result.regions.size() - 1;
  for (std::size_t i = 0; i < s.size(); ++i) {
    double c = std::fabs(s[i]) * 0.5 * (dist[i].hi - dist[i].lo);
    if (c >= region.ranked[i].contribution) {
      region.ranked[i].contribution = c;
      region.ranked[i].sensitivity = s[i];
    }
  }
}

void rank_regions(ToleranceResult& result) {
  for (ContactRegion& region : result.regions) {
    double total = 0;
    for (const ParameterContribution& c : region.ranked) total += c.contribution;
    for (ParameterContribution& c : region.ranked) c.share = total > 0 ? c.contribution / total : 0;
    std::stable_sort(region.ranked.begin(), region.ranked.end(),
                     [](const ParameterContribution& a, const ParameterContribution& b) {
                       return a.contribution > b.contribution;
                     });
  }
}

// Outside the certified band only when certainly so: the sample's enclosure apart from the band's
// (session 62: an enclosure merely reaching past the band is no evidence; at zero tolerances the
// band is itself an enclosure of the nominal root as narrow as the sample's, and ratchet.json's
// 8 samples were reported "outside the certified band: 240 (A DEFECT)").
// Inside only when certainly so (session 63): an enclosure meeting an edge of the band is
// undecided, counted on its own (until session 63 it was counted inside).
void MonteCarloOutcome::record(std::size_t k, const Interval& part, const VariationSample& sample) {
  if (part.hi < sample.certified.lower || part.lo > sample.certified.upper) ++outside_certified;
  else if (!(part.lo >= sample.certified.lower && part.hi <= sample.certified.upper)) ++undecided_certified;
  record_linear(k, part.middle(), sample);
}

void MonteCarloOutcome::record_linear(std::size_t k, double v, const VariationSample& sample) {
  value[k] = v;
  double e = std::max(v - sample.linear_upper, sample.linear_lower - v);
  if (e > 0) {
    ++outside_linear;
    excess = std::max(excess, e);
  }
}

void merge_monte_carlo(const std::vector<MonteCarloOutcome>& outcomes, MonteCarloSummary& summary,
                       ToleranceResult& result) {
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const MonteCarloOutcome& o = outcomes[i];
    summary.outside_certified += o.outside_certified;
    summary.not_certified += o.not_certified;
    summary.undecided_certified += o.undecided_certified;
    summary.outside_linear += o.outside_linear;
    summary.evaluations += o.evaluations;
    summary.linearisation_error = std::max(summary.linearisation_error, o.excess);
    for (std::size_t k = 0; k < o.value.size(); ++k) {
      double v = o.value[k];
      if (std::isnan(v)) continue;
      VariationSample& sample = result.samples[k];
      if (!sample.has_monte_carlo) {
        sample.has_monte_carlo = true;
        sample.monte_carlo_min = sample.monte_carlo_max = v;
      } else {
        sample.monte_carlo_min = std::min(sample.monte_carlo_min, v);
        sample.monte_carlo_max = std::max(sample.monte_carlo_max, v);
      }
    }
    if (i < 12) result.monte_carlo_curves.push_back(o.value);
  }
}

void parallel_for(unsigned threads, std::size_t count, const std::function<void(std::size_t)>& task) {
  parallel_for(threads, count, task, {});
}

void parallel_for(unsigned threads, std::size_t count, const std::function<void(std::size_t)>& task,
                  const std::function<void(std::size_t)>& done) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
  std::atomic<std::size_t> next{0}, finished{0};
  auto work = [&](bool caller) {
    for (std::size_t i = next++; i < count; i = next++) {
      task(i);
      std::size_t n = ++finished;
      if (caller && done) done(n);
    }
  };
  std::vector<std::future<void>> workers;
  for (unsigned t = 1; t < threads; ++t) workers.push_back(std::async(std::launch::async, work, false));
  work(true);
  for (auto& worker : workers) {
    // the calling thread's own tasks are done: it reports the workers' while they finish theirs
    if (done)
      while (worker.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) done(finished.load());
    worker.get();
  }
  if (done) done(count);
}

}  // namespace tolerance_detail

namespace {

using tolerance_detail::Box;
using tolerance_detail::CurveSlice;
using tolerance_detail::CurveSolver;
using Interval = kernels::Interval;
constexpr double pi = std::numbers::pi;

using tolerance_detail::seconds_since;

// CPU time of the calling thread, or of the whole process (s).
double cpu_seconds(bool process = false) {
  timespec t{};
  clock_gettime(process ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct ChartValue {
  Rational t;
  bool half = false;
};

// A part coordinate for CSpace::to_chart: tan(theta/2) of a rotation, the offset of a translation.
PartCoordinate part_coordinate(bool rotates, double coordinate) {
  PartCoordinate p;
  if (!rotates) {
    p.kind = PartCoordinate::Kind::offset;
    p.value = Rational(coordinate);
    return p;
  }
  double wrapped = std::remainder(coordinate, 2 * pi);
  if (std::fabs(wrapped) == pi) {
    p.kind = PartCoordinate::Kind::half_turn;
    return p;
  }
  p.kind = PartCoordinate::Kind::half_angle_tangent;
  p.value = Rational(std::tan(wrapped / 2));
  return p;
}

using tolerance_detail::chart_slope;
using tolerance_detail::to_part;

// Build options passing a C-space build's fraction done to `sink` (a part of the bar:
// StagedProgress::within); an empty sink (no progress asked for) asks for no reports.
CSpaceBuildOptions reporting(std::function<void(double)> sink) {
  CSpaceBuildOptions options;
  if (sink) options.progress = [sink = std::move(sink)](const CSpaceBuildProgress& report) { sink(report.fraction); };
  return options;
}

// A side of the follower's channel in a slice: where, and the feature pairs there.
struct Side {
  bool present = false;
  double value = 0;                  // chart coordinate (approximate, for reports)
  AlgebraicNumber exact;             // chart coordinate (exact: the decisions use this)
  std::vector<FeatureId> features;
};

struct SampleState {
  bool valid = false;
  bool ambiguous = false;            // in contact, but equidistant from two slice points
  ChartValue driver_chart, follower_chart;
  std::size_t chart = no_index;
  bool contact = false;
  FeatureId feature;
  CurveSlice curve;
  double v = 0;                      // follower chart coordinate on the curve
  std::vector<double> s_chart;       // dv/dp
  Interval certified_chart;
  Side lower, upper;                 // the channel
};

using tolerance_detail::Distribution;
using tolerance_detail::distributions;
using tolerance_detail::draw;

class Analysis {
 public:
  Analysis(std::string_view text, const ToleranceOptions& options, std::string source_name = "<string>")
      : options_(options), text_(text), source_name_(std::move(source_name)) {
    if (!options_.parameter_values.empty() && (options_.certify || options_.certify_free_path))
      throw ModelError("", "tolerance certificates are about the model file as written (hipair-verify checks them "
                           "against it): write the changed nominal values into the model instead of --set");
    model_ = tolerance_detail::analysed_form(
        model_detail::ParametricModel::read(text, "<string>", tolerance_detail::design_read_options(options_)), options_);
    start_solver();
  }
  // On `model`, the parametric form of `text` read with design_read_options(options) (an
  // assembly chain's, recorded once for all its pairs).
  Analysis(std::string_view text, std::shared_ptr<const model_detail::ParametricModel> model,
           const ToleranceOptions& options)
      : options_(options), text_(text), source_name_("<string>"), model_(std::move(model)) {
    start_solver();
  }

  // One pair of an assembly chain at the chain's positions (stage.hpp): the nominal path is
  // given, and only the sensitivities and the linearised and RSS bands are computed here.
  // `space`: the pair's C-space when the caller built it already (the chain's kinematics), else
  // built here.
  tolerance_detail::StageAnalysis stage(const std::vector<tolerance_detail::StagePosition>& path,
                                        const CSpace* space = nullptr) {
    solver_->set_second_order(false);   // as the kernel path's stages (chain.cpp)
    solver_->set_taylor_partials(options_.taylor_partials);
    start(space);
    for (const tolerance_detail::StagePosition& position : path)
      add_sample(position.driver, position.follower, position.contact);
    sensitivities();
    tolerance_detail::StageAnalysis out;
    for (const SampleState& state : states_) {
      tolerance_detail::StageContact c;
      c.contact = state.contact;
      if (state.contact) {
        c.curve = state.curve;
        c.label = space_->feature_pair(state.feature).label;
        c.v = state.v;
        c.follower_half = state.follower_chart.half;
        c.s_chart = state.s_chart;
      }
      out.contacts.push_back(std::move(c));
    }
    out.result = std::move(result_);
    out.solver = std::move(solver_);
    out.distributions = dist_;
    out.box = box_;
    return out;
  }

  // What run() and stage() share: the parts, the distributions and box, the pair's C-space.
  void start(const CSpace* given = nullptr) {
    const Model& m = model_->nominal();
    result_.model_name = m.name;
    result_.parameters = m.parameters;
    result_.length_exponent = model_->length_exponent();
    choose_parts();
    // A certificate of a mechanism analysed in units of 10^E mm (analysed_form): the producer works
    // on that copy; when both parts rotate, every number of the claim is an angle or a
    // parameter's deviation (the copy keeps the parameters as read) but the second-order margins,
    // which it writes at the file's scale (certificate.cpp file_scale_margins), so it is a
    // certificate of the model file as written, and certify_no_jam checks it against the file's
    // text (hipair-verify's check, exact at any scale) before it is kept. A translating part's
    // offsets and brackets would be the copy's: still refused (session 56, scale56; until then
    // refused at every such scale).
    if ((options_.certify || options_.certify_free_path) && model_->length_exponent() != 0 &&
        !(result_.driver_rotates && result_.follower_rotates)) {
      const Part& moving = m.parts[result_.driver_rotates ? follower_ : driver_];
      throw ModelError(moving.pointer, "--certify: this model's lengths lie outside about 1e-9 .. 1e9 mm and part '" +
                                           moving.name + "' translates: its tolerance analysis runs on the model "
                                           "divided exactly by 1e" + std::to_string(model_->length_exponent()) +
                                           ", whose offsets a certificate would give, while hipair-verify checks it "
                                           "against the model file: run the analysis without --certify, or certify "
                                           "the model drawn in a unit near its size");
    }
    std::size_t n = m.parameters.size();
    dist_ = distributions(m);
    box_.lo.resize(n);
    box_.hi.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      // Outward: the band's box contains the exact rational tolerance box (the nearest doubles
      // of its ends could leave out half an ulp of it).
      box_.lo[i] = dist_[i].box_lo;
      box_.hi[i] = dist_[i].box_hi;
      result_.sigma.push_back(dist_[i].sigma);
      result_.mean_shift.push_back(dist_[i].mean);
    }
    // The generic forms follow the templates' nominal shapes: a box that may change one refused
    // (the templates' rules decided over the exact box where the doubles' enclosures cannot).
    {
      std::vector<Rational> lo(n), hi(n);
      for (std::size_t i = 0; i < n; ++i) {
        lo[i] = m.parameters[i].range.lo - m.parameters[i].nominal;
        hi[i] = m.parameters[i].range.hi - m.parameters[i].nominal;
      }
      model_->check_choices(lo, hi);
    }
    std::size_t edges = 0;
    for (std::size_t part : {driver_, follower_})
      for (const Loop& loop : m.parts[part].loops) edges += loop.edges.size();
    if (given) {
      space_ = std::make_unique<CSpace>(*given);
    } else if (edges > 120) {
      large_pair_ = true;
      // A large pair (a gear pair's z1 z2 tooth encounters): the nominal path is analyze's, on
      // the contact kernels, and the exact C-space is its operating region along that path (the
      // tiles of the path's channel the path runs through), as analyze draws it; the whole space
      // of the 18 x 27 spur gears took minutes to build and slice.
      kernel_path_ = path_kinematics(SliceMethod::kernels, {});
      std::vector<std::array<double, 2>> along;
      std::string x_part, y_part;
      for (const PairPath& path : kernel_path_->paths) {
        if (path.y_part.empty()) continue;
        x_part = path.x_part;
        y_part = path.y_part;
        for (const PathPoint& point : path.points) along.push_back({point.x, point.y});
      }
      if (along.empty()) throw GeometryError("the nominal path of pair " + pair_first_ + ":" + pair_second_ + " is empty");
      space_ = std::make_unique<CSpace>(build_operating_region_along(m, x_part, y_part, along));
    } else {
      // the build's progress, as its stage's
      space_ = std::make_unique<CSpace>(CSpace::build(m, pair_first_, pair_second_, reporting(bar_.within())));
    }
    driver_is_x_ = space_->x_part() == result_.driver;
    kernel_confirmations_ = large_pair_ || !tolerance_detail::whole_space_confirmations_switch();
  }

  /// The parametric form the analysis runs on (analysed_form).
  const model_detail::ParametricModel& model() const { return *model_; }

  ToleranceResult run() {
    bar_.begin(0);
    auto t0 = std::chrono::steady_clock::now();
    start();
    bar_.begin(1);
    nominal_path();
    bar_.begin(2);
    sensitivities();
    result_.seconds_sensitivity = seconds_since(t0);
    bar_.begin(3);
    auto t1 = std::chrono::steady_clock::now();
    double c1 = cpu_seconds(true);
    certified();
    result_.seconds_certified = seconds_since(t1);
    result_.cpu_seconds_certified = cpu_seconds(true) - c1;
    bar_.begin(4);
    auto t2 = std::chrono::steady_clock::now();
    double c2 = cpu_seconds(true);
    zones();
    result_.seconds_zones = seconds_since(t2);
    result_.cpu_seconds_zones = cpu_seconds(true) - c2;
    bar_.begin(5);
    if (options_.monte_carlo > 0) monte_carlo();
    bar_.begin(6);
    if (options_.threshold) {
      auto t3 = std::chrono::steady_clock::now();
      threshold();
      result_.seconds_threshold = seconds_since(t3);
    }
    bar_.begin(7);
    if (options_.contact_changes) contact_changes();
    bar_.begin(8);
    if (options_.certify) certify();
    bar_.finish();
    return std::move(result_);
  }

 private:
  // The current stage's `done` of `total` work units, for a parallel stage's progress.
  std::function<void(std::size_t)> units_of(std::size_t total) {
    if (!bar_.active()) return {};
    return [this, total](std::size_t done) { bar_.units(done, total); };
  }

  void choose_parts() {
    const Model& m = model_->nominal();
    auto moving = [&](std::size_t k) {
      auto kind = m.parts[k].motion.kind;
      return kind == Motion::Kind::rotation || kind == Motion::Kind::translation;
    };
    std::optional<std::size_t> driver, follower;
    if (!options_.driver.empty()) {
      driver = m.find_part(options_.driver);
      if (!driver) throw ModelError("", "unknown driver part '" + options_.driver + "' (--driver)");
    }
    if (!options_.follower.empty()) {
      follower = m.find_part(options_.follower);
      if (!follower) throw ModelError("", "unknown part '" + options_.follower + "' (--pair)");
    }
    for (const PairSpec& pair : m.pairs) {
      if (!moving(pair.first) || !moving(pair.second)) continue;
      bool matches = (!driver || pair.first == *driver || pair.second == *driver) &&
                     (!follower || pair.first == *follower || pair.second == *follower);
      if (!matches) continue;
      std::size_t d = driver ? *driver : (follower && *follower == pair.first ? pair.second : pair.first);
      std::size_t f = d == pair.first ? pair.second : pair.first;
      if (follower && f != *follower) continue;
      driver_ = d;
      follower_ = f;
      pair_first_ = m.parts[pair.first].name;
      pair_second_ = m.parts[pair.second].name;
      result_.driver = m.parts[d].name;
      result_.follower = m.parts[f].name;
      result_.driver_rotates = m.parts[d].motion.kind == Motion::Kind::rotation;
      result_.follower_rotates = m.parts[f].motion.kind == Motion::Kind::rotation;
      return;
    }
    throw ModelError("/pairs", "no pair of two parts with rotation or translation motions matches the driver and pair asked for");
  }

  // The nominal mechanism's kinematics over the range, on the analysed pair only.
  KinematicsResult path_kinematics(SliceMethod method, const std::vector<CSpace>& spaces) {
    const Model& m = model_->nominal();
    KinematicsOptions k;
    k.driver = result_.driver;
    k.range = tolerance_detail::range_in_unit(options_, result_.driver_rotates, model_->length_exponent());
    k.steps_per_cycle = static_cast<unsigned>(std::max<std::size_t>(8, options_.positions));
    k.reversal = false;
    k.method = method;
    // the sweep's progress within its stage of the bar (a long --range ran minutes at "2%")
    k.progress = bar_.within();
    // Only the analysed pair: a model holding more parts is cut to the two.
    Model pair_model = m;
    pair_model.pairs.clear();
    for (const PairSpec& pair : m.pairs)
      if ((pair.first == driver_ && pair.second == follower_) || (pair.first == follower_ && pair.second == driver_))
        pair_model.pairs.push_back(pair);
    return analyze_kinematics(pair_model, k, spaces);
  }

  void nominal_path() {
    // The nominal path on the pair's C-space as analyze takes it (SliceMethod::automatic): its
    // slicer cuts across the space's x axis, so a driver that is the pair's second part (the
    // space's y part: cam-follower's --driver follower, hostile74 M2) takes the contact kernels'
    // exact slices, as analyze does; the samples are located in the space either way (locate()).
    KinematicsResult kinematics = kernel_path_ ? std::move(*kernel_path_) : path_kinematics(SliceMethod::automatic, {*space_});
    auto follower_index = std::find(kinematics.followers.begin(), kinematics.followers.end(), result_.follower);
    if (follower_index == kinematics.followers.end())
      throw GeometryError("the follower '" + result_.follower + "' is not moved by the driver over the range");
    std::size_t fi = static_cast<std::size_t>(follower_index - kinematics.followers.begin());
    if (kinematics.jam) result_.notes.push_back("the nominal mechanism jams: " + kinematics.jam->description);
    for (const KinematicSample& ks : kinematics.samples) {
      // Contact or free is the exact kinematic engine's decision (its contacts at the
      // follower's exact position); locate() then matches the slice point exactly.
      bool in_contact = std::any_of(ks.contacts[fi].begin(), ks.contacts[fi].end(),
                                    [](const ContactLabel& c) { return !c.limit; });
      add_sample(ks.driver, ks.positions[fi], in_contact);
    }
  }

  void add_sample(double driver, double follower, bool in_contact) {
    {
      VariationSample sample;
      sample.driver = driver;
      sample.nominal = follower;
      SampleState state = locate(driver, follower, in_contact);
      if (state.ambiguous)
        result_.notes.push_back("driver " + std::to_string(driver) +
                                ": the follower is equidistant from two slice points; position not analysed");
      sample.contact = state.contact;
      sample.play = state.lower.present && state.upper.present ? state.upper.value - state.lower.value : -1;
      if (state.lower.present && state.upper.present && result_.follower_rotates) {
        // play in part units (rad)
        double lo = 2 * std::atan(state.lower.value), hi = 2 * std::atan(state.upper.value);
        sample.play = hi - lo;
      }
      result_.samples.push_back(sample);
      states_.push_back(std::move(state));
    }
  }

  // The slice of the nominal C-space at the driver position, and the follower in it.
  SampleState locate(double driver, double follower, bool in_contact) {
    SampleState s;
    PartCoordinate d = part_coordinate(result_.driver_rotates, driver);
    PartCoordinate f = part_coordinate(result_.follower_rotates, follower);
    std::optional<ChartPoint> point = driver_is_x_ ? space_->to_chart(d, f) : space_->to_chart(f, d);
    if (!point) return s;
    const CSpaceChart& chart = space_->charts()[point->chart];
    s.chart = point->chart;
    // to_chart may pick a chart centred elsewhere; use its own coordinates.
    bool driver_half = driver_is_x_ ? chart.x_half_turn : chart.y_half_turn;
    bool follower_half = driver_is_x_ ? chart.y_half_turn : chart.x_half_turn;
    s.driver_chart = ChartValue{driver_is_x_ ? point->x : point->y, driver_half};
    s.follower_chart = ChartValue{driver_is_x_ ? point->y : point->x, follower_half};
    // The slice around the follower only: its channel's sides and the points next to them (two
    // cell boundaries each way: the point holding a contact and its neighbours beyond).
    std::optional<Slice> near = space_->complete()
                                    ? slice_near(*space_, point->chart, driver_is_x_ ? SliceAxis::x : SliceAxis::y,
                                                 s.driver_chart.t, s.follower_chart.t, 2)
                                    : region_slice_near(point->chart, s.driver_chart.t, s.follower_chart.t, 2);
    if (!near) return s;
    const Slice* slice = &*near;
    s.valid = true;
    double v = s.follower_chart.t.get_d();
    // Exact: the points below the follower's chart coordinate, and (in contact) the slice point
    // holding it, the nearest neighbour decided on exact enclosures (exact_order.hpp).
    tolerance_detail::PointMatch match = tolerance_detail::match_point(slice->points, s.follower_chart.t, in_contact);
    s.ambiguous = match.ambiguous;
    std::size_t below = match.below;
    std::optional<std::size_t> at = match.at;
    auto side = [&](std::size_t k) {
      Side result;
      if (k >= slice->points.size()) return result;
      result.present = true;
      result.exact = slice->points[k].at;
      result.value = slice->points[k].at.approximate();
      result.features = slice->points[k].features;
      return result;
    };
    if (at) {
      s.contact = !slice->points[*at].features.empty();
      std::size_t k = *at;
      bool free_above = slice->intervals[k + 1].kind == CellKind::free;
      if (free_above) {
        s.lower = side(k);
        s.upper = side(k + 1);
      } else {
        if (k > 0) s.lower = side(k - 1);
        s.upper = side(k);
      }
    } else {
      if (below > 0) s.lower = side(below - 1);
      s.upper = side(below);
    }
    if (s.contact) {
      for (FeatureId id : slice->points[*at].features) {
        CurveSlice curve = curve_for(id, s);
        double value = v;
        try {
          s.s_chart = solver_->sensitivities(curve, value);
        } catch (const Error&) {
          continue;
        }
        s.feature = id;
        s.curve = curve;
        s.v = value;
        break;
      }
      if (!s.feature.valid()) s.contact = false;
    }
    return s;
  }

  // slice_near across the tiles of an operating region (a large pair's space, session 59): each
  // tile is a chart of its own, and its slice ends at the tile's border, so a channel side lying
  // in the next tile along the follower axis was missing ("no contact below it": the
  // certificate and the bracket's corner search then refused the range). The slice is continued
  // through the built tiles adjacent along the follower axis (same driver range and half turns,
  // sharing the border exactly) until `boundaries` points lie on each side of `at` or no built
  // tile follows (beyond it nothing is known: the slice ends there as at a chart's end). A
  // tile's first interval continues its neighbour's last (one face of the space crossing the
  // border) when both have the same kind and cell; otherwise the border itself, an exact
  // rational, is a boundary point with no feature pair.
  // Session 60: also across the follower's half-turn seam (its chart's end, t = +-1, glued to
  // the other half-turn chart's -+1: the same angle is t' = -1 / t there; base60 refused the
  // spur gears' whole turn at 135 deg). The tiles beyond the seam are walked in their own
  // coordinates and their points and intervals brought into the home chart's exactly
  // (exact_order.hpp other_half_turn); the home chart's coordinate runs to infinity at the
  // other chart's 0 (half a turn from the home chart's centre), where the walk stops.
  std::optional<Slice> region_slice_near(std::size_t chart, const Rational& value, const Rational& at,
                                         std::size_t boundaries) const {
    const SliceAxis axis = driver_is_x_ ? SliceAxis::x : SliceAxis::y;
    std::optional<Slice> slice = slice_near(*space_, chart, axis, value, at, boundaries);
    if (!slice) return slice;
    const std::vector<CSpaceChart>& charts = space_->charts();
    auto fixed_range = [&](const CSpaceChart& c) {
      return driver_is_x_ ? std::make_pair(c.x_lo, c.x_hi) : std::make_pair(c.y_lo, c.y_hi);
    };
    auto free_range = [&](const CSpaceChart& c) {
      return driver_is_x_ ? std::make_pair(c.y_lo, c.y_hi) : std::make_pair(c.x_lo, c.x_hi);
    };
    auto driver_half = [&](const CSpaceChart& c) { return driver_is_x_ ? c.x_half_turn : c.y_half_turn; };
    auto follower_half = [&](const CSpaceChart& c) { return driver_is_x_ ? c.y_half_turn : c.x_half_turn; };
    const CSpaceChart& home = charts[chart];
    const bool rotates = (driver_is_x_ ? home.y_kind : home.x_kind) == AxisKind::rotation;
    // The built tile whose follower range starts (up) or ends (down) at `border` of a chart of
    // follower half turn `half`: in its own half turn, or across the seam (border +-1 there is
    // -+1 in the other half turn's chart) when `seam`.
    auto neighbour = [&](const Rational& border, bool half, bool up, bool seam) -> std::optional<std::size_t> {
      if (seam && (!rotates || border * border != 1)) return std::nullopt;
      const Rational start = seam ? Rational(-border) : border;
      for (std::size_t c = 0; c < charts.size(); ++c) {
        const CSpaceChart& other = charts[c];
        if (c == chart || driver_half(other) != driver_half(home) || follower_half(other) != (seam ? !half : half)) continue;
        auto [lo, hi] = fixed_range(other);
        if (value < lo || value > hi) continue;
        auto [free_lo, free_hi] = free_range(other);
        if ((up ? free_lo : free_hi) == start) return c;
      }
      return std::nullopt;
    };
    auto same_face = [](const Slice::Interval& a, const Slice::Interval& b) { return a.kind == b.kind && a.cell == b.cell; };
    // `more` (a slice in the other half turn's chart, continuing `slice` away from `at`) in the
    // home chart's coordinates; false when it reaches the other chart's 0 (the home chart's
    // infinity): it is then cut there, its last interval ending a unit beyond its last point.
    auto to_home = [&](Slice& more, bool up) {
      const int side = up ? -1 : 1;   // the sign of the other chart's coordinates on the home side
      auto on_home_side = [&](const Rational& q) { return sgn(q) == side; };
      auto home_of = [](const Rational& q) { return Rational(Rational(-1) / q); };
      // the points in walking order (away from `at`)
      std::vector<std::size_t> order(more.points.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = up ? i : order.size() - 1 - i;
      std::vector<Slice::Point> points;
      for (std::size_t i : order) {
        if (tolerance_detail::compare(more.points[i].at, Rational(0)) * side <= 0) break;
        std::optional<AlgebraicNumber> a = tolerance_detail::other_half_turn(more.points[i].at);
        points.push_back(Slice::Point{std::move(*a), more.points[i].features});
      }
      const std::size_t kept = points.size();
      const Rational far = up ? more.upper : more.lower;
      const bool whole = kept == order.size() && on_home_side(far);
      // the cut's window: from the last kept point (or the border) to a unit beyond it
      const Rational last = kept == 0 ? Rational(up ? slice->upper : slice->lower)
                                      : Rational(up ? points.back().at.upper : points.back().at.lower);
      const Rational end = whole ? home_of(far) : up ? Rational(last + 1) : Rational(last - 1);
      // intervals in walking order: the first kept + 1 (those before the cut lie between points
      // on the home side, so do their samples)
      std::vector<Slice::Interval> intervals;
      for (std::size_t k = 0; k <= kept; ++k) {
        Slice::Interval interval = more.intervals[up ? k : more.intervals.size() - 1 - k];
        bool cut = k == kept && !whole;
        interval.sample = !cut ? home_of(interval.sample) : up ? Rational(last + Rational(1, 2)) : Rational(last - Rational(1, 2));
        intervals.push_back(std::move(interval));
      }
      if (!up) {
        std::reverse(points.begin(), points.end());
        std::reverse(intervals.begin(), intervals.end());
      }
      more.points = std::move(points);
      more.intervals = std::move(intervals);
      (up ? more.upper : more.lower) = end;
      return whole;
    };
    // One walk away from `at`, upwards or downwards.
    auto walk = [&](bool up) {
      bool flipped = false;   // the last tile walked is in the other half turn's chart
      const bool half = follower_half(home);
      for (std::size_t guard = 0; guard < charts.size(); ++guard) {
        std::size_t beyond = 0;
        for (const Slice::Point& point : slice->points)
          if (tolerance_detail::compare(point.at, at) * (up ? 1 : -1) > 0) ++beyond;
        if (beyond >= boundaries) return;
        const Rational border = up ? slice->upper : slice->lower;
        // the border in the last tile's own coordinates
        const Rational own = flipped ? Rational(Rational(-1) / border) : border;
        bool seam = false;
        std::optional<std::size_t> next = neighbour(own, flipped ? !half : half, up, false);
        if (!next && !flipped) next = neighbour(own, half, up, seam = true);
        if (!next) return;
        const bool across = flipped || seam;
        const Rational start = seam ? Rational(-own) : own;
        std::optional<Slice> more = slice_near(*space_, *next, axis, value, start, boundaries);
        if (!more) return;
        const bool open = across ? to_home(*more, up) : true;
        Slice& low = up ? *slice : *more;
        Slice& high = up ? *more : *slice;
        std::vector<Slice::Point> points = std::move(low.points);
        std::vector<Slice::Interval> intervals = std::move(low.intervals);
        if (same_face(intervals.back(), high.intervals.front())) {
          // one face across the border: the home side's interval stays
          if (up) high.intervals.erase(high.intervals.begin());
          else intervals.pop_back();
        } else {
          points.push_back(Slice::Point{tolerance_detail::exact_algebraic(border), {}});
        }
        points.insert(points.end(), high.points.begin(), high.points.end());
        intervals.insert(intervals.end(), high.intervals.begin(), high.intervals.end());
        const Rational lower = low.lower, upper = high.upper;
        slice->points = std::move(points);
        slice->intervals = std::move(intervals);
        slice->lower = lower;
        slice->upper = upper;
        flipped = across;
        if (!open) return;
      }
    };
    walk(true);
    walk(false);
    return slice;
  }

  CurveSlice curve_for(FeatureId id, const SampleState& s) const {
    const FeaturePair& pair = space_->feature_pair(id);
    CurveSlice curve;
    curve.first = pair.first;
    curve.second = pair.second;
    curve.fixed_part = driver_;
    curve.free_part = follower_;
    curve.fixed_half_turn = s.driver_chart.half;
    curve.free_half_turn = s.follower_chart.half;
    curve.fixed_value = s.driver_chart.t;
    return curve;
  }

  // Per sample: linearised and statistical bands; per region: the sensitivity table.
  void sensitivities() {
    std::size_t n = result_.parameters.size();
    for (std::size_t k = 0; k < states_.size(); ++k) {
      VariationSample& sample = result_.samples[k];
      SampleState& state = states_[k];
      bar_.units(k, states_.size());
      sample.linear_lower = sample.linear_upper = sample.rss_lower = sample.rss_upper = sample.nominal;
      sample.certified = CertifiedRange{sample.nominal, sample.nominal};
      if (!state.contact) continue;
      double slope = chart_slope(state.v, result_.follower_rotates);
      std::vector<double> s(n);
      for (std::size_t i = 0; i < n; ++i) s[i] = state.s_chart[i] * slope;
      auto [lower, upper] = tolerance_detail::linear_bands(sample, s, dist_);
      const FeaturePair& pair = space_->feature_pair(state.feature);
      tolerance_detail::extend_regions(result_, k, pair.label, pair.first, pair.second, s, dist_, 0.5 * (upper - lower));
    }
    tolerance_detail::rank_regions(result_);
  }

  // Runs task(0 .. count-1) on the analysis' threads (ToleranceOptions::threads); each task
  // writes only its own slot, so the results do not depend on the number of threads.
  void parallel_for(std::size_t count, const std::function<void(std::size_t)>& task,
                    const std::function<void(std::size_t)>& done = {}) const {
    tolerance_detail::parallel_for(options_.threads, count, task, done);
  }

  // One certified enclosure of a curve's root over the whole box (the band's or a zone's).
  struct Enclosure {
    Interval chart;
    std::size_t boxes = 0;
    bool ok = false;
  };
  Enclosure enclose(const CurveSlice& curve, double v, const std::vector<double>& s) const {
    Enclosure e;
    try {
      e.chart = solver_->certified_range(curve, box_, v, s, options_.relative_accuracy, options_.absolute_accuracy, e.boxes);
      e.ok = true;
    } catch (const NumericError&) {
    }
    return e;
  }

  void certified() {
    std::size_t uncertified = 0;
    std::vector<Enclosure> enclosures(states_.size());
    parallel_for(states_.size(), [&](std::size_t k) {
      const SampleState& state = states_[k];
      if (state.contact) enclosures[k] = enclose(state.curve, state.v, state.s_chart);
    }, units_of(states_.size()));
    for (std::size_t k = 0; k < states_.size(); ++k) {
      SampleState& state = states_[k];
      if (!state.contact) continue;
      VariationSample& sample = result_.samples[k];
      result_.certified_boxes += enclosures[k].boxes;
      if (!enclosures[k].ok) {
        // Not certified here (a singular curve, or a contact change inside the box): the band
        // is the whole line, which keeps every statement about it true, and it is reported.
        ++uncertified;
        state.certified_chart = Interval(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
        sample.certified = CertifiedRange{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        continue;
      }
      state.certified_chart = enclosures[k].chart;
      Interval part = to_part(state.certified_chart, result_.follower_rotates, state.follower_chart.half, sample.nominal);
      sample.certified = CertifiedRange{part.lo, part.hi};
      double excess = (part.hi - part.lo) - (sample.linear_upper - sample.linear_lower);
      result_.certified_excess = std::max(result_.certified_excess, excess);
    }
    if (uncertified > 0)
      result_.notes.push_back("the certified band could not be computed at " + std::to_string(uncertified) +
                              " driver position(s) (shown unbounded)");
  }

  void zones() {
    const Model& m = model_->nominal();
    std::size_t x_index = *m.find_part(space_->x_part());
    std::size_t y_index = *m.find_part(space_->y_part());
    bool x_rotates = m.parts[x_index].motion.kind == Motion::Kind::rotation;
    bool y_rotates = m.parts[y_index].motion.kind == Motion::Kind::rotation;
    std::size_t n = result_.parameters.size();
    // The samples of every zone (nominal curve point and sensitivities: sequential), then their
    // certified enclosures (in parallel), then the zones in edge order.
    struct ZoneSample {
      std::size_t zone = 0;
      double xd = 0, v = 0;
      CurveSlice curve;
      std::vector<double> s;
      Enclosure range;
    };
    std::vector<ContactZone> zones;
    std::vector<ZoneSample> samples;
    // progress: the samples' sensitivities (by edge) the stage's first fifth, their certified
    // enclosures (by sample) the rest
    const std::size_t edge_count = space_->edges().size();
    for (std::size_t e = 0; e < edge_count; ++e) {
      bar_.fraction(0.2 * static_cast<double>(e) / static_cast<double>(edge_count));
      const CSpaceEdge& edge = space_->edges()[e];
      if (edge.role != EdgeRole::contact || edge.vertical || edge.curves.empty()) continue;
      const FeaturePair& pair = space_->feature_pair(FeatureId(edge.curves.front()));
      bool on_path = false;
      for (const ContactRegion& region : result_.regions)
        on_path = on_path || (region.first == pair.first && region.second == pair.second);
      if (!on_path) continue;
      const CSpaceChart& chart = space_->charts()[edge.chart];
      ContactZone zone;
      zone.contact = pair.label;
      zone.edge = e;
      zone.x_rotates = x_rotates;
      zone.y_rotates = y_rotates;
      double x0 = edge.x_chart.lower, x1 = edge.x_chart.upper;
      if (!(x1 > x0)) continue;
      for (std::size_t j = 0; j < options_.zone_samples; ++j) {
        ZoneSample sample;
        sample.zone = zones.size();
        sample.xd = x0 + (x1 - x0) * (static_cast<double>(j) + 0.5) / static_cast<double>(options_.zone_samples);
        sample.curve.first = pair.first;
        sample.curve.second = pair.second;
        sample.curve.fixed_part = x_index;
        sample.curve.free_part = y_index;
        sample.curve.fixed_half_turn = chart.x_half_turn;
        sample.curve.free_half_turn = chart.y_half_turn;
        sample.curve.fixed_value = Rational(sample.xd);
        try {
          sample.v = space_->evaluate(e, sample.xd).value;
          sample.s = solver_->sensitivities(sample.curve, sample.v);
        } catch (const Error&) {
          continue;
        }
        samples.push_back(std::move(sample));
      }
      zones.push_back(std::move(zone));
    }
    parallel_for(samples.size(), [&](std::size_t k) {
      ZoneSample& sample = samples[k];
      sample.range = enclose(sample.curve, sample.v, sample.s);
    }, [&](std::size_t done) {
      bar_.fraction(0.2 + 0.8 * static_cast<double>(done) / static_cast<double>(std::max<std::size_t>(1, samples.size())));
    });
    for (const ZoneSample& sample : samples) {
      result_.certified_boxes += sample.range.boxes;
      if (!sample.range.ok) continue;
      ContactZone& zone = zones[sample.zone];
      const CSpaceChart& chart = space_->charts()[space_->edges()[zone.edge].chart];
      const std::vector<double>& s = sample.s;
      double v = sample.v, xd = sample.xd;
      double slope = chart_slope(v, y_rotates);
      double lower = 0, upper = 0;
      for (std::size_t i = 0; i < n; ++i) {
        lower += std::min(s[i] * dist_[i].lo, s[i] * dist_[i].hi) * slope;
        upper += std::max(s[i] * dist_[i].lo, s[i] * dist_[i].hi) * slope;
      }
      double y = y_rotates ? chart.y_to_coordinate(v) : v;
      Interval part = to_part(sample.range.chart, y_rotates, chart.y_half_turn, y);
      zone.x.push_back(x_rotates ? chart.x_to_coordinate(xd) : xd);
      zone.nominal.push_back(y);
      zone.linear_lower.push_back(y + lower);
      zone.linear_upper.push_back(y + upper);
      zone.certified_lower.push_back(part.lo);
      zone.certified_upper.push_back(part.hi);
    }
    for (ContactZone& zone : zones)
      if (!zone.x.empty()) result_.zones.push_back(std::move(zone));
  }

  void monte_carlo() {
    auto start = std::chrono::steady_clock::now();
    double cpu_start = cpu_seconds(true);
    MonteCarloSummary summary;
    summary.samples = options_.monte_carlo;
    summary.seed = options_.seed;
    std::size_t count = states_.size();
    using Outcome = tolerance_detail::MonteCarloOutcome;
    std::atomic<std::size_t> done{0};
    auto evaluate = [&](std::size_t index) {
      Outcome outcome;
      outcome.value.assign(count, std::nan(""));
      std::vector<double> deviations = draw(dist_, options_.seed, index);
      auto geometry = solver_->point_parameters(deviations);
      // The contact curve's geometry at this vector, shared by the positions along one feature
      // pair (it does not depend on the driver position).
      std::optional<tolerance_detail::PairGeometry<Interval>> pair_geometry;
      const CurveSlice* pair_curve = nullptr;
      for (std::size_t k = 0; k < count; ++k) {
        const SampleState& state = states_[k];
        if (!state.contact) continue;
        bool same_pair = pair_curve && pair_curve->first == state.curve.first && pair_curve->second == state.curve.second &&
                         pair_curve->fixed_part == state.curve.fixed_part && pair_curve->free_part == state.curve.free_part;
        if (!same_pair || !options_.fast_paths) {
          pair_geometry = solver_->point_geometry(state.curve, geometry);
          pair_curve = &state.curve;
        }
        const VariationSample& sample = result_.samples[k];
        Interval c = state.certified_chart;
        // Not sampled where the band is unbounded (not certified): every value lies in it, and
        // there is no band to bracket the root with (as for assembly chains).
        if (!std::isfinite(c.lo) || !std::isfinite(c.hi)) continue;
        double w = c.width() + 1e-12 * (1 + std::fabs(state.v));
        Interval root;
        if (!solver_->certified_point_root(state.curve, *pair_geometry, Interval(c.lo - w, c.hi + w), root)) {
          // The bracket failed (an end sign undecided or both alike): the wider search, then a
          // value certified in the band, certified outside it (a defect), or not certified.
          auto sign = [&](double v) { return solver_->point_sign(state.curve, *pair_geometry, v); };
          auto range_sign = [&](Interval y) { return solver_->range_sign(state.curve, *pair_geometry, y); };
          auto refine = [&](Interval bracket, Interval& r) {
            return solver_->certified_point_root(state.curve, *pair_geometry, bracket, r);
          };
          // (windows up to 1 chart unit, as the chain's brackets)
          tolerance_detail::BandedRoot found = tolerance_detail::search_band_root(sign, range_sign, refine, c, 4 * w, 1.0);
          if (found.kind == tolerance_detail::BandedRootKind::not_certified) {
            ++outcome.not_certified;
            continue;
          }
          root = found.root;
        }
        ++outcome.evaluations;
        // A root enclosure meeting an edge of the band (session 63) is narrowed there by the
        // contact function's sign at the edge: certain and that of the enclosure's lower end, the
        // sign change (the root) lies above the edge; that of its upper end, below it; exactly 0,
        // the root is the edge. An edge where the sign is not certain leaves the value undecided.
        auto cut = [&](double edge) {
          if (!(root.lo < edge && edge < root.hi)) return;
          const int at_edge = solver_->point_sign(state.curve, *pair_geometry, edge);
          if (at_edge == 0) {
            root = Interval(edge, edge);
            return;
          }
          const int at_lo = solver_->point_sign(state.curve, *pair_geometry, root.lo);
          const int at_hi = solver_->point_sign(state.curve, *pair_geometry, root.hi);
          if ((at_lo != 1 && at_lo != -1) || at_hi != -at_lo || (at_edge != 1 && at_edge != -1)) return;
          root = at_edge == at_lo ? Interval(edge, root.hi) : Interval(root.lo, edge);
        };
        cut(c.lo);
        cut(c.hi);
        // Outside the certified band: decided on the chart enclosure (the band's own units), only
        // when the root's enclosure is apart from the band's (record above); inside only when it
        // lies within it; else undecided (session 63: until then counted inside).
        if (root.hi < c.lo || root.lo > c.hi) ++outcome.outside_certified;
        else if (!(root.lo >= c.lo && root.hi <= c.hi)) ++outcome.undecided_certified;
        Interval part = to_part(root, result_.follower_rotates, state.follower_chart.half, sample.nominal);
        outcome.record_linear(k, part.middle(), sample);
      }
      ++done;
      return outcome;
    };
    unsigned threads = options_.threads ? options_.threads : std::max(1u, std::thread::hardware_concurrency());
    std::vector<Outcome> outcomes(options_.monte_carlo);
    std::atomic<std::size_t> next{0};
    std::vector<std::future<void>> workers;
    for (unsigned t = 0; t < threads; ++t)
      workers.push_back(std::async(std::launch::async, [&] {
        for (std::size_t i = next++; i < outcomes.size(); i = next++) outcomes[i] = evaluate(i);
      }));
    for (auto& worker : workers) {
      while (worker.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready)
        bar_.units(done.load(), outcomes.size());
      worker.get();
    }
    tolerance_detail::merge_monte_carlo(outcomes, summary, result_);
    if (summary.not_certified > 0)
      result_.notes.push_back(
          "Monte Carlo: no value certified at " + std::to_string(summary.not_certified) +
          " sampled position(s) (the contact's root bracketed neither about the band nor by the wider search: no "
          "certain sign change found, e.g. a tangency or a band narrower than the function's rounding); counted as "
          "not certified, neither inside nor outside the certified band");
    summary.seconds = seconds_since(start);
    summary.cpu_seconds = cpu_seconds(true) - cpu_start;
    result_.monte_carlo = summary;
  }

  // The channel's sides at a sample: sensitivities of both (chart units) and the nominal play.
  struct Channel {
    bool ok = false;
    std::size_t sample = 0;
    CurveSlice lower, upper;
    double lower_value = 0, upper_value = 0;
    std::vector<double> lower_s, upper_s;
    std::string lower_label, upper_label;
  };

  bool side_curve(const SampleState& state, const Side& side, CurveSlice& curve, double& value,
                  std::vector<double>& s, std::string& label) {
    for (FeatureId id : side.features) {
      CurveSlice candidate = curve_for(id, state);
      double v = side.value;
      try {
        s = solver_->sensitivities(candidate, v);
      } catch (const Error&) {
        continue;
      }
      curve = candidate;
      value = v;
      label = space_->feature_pair(id).label;
      return true;
    }
    return false;
  }

  // The parameters the threshold search and the certificate vary: every toleranced one, or
  // the named ones (each must have a tolerance).
  std::vector<bool> varied_parameters() const {
    const Model& m = model_->nominal();
    std::size_t n = m.parameters.size();
    std::vector<bool> varied(n, false);
    for (std::size_t i = 0; i < n; ++i) varied[i] = m.parameters[i].range.lo < m.parameters[i].range.hi;
    if (!options_.threshold_parameters.empty()) {
      varied.assign(n, false);
      for (const std::string& name : options_.threshold_parameters) {
        const Parameter* p = m.find_parameter(name);
        if (!p) throw ModelError("/parameters", "unknown parameter '" + name + "' for the threshold search");
        if (!(p->range.lo < p->range.hi))
          throw ModelError("/parameters", "parameter '" + name + "' has no tolerance to vary");
        varied[static_cast<std::size_t>(p - m.parameters.data())] = true;
      }
    }
    return varied;
  }

  // The no-jam tolerance certificate (certificate.hpp): the nominal channel along the range,
  // then the branch-and-bound.
  void certify() {
    tolerance_detail::CertifyRequest request = certify_request();
    request.scale = options_.certify_scale;
    if (options_.certify_relative_to_threshold) {
      if (!result_.threshold || !result_.threshold->found) {
        result_.notes.push_back("certificate: no jamming threshold was found to scale the box by");
        return;
      }
      // fraction x threshold, rounded down to 4 significant digits.
      double value = (options_.certify_scale.get_d()) * result_.threshold->scale;
      double unit = std::pow(10.0, std::floor(std::log10(value)) - 3);
      Rational q(mpz_class(std::floor(value / unit)), 1);
      request.scale = unit >= 1 ? Rational(q * Rational(unit)) : Rational(q / Rational(static_cast<long>(std::llround(1 / unit))));
    }
    if (!(request.scale > 0)) throw ModelError("", "the certificate's tolerance scale must be positive");
    request.progress = bar_.within();   // the corner search, the leaves' share of the region
    result_.certification = tolerance_detail::certify_no_jam(request);
  }

  // The certificate's request without its scale: the varied parameters, the driver range and
  // the nominal channel's sides at every analysed position in it.
  tolerance_detail::CertifyRequest certify_request() {
    const Model& m = model_->nominal();
    tolerance_detail::CertifyRequest request;
    request.model = model_;
    request.model_text = text_;
    request.model_file = source_name_;
    request.driver = driver_;
    request.follower = follower_;
    request.max_leaves = options_.certify_max_leaves;
    request.free_path_leaves = options_.certify_free_path;
    request.witness_splits = options_.certify_witness_splits;
    std::vector<bool> varied = varied_parameters();
    for (std::size_t i = 0; i < varied.size(); ++i)
      if (varied[i]) request.varied.push_back(i);
    if (request.varied.empty()) throw ModelError("/parameters", "no toleranced parameter to certify over");
    if (options_.range) {
      request.range = {std::min(options_.range->first, options_.range->second),
                       std::max(options_.range->first, options_.range->second)};
    } else {
      // One turn as analysed: the first and last driver positions, rounded inwards to 1e-9.
      auto inward = [](double x, bool up) {
        Rational q(mpz_class(up ? std::ceil(x * 1e9) : std::floor(x * 1e9)), mpz_class(1000000000));
        q.canonicalize();
        return q;
      };
      request.range = {inward(result_.samples.front().driver, true), inward(result_.samples.back().driver, false)};
    }
    double lo = request.range.lo.get_d(), hi = request.range.hi.get_d();
    for (std::size_t k = 0; k < states_.size(); ++k) {
      const VariationSample& sample = result_.samples[k];
      if (sample.driver < lo - 1e-12 || sample.driver > hi + 1e-12) continue;
      const SampleState& state = states_[k];
      tolerance_detail::ChannelSample c;
      c.driver = sample.driver;
      CurveSlice lower, upper;
      double lv = 0, uv = 0;
      std::vector<double> s;
      std::string label;
      if (state.valid && state.lower.present && state.upper.present && side_curve(state, state.lower, lower, lv, s, label) &&
          side_curve(state, state.upper, upper, uv, s, label)) {
        c.bounded = true;
        c.lower_first = lower.first;
        c.lower_second = lower.second;
        c.upper_first = upper.first;
        c.upper_second = upper.second;
        auto coordinate = [&](double t) {
          if (!result_.follower_rotates) return t;
          double theta = 2 * std::atan(t) + (state.follower_chart.half ? pi : 0.0);
          return theta + 2 * pi * std::round((sample.nominal - theta) / (2 * pi));
        };
        c.lower = coordinate(lv);
        c.upper = coordinate(uv);
      } else {
        // Why, for the certificate's "not bounded" message (session 51: a range starting where the
        // follower's initial position is outside its channel said only "not bounded").
        std::ostringstream why;
        why << std::setprecision(6) << "'" << m.parts[follower_].name << "' at " << sample.nominal
            << (result_.follower_rotates ? " rad" : " mm");
        if (!state.valid)
          why << ": no configuration of the pair located there";
        else if (!state.lower.present || !state.upper.present)
          why << " has no contact " << (state.lower.present ? "above it (increasing " : state.upper.present ? "below it (decreasing "
                                                                                                           : "on either side (")
              << (result_.follower_rotates ? "angle)" : "offset)");
        else
          why << ": the feature pairs of its sides were not followed";
        c.unbounded_why = why.str();
      }
      request.samples.push_back(c);
    }
    return request;
  }

  // The intervals (indices into kinds) of a kernel slice that are free (or outside the slicer's
  // window) and meet the open channel (lower, upper), decided exactly (exact_order.hpp): an
  // interval (a, b) meets it when b > lower and a < upper; a null side is unbounded.
  static std::vector<std::size_t> kernel_free_meeting(const KernelSlice& slice, const AlgebraicNumber* lower,
                                                      const AlgebraicNumber* upper) {
    std::vector<std::size_t> meeting;
    const std::vector<KernelSlice::Point>& at = slice.points;
    for (std::size_t j = 0; j < slice.kinds.size(); ++j) {
      if (slice.kinds[j] != KernelSlice::Kind::free && slice.kinds[j] != KernelSlice::Kind::outside) continue;
      bool below_upper = j == 0 || !upper || tolerance_detail::compare(at[j - 1].at, *upper) < 0;        // a < upper
      bool above_lower = j == at.size() || !lower || tolerance_detail::compare(at[j].at, *lower) > 0;   // b > lower
      if (below_upper && above_lower) meeting.push_back(j);
    }
    return meeting;
  }

  // The exact kernel slice of `slicer`'s pair (the nominal pair or one at other parameters) at
  // the sample's driver chart coordinate, from the contact polynomials and the exact overlap
  // oracle (the kernel slicer `hipair analyze` runs on large pairs), in the follower chart with
  // the nominal chart's half turn. nullopt: no chart holds the position.
  // The kernel slice ends at the follower chart's ends (t = +-1, the half-turn seam); since
  // session 60 it is continued across the seam into the other half turn's chart (t' = -1 / t,
  // exact_order.hpp other_half_turn) at an end where the nominal channel crosses it or a free
  // interval meeting the channel reaches it, so that no part of the channel beyond the seam goes
  // unexamined (a free interval there would otherwise be missed, and a closed channel claimed).
  // A translating follower's chart is its whole stroke (one chart, no seam: its coordinate is a
  // length, and t = +-1 are ordinary offsets): its slice is the whole one. Until session 62 the
  // seam was looked for there too, and a channel reaching past +-1 unit of length had no slice.
  std::optional<KernelSlice> kernel_slice_at(const KernelSlicer& slicer, const SampleState& state) const {
    std::optional<KernelSlice> slice =
        slicer.slice(state.driver_chart.t, state.driver_chart.half, state.follower_chart.t, state.follower_chart.half);
    if (!slice || !state.lower.present || !state.upper.present || !result_.follower_rotates) return slice;
    std::vector<std::size_t> meeting = kernel_free_meeting(*slice, &state.lower.exact, &state.upper.exact);
    auto meets = [&](std::size_t j) { return std::find(meeting.begin(), meeting.end(), j) != meeting.end(); };
    const bool below = meets(0) || tolerance_detail::compare(state.lower.exact, Rational(-1)) < 0;
    const bool above = meets(slice->points.size()) || tolerance_detail::compare(state.upper.exact, Rational(1)) > 0;
    for (bool up : {false, true}) {
      if (!(up ? above : below)) continue;
      const Rational seam(up ? 1 : -1);
      std::optional<KernelSlice> other =
          slicer.slice(state.driver_chart.t, state.driver_chart.half, Rational(-seam), !state.follower_chart.half);
      if (!other) return std::nullopt;   // nothing known beyond the seam: no decision on this slice
      // the other chart's points on the home side of its 0 (t' > 0 below the seam, < 0 above),
      // in the home chart's coordinates; kinds[i] before points[i] as in KernelSlice
      KernelSlice part;
      std::size_t first = 0, last = other->points.size();   // [first, last) kept
      if (up) {
        while (first < last && tolerance_detail::compare(other->points[last - 1].at, Rational(0)) >= 0) --last;
      } else {
        while (first < last && tolerance_detail::compare(other->points[first].at, Rational(0)) <= 0) ++first;
      }
      for (std::size_t i = first; i < last; ++i) {
        KernelSlice::Point point = other->points[i];
        point.at = *tolerance_detail::other_half_turn(point.at);
        part.points.push_back(std::move(point));
        part.kinds.push_back(other->kinds[i]);
      }
      part.kinds.push_back(other->kinds[last]);
      // the seam: a point of both slices there is one point; one interval on both sides is one
      KernelSlice& low = up ? *slice : part;
      KernelSlice& high = up ? part : *slice;
      KernelSlice joined;
      joined.points = low.points;
      joined.kinds = low.kinds;
      const bool low_ends_on_seam = !low.points.empty() && tolerance_detail::compare(low.points.back().at, seam) == 0;
      const bool high_starts_on_seam = !high.points.empty() && tolerance_detail::compare(high.points.front().at, seam) == 0;
      // high's points from `points_from` and kinds from `kinds_from` follow; an empty (seam, seam)
      // interval of either side goes, a point of both is kept once
      std::size_t points_from = 0, kinds_from = 0;
      if (low_ends_on_seam) {
        joined.kinds.pop_back();
        if (high_starts_on_seam) points_from = kinds_from = 1;
      } else if (high_starts_on_seam) {
        kinds_from = 1;
      } else if (low.kinds.back() == high.kinds.front()) {
        joined.kinds.pop_back();   // one interval across the seam
      } else {
        joined.points.push_back(KernelSlice::Point{tolerance_detail::exact_algebraic(seam), false, {}});
      }
      joined.points.insert(joined.points.end(), high.points.begin() + static_cast<std::ptrdiff_t>(points_from), high.points.end());
      joined.kinds.insert(joined.kinds.end(), high.kinds.begin() + static_cast<std::ptrdiff_t>(kinds_from), high.kinds.end());
      *slice = std::move(joined);
    }
    return slice;
  }

  // A jam confirmation without a C-space (session 58: large pairs; session 59: the bracket's and
  // the contact changes' too): the number of free intervals of the kernel slice at the sample
  // meeting the nominal channel's open interval (exact comparisons, exact_order.hpp), and in
  // `points` the slice's size. A point inside the channel that may be a zero-clearance fit
  // (touching, or its touching undecided) counts as open. nullopt: no chart holds the position.
  std::optional<std::size_t> kernel_free_intervals_in_channel(const KernelSlicer& slicer, const SampleState& state,
                                                              std::size_t& points) const {
    std::optional<KernelSlice> slice = kernel_slice_at(slicer, state);
    if (!slice) return std::nullopt;
    points = slice->points.size();
    const AlgebraicNumber& lower = state.lower.exact;
    const AlgebraicNumber& upper = state.upper.exact;
    std::size_t open = 0;
    for (const KernelSlice::Point& point : slice->points)
      if (point.may_touch && tolerance_detail::compare(point.at, lower) > 0 && tolerance_detail::compare(point.at, upper) < 0)
        ++open;
    return open + kernel_free_meeting(*slice, &lower, &upper).size();
  }

  // The slice of `space` (an exact C-space at other parameters) at the sample's driver chart
  // coordinate, in the (last) chart with the nominal chart's half turns.
  std::optional<Slice> slice_like(const CSpace& space, const SampleState& state) const {
    const CSpaceChart& nominal_chart = space_->charts()[state.chart];
    std::vector<Slice> slices = space.slice(driver_is_x_ ? SliceAxis::x : SliceAxis::y, state.driver_chart.t);
    for (auto candidate = slices.rbegin(); candidate != slices.rend(); ++candidate) {
      const CSpaceChart& c = space.charts()[candidate->chart];
      if (c.x_half_turn == nominal_chart.x_half_turn && c.y_half_turn == nominal_chart.y_half_turn) return *candidate;
    }
    return std::nullopt;
  }

  // docs/tolerance.md "The threshold, bracketed": the corner search bisected over the scale,
  // then the exact C-space at the jam witness, sliced at its driver position.
  void bracket_threshold(JammingThreshold& result) {
    const Model& m = model_->nominal();
    tolerance_detail::CertifyRequest request = certify_request();
    request.progress = bar_.within(0.6, 0.8);   // the bisection's corner searches
    Rational below = Rational(0.9) * Rational(result.scale), above = Rational(1.1) * Rational(result.scale);
    tolerance_detail::ThresholdBracket b =
        tolerance_detail::bracket_threshold(request, below, above, options_.threshold_bracket);
    result.bracket_steps = b.steps;
    if (!b.found) {
      result.bracket_evidence = "no bracket: the corner search " + std::string(b.steps == 1 ? "jams at 0.9 x the linearised threshold"
                                                                                           : "found no jam up to 5 x it");
      // (a search that could not start says why: a channel not bounded on both sides, ...)
      if (b.steps > 1 && !b.witness.reason.empty()) result.bracket_evidence += " (" + b.witness.reason + ")";
      return;
    }
    result.bracketed = true;
    result.bracket_below = b.below;
    result.bracket_above = b.above;
    result.bracket_play_below = b.below_play;
    result.bracket_driver = b.witness.witness_coordinate.value_or(Rational(0));
    result.bracket_lower = b.witness.witness_lower.value_or(RationalInterval{});
    result.bracket_upper = b.witness.witness_upper.value_or(RationalInterval{});
    std::vector<Rational> deviations(m.parameters.size(), Rational(0));
    for (const auto& [name, deviation] : b.witness.witness_parameters) {
      const Parameter* p = m.find_parameter(name);
      deviations[static_cast<std::size_t>(p - m.parameters.data())] = deviation;
      result.bracket_values.emplace_back(name, p->nominal + deviation);
    }
    // The exact confirmation: the C-space of the exact model at the witness, sliced at the
    // chart coordinate nearest the witness' driver; the nominal channel's exact sides there
    // come from the nominal C-space's slice at the same coordinate (the follower between the
    // witness' two roots, which lie in the nominal channel's neighbourhood).
    double d = result.bracket_driver.get_d();
    double follower = 0.5 * (result.bracket_lower.lo.get_d() + result.bracket_upper.hi.get_d());
    SampleState state = locate(d, follower, false);
    if (!state.valid || !state.lower.present || !state.upper.present) {
      result.bracket_evidence = "not confirmed: the nominal slice at the witness' driver position has no bounded channel there";
      return;
    }
    Model worst;
    try {
      worst = model_->exact_model(deviations);
    } catch (const ModelError& error) {
      result.bracket_evidence = std::string("not confirmed: the witness geometry is invalid: ") + error.what();
      return;
    }
    if (kernel_confirmations_) {
      confirm_bracket_on_kernels(result, std::move(worst), state, b.above);
      return;
    }
    // the witness' exact C-space
    CSpace space = CSpace::build(worst, pair_first_, pair_second_, reporting(bar_.within(0.8, 1.0)));
    std::optional<Slice> slice = slice_like(space, state);
    if (!slice) {
      result.bracket_evidence = "not confirmed: no slice of the witness' C-space at that driver position";
      return;
    }
    // The nominal channel there: the follower between the witness' roots must lie in a free
    // interval of the nominal slice (else its neighbours bound no channel).
    std::vector<Slice> nominal_slices = space_->slice(driver_is_x_ ? SliceAxis::x : SliceAxis::y, state.driver_chart.t);
    std::size_t nominal_open = 0;
    for (const Slice& candidate : nominal_slices)
      if (candidate.chart == state.chart)
        nominal_open = tolerance_detail::free_intervals_in_channel(candidate, state.lower.exact, state.upper.exact);
    if (nominal_open != 1) {
      result.bracket_evidence = "not confirmed: the witness' follower position is not in a free channel of the nominal slice";
      return;
    }
    std::size_t open = tolerance_detail::free_intervals_in_channel(*slice, state.lower.exact, state.upper.exact);
    std::ostringstream points;   // for the reader only (approximate)
    points.precision(9);
    points << "; nominal channel (" << state.lower.exact.approximate() << ", " << state.upper.exact.approximate()
           << "), the witness' slice points";
    for (const Slice::Point& point : slice->points) points << " " << point.at.approximate();
    points << ", intervals";
    for (const Slice::Interval& interval : slice->intervals) points << (interval.kind == CellKind::free ? " free" : " blocked");
    std::string where = "exact C-space at the witness (tolerances x " + to_exact_string(b.above) +
                        "), sliced at driver chart coordinate " + to_exact_string(state.driver_chart.t);
    result.bracket_confirmed = open == 0;
    result.bracket_evidence = open == 0 ? where + ": no free interval between the two sides of the nominal channel (" +
                                              std::to_string(slice->intervals.size()) + " intervals)"
                                        : where + ": still " + std::to_string(open) + " free interval(s) in the channel";
    result.bracket_evidence += points.str() + " (chart coordinates)";
  }

  // The bracket's exact confirmation without a C-space (a large pair's: its whole witness space
  // takes minutes; session 59): the exact kernel slices of the nominal pair and of the witness'
  // at the nominal channel's driver chart coordinate, the same decisions as on the two C-spaces'
  // slices (the follower between the witness' roots in one free interval of the nominal slice;
  // no free interval of the witness' slice between the nominal channel's sides).
  void confirm_bracket_on_kernels(JammingThreshold& result, Model&& worst, const SampleState& state,
                                  const Rational& scale) {
    std::size_t nominal_points = 0, points = 0;
    std::optional<std::size_t> nominal_open =
        kernel_free_intervals_in_channel(KernelSlicer(model_->nominal(), driver_, follower_), state, nominal_points);
    if (!nominal_open || *nominal_open != 1) {
      result.bracket_evidence = "not confirmed: the witness' follower position is not in a free channel of the nominal slice";
      return;
    }
    bar_.fraction(0.9);
    std::optional<std::size_t> open = kernel_free_intervals_in_channel(KernelSlicer(std::move(worst), driver_, follower_), state, points);
    if (!open) {
      result.bracket_evidence = "not confirmed: no slice of the witness' pair at that driver position";
      return;
    }
    std::ostringstream channel;   // for the reader only (approximate)
    channel.precision(9);
    channel << "; nominal channel (" << state.lower.exact.approximate() << ", " << state.upper.exact.approximate()
            << ") (chart coordinates)";
    std::string where = "exact slice (contact kernels and the exact overlap oracle) of the pair at the witness (tolerances x " +
                        to_exact_string(scale) + ") at driver chart coordinate " + to_exact_string(state.driver_chart.t);
    result.bracket_confirmed = *open == 0;
    result.bracket_evidence = *open == 0 ? where + ": no free interval between the two sides of the nominal channel (" +
                                               std::to_string(points + 1) + " intervals)"
                                         : where + ": still " + std::to_string(*open) + " free interval(s) in the channel";
    result.bracket_evidence += channel.str();
  }

  void threshold() {
    const Model& m = model_->nominal();
    std::size_t n = m.parameters.size();
    std::vector<bool> varied = varied_parameters();
    JammingThreshold result;
    double best = std::numeric_limits<double>::infinity();
    Channel critical;
    for (std::size_t k = 0; k < states_.size(); ++k) {
      const SampleState& state = states_[k];
      if (!state.valid || !state.lower.present || !state.upper.present) continue;
      Channel channel;
      channel.sample = k;
      if (!side_curve(state, state.lower, channel.lower, channel.lower_value, channel.lower_s, channel.lower_label) ||
          !side_curve(state, state.upper, channel.upper, channel.upper_value, channel.upper_s, channel.upper_label))
        continue;
      double play = channel.upper_value - channel.lower_value;
      double closing = 0;   // largest decrease of the play per unit scale of the tolerances
      for (std::size_t i = 0; i < n; ++i) {
        if (!varied[i]) continue;
        double d = channel.upper_s[i] - channel.lower_s[i];
        closing -= std::min(d * dist_[i].lo, d * dist_[i].hi);
      }
      if (closing <= 0 || play <= 0) continue;
      double scale = play / closing;
      if (scale < best) {
        best = scale;
        critical = channel;
        critical.ok = true;
      }
    }
    if (!critical.ok) {
      result_.threshold = result;
      result_.notes.push_back("threshold: no bounded channel along the path");
      return;
    }
    result.found = true;
    result.scale = best;
    result.driver = result_.samples[critical.sample].driver;
    result.lower_contact = critical.lower_label;
    result.upper_contact = critical.upper_label;
    result.nominal_play = result_.samples[critical.sample].play;
    // progress within the stage: the certified scales its first tenth, the exact C-spaces (each
    // build's own progress) up to 0.6 when a bracket follows, else to the end
    const double confirm_end = options_.threshold_bracket > 0 ? 0.6 : 1.0;
    std::size_t tried = 0;
    // Certified: the largest of a few scales below the threshold at which both sides' certified
    // enclosures stay apart at the critical position.
    for (double factor : {0.95, 0.9, 0.8, 0.6, 0.4}) {
      bar_.fraction(0.1 * static_cast<double>(tried++) / 5);
      // The box at the scale reported (the double best * factor, exactly), rounded outwards
      // from the exact rational tolerance box.
      Rational scale(best * factor);
      Box scaled = box_;
      std::vector<Rational> exact_lo(n, Rational(0)), exact_hi(n, Rational(0));
      for (std::size_t i = 0; i < n; ++i) {
        const Parameter& p = m.parameters[i];
        if (varied[i]) {
          exact_lo[i] = scale * (p.range.lo - p.nominal);
          exact_hi[i] = scale * (p.range.hi - p.nominal);
        }
        scaled.lo[i] = varied[i] ? tolerance_detail::round_to_double(exact_lo[i], false) : 0;
        scaled.hi[i] = varied[i] ? tolerance_detail::round_to_double(exact_hi[i], true) : 0;
      }
      try {
        model_->check_choices(exact_lo, exact_hi);   // (a template's shape kept over the scaled box)
        std::size_t boxes = 0;
        // Separation needs no tight band: a coarse accuracy subdivides less and fails less.
        double accuracy = std::max(options_.relative_accuracy, 1.0);
        Interval lo = solver_->certified_range(critical.lower, scaled, critical.lower_value, critical.lower_s,
                                               accuracy, options_.absolute_accuracy, boxes);
        Interval hi = solver_->certified_range(critical.upper, scaled, critical.upper_value, critical.upper_s,
                                               accuracy, options_.absolute_accuracy, boxes);
        if (hi.lo > lo.hi) {
          result.certified_open_scale = scale.get_d();
          break;
        }
      } catch (const Error&) {
      }
    }
    // Exact confirmation: the worst-case vector at a scale a little above the linearised one,
    // an exact C-space built there, and its slice at the critical driver position.
    const SampleState& state = states_[critical.sample];
    tried = 0;
    for (int step : {21, 22, 24, 28, 36}) {   // scale x step/20
      const double from = 0.1 + (confirm_end - 0.1) * static_cast<double>(tried++) / 5;
      Rational factor = Rational(step, 20) * Rational(best);
      std::vector<Rational> deviations(n, Rational(0));
      for (std::size_t i = 0; i < n; ++i) {
        if (!varied[i]) continue;
        double d = critical.upper_s[i] - critical.lower_s[i];
        const Parameter& p = m.parameters[i];
        deviations[i] = factor * (d > 0 ? Rational(p.range.lo - p.nominal) : Rational(p.range.hi - p.nominal));
      }
      Model worst;
      try {
        worst = model_->exact_model(deviations);
      } catch (const ModelError& error) {
        result.evidence = std::string("the worst-case geometry is invalid: ") + error.what();
        continue;
      }
      if (kernel_confirmations_) {
        // A large pair: the exact slice at the critical position from the contact kernels (the
        // whole worst-case C-space took minutes per scale; session 58).
        std::size_t points = 0;
        std::optional<std::size_t> open = kernel_free_intervals_in_channel(KernelSlicer(std::move(worst), driver_, follower_), state, points);
        if (!open) continue;
        result.confirmed_scale = factor.get_d();
        result.worst_values.clear();
        for (std::size_t i = 0; i < n; ++i)
          if (deviations[i] != 0) result.worst_values.emplace_back(m.parameters[i].name, m.parameters[i].nominal + deviations[i]);
        if (*open == 0) {
          result.confirmed = true;
          result.evidence = "exact slice (contact kernels and the exact overlap oracle) of the worst-case pair at tolerances x " +
                            std::to_string(factor.get_d()) +
                            " at the critical driver position: no free interval between the two sides of the nominal channel (" +
                            std::to_string(points + 1) + " intervals, all blocked there)";
          break;
        }
        result.evidence = "exact slice (contact kernels) of the worst-case pair at tolerances x " + std::to_string(factor.get_d()) +
                          ": still " + std::to_string(*open) + " free interval(s) in the channel";
        continue;
      }
      CSpace space =
          CSpace::build(worst, pair_first_, pair_second_, reporting(bar_.within(from, from + (confirm_end - 0.1) / 5)));
      std::optional<Slice> slice = slice_like(space, state);
      if (!slice) continue;
      // Free intervals of the slice meeting the nominal channel (lower, upper).
      // Decided exactly against the nominal channel's exact sides (exact_order.hpp).
      std::size_t open = tolerance_detail::free_intervals_in_channel(*slice, state.lower.exact, state.upper.exact);
      result.confirmed_scale = factor.get_d();
      result.worst_values.clear();
      for (std::size_t i = 0; i < n; ++i)
        if (deviations[i] != 0) result.worst_values.emplace_back(m.parameters[i].name, m.parameters[i].nominal + deviations[i]);
      if (open == 0) {
        result.confirmed = true;
        result.evidence = "exact C-space at tolerances x " + std::to_string(factor.get_d()) +
                          ": the slice at the critical driver position has no free interval between the two sides of the nominal channel (" +
                          std::to_string(slice->intervals.size()) + " intervals, all blocked there)";
        break;
      }
      result.evidence = "exact C-space at tolerances x " + std::to_string(factor.get_d()) + ": still " +
                        std::to_string(open) + " free interval(s) in the channel";
    }
    if (options_.threshold_bracket > 0) bracket_threshold(result);
    result_.threshold = result;
  }

  // ------------------------------------------------------------ contacts appearing/disappearing
  using PairKey = std::pair<FeatureIdentity, FeatureIdentity>;
  // (the feature of the part with the smaller model index first: a C-space's feature pairs and
  // a kernel slicer's name the same pair alike)
  static PairKey key_of(const FeatureIdentity& a, const FeatureIdentity& b) {
    return a.part <= b.part ? PairKey{a, b} : PairKey{b, a};
  }
  static PairKey key_of(const FeaturePair& pair) { return key_of(pair.first, pair.second); }

  // The feature pairs of a C-space at the ends of the free intervals of its slice at the sample's
  // driver position that meet the sample's nominal channel (exact: exact_order.hpp).
  std::optional<std::vector<PairKey>> channel_bounds(const CSpace& space, std::size_t k) const {
    const SampleState& state = states_[k];
    const CSpaceChart& nominal_chart = space_->charts()[state.chart];
    std::vector<Slice> slices = space.slice(SliceAxis::x, state.driver_chart.t);
    const Slice* slice = nullptr;
    for (const Slice& candidate : slices) {
      const CSpaceChart& c = space.charts()[candidate.chart];
      if (c.x_half_turn == nominal_chart.x_half_turn && c.y_half_turn == nominal_chart.y_half_turn) slice = &candidate;
    }
    if (!slice) return std::nullopt;
    std::vector<PairKey> keys;
    auto add = [&](std::size_t point) {
      for (FeatureId id : slice->points[point].features) keys.push_back(key_of(space.feature_pair(id)));
    };
    for (std::size_t j : tolerance_detail::free_intervals_meeting(*slice, state.lower.present ? &state.lower.exact : nullptr,
                                                                   state.upper.present ? &state.upper.exact : nullptr)) {
      if (j > 0) add(j - 1);
      if (j < slice->points.size()) add(j);
    }
    return keys;
  }

  // channel_bounds on the exact kernel slice of `slicer`'s pair at the sample's driver position
  // instead of a C-space's slice (large pairs; session 59): the feature pairs at the ends of its
  // free intervals meeting the sample's nominal channel (exact: exact_order.hpp).
  // Read off a windowed slice about the nominal channel first (session 61: the witness slicer
  // then forms and culls the contact curves of the window's follower cells only; the whole
  // turn's 72 spur-gear changes took 42 s CPU on whole-chart slices), when the window holds
  // every free interval meeting the channel whole, with a contact point at each end strictly
  // inside it; otherwise a window 8 and 64 times as wide, then the whole chart's slice. The
  // result is the whole slice's: the windowed slice has its points, features and classes
  // inside the window (KernelSlicer::slice), and an accepted window leaves the whole slice
  // nothing to continue across the half-turn seam (its channel within the chart, no free
  // interval meeting it reaching the chart's end).
  std::optional<std::vector<PairKey>> kernel_channel_bounds(const KernelSlicer& slicer, std::size_t k) const {
    const SampleState& state = states_[k];
    // (a translating follower's chart has no seam: its channel may lie anywhere along the stroke)
    if (state.lower.present && state.upper.present &&
        (!result_.follower_rotates || (tolerance_detail::compare(state.lower.exact, Rational(-1)) >= 0 &&
                                       tolerance_detail::compare(state.upper.exact, Rational(1)) <= 0))) {
      const Rational width = state.upper.exact.upper - state.lower.exact.lower;
      for (int widening : {1, 8, 64}) {
        const Rational margin = width * widening;
        const Rational window_lo = state.lower.exact.lower - margin, window_hi = state.upper.exact.upper + margin;
        if (!(window_lo < window_hi)) break;
        std::optional<KernelSlice> slice = slicer.slice(state.driver_chart.t, state.driver_chart.half, state.follower_chart.t,
                                                        state.follower_chart.half, window_lo, window_hi);
        if (!slice) return std::nullopt;   // as the whole slice: no chart holds the position
        std::vector<std::size_t> meeting = kernel_free_meeting(*slice, &state.lower.exact, &state.upper.exact);
        const bool inside = std::all_of(meeting.begin(), meeting.end(), [&](std::size_t j) {
          return j > 0 && j < slice->points.size() && tolerance_detail::compare(slice->points[j - 1].at, window_lo) > 0 &&
                 tolerance_detail::compare(slice->points[j].at, window_hi) < 0;
        });
        if (!inside) continue;
        std::vector<PairKey> keys;
        auto add = [&](std::size_t point) {
          for (const auto& [first, second] : slice->points[point].features) keys.push_back(key_of(first, second));
        };
        for (std::size_t j : meeting) {
          add(j - 1);
          add(j);
        }
        return keys;
      }
    }
    std::optional<KernelSlice> slice = kernel_slice_at(slicer, state);
    if (!slice) return std::nullopt;
    std::vector<PairKey> keys;
    auto add = [&](std::size_t point) {
      for (const auto& [first, second] : slice->points[point].features) keys.push_back(key_of(first, second));
    };
    for (std::size_t j : kernel_free_meeting(*slice, state.lower.present ? &state.lower.exact : nullptr,
                                             state.upper.present ? &state.upper.exact : nullptr)) {
      if (j > 0) add(j - 1);
      if (j < slice->points.size()) add(j);
    }
    return keys;
  }

  // docs/tolerance.md "Contacts that appear or disappear". At every driver position with a
  // channel, every contact curve of the nominal C-space (contact and spurious edges: the curves
  // the build kept) lying beyond a side of the channel is enclosed over the whole box, as is the
  // side: enclosures apart = certainly never overtakes it there. Otherwise the box corner that
  // the linearised model says moves it furthest past the side is tried (both roots certified at
  // that vector), and the largest such overshoot per (curve, side) is confirmed by an exact
  // C-space at that vector: its slice shows the curve bounding the channel.
  void contact_changes() {
    auto start = std::chrono::steady_clock::now();
    ContactChangeCheck check;
    const Model& m = model_->nominal();
    std::size_t n = m.parameters.size();
    if (!driver_is_x_) {
      result_.notes.push_back("contact changes: not searched (the driver is the C-space's second part)");
      result_.contact_changes = check;
      return;
    }
    // Every feature pair bounding the nominal channel somewhere along the path, and where.
    std::vector<std::pair<PairKey, std::pair<std::size_t, bool>>> side_positions;   // key, (sample, lower)
    auto side_keys = [&](const Side& side) {
      std::vector<PairKey> keys;
      if (side.present)
        for (FeatureId id : side.features) keys.push_back(key_of(space_->feature_pair(id)));
      return keys;
    };
    for (std::size_t k = 0; k < states_.size(); ++k) {
      if (!states_[k].valid) continue;
      for (bool lower : {true, false})
        for (const PairKey& key : side_keys(lower ? states_[k].lower : states_[k].upper))
          side_positions.push_back({key, {k, lower}});
    }
    auto bounds_on_path = [&](const PairKey& key) {
      return std::any_of(side_positions.begin(), side_positions.end(), [&](const auto& e) { return e.first == key; });
    };
    struct Candidate {
      PairKey key, side_key;
      std::string label, side_label;
      bool lower = true;
      std::size_t sample = 0;
      double overshoot = 0;           // part units
      bool certified = false;
      std::vector<Rational> corner;   // deviations: ends of the exact tolerance ranges
    };
    std::vector<Candidate> found;
    double accuracy = std::max(options_.relative_accuracy, 1.0);   // separation needs no tight band
    for (std::size_t k = 0; k < states_.size(); ++k) {
      const SampleState& state = states_[k];
      if (!state.valid || (!state.lower.present && !state.upper.present)) continue;
      ++check.positions;
      struct SideCurve {
        bool ok = false;
        CurveSlice curve;
        double value = 0;
        std::vector<double> s;
        std::string label;
        Interval range;
        std::vector<PairKey> keys;
      } sides[2];
      for (int j = 0; j < 2; ++j) {
        const Side& side = j == 0 ? state.lower : state.upper;
        if (!side.present) continue;
        SideCurve& sc = sides[j];
        sc.keys = side_keys(side);
        if (!side_curve(state, side, sc.curve, sc.value, sc.s, sc.label)) continue;
        try {
          sc.range = solver_->certified_range(sc.curve, box_, sc.value, sc.s, accuracy, options_.absolute_accuracy,
                                              result_.certified_boxes);
          sc.ok = true;
        } catch (const Error&) {
        }
      }
      double x = state.driver_chart.t.get_d();
      // the charts holding the slice: the sample's, and on an operating region the built tiles
      // of its column (region_slice_near)
      const CSpaceChart& home = space_->charts()[state.chart];
      auto in_column = [&](std::size_t c) {
        if (c == state.chart) return true;
        if (space_->complete()) return false;
        const CSpaceChart& other = space_->charts()[c];
        return other.x_half_turn == home.x_half_turn && other.y_half_turn == home.y_half_turn &&
               other.x_lo <= state.driver_chart.t && state.driver_chart.t <= other.x_hi;
      };
      std::vector<std::pair<PairKey, double>> seen;
      for (std::size_t e = 0; e < space_->edges().size(); ++e) {
        const CSpaceEdge& edge = space_->edges()[e];
        if (!in_column(edge.chart) || edge.vertical || edge.curves.empty()) continue;
        if (edge.role != EdgeRole::contact && edge.role != EdgeRole::spurious) continue;
        if (!(edge.x_chart.lower <= x && x <= edge.x_chart.upper)) continue;
        FeatureId id(edge.curves.front());
        const FeaturePair& pair = space_->feature_pair(id);
        PairKey key = key_of(pair);
        bool is_side = false;
        for (const SideCurve& sc : sides) is_side = is_side || std::find(sc.keys.begin(), sc.keys.end(), key) != sc.keys.end();
        if (is_side) continue;
        double y = 0;
        try {
          y = space_->evaluate(e, x).value;
        } catch (const Error&) {
          continue;
        }
        bool duplicate = std::any_of(seen.begin(), seen.end(), [&](const auto& p) {
          return p.first == key && std::fabs(p.second - y) <= 1e-9 * (1 + std::fabs(y));
        });
        if (duplicate) continue;
        seen.push_back({key, y});
        // Beyond which side? (A curve inside the channel touches in free space: not a side.)
        int j = state.lower.present && y < state.lower.value ? 0 : state.upper.present && y > state.upper.value ? 1 : -1;
        if (j < 0) continue;
        ++check.candidates;
        const SideCurve& side = sides[j];
        CurveSlice curve = curve_for(id, state);
        std::vector<double> s;
        Interval range;
        try {
          if (!side.ok) throw NumericError("side not enclosed");
          s = solver_->sensitivities(curve, y);
          range = solver_->certified_range(curve, box_, y, s, accuracy, options_.absolute_accuracy, result_.certified_boxes);
        } catch (const Error&) {
          ++check.undecided;
          continue;
        }
        bool lower = j == 0;
        if (lower ? range.hi < side.range.lo : range.lo > side.range.hi) {
          ++check.excluded;
          continue;
        }
        ++check.possible;
        if (bounds_on_path(key)) {
          ++check.switch_shifts;
          continue;
        }
        // The corner moving the curve furthest past the side (linearised), inside the box.
        Candidate c;
        c.key = key;
        c.label = pair.label;
        c.side_label = side.label;
        c.side_key = side.keys.front();
        for (FeatureId fid : (lower ? state.lower : state.upper).features)
          if (space_->feature_pair(fid).label == side.label) c.side_key = key_of(space_->feature_pair(fid));
        c.lower = lower;
        c.sample = k;
        c.corner.assign(n, Rational(0));
        std::vector<Interval> corner(n, Interval(0));
        double chart_overshoot = lower ? y - side.value : side.value - y;
        for (std::size_t i = 0; i < n; ++i) {
          double d = lower ? s[i] - side.s[i] : side.s[i] - s[i];
          const Parameter& p = m.parameters[i];
          if (d == 0 || !(p.range.lo < p.range.hi)) continue;
          c.corner[i] = d > 0 ? Rational(p.range.hi - p.nominal) : Rational(p.range.lo - p.nominal);
          corner[i] = Interval::enclose(c.corner[i]);
          chart_overshoot += d * (d > 0 ? dist_[i].hi : dist_[i].lo);
        }
        if (!(chart_overshoot > 0)) continue;
        c.overshoot = chart_overshoot * chart_slope(side.value, result_.follower_rotates);
        std::vector<Interval> geometry = model_->parameter_values(corner);
        auto widen = [](const Interval& r) {
          double w = 1e-12 * (1 + std::max(std::fabs(r.lo), std::fabs(r.hi)));
          return Interval(r.lo - w, r.hi + w);
        };
        Interval root, side_root;
        if (solver_->certified_point_root(curve, geometry, widen(range), root) &&
            solver_->certified_point_root(side.curve, geometry, widen(side.range), side_root))
          c.certified = lower ? root.lo > side_root.hi : root.hi < side_root.lo;
        found.push_back(std::move(c));
      }
      bar_.units(k + 1, states_.size());
    }
    // One change per (curve, side it overtakes, side of the channel): its largest overshoot.
    struct Group {
      std::size_t best = 0;
      std::vector<std::size_t> samples;
    };
    std::vector<Group> groups;
    for (std::size_t c = 0; c < found.size(); ++c) {
      auto same = [&](const Group& g) {
        const Candidate& b = found[g.best];
        return b.key == found[c].key && b.side_key == found[c].side_key && b.lower == found[c].lower;
      };
      auto g = std::find_if(groups.begin(), groups.end(), same);
      if (g == groups.end()) {
        groups.push_back(Group{c, {}});
        g = groups.end() - 1;
      }
      g->samples.push_back(found[c].sample);
      if (found[c].overshoot > found[g->best].overshoot) g->best = c;
    }
    std::stable_sort(groups.begin(), groups.end(),
                     [&](const Group& a, const Group& b) { return found[a.best].overshoot > found[b.best].overshoot; });
    // A large pair's witnesses are sliced on one kernel slicer per distinct witness vector (its
    // strips serve every slice), and the limit counts those slicers: the changes sharing a
    // witness (spur-gears.json: every one at the same box corner) are all examined.
    // Each witness' slices are kept by position: the changes sharing it ask for the same ones.
    struct WitnessSlices {
      std::shared_ptr<KernelSlicer> slicer;
      std::map<std::size_t, std::optional<std::vector<PairKey>>> bounds;
    };
    std::vector<std::pair<std::vector<Rational>, WitnessSlices>> slicers;
    // the label of a feature pair (the nominal space's), for the evidence
    auto label_of = [&](const PairKey& key) {
      for (const FeaturePair& pair : space_->feature_pairs())
        if (key_of(pair) == key) return "'" + pair.label + "'";
      return std::string("an unlabelled feature pair");
    };
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const Group& g = groups[gi];
      const Candidate& best = found[g.best];
      ContactChange change;
      change.kind = ContactChange::Kind::appears;
      change.contact = best.label;
      change.other = best.side_label;
      change.lower_side = best.lower;
      change.driver_first = result_.samples[g.samples.front()].driver;
      change.driver_last = result_.samples[g.samples.back()].driver;
      change.positions = g.samples.size();
      change.driver = result_.samples[best.sample].driver;
      change.overshoot = best.overshoot;
      change.certified_at_witness = best.certified;
      const std::vector<Rational>& deviations = best.corner;
      for (std::size_t i = 0; i < n; ++i) {
        if (m.parameters[i].range.lo < m.parameters[i].range.hi)
          change.witness.emplace_back(m.parameters[i].name, m.parameters[i].nominal + deviations[i]);
      }
      std::optional<ContactChange> disappears;
      auto cached = std::find_if(slicers.begin(), slicers.end(), [&](const auto& s) { return s.first == deviations; });
      const std::size_t builds = kernel_confirmations_ ? slicers.size() : gi;
      if ((!kernel_confirmations_ || cached == slicers.end()) && builds >= options_.contact_change_confirmations) {
        change.evidence = "not confirmed: only the " + std::to_string(options_.contact_change_confirmations) +
                          (kernel_confirmations_ ? " largest changes' witnesses are sliced exactly"
                                                 : " largest changes are confirmed by an exact C-space");
      } else {
        try {
          // the witness' exact C-space, or (a large pair) its pair's exact kernel slices
          std::optional<CSpace> space;
          std::shared_ptr<KernelSlicer> slicer;
          if (kernel_confirmations_) {
            if (cached == slicers.end()) {
              slicers.emplace_back(deviations, WitnessSlices{std::make_shared<KernelSlicer>(model_->exact_model(deviations),
                                                                                            driver_, follower_),
                                                             {}});
              cached = slicers.end() - 1;
            }
            slicer = cached->second.slicer;
          } else {
            space.emplace(CSpace::build(model_->exact_model(deviations), pair_first_, pair_second_));
          }
          auto bounds = [&](std::size_t k) {
            if (space) return channel_bounds(*space, k);
            auto [at, added] = cached->second.bounds.try_emplace(k);
            if (added) at->second = kernel_channel_bounds(*slicer, k);
            return at->second;
          };
          const std::string exact = space ? "exact C-space at the witness: "
                                          : "exact slices (contact kernels and the exact overlap oracle) at the witness: ";
          // Refuted (session 60): at every position the exact slice holds a channel meeting the
          // nominal one and the contact bounds none of it (e.g. a vertex of a tangent-continuous
          // joint, whose curve overtakes the side only inside blocked space).
          std::size_t sliced = 0;
          std::vector<PairKey> others;   // what bounds it instead, at the first such position
          for (std::size_t k : g.samples) {
            std::optional<std::vector<PairKey>> keys = bounds(k);
            if (!keys || keys->empty()) continue;
            ++sliced;
            if (std::find(keys->begin(), keys->end(), best.key) != keys->end()) ++change.confirmed_positions;
            else if (others.empty()) others = *keys;
          }
          change.confirmed = change.confirmed_positions > 0;
          if (!change.confirmed && sliced == g.samples.size()) {
            std::string instead;
            for (auto key = others.begin(); key != others.end(); ++key)
              if (std::find(others.begin(), key, *key) == key) instead += (instead.empty() ? "" : ", ") + label_of(*key);
            // (the scope stated: this vector and these positions, not the whole box; session 61)
            change.evidence = "refuted: " + exact + "at none of the " + std::to_string(g.samples.size()) +
                              " positions does the contact bound the channel (bounded there by " + instead +
                              "); refuted at this witness vector and these positions only, not over the whole box";
          } else {
            change.evidence = exact + "at " + std::to_string(change.confirmed_positions) + " of " +
                              std::to_string(g.samples.size()) + " positions the contact bounds the channel";
          }
          // The side it overtakes: does it still bound the channel anywhere along the path?
          // (one position where it does settles it: the positions already sliced are asked
          // first, and the search stops there; session 61)
          std::vector<std::size_t> side_at;
          for (const auto& [key, at] : side_positions)
            if (key == best.side_key) side_at.push_back(at.first);
          const std::size_t where = side_at.size();
          if (!space)
            std::stable_partition(side_at.begin(), side_at.end(),
                                  [&](std::size_t k) { return cached->second.bounds.count(k) > 0; });
          const bool bounded = std::any_of(side_at.begin(), side_at.end(), [&](std::size_t k) {
            std::optional<std::vector<PairKey>> keys = bounds(k);
            return !keys || std::find(keys->begin(), keys->end(), best.side_key) != keys->end();
          });
          if (where > 0 && !bounded) {
            ContactChange gone = change;
            gone.kind = ContactChange::Kind::disappears;
            gone.contact = best.side_label;
            gone.other = best.label;
            gone.positions = where;
            gone.confirmed = true;
            gone.confirmed_positions = where;
            gone.evidence = exact + "at none of the " + std::to_string(where) +
                            " positions where it bounds the nominal channel does it bound the channel";
            disappears = gone;
          }
        } catch (const Error& error) {
          change.evidence = std::string("no exact C-space at the witness: ") + error.what();
        }
      }
      check.changes.push_back(change);
      if (disappears) check.changes.push_back(*disappears);
    }
    check.seconds = seconds_since(start);
    result_.contact_changes = check;
  }

  // The generic form refused when a template has none; the curve solver on the model.
  void start_solver() {
    model_->require_generic();
    solver_ = std::make_shared<CurveSolver>(model_);
    solver_->set_compact_jets(options_.fast_paths);
  }

  ToleranceOptions options_;
  // The bar's stages: the pair's C-space, the nominal sweep, sensitivities, the certified band,
  // the zones, the Monte Carlo, the threshold and contact changes, the certificate.
  tolerance_detail::StagedProgress bar_{options_.progress, {0, 0.02, 0.2, 0.3, 0.45, 0.55, 0.85, 0.9, 0.95, 1}};
  std::string text_, source_name_;
  std::shared_ptr<const model_detail::ParametricModel> model_;
  std::shared_ptr<CurveSolver> solver_;
  std::unique_ptr<CSpace> space_;
  // a large pair's nominal kinematics on the contact kernels, computed before its space
  std::optional<KinematicsResult> kernel_path_;
  bool large_pair_ = false;   ///< > 120 boundary edges and no space given: analyze's kernel path (start())
  /// the exact confirmations on kernel slices, no C-space (large pairs, or the test switch off)
  bool kernel_confirmations_ = false;
  ToleranceResult result_;
  std::vector<Distribution> dist_;
  Box box_;
  std::size_t driver_ = 0, follower_ = 0;
  std::string pair_first_, pair_second_;
  bool driver_is_x_ = true;
  std::vector<SampleState> states_;
};

}  // namespace

namespace tolerance_detail {

std::shared_ptr<const model_detail::ParametricModel> analysed_form(model_detail::ParametricModel form,
                                                                    const ToleranceOptions& options) {
  const long exponent = kinematic_decimal_exponent(form.nominal());
  if (exponent == 0) return std::make_shared<const model_detail::ParametricModel>(std::move(form));
  return std::make_shared<const model_detail::ParametricModel>(form.rescaled(exponent));
}

std::optional<std::pair<Rational, Rational>> range_in_unit(const ToleranceOptions& options, bool driver_rotates,
                                                           long exponent) {
  if (!options.range || driver_rotates || exponent == 0) return options.range;
  const Rational unit = power_of_ten_rational(exponent);
  return std::make_pair(Rational(options.range->first / unit), Rational(options.range->second / unit));
}

StageAnalysis analyze_stage(std::string_view text, const ToleranceOptions& options, const std::vector<StagePosition>& path,
                            const CSpace* space) {
  return Analysis(text, options).stage(path, space);
}

StageAnalysis analyze_stage(std::string_view text, std::shared_ptr<const model_detail::ParametricModel> model,
                            const ToleranceOptions& options, const std::vector<StagePosition>& path,
                            const CSpace* space) {
  return Analysis(text, std::move(model), options).stage(path, space);
}

}  // namespace tolerance_detail

namespace {

// The model file's text, read once.
std::string model_file_text(const std::filesystem::path& model_file) {
  std::error_code error;
  if (std::filesystem::is_directory(model_file, error))
    throw IoError("cannot read model file '" + model_file.string() + "': it is a directory");
  std::ifstream file(model_file, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + model_file.string() + "'");
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

// The budgets and options that bound an analysis' result (ToleranceResult::budgets, session 72;
// a chain's own sub-box budgets are recorded by the chain, chain.cpp).
void record_budgets(ToleranceResult& result, const ToleranceOptions& options) {
  auto& b = result.budgets;
  b.insert(b.begin(), {{"relative_accuracy", options.relative_accuracy}, {"absolute_accuracy", options.absolute_accuracy}});
  if (options.monte_carlo > 0) b.emplace_back("monte_carlo_samples", static_cast<double>(options.monte_carlo));
  if (options.certify || options.certify_free_path) {
    b.emplace_back("certify_max_leaves", static_cast<double>(options.certify_max_leaves));
    b.emplace_back("certify_witness_splits", static_cast<double>(options.certify_witness_splits));
    b.emplace_back("certify_free_path", options.certify_free_path ? 1.0 : 0.0);
  }
}

// The analysis, and with `exponents` its parameters' scale exponents (session 67:
// model_detail::parameter_scale_exponents of the form it ran on).
ToleranceResult analyze(std::string_view text, const ToleranceOptions& options, std::string source_name,
                        std::vector<long>* exponents) {
  if (exponents) exponents->clear();
  if (options.chain) {
    // the chain's pairs run on analysed_form of the model (chain.cpp): at an extreme scale the
    // exponents of that form, handed back by the chain (session 70: no longer read and rescaled
    // a second time here)
    ToleranceResult result = tolerance_detail::analyze_chain(text, options, {}, exponents);
    if (exponents && result.length_exponent == 0)
      exponents->assign(result.parameters.size(), 0);   // all 0, as for a pair (session 68)
    record_budgets(result, options);
    return result;
  }
  Analysis analysis(text, options, std::move(source_name));
  ToleranceResult result = analysis.run();
  record_budgets(result, options);
  if (exponents) *exponents = model_detail::parameter_scale_exponents(analysis.model());
  return result;
}

}  // namespace

ToleranceResult analyze_tolerances_text(std::string_view json_text, const ToleranceOptions& options) {
  return analyze(json_text, options, "<string>", nullptr);
}

ToleranceResult analyze_tolerances(const std::filesystem::path& model_file, const ToleranceOptions& options) {
  return analyze(model_file_text(model_file), options, model_file.filename().string(), nullptr);
}

ToleranceResult analyze_tolerances_text(std::string_view json_text, const ToleranceOptions& options,
                                        std::vector<long>& parameter_exponents) {
  return analyze(json_text, options, "<string>", &parameter_exponents);
}

ToleranceResult analyze_tolerances(const std::filesystem::path& model_file, const ToleranceOptions& options,
                                   std::vector<long>& parameter_exponents) {
  return analyze(model_file_text(model_file), options, model_file.filename().string(), &parameter_exponents);
}

}  // namespace hipair
