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
#include "tolerance_band_check.hpp"
#include "test_paths.hpp"

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

// Session 48's narrowings (tol48: the hand-over walk's Taylor-model slopes, the widened whole
// box's split) off in both runs, so that the comparison isolates the case split (with them the run
// without the split is narrower already: 0.195 rad's best ratio 0.435 instead of < 0.25).
ToleranceResult run(const std::string& text, const ToleranceOptions& options, int on) {
  test_band::ScopedSwitch split(tolerance_detail::chain_case_split(), on);
  test_band::ScopedSwitch taylor(tolerance_detail::handover_taylor_partials(), 0);
  test_band::ScopedSwitch widened(tolerance_detail::chain_widened_split(), 0);
  return analyze_tolerances_text(text, options);
}

// The analysis of `text` over `range` at `steps` per turn with the split off and on: every band
// with it no wider than the one without (`nested`: inside it), the narrower ones counted (the
// narrowest ratio returned). (Not nested in general: the split narrows a sub-box's enclosure, so
// the shared-parameter bisection may accept a sub-box it would have split without the split, and
// the hull of the coarser partition can reach further on one side — gear-train-3 at 0.169 rad:
// lower end 0.131958 with the split against 0.131979 without, the band 0.0312 against 0.0322 wide.
// Both are enclosures: any partition of the box is sound.) Then
// probes per held position — the vertices maximising and minimising the linearised output, the
// same with the least effective parameter flipped and with the most effective one nominal — and
// `random_vectors` random vectors of the box (a grid of 1/1000 of each range): the exact train
// (the model rebuilt exactly, the kernel-sliced exact engine over the same range and grid) inside
// every band with the split, within 4 ulps. Returns the values checked.
struct SplitCheck {
  std::size_t held = 0, narrowed = 0, checked = 0, trains = 0;
  double best = 1;
};
SplitCheck check_split(const std::string& text, const std::pair<Rational, Rational>& range, std::size_t steps,
                       const std::string& output_part, int random_vectors, unsigned seed, bool nested) {
  SplitCheck out;
  ToleranceOptions options = test_gears::chain_options(range.second, 0, 45);
  options.range = range;
  options.positions = steps;
  ToleranceResult off = run(text, options, 0);
  ToleranceResult r = run(text, options, 1);
  EXPECT_EQ(r.samples.size(), off.samples.size());
  if (r.samples.size() != off.samples.size()) return out;

  // The split only meets the composition's band with the cases' hull: never wider, and
  // narrower where a middle mesh widened.
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const VariationSample& a = r.samples[i];
    const VariationSample& b = off.samples[i];
    EXPECT_EQ(a.contact, b.contact);
    if (!a.contact || !b.contact) continue;
    ++out.held;
    EXPECT_TRUE(bounded(b)) << "driver " << b.driver;
    EXPECT_TRUE(bounded(a)) << "driver " << a.driver;
    if (!bounded(a) || !bounded(b)) continue;
    if (nested) {
      EXPECT_GE(a.certified.lower, b.certified.lower) << "driver " << a.driver;
      EXPECT_LE(a.certified.upper, b.certified.upper) << "driver " << a.driver;
    }
    double ratio = (a.certified.upper - a.certified.lower) / (b.certified.upper - b.certified.lower);
    EXPECT_LE(ratio, 1.0) << "driver " << a.driver;
    if (ratio < 1) ++out.narrowed;
    out.best = std::min(out.best, ratio);
  }

  std::vector<std::vector<Rational>> probes;
  for (const VariationSample& sample : r.samples) {
    if (!sample.contact) continue;
    const test_gears::Effects e = test_gears::effects(sample, r.parameters);
    EXPECT_LT(e.most, r.parameters.size());
    if (e.most >= r.parameters.size()) continue;
    for (auto& probe : test_gears::corner_probes(sample, r.parameters, e)) probes.push_back(std::move(probe.second));
  }
  std::mt19937 rng(seed);
  for (int k = 0; k < random_vectors; ++k) probes.push_back(test_gears::random_deviations(r.parameters, rng));
  std::set<std::vector<Rational>> distinct(probes.begin(), probes.end());
  out.trains = distinct.size();

  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  // per held position: the least gap of an exact value to the band's upper and lower edges,
  // as fractions of the band's width
  std::vector<double> upper_gap(r.samples.size(), 1), lower_gap(r.samples.size(), 1);
  for (const std::vector<Rational>& d : distinct) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = steps;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    KinematicsResult e = analyze_kinematics(model->exact_model(d), k);
    test_band::visit_exact_values(e, output_part, r.samples, [&](std::size_t i, double value, double ulp) {
      const VariationSample& sample = r.samples[i];
      ++out.checked;
      EXPECT_GE(value, sample.certified.lower - ulp) << "driver " << sample.driver;
      EXPECT_LE(value, sample.certified.upper + ulp) << "driver " << sample.driver;
      double width = sample.certified.upper - sample.certified.lower;
      upper_gap[i] = std::min(upper_gap[i], (sample.certified.upper - value) / width);
      lower_gap[i] = std::min(lower_gap[i], (value - sample.certified.lower) / width);
    });
  }
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const VariationSample& a = r.samples[i];
    if (!a.contact) continue;
    const VariationSample& b = off.samples[i];
    std::printf("driver %.4f: band [%.5f, %.5f] (without the split [%.5f, %.5f], linearised [%.5f, %.5f]); exact values "
                "within %.4f / %.4f of the band's width of its upper / lower edge\n",
                a.driver, a.certified.lower, a.certified.upper, b.certified.lower, b.certified.upper, a.linear_lower,
                a.linear_upper, upper_gap[i], lower_gap[i]);
  }
  std::printf("%zu exact trains (%zu probes), %zu values checked\n", distinct.size(), probes.size(), out.checked);
  return out;
}

TEST(ChainCaseSplit, WidenedMeshBandNarrowsAndHoldsTheExactTrain) {
  SplitCheck c = check_split(test_gears::gear_train(9), std::make_pair(Rational(3, 20), Rational(6, 25)), 120, "gear-I",
                             16, 45, true);
  EXPECT_EQ(c.held, 3u);
  EXPECT_GE(c.narrowed, 1u);
  EXPECT_LT(c.best, 0.25);   // (0.195 rad: 13.9 x the linearised width without the split)
  EXPECT_EQ(c.checked, c.trains * c.held);
}

// Session 46 (tol46): the first mesh of gear-train-3 (test_gears::gear_train(3)) at its hand-over
// near 0.169 rad (2000 positions per turn): A:B widens (the next tooth pair may take over inside
// the box), and its envelope's far end carries the output beyond the holder case — there the
// band's upper end is the far-end case's (chart units 0.0831 against the holder case's 0.0813 at
// the whole box). The exact train at the probes must lie inside every band.
TEST(ChainCaseSplit, FirstMeshHandOverFarEndHoldsTheExactTrain) {
  SplitCheck c = check_split(test_gears::gear_train(3), std::make_pair(Rational(4, 25), Rational(7, 40)), 2000, "gear-C",
                             24, 46, false);
  EXPECT_EQ(c.held, 6u);
  EXPECT_GE(c.narrowed, 1u);
  EXPECT_EQ(c.checked, c.trains * c.held);
}

// Session 67 (chain67): the case split's two cases resume from the state the composition recorded
// at the widened pair (chain.cpp compose_once, Prefix; tolerance_detail::chain_case_resume())
// instead of computing the pairs up to it again, and a chain's certified band is replayed by a
// later analysis of the same run from ChainBandMemo. On gear-train-3 across its first mesh's
// hand-over (0.166..0.173 rad at 2000 per turn, where A:B widens: FirstMeshHandOverFarEnd...
// above), with and without the resume: every band bit for bit, the notes and every pair's
// sub-box count equal, cases resumed only with it. The same analysis again with the memo the
// resumed run filled: every held position replayed and the same result; with another switch (the
// widened whole box's split off) nothing replayed. Mutants (temporary, built, run, removed): listed in
// docs/performance.md "Session 67 (chain67)".
std::size_t expect_same_bands(const ToleranceResult& a, const ToleranceResult& b) {
  std::size_t held = 0;
  EXPECT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < std::min(a.samples.size(), b.samples.size()); ++i) {
    const VariationSample &x = a.samples[i], &y = b.samples[i];
    EXPECT_EQ(x.contact, y.contact);
    held += y.contact;
    EXPECT_EQ(x.certified.lower, y.certified.lower) << x.driver;
    EXPECT_EQ(x.certified.upper, y.certified.upper) << x.driver;
  }
  test_band::expect_same_notes_and_boxes(a, b);
  return held;
}

TEST(ChainCaseResume, CasesResumedAndBandsReplayedGiveTheSameBandsNotesAndCounts) {
  const std::string text = test_gears::gear_train(3);
  ToleranceOptions options = test_gears::chain_options(Rational(7, 40), 0, 67);
  options.range = std::make_pair(Rational(83, 500), Rational(173, 1000));
  options.positions = 2000;
  // the run with the resume keeps its bands in the memo
  auto memo = std::make_shared<tolerance_detail::ChainBandMemo>();
  tolerance_detail::ChainPaths paths;
  paths.band_memo = memo;
  ToleranceResult r[2];
  std::size_t resumed[2];
  for (int on : {0, 1}) {
    test_band::ScopedSwitch resume(tolerance_detail::chain_case_resume(), on);
    const std::size_t before = tolerance_detail::chain_cases_resumed().load();
    r[on] = on ? tolerance_detail::analyze_chain(text, options, paths) : tolerance_detail::analyze_chain(text, options);
    resumed[on] = tolerance_detail::chain_cases_resumed().load() - before;
  }
  const std::size_t held = expect_same_bands(r[0], r[1]);
  EXPECT_EQ(held, 4u);
  EXPECT_EQ(resumed[0], 0u);
  EXPECT_GT(resumed[1], 0u);   // not vacuous: the case split ran, its cases resumed

  EXPECT_EQ(memo->replayed, 0u);
  ToleranceResult again = tolerance_detail::analyze_chain(text, options, paths);
  EXPECT_EQ(memo->replayed, held);
  expect_same_bands(r[1], again);
  {
    // another run (a switch of the band changed): the memo cleared, nothing replayed
    test_band::ScopedSwitch widened(tolerance_detail::chain_widened_split(), 0);
    tolerance_detail::analyze_chain(text, options, paths);
    EXPECT_EQ(memo->replayed, held);
  }
  std::printf("%zu held positions, %zu cases resumed, %zu sub-boxes\n", held, resumed[1], r[1].certified_boxes);
}

}  // namespace
}  // namespace hipair
