// Session 48 (tol48): a whole box composed only through a widened hand-over envelope is split as
// a failed one would be, and the band is the meet of the whole box's and the halves' (issue 12;
// docs/tolerance.md "Assembly chains", "A widened whole box split").
//
// On the 8-mesh train (test_gears::gear_train(9), gear-train.json's model) over 1.440..1.466 rad
// (two positions; the 1.309..1.745 rad range of session 48 took 69 s of CPU), the whole box
// composes at 1.466 rad only through a hand-over envelope far beyond the linearised width. With the split (chain_widened_split() = 1) every band
// must lie inside the one without (the same whole-box composition, met), at least one strictly,
// and the exact train (the model rebuilt exactly, the kernel-sliced exact engine over the same
// range and grid) at the vertices of the box the linearisation moves furthest at each narrowed
// position (and near them) and at random vectors must lie inside every band. Mutants run:
// docs/performance.md "Session 48 (tol48)".
#include "gear_train_models.hpp"
#include "tolerance_band_check.hpp"
#include "tolerance_chain_oracle.hpp"

#include "model/parametric/parametric.hpp"
#include "tolerance/stage.hpp"

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

TEST(ChainWidenedSplit, WidenedWholeBoxBandsMetWithTheHalvesHoldTheExactTrain) {
  const std::string text = test_gears::gear_train(9);
  const std::pair<Rational, Rational> range(Rational(1439896633, 1000000000), Rational(1466076572, 1000000000));
  ToleranceOptions options = test_gears::chain_options(range.second, 0, 48);
  options.range = range;
  ToleranceResult split, whole;
  {
    test_band::ScopedSwitch on(tolerance_detail::chain_widened_split(), 1);
    split = analyze_tolerances_text(text, options);
  }
  {
    test_band::ScopedSwitch off(tolerance_detail::chain_widened_split(), 0);
    whole = analyze_tolerances_text(text, options);
  }
  ASSERT_EQ(split.samples.size(), 2u);
  ASSERT_EQ(whole.samples.size(), split.samples.size());
  std::vector<std::size_t> narrowed;
  std::size_t held = 0;
  for (std::size_t i = 0; i < split.samples.size(); ++i) {
    const VariationSample &a = split.samples[i], &b = whole.samples[i];
    ASSERT_EQ(a.contact, b.contact);
    if (!a.contact) continue;
    ++held;
    EXPECT_TRUE(bounded(a)) << "driver " << a.driver;
    EXPECT_TRUE(bounded(b)) << "driver " << b.driver;
    if (!bounded(a) || !bounded(b)) continue;
    // the meet lies inside the whole box's band
    EXPECT_GE(a.certified.lower, b.certified.lower) << "driver " << a.driver;
    EXPECT_LE(a.certified.upper, b.certified.upper) << "driver " << a.driver;
    if (a.certified.lower > b.certified.lower || a.certified.upper < b.certified.upper) narrowed.push_back(i);
  }
  EXPECT_EQ(held, 2u);
  EXPECT_GE(narrowed.size(), 1u) << "no band narrowed by the split";   // none without it

  // probes: at each narrowed position the vertices maximising and minimising its linearised
  // output, the same with the least effective parameter flipped and with the most effective one
  // nominal; and random vectors of the box
  std::vector<std::vector<Rational>> probes;
  for (std::size_t i : narrowed) {
    const VariationSample& s = split.samples[i];
    const test_gears::Effects e = test_gears::effects(s, split.parameters);
    ASSERT_LT(e.most, split.parameters.size());
    for (auto& probe : test_gears::corner_probes(s, split.parameters, e)) probes.push_back(std::move(probe.second));
  }
  std::mt19937 rng(48);
  for (int k = 0; k < 3; ++k) probes.push_back(test_gears::random_deviations(split.parameters, rng));
  std::set<std::vector<Rational>> distinct(probes.begin(), probes.end());

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::size_t checked = 0;
  for (const std::vector<Rational>& d : distinct) {
    const std::vector<test_chain::TrainSample> exact =
        test_chain::chain_path(model->exact_model(d), "gear-A", range, "gear-I", options.positions);
    for (const VariationSample& sample : split.samples) {
      if (!bounded(sample)) continue;
      auto at = std::find_if(exact.begin(), exact.end(), [&](const test_chain::TrainSample& s) { return s.driver == sample.driver; });
      EXPECT_NE(at, exact.end()) << "driver " << sample.driver;
      if (at == exact.end()) continue;
      EXPECT_TRUE(std::isfinite(at->output));
      ++checked;
      // (the exact engine's position is the exact root rounded to a double: within an ulp)
      double ulp = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(at->output));
      EXPECT_GE(at->output, sample.certified.lower - ulp) << "driver " << sample.driver;
      EXPECT_LE(at->output, sample.certified.upper + ulp) << "driver " << sample.driver;
    }
  }
  EXPECT_EQ(checked, distinct.size() * held);
  for (std::size_t i : narrowed)
    std::printf("driver %.4f: band [%.5f, %.5f] (whole box [%.5f, %.5f], linearised [%.5f, %.5f])\n", split.samples[i].driver,
                split.samples[i].certified.lower, split.samples[i].certified.upper, whole.samples[i].certified.lower,
                whole.samples[i].certified.upper, split.samples[i].linear_lower, split.samples[i].linear_upper);
  std::printf("%zu exact trains, %zu values checked\n", distinct.size(), checked);
}

}  // namespace
}  // namespace hipair
