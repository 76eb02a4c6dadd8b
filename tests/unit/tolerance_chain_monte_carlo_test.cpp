// The assembly chain's Monte Carlo follows tooth hand-overs (src/tolerance/chain.cpp,
// monte_carlo and actual_root; docs/tolerance.md "Monte Carlo"): at each sampled parameter
// vector and driver position the output's value is the one the actual contact gives (the first
// contact each follower meets), not its nominal holder's root, and it is certified. Oracle: the
// exact kinematic engine on the exact model rebuilt at the vector (its deviations are doubles:
// exact rationals), the train followed from the range's start as the analysis does
// (tolerance_chain_oracle.hpp), independent of the Monte Carlo's code; on one-mesh trains also
// each value's configuration by the exact overlap predicate (a contact: overlapping just beyond
// its enclosure on exactly one side). Mutation (session 28): the nominal holder only fails the
// overlap check at 49 values of ExactTrainAtAHandOver ("overlapping on both sides").
//
// Vectors: the box corners that the linearisation moves furthest down and up at every position
// next to a change of the nominal holder (a hand-over; the neighbour's sensitivities, as the
// hand-over tests' witnesses), the same at the position's own sensitivities, and the Monte
// Carlo's own draws (draw(seed, index)). Named mutation: the Monte Carlo following each pair's
// nominal holder only (as before session 26) fails ExactTrainAtAHandOver (at driver 0.181 rad
// a corner's exact train is -0.14756 rad, the holder's root above -0.14631).
#include "gear_train_models.hpp"
#include "kinematics_test_support.hpp"
#include "gear_train_tolerances.hpp"
#include "tolerance_chain_oracle.hpp"

#include "curves/pose.hpp"
#include "model/parametric/parametric.hpp"
#include "oracle/overlap.hpp"
#include "tolerance/sampling.hpp"
#include "tolerance/stage.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using tolerance_detail::ChainPaths;
using tolerance_detail::Distribution;

// The deviations (doubles in the box: each distribution's sample range) that the linearisation
// with sensitivities `s` moves furthest down (`down`) or up.
std::vector<double> corner(const std::vector<Distribution>& d, const std::vector<double>& s, bool down) {
  std::vector<double> v(d.size(), 0.0);
  for (std::size_t i = 0; i < v.size() && i < s.size(); ++i)
    if (s[i] != 0 && d[i].sample_lo < d[i].sample_hi) v[i] = (s[i] > 0) == down ? d[i].sample_lo : d[i].sample_hi;
  return v;
}

struct Case {
  std::string name, text;
  std::pair<Rational, Rational> range;
  unsigned positions = 360;
  std::size_t draws = 4;   // Monte Carlo draws besides the corners
  std::size_t max_corners = 64;   // corners kept (evenly over the hand-over positions' corners)
  // also the box corners of the first `first_corners` held positions' own sensitivities (the
  // train's start)
  std::size_t first_corners = 0;
};

struct Outcome {
  std::size_t checked = 0, handed_over = 0;
  // one-mesh trains: values whose claimed configuration the exact overlap predicate confirmed
  // as a contact (overlapping just on one side of the enclosure, not on the other)
  std::size_t contacts = 0;
  // values where the exact train is held by a feature pair that holds no follower anywhere along
  // the analysed nominal path (outside the Monte Carlo's candidates: not compared, counted)
  std::size_t off_path = 0;
  // values where some follower is untouched in the exact train (an unloaded follower waiting
  // where it started: the Monte Carlo's value is then where it waits, not the contact's root)
  std::size_t waiting = 0;
  double widest = 0;   // widest certified enclosure of a value (output units)
};

std::size_t index_of(const Model& m, const std::string& name) {
  for (std::size_t k = 0; k < m.parts.size(); ++k)
    if (m.parts[k].name == name) return k;
  ADD_FAILURE() << "no part " << name;
  return 0;
}

// The exact overlap predicate on the two parts of model `m`, `a` rotated to `ta` and `b` to
// `tb` (rad; each angle's half-angle tangent taken as the double's exact rational, the chart
// about pi beyond a quarter turn).
cspace::Overlap posed_relation(const Model& m, std::size_t a, double ta, std::size_t b, double tb) {
  auto map = [&](std::size_t k, double theta) {
    const double th = std::remainder(theta, 2 * std::numbers::pi);
    cspace::ChartAxis axis;
    axis.kind = cspace::ChartAxis::Kind::rotation;
    axis.half_turn = std::fabs(th) > std::numbers::pi / 2;
    const double t = std::tan((axis.half_turn ? std::remainder(th - std::numbers::pi, 2 * std::numbers::pi) : th) / 2);
    return cspace::world_map(m.parts[k], true, axis, Rational(t));
  };
  return cspace::analyse_overlap(m.parts[a], map(a, ta), m.parts[b], map(b, tb)).relation;
}

// The case's chain analysed with the corners and draws as its Monte Carlo vectors; every value
// checked against the exact train at its vector, and on a one-mesh train (the output's driver
// is the chain's driver, at the sample's position) every value's configuration by the exact
// overlap predicate: a follower held by a contact overlaps the driver just beyond the
// enclosure on one side (10^-9 rad) and not on the other, whatever the kinematic engine does.
Outcome check_case(const Case& c) {
  SCOPED_TRACE(c.name);
  ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = c.range;
  options.positions = c.positions;
  options.threads = 2;
  options.seed = 26;
  // (the corners need the sensitivities only: the band under the nominal holders is cheaper)
  ToleranceOptions nominal_holders = options;
  nominal_holders.chain_assume_nominal_holder = true;
  ToleranceResult plain = tolerance_detail::analyze_chain(c.text, nominal_holders);
  model_detail::ParametricModel model = model_detail::ParametricModel::read(c.text);
  std::vector<Distribution> dist = tolerance_detail::distributions(model.nominal());
  std::vector<std::vector<double>> vectors;
  for (std::size_t k = 0; k < plain.samples.size(); ++k) {
    const VariationSample& s = plain.samples[k];
    if (!s.contact) continue;
    for (std::size_t j : {k == 0 ? k : k - 1, k + 1 < plain.samples.size() ? k + 1 : k}) {
      if (j == k || !plain.samples[j].contact || plain.samples[j].region == s.region) continue;
      for (bool down : {true, false}) {
        vectors.push_back(corner(dist, plain.samples[j].sensitivities, down));
        vectors.push_back(corner(dist, s.sensitivities, down));
      }
    }
  }
  if (vectors.size() > c.max_corners) {
    std::vector<std::vector<double>> kept;
    for (std::size_t k = 0; k < c.max_corners; ++k) kept.push_back(vectors[k * vectors.size() / c.max_corners]);
    vectors.swap(kept);
  }
  for (std::size_t k = 0, held = 0; k < plain.samples.size() && held < c.first_corners; ++k) {
    if (!plain.samples[k].contact) continue;
    ++held;
    for (bool down : {true, false}) vectors.push_back(corner(dist, plain.samples[k].sensitivities, down));
  }
  const std::size_t corners = vectors.size();
  for (std::size_t r = 0; r < c.draws; ++r) vectors.push_back(tolerance_detail::draw(dist, options.seed, corners + r));
  ChainPaths paths;
  paths.monte_carlo_vector = [&](std::size_t index) { return vectors.at(index); };
  std::mutex mutex;
  std::map<std::pair<std::size_t, std::size_t>, kernels::Interval> values;
  paths.monte_carlo_value = [&](std::size_t index, std::size_t k, const kernels::Interval& x) {
    std::lock_guard<std::mutex> lock(mutex);
    values[{index, k}] = x;
  };
  options.monte_carlo = vectors.size();
  ToleranceResult result = tolerance_detail::analyze_chain(c.text, options, paths);
  Outcome out;
  std::size_t held = 0;
  for (const VariationSample& s : result.samples) held += s.contact;
  EXPECT_EQ(values.size(), vectors.size() * held) << "every held position evaluated at every vector";
  EXPECT_EQ(result.monte_carlo->evaluations, vectors.size() * held);
  EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  for (const std::string& note : result.notes) {
    std::smatch m;
    if (std::regex_search(note, m, std::regex("held a follower ([0-9]+) time"))) out.handed_over = std::stoul(m[1]);
  }
  // the feature pairs holding the followers anywhere along the nominal path
  std::set<std::string> holders;
  for (const test_chain::TrainSample& t :
       test_chain::chain_path(model.nominal(), "gear-A", c.range, result.follower, c.positions))
    holders.insert(t.touching.begin(), t.touching.end());
  for (std::size_t v = 0; v < vectors.size(); ++v) {
    std::vector<Rational> d;
    for (double x : vectors[v]) d.emplace_back(x);
    const Model exact = model.exact_model(d);
    auto path = test_chain::chain_path(exact, "gear-A", c.range, result.follower, c.positions);
    for (std::size_t k = 0; k < result.samples.size(); ++k) {
      auto it = values.find({v, k});
      if (it == values.end()) continue;
      const double driver = result.samples[k].driver;
      auto at = std::find_if(path.begin(), path.end(), [&](const auto& p) { return p.driver == driver; });
      if (at == path.end()) {
        ADD_FAILURE() << "driver " << driver << " is not a sample of the exact train";
        continue;
      }
      if (!std::includes(holders.begin(), holders.end(), at->touching.begin(), at->touching.end())) {
        ++out.off_path;
        continue;
      }
      if (at->touching.size() < result.chain.size()) ++out.waiting;
      ++out.checked;
      out.widest = std::max(out.widest, it->second.width());
      // (the oracle's position is a double of the exact engine's: 1e-10 covers its rounding)
      EXPECT_GE(at->output, it->second.lo - 1e-10) << "vector " << v << (v < corners ? " (corner)" : " (draw)")
                                                     << ", driver " << driver << ": [" << it->second.lo << ", "
                                                     << it->second.hi << "]";
      EXPECT_LE(at->output, it->second.hi + 1e-10) << "vector " << v << (v < corners ? " (corner)" : " (draw)")
                                                     << ", driver " << driver << ": [" << it->second.lo << ", "
                                                     << it->second.hi << "]";
      if (result.chain.size() == 1 && at->touching.size() == result.chain.size()) {
        const std::size_t a = index_of(exact, "gear-A"), b = index_of(exact, result.follower);
        const bool below = posed_relation(exact, a, driver, b, it->second.lo - 1e-9) == cspace::Overlap::overlapping;
        const bool above = posed_relation(exact, a, driver, b, it->second.hi + 1e-9) == cspace::Overlap::overlapping;
        EXPECT_NE(below, above) << "vector " << v << ", driver " << driver << ": the claimed value [" << it->second.lo
                                << ", " << it->second.hi << "] is no contact (overlapping " << (below ? "on both sides"
                                                                                                      : "on neither side")
                                << ")";
        out.contacts += below != above;
      }
    }
  }
  std::printf("[ monte carlo ] %s: %zu vectors (%zu corners), %zu values = exact train, %zu hand-over(s) followed, "
              "widest enclosure %.3g; %zu value(s) held off the nominal path's holders (not compared), %zu with a follower "
              "untouched; %zu configuration(s) a contact by the exact overlap predicate\n",
              c.name.c_str(), vectors.size(), corners, out.checked, out.handed_over, out.widest, out.off_path,
              out.waiting, out.contacts);
  return out;
}

TEST(ToleranceChainMonteCarlo, ExactTrainAtAHandOver) {
  Case c{"gear pair, flank toleranced wide, 0.16..0.19 rad",
         test_gears::handover_model(test_gears::gear_train(2)),
         {Rational(16, 100), Rational(19, 100)},
         2000,
         6};
  Outcome o = check_case(c);
  EXPECT_GE(o.checked, 50u);
  EXPECT_EQ(o.off_path, 0u) << "the hand-over lies inside the range: every holder is on the nominal path";
  EXPECT_GE(o.handed_over, 1u) << "the vectors reach the hand-over";
  EXPECT_EQ(o.contacts, o.checked) << "every value's configuration checked by the exact overlap predicate";
}

// Generated trains over more than a tooth period (hand-overs in each).
TEST(ToleranceChainMonteCarlo, ExactTrainOnGeneratedTrains) {
  std::vector<Case> cases{
      {"2 gears 10/12", test_gears::gear_train(2, 10, 12), {Rational(0), Rational(7, 10)}, 90, 3},
      {"3 gears 9/11, tolerances x2", test_gears::scaled(test_gears::gear_train(3, 9, 11), 2.0),
       {Rational(1, 10), Rational(8, 10)}, 90, 3},
  };
  std::size_t checked = 0, handed_over = 0;
  for (const Case& c : cases) {
    Outcome o = check_case(c);
    checked += o.checked;
    handed_over += o.handed_over;
  }
  EXPECT_GE(checked, 150u);
  EXPECT_GE(handed_over, 1u);
}

// The example trains over a range of several hand-overs (the exact engine on 3 and 9 gears:
// a few corners and one draw each).
TEST(ToleranceChainMonteCarlo, ExactTrainOnExampleTrains) {
  std::vector<Case> cases{
      {"gear-train-3.json", test::example_text("gear-train-3.json"), {Rational(0), Rational(3, 10)}, 360, 1, 6},
      {"gear-train.json", test::example_text("gear-train.json"), {Rational(15, 100), Rational(25, 100)}, 360, 1, 4},
  };
  std::size_t checked = 0;
  for (const Case& c : cases) checked += check_case(c).checked;
  EXPECT_GE(checked, 40u);
}

// The train's free start (session 27): over 0..0.25 rad the generated 2-gear train starts in
// its backlash (the follower, unloaded, free), the driver taking it up a few positions in; at
// the box corners of the first held positions that move the contact back, the contact has not
// met the follower yet there and it still waits where it started (the exact train's value).
// Mutation: the Monte Carlo dropping that rule (the follower on the contact's root wherever it
// is) fails it.
TEST(ToleranceChainMonteCarlo, UnloadedFollowerWaitsAtTheFreeStart) {
  Case c{"2 gears 10/12, the backlash taken up", test_gears::gear_train(2, 10, 12), {Rational(0), Rational(25, 100)},
         360, 2};
  c.first_corners = 6;
  c.max_corners = 0;
  Outcome o = check_case(c);
  EXPECT_GE(o.checked, 50u);
  EXPECT_GE(o.waiting, 1u) << "some vector's follower has not been met yet at a nominally held position";
}

}  // namespace
}  // namespace hipair
