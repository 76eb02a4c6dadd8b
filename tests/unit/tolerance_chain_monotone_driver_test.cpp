// Session 47 (tol47): the hand-over envelope's driver-monotone route against the exact train
// (issue 12; docs/tolerance.md "Assembly chains", "The driver-monotone route").
//
// At the late meshes of gear-train.json the driver's range T (the previous mesh's enclosure) is
// wide, and the envelope's walk over box x T cannot exclude the next tooth pair from the window
// beyond the holder's enclosure. The route (handover.cpp, step 5) proves instead that the
// follower moves in its driver as the holder does (every feature pair that may push it in
// [Y, M) has F_t of the holder's sign), walks the box at the one end of T where the follower is
// furthest (and the nominal parameters along T up to it), and walks the rest of T (where the
// proof does not hold) from there. Here, on the 8-mesh train (test_gears::gear_train(9),
// gear-train.json's model) over 1.309..1.745 rad at 120 per turn, the last position (1.745 rad)
// is unbounded without the route (mesh H:I: gear-H tooth 7 flank R / gear-I tooth 10 flank R not
// excluded) and bounded with it; the exact train (the model rebuilt exactly, the kernel-sliced
// exact engine over the same range and grid) at the vertices of the box the linearisation moves
// furthest up and down at that position (and near them) and at random vectors must lie inside
// every bounded band. Mutants run: docs/performance.md "Session 47 (tol47)".
#include "gear_train_models.hpp"
#include "tolerance_band_check.hpp"

#include "model/parametric/parametric.hpp"
#include "tolerance/handover.hpp"
#include "tolerance/stage.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/rational.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test_band::bounded;

TEST(ChainMonotoneDriver, LateMeshBandBoundedThroughTheDriverHoldsTheExactTrain) {
  const std::string text = test_gears::gear_train(9);
  const std::pair<Rational, Rational> range(Rational(1308996939, 1000000000), Rational(1745329252, 1000000000));
  ToleranceOptions options = test_gears::chain_options(range.second, 0, 47);
  options.range = range;
  ToleranceResult r;
  {
    // the widened whole box split (session 48) off: the band at the last position is then the
    // route's own (with it, the meet with its halves', tested in ChainWidenedSplit), and the
    // test costs what it did before (two split positions, 46 -> 24 s user)
    test_band::ScopedSwitch route(tolerance_detail::handover_monotone_driver(), 1);
    test_band::ScopedSwitch split(tolerance_detail::chain_widened_split(), 0);
    r = analyze_tolerances_text(text, options);
  }
  ASSERT_EQ(r.samples.size(), 10u);
  std::size_t held = 0, unbounded = 0;
  for (const VariationSample& s : r.samples) {
    if (!s.contact) continue;
    ++held;
    if (!bounded(s)) ++unbounded;
  }
  EXPECT_EQ(held, 9u);
  const VariationSample& last = r.samples.back();
  EXPECT_TRUE(bounded(last)) << "driver " << last.driver;   // unbounded without the route
  EXPECT_EQ(unbounded, 0u);

  // probes: the vertices maximising and minimising the linearised output at the last position,
  // the same with the least effective parameter flipped and with the most effective one nominal,
  // and random vectors of the box
  std::vector<std::vector<Rational>> probes;
  const test_gears::Effects e = test_gears::effects(last, r.parameters);
  ASSERT_LT(e.most, r.parameters.size());
  for (auto& probe : test_gears::corner_probes(last, r.parameters, e)) probes.push_back(std::move(probe.second));
  std::mt19937 rng(47);
  for (int k = 0; k < 6; ++k) probes.push_back(test_gears::random_deviations(r.parameters, rng));
  std::set<std::vector<Rational>> distinct(probes.begin(), probes.end());

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  double upper_gap = 1, lower_gap = 1;   // at the last position, fractions of its band's width
  for (const std::vector<Rational>& d : distinct) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = options.positions;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult exact = analyze_kinematics(model->exact_model(d), k);
    test_band::visit_exact_values(exact, "gear-I", r.samples, [&](std::size_t i, double value, double ulp) {
      const VariationSample& sample = r.samples[i];
      ++checked;
      EXPECT_GE(value, sample.certified.lower - ulp) << "driver " << sample.driver;
      EXPECT_LE(value, sample.certified.upper + ulp) << "driver " << sample.driver;
      if (&sample == &last) {
        double width = sample.certified.upper - sample.certified.lower;
        upper_gap = std::min(upper_gap, (sample.certified.upper - value) / width);
        lower_gap = std::min(lower_gap, (value - sample.certified.lower) / width);
      }
    });
  }
  EXPECT_EQ(checked, distinct.size() * held);
  std::printf("driver %.4f: band [%.5f, %.5f] (linearised [%.5f, %.5f]); exact values within %.4f / %.4f of the band's "
              "width of its upper / lower edge; %zu exact trains, %zu values checked\n",
              last.driver, last.certified.lower, last.certified.upper, last.linear_lower, last.linear_upper, upper_gap,
              lower_gap, distinct.size(), checked);
}


// A chain where the later stage is NOT monotone in its driver, so that the route's certificate (a)
// and the walk of the rest of T are what keep it sound (the gear trains cannot show it: a gear's
// follower is monotone in its driver, so there a route without (a), or with E_1 taken over the whole
// of T, still gives a band the exact train stays in). cam -> lifter1 (translating along x, its face
// at 30 + f, f = 0 +- 5: lifter1's range T about 10 mm wide) -> lifter2 (translating along y under
// its weight), pushed by lifter1's roller (radius 5, centre at x = u = 30 - f + e cos(theta)) on
// its underside: a shallow slope (the holder; lifter2 falls by 0.02 per mm of u, so the follower is
// furthest up at T's low end, T_e) and, beyond it, a ridge hanging down at x = 35.5 .. 39.5 that
// lifts lifter2 to about 2.8 mm when u nears 35 (f = -5), far above the holder's [0.79, 1.01]. The
// walk over box x T cannot exclude the ridge (its window reaches twice the holder's width), so the
// route is tried: the ridge pushes against the holder's sense (F_t of the other sign), so (a) holds
// only over T less its last quarter, and the rest of T must be walked — which meets the ridge. Every
// bounded band must hold the exact train at the box's corners and random vectors (with the route
// correct, the positions stay unbounded here: the rest's walk fails as the first walk did).
// `left`: with a second ridge hanging down at x = 22 (its vertex at 42.7), which lifts lifter2 to
// about 1.3 mm at T's low end (T_e) and in the holder's sense: E_1 then reaches 1.3, the rest's walk
// (its window twice the width of [0.81, E_1]) meets the right ridge (here at 42.33, lifting lifter2
// to 2.0 at f = -5) and ends beyond it at pi/2 (the other positions stay unbounded).
std::string ridge_chain(bool left) {
  const std::string profile =
      left ? R"({"line_to": [20, 43.89]}, {"line_to": [22, 42.7]}, {"line_to": [24, 43.97]}, {"line_to": [35.5, 44.2]}, {"line_to": [37.5, 42.33]})"
           : R"({"line_to": [35.5, 44.2]}, {"line_to": [37.5, 41.95]})";
  return R"({"hipair": 1, "name": "ridge-chain", "units": {"length": "mm", "angle": "rad"},
 "parameters": {"e": {"nominal": 5, "tolerance": 0.01}, "f": {"nominal": 0, "tolerance": 5}},
 "parts": [
  {"name": "cam", "motion": {"rotation": {"pivot": [0, 0]}}, "initial": {"angle": 0},
   "loops": [{"circle": {"center": ["e", 0], "radius": 20}}]},
  {"name": "lifter1", "motion": {"translation": {"direction": [1, 0], "limits": [-40, 40]}}, "initial": {"offset": -10},
   "loops": [{"start": ["30 + f", -30], "edges": [{"line_to": [50, -30]}, {"line_to": [50, 30]}, {"line_to": ["30 + f", 30]}, {"line_to": ["30 + f", -30]}]},
             {"circle": {"center": [40, 40], "radius": 5}}],
   "dynamics": {"mass": 0.1, "force": [-10, 0]}},
  {"name": "lifter2", "motion": {"translation": {"direction": [0, 1], "limits": [-40, 40]}}, "initial": {"offset": 0},
   "loops": [{"start": [10, 80], "edges": [{"line_to": [10, 43.69]}, )" + profile + R"(, {"line_to": [39.5, 50]}, {"line_to": [60, 50]}, {"line_to": [60, 80]}, {"line_to": [10, 80]}]}],
   "dynamics": {"mass": 0.1, "force": [0, -10]}}],
 "pairs": [{"parts": ["cam", "lifter1"]}, {"parts": ["lifter1", "lifter2"]}]})";
}

TEST(ChainMonotoneDriver, NonMonotoneLaterStageBandsHoldTheExactChain) {
 for (bool left : {false, true}) {
  SCOPED_TRACE(left ? "two ridges" : "one ridge");
  const std::string text = ridge_chain(left);
  const std::pair<Rational, Rational> range(Rational(7, 5), Rational(8, 5));
  ToleranceOptions options;
  options.driver = "cam";
  options.chain = true;
  options.range = range;
  options.positions = 120;
  options.threads = 1;
  ToleranceResult r;
  {
    test_band::ScopedSwitch route(tolerance_detail::handover_monotone_driver(), 1);
    r = analyze_tolerances_text(text, options);
  }
  ASSERT_EQ(r.samples.size(), 6u);
  std::size_t held = 0, with_band = 0;
  for (const VariationSample& s : r.samples) {
    held += s.contact ? 1 : 0;
    with_band += bounded(s) ? 1 : 0;
  }
  EXPECT_EQ(held, 6u);
  // probes: the box's 4 corners, f at its low end with e nominal (the ridge's deepest reach), and
  // 4 random vectors
  std::vector<std::vector<Rational>> probes;
  ASSERT_EQ(r.parameters.size(), 2u);
  for (int a : {0, 1})
    for (int b : {0, 1}) {
      std::vector<Rational> d(2);
      for (std::size_t q = 0; q < 2; ++q) {
        const Parameter& p = r.parameters[q];
        d[q] = ((q == 0 ? a : b) ? p.range.hi : p.range.lo) - p.nominal;
      }
      probes.push_back(d);
    }
  {
    std::size_t f = r.parameters[0].name == "f" ? 0 : 1;
    std::vector<Rational> d(2, Rational(0));
    d[f] = r.parameters[f].range.lo - r.parameters[f].nominal;
    probes.push_back(d);
  }
  std::mt19937 rng(4747);
  for (int k = 0; k < 4; ++k) probes.push_back(test_gears::random_deviations(r.parameters, rng));

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  double highest = -std::numeric_limits<double>::infinity();
  for (const std::vector<Rational>& d : probes) {
    KinematicsOptions k;
    k.driver = "cam";
    k.range = range;
    k.steps_per_cycle = options.positions;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult exact = analyze_kinematics(model->exact_model(d), k);
    std::size_t output = static_cast<std::size_t>(std::find(exact.followers.begin(), exact.followers.end(), "lifter2") -
                                                  exact.followers.begin());
    ASSERT_LT(output, exact.followers.size());
    for (const VariationSample& sample : r.samples) {
      auto at = std::find_if(exact.samples.begin(), exact.samples.end(),
                             [&](const KinematicSample& s) { return s.driver == sample.driver; });
      EXPECT_NE(at, exact.samples.end()) << "driver " << sample.driver;
      if (at == exact.samples.end()) continue;
      double value = at->positions.at(output);
      EXPECT_TRUE(std::isfinite(value));
      highest = std::max(highest, value);
      if (!bounded(sample)) continue;
      ++checked;
      double ulp = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(value));
      EXPECT_GE(value, sample.certified.lower - ulp) << "driver " << sample.driver;
      EXPECT_LE(value, sample.certified.upper + ulp) << "driver " << sample.driver;
    }
  }
  // the ridge is reached: the exact chain goes far beyond the holder's enclosure (what a route
  // without (a) or without the rest's walk would give: [0.79, 1.01], or E_1 ~ 1.3 with two ridges)
  EXPECT_GE(highest, left ? 1.99 : 2.7);
  // with two ridges the route bounds pi/2 (without it: unbounded), so the soundness check is not
  // vacuous there
  if (left) EXPECT_GE(with_band, 1u);
  std::printf("%s: %zu of %zu held positions bounded, %zu exact values checked against them; highest exact "
              "value %.4f\n",
              left ? "two ridges" : "one ridge", with_band, held, checked, highest);
 }
}

}  // namespace
}  // namespace hipair
