// Session 45 (tol45): the case split at a chain's last widened pair against the exact train
// (issue 12; docs/tolerance.md "Assembly chains", "The case split at a widened mesh").
//
// Where a middle mesh's envelope widens (another tooth pair may take over inside the box), the
// composition carries the widening as a remainder through every later mesh, and the later
// meshes' driver ranges grow with it: at 0.195 rad gear-train.json's band is 13.9 x its
// linearised width. The case split (chain.cpp compose_over) proves every later mesh monotone in
// its driver over the composition's regions (dy/dt's enclosure excludes 0) and takes the hull of
// two compositions: the widened pair's follower at its holder's root, and at the envelope's far
// end (a point). Here, on the 8-mesh train (test_gears::gear_train(9), gear-train.json's model)
// over 0.15..0.24 rad at 120 per turn, the bands with the split must lie inside those without
// it, the widened position's must narrow, and the exact train (the model rebuilt exactly, the
// kernel-sliced exact engine) at the vertices the linearisation moves furthest up and down (and
// near them) and at random vectors of the box must lie inside every band with the split.
// Mutants run (docs/performance.md "Session 45 (tol45)"): listed there with their failure counts.
#include "gear_train_models.hpp"
#include "test_paths.hpp"

#include "model/parametric/parametric.hpp"
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

struct CaseSplit {
  explicit CaseSplit(int on) : saved(tolerance_detail::chain_case_split()) { tolerance_detail::chain_case_split() = on; }
  ~CaseSplit() { tolerance_detail::chain_case_split() = saved; }
  int saved;
};

ToleranceResult run(const std::string& text, const ToleranceOptions& options, int on) {
  CaseSplit split(on);
  return analyze_tolerances_text(text, options);
}

bool bounded(const VariationSample& s) { return s.contact && std::isfinite(s.certified.upper - s.certified.lower); }

TEST(ChainCaseSplit, WidenedMeshBandNarrowsAndHoldsTheExactTrain) {
  const std::string text = test_gears::gear_train(9);
  const std::pair<Rational, Rational> range(Rational(3, 20), Rational(6, 25));
  ToleranceOptions options = test_gears::chain_options(range.second, 0, 45);
  options.range = range;
  ToleranceResult off = run(text, options, 0);
  ToleranceResult r = run(text, options, 1);
  ASSERT_EQ(r.chain.size(), 8u);
  ASSERT_EQ(r.samples.size(), off.samples.size());

  // The split only meets the composition's band with the cases' hull: never wider, and here
  // narrower where the middle mesh widened.
  std::size_t held = 0, narrowed = 0;
  double best = 1;   // the narrowest band with the split over the one without it
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const VariationSample& a = r.samples[i];
    const VariationSample& b = off.samples[i];
    ASSERT_EQ(a.contact, b.contact);
    if (!a.contact) continue;
    ++held;
    ASSERT_TRUE(bounded(b)) << "driver " << b.driver;
    ASSERT_TRUE(bounded(a)) << "driver " << a.driver;
    EXPECT_GE(a.certified.lower, b.certified.lower) << "driver " << a.driver;
    EXPECT_LE(a.certified.upper, b.certified.upper) << "driver " << a.driver;
    double ratio = (a.certified.upper - a.certified.lower) / (b.certified.upper - b.certified.lower);
    if (ratio < 1) ++narrowed;
    best = std::min(best, ratio);
  }
  EXPECT_EQ(held, 3u);
  EXPECT_GE(narrowed, 1u);
  EXPECT_LT(best, 0.25);   // (0.195 rad: 13.9 x the linearised width without the split)

  // Probes per held position: the vertices maximising and minimising the linearised output, the
  // same with the least effective parameter flipped and with the most effective one nominal;
  // then random vectors of the box (a grid of 1/1000 of each range).
  std::vector<std::vector<Rational>> probes;
  for (const VariationSample& sample : r.samples) {
    if (!sample.contact) continue;
    std::size_t least = r.parameters.size(), most = r.parameters.size();
    double least_effect = std::numeric_limits<double>::infinity(), most_effect = -1;
    for (std::size_t p = 0; p < r.parameters.size() && p < sample.sensitivities.size(); ++p) {
      const Parameter& q = r.parameters[p];
      if (q.range.lo == q.range.hi) continue;
      double effect = std::fabs(sample.sensitivities[p]) * Rational(q.range.hi - q.range.lo).get_d();
      if (effect > 0 && effect < least_effect) least_effect = effect, least = p;
      if (effect > most_effect) most_effect = effect, most = p;
    }
    ASSERT_LT(most, r.parameters.size());
    for (int way : {1, -1}) {
      std::vector<Rational> d(r.parameters.size(), Rational(0));
      for (std::size_t p = 0; p < d.size() && p < sample.sensitivities.size(); ++p) {
        const Parameter& q = r.parameters[p];
        if (q.range.lo == q.range.hi) continue;
        bool up = (sample.sensitivities[p] >= 0) == (way > 0);
        d[p] = (up ? q.range.hi : q.range.lo) - q.nominal;
      }
      probes.push_back(d);
      if (least < d.size()) {
        std::vector<Rational> flipped = d;
        const Parameter& q = r.parameters[least];
        flipped[least] = (d[least] == q.range.hi - q.nominal ? q.range.lo : q.range.hi) - q.nominal;
        probes.push_back(flipped);
      }
      std::vector<Rational> centred = d;
      centred[most] = Rational(0);
      probes.push_back(centred);
    }
  }
  std::mt19937 rng(45);
  for (int k = 0; k < 16; ++k) probes.push_back(test_gears::random_deviations(r.parameters, rng));
  std::set<std::vector<Rational>> distinct(probes.begin(), probes.end());

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  // per held position: the least gap of an exact value to the band's upper and lower edges,
  // as fractions of the band's width
  std::vector<double> upper_gap(r.samples.size(), 1), lower_gap(r.samples.size(), 1);
  for (const std::vector<Rational>& d : distinct) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = 120;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult e = analyze_kinematics(model->exact_model(d), k);
    std::size_t output = static_cast<std::size_t>(std::find(e.followers.begin(), e.followers.end(), "gear-I") - e.followers.begin());
    ASSERT_LT(output, e.followers.size());
    for (std::size_t i = 0; i < r.samples.size(); ++i) {
      const VariationSample& sample = r.samples[i];
      if (!bounded(sample)) continue;
      auto at = std::find_if(e.samples.begin(), e.samples.end(), [&](const KinematicSample& s) { return s.driver == sample.driver; });
      ASSERT_NE(at, e.samples.end()) << "driver " << sample.driver;
      double out = at->positions.at(output);
      ASSERT_TRUE(std::isfinite(out));
      ++checked;
      // (the exact engine's position is the exact root rounded to a double: within an ulp)
      double ulp = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(out));
      EXPECT_GE(out, sample.certified.lower - ulp) << "driver " << sample.driver;
      EXPECT_LE(out, sample.certified.upper + ulp) << "driver " << sample.driver;
      double width = sample.certified.upper - sample.certified.lower;
      upper_gap[i] = std::min(upper_gap[i], (sample.certified.upper - out) / width);
      lower_gap[i] = std::min(lower_gap[i], (out - sample.certified.lower) / width);
    }
  }
  EXPECT_EQ(checked, distinct.size() * held);
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const VariationSample& a = r.samples[i];
    if (!a.contact) continue;
    const VariationSample& b = off.samples[i];
    std::printf("driver %.4f: band [%.4f, %.4f] (without the split [%.4f, %.4f], linearised [%.4f, %.4f]); exact values "
                "within %.4f / %.4f of the band's width of its upper / lower edge\n",
                a.driver, a.certified.lower, a.certified.upper, b.certified.lower, b.certified.upper, a.linear_lower,
                a.linear_upper, upper_gap[i], lower_gap[i]);
  }
  std::printf("%zu exact trains (%zu probes), %zu values checked\n", distinct.size(), probes.size(), checked);
}

}  // namespace
}  // namespace hipair
