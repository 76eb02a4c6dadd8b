// Session 43 (tol43): the chain's certified band against the exact train where the band's edge
// is nearest (issue 12; docs/tolerance.md "Assembly chains", step 4).
//
// The gear train's band over the full 100-parameter box is 1.5-4 x its linearised width, so an
// exact train at the box's extreme corners stays far inside it, and an unsound composition (a
// term of the mean-value form dropped, a remainder dropped, half the box composed: session 42
// found that ChainFailureSplit passes with the last) goes unseen. Here the same 8-mesh train
// (examples/models/gear-train.json's model, test_gears::gear_train(9)) has every tolerance
// divided by `shrink`: the composition's excess over the linearisation is second order in the
// box's widths, so the band tightens onto the linearised width, and the exact train at the
// vertices of the box that maximise and minimise the linearised output (each deviation at the
// end its sensitivity's sign points to) comes within a small fraction of the band's width of
// its edges. Every such value must lie inside the band; the nearest approach, measured against
// the band's width, is the test's power: a composition that drops more than that fraction of
// the width on a side is caught. Mutants run (docs/performance.md "Session 43 (tol43)"): the
// band over half the box (split along the parameter of largest share) fails 4 assertions; the
// chain rule without the driver's term (D_k = G_k) fails at least 11; the mean-value form
// without its largest term (the module's) narrows the band 1.100 -> 1.052 x the linearised
// width and passes (nearest approach 0.024), as does a Taylor-model product without its
// second-order remainder (the band unchanged at this box: the models' remainders are
// negligible there).
// Near-extreme vectors too: the extreme vertex with the parameter of least linearised effect
// flipped, and with the parameter of largest effect at its nominal value.
#include "gear_train_models.hpp"
#include "test_paths.hpp"

#include "model/parametric/parametric.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/rational.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace hipair {
namespace {

// `text` with every "tolerance": x divided by `shrink` (x a decimal number).
std::string shrink_tolerances(const std::string& text, int shrink) {
  static const std::regex tolerance("\"tolerance\": ([0-9.]+)");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), tolerance);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    out += text.substr(last, static_cast<std::size_t>(m.position(0)) - last);
    // an exact decimal: x / shrink with shrink a power of 10 times 1, 2 or 5 keeps it decimal
    Rational x = parse_rational(m[1].str()) / Rational(shrink);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.12g", x.get_d());
    EXPECT_EQ(parse_rational(buffer), x) << m[1].str();
    out += "\"tolerance\": " + std::string(buffer);
    last = static_cast<std::size_t>(m.position(0) + m.length(0));
  }
  out += text.substr(last);
  return out;
}

TEST(ChainBandEdge, ShrunkGearTrainBandHoldsTheExactTrainAtTheVerticesNearestItsEdges) {
  constexpr int shrink = 20;
  const std::string text = shrink_tolerances(test_gears::gear_train(9), shrink);
  const std::pair<Rational, Rational> range(Rational(0), Rational(3, 20));
  ToleranceOptions options = test_gears::chain_options(range.second, 0, 43);
  ToleranceResult r = analyze_tolerances_text(text, options);
  ASSERT_EQ(r.chain.size(), 8u);
  std::size_t held = 0, bounded = 0;
  for (const VariationSample& sample : r.samples) {
    if (!sample.contact) continue;
    ++held;
    if (std::isfinite(sample.certified.upper - sample.certified.lower)) ++bounded;
  }
  EXPECT_EQ(held, 2u);   // (the positions where the output gear is held)
  EXPECT_EQ(bounded, held);

  // Per bounded position: the vertices the linearisation moves furthest up and down, then the
  // same with the least effective parameter flipped and with the most effective one nominal.
  struct Probe {
    std::size_t position;   // index into r.samples
    int way;                // +1: towards the upper edge, -1: the lower
    std::vector<Rational> d;
  };
  std::vector<Probe> probes;
  std::set<std::vector<Rational>> distinct;
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const VariationSample& sample = r.samples[i];
    if (!sample.contact || !std::isfinite(sample.certified.upper - sample.certified.lower)) continue;
    const test_gears::Effects e = test_gears::effects(sample, r.parameters);
    ASSERT_LT(e.most, r.parameters.size());
    for (auto& [way, d] : test_gears::corner_probes(sample, r.parameters, e)) probes.push_back({i, way, std::move(d)});
  }
  for (const Probe& probe : probes) distinct.insert(probe.d);

  // The exact train at each distinct vector: the model rebuilt exactly, the kernel-sliced exact
  // engine over the same range and grid (the same start, so the same assembly).
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  std::vector<std::vector<Rational>> vectors(distinct.begin(), distinct.end());
  std::vector<KinematicsResult> exact;
  for (const std::vector<Rational>& d : vectors) {
    KinematicsOptions k;
    k.driver = "gear-A";
    k.range = range;
    k.steps_per_cycle = 120;
    k.reversal = false;
    k.method = SliceMethod::kernels;
    exact.push_back(analyze_kinematics(model->exact_model(d), k));
  }
  auto output_at = [&](const std::vector<Rational>& d, double driver) {
    std::size_t v = static_cast<std::size_t>(std::find(vectors.begin(), vectors.end(), d) - vectors.begin());
    const KinematicsResult& e = exact.at(v);
    std::size_t output = static_cast<std::size_t>(std::find(e.followers.begin(), e.followers.end(), "gear-I") - e.followers.begin());
    EXPECT_LT(output, e.followers.size());
    auto at = std::find_if(e.samples.begin(), e.samples.end(), [&](const KinematicSample& s) { return s.driver == driver; });
    EXPECT_NE(at, e.samples.end()) << "driver " << driver;
    return at == e.samples.end() || output >= e.followers.size() ? std::numeric_limits<double>::quiet_NaN()
                                                                 : at->positions.at(output);
  };
  // The nearest approach of an extreme vertex to the edge it points at, as a fraction of the
  // band's width (per position and side), and the band's width over the linearised one.
  double nearest = std::numeric_limits<double>::infinity(), widest = 0;
  std::size_t checked = 0;
  for (const Probe& probe : probes) {
    const VariationSample& sample = r.samples[probe.position];
    double out = output_at(probe.d, sample.driver);
    ASSERT_TRUE(std::isfinite(out));
    ++checked;
    // (the exact engine's position is the exact root rounded to a double: within an ulp)
    double ulp = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(out));
    EXPECT_GE(out, sample.certified.lower - ulp) << "driver " << sample.driver << " way " << probe.way;
    EXPECT_LE(out, sample.certified.upper + ulp) << "driver " << sample.driver << " way " << probe.way;
    double width = sample.certified.upper - sample.certified.lower;
    double gap = probe.way > 0 ? sample.certified.upper - out : out - sample.certified.lower;
    nearest = std::min(nearest, gap / width);
    widest = std::max(widest, width / (sample.linear_upper - sample.linear_lower));
  }
  EXPECT_EQ(checked, probes.size());
  // The test's power: the extreme vertices come within this fraction of the band's width of its
  // edges, so a band losing more than it on a side fails above (measured 0.0428 on 0bdc449).
  EXPECT_LT(nearest, 0.1);
  std::printf("gear-train(9), tolerances / %d, over 0..0.15 rad: %zu of %zu held positions bounded, %zu probes (%zu "
              "vectors) inside; nearest approach %.4f of the band's width; band <= %.4f x the linearised width\n",
              shrink, bounded, held, checked, vectors.size(), nearest, widest);
}

}  // namespace
}  // namespace hipair
