// Assembly chains on the kernel path (session 13; docs/tolerance.md "Assembly chains"): a chain
// whose parts all rotate without limits (a gear train) takes its nominal motion from the
// kinematics sliced from the contact kernels and each pair's touching feature pair from the exact
// kinematic engine, with no C-space built. On generated 2-4 gear trains with random tooth counts
// at random driver ranges, two oracles:
//  - the lookup: the same chain with every pair analysed on its built, sliced exact C-space at
//    the same nominal motion (ChainPaths::cspace_lookup): the same contacts (feature pairs,
//    exactly), kinematic function, sensitivities, bands and certified band, equal to the last bit
//    (the same inputs reach the same arithmetic);
//  - the nominal motion: the chain as before session 13 (ChainPaths::kernel_kinematics = false,
//    the kinematics on the C-space slicer): the same positions in contact, the same contact
//    regions and feature pairs; the kinematic function within 8 ulps (each path's position is
//    the double of an exact algebraic number, its chart value the truncation of a 2^-60-accurate
//    midpoint: the two differ by at most 1 ulp of t in [-1, 1], 2 ulps of the angle, plus the
//    roundings of atan, the doubling and the whole turns, 1 ulp each on each side); its
//    certified band is not computed (ChainPaths::certified_band), nothing of it being compared.
// A lookup mutated to a wrong branch (the follower's other chart) or a wrong feature pair (the
// neighbouring flank) must be caught by the first comparison. Monte Carlo samples of the kernel
// path stay in its certified band.
#include "gear_train_models.hpp"

#include "tolerance/stage.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using tolerance_detail::ChainPaths;
using tolerance_detail::CurveSlice;

// Differences between two chain results (empty: equal). Play is not compared: the kernel path
// reports the follower's channel in the whole model (the kinematics'), the C-space path in the
// last pair's slice (docs/tolerance.md).
std::vector<std::string> differences(const ToleranceResult& a, const ToleranceResult& b) {
  std::vector<std::string> out;
  auto differ = [&](bool same, const std::string& what) {
    if (!same) out.push_back(what);
  };
  differ(a.samples.size() == b.samples.size(), "sample count");
  for (std::size_t i = 0; i < std::min(a.samples.size(), b.samples.size()); ++i) {
    const VariationSample& x = a.samples[i];
    const VariationSample& y = b.samples[i];
    std::string at = "position " + std::to_string(i) + ": ";
    differ(x.driver == y.driver, at + "driver");
    differ(x.nominal == y.nominal, at + "kinematic function");
    differ(x.contact == y.contact, at + "contact");
    differ(x.sensitivities == y.sensitivities, at + "sensitivities");
    differ(x.linear_lower == y.linear_lower && x.linear_upper == y.linear_upper, at + "linearised band");
    differ(x.rss_lower == y.rss_lower && x.rss_upper == y.rss_upper, at + "RSS band");
    differ(x.certified.lower == y.certified.lower && x.certified.upper == y.certified.upper, at + "certified band");
  }
  differ(a.regions.size() == b.regions.size(), "region count");
  for (std::size_t r = 0; r < std::min(a.regions.size(), b.regions.size()); ++r) {
    const ContactRegion& x = a.regions[r];
    const ContactRegion& y = b.regions[r];
    std::string at = "region " + std::to_string(r) + ": ";
    differ(x.contact == y.contact, at + "contact label '" + x.contact + "' / '" + y.contact + "'");
    differ(x.first == y.first && x.second == y.second, at + "feature pair");
    differ(x.first_sample == y.first_sample && x.last_sample == y.last_sample, at + "extent");
    differ(x.ranked.size() == y.ranked.size(), at + "ranking size");
    for (std::size_t p = 0; p < std::min(x.ranked.size(), y.ranked.size()); ++p)
      differ(x.ranked[p].parameter == y.ranked[p].parameter && x.ranked[p].contribution == y.ranked[p].contribution,
             at + "ranking " + std::to_string(p));
  }
  differ(a.chain.size() == b.chain.size(), "pair count");
  for (std::size_t s = 0; s < std::min(a.chain.size(), b.chain.size()); ++s)
    differ(a.chain[s].contact_positions == b.chain[s].contact_positions &&
               a.chain[s].certified_boxes == b.chain[s].certified_boxes,
           "pair " + std::to_string(s) + " contacts / certified sub-boxes");
  return out;
}

ToleranceOptions options_for(double start, double width, std::size_t monte_carlo) {
  ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = std::make_pair(Rational(start), Rational(start + width));
  options.positions = 240;
  options.threads = 2;
  options.monte_carlo = monte_carlo;
  options.seed = 11;
  return options;
}

// The kinematic function (part units) of two paths within the bound stated at the top.
bool within_ulps(double a, double b, double ulps) {
  double scale = std::max({std::fabs(a), std::fabs(b), 1.0});
  return std::fabs(a - b) <= ulps * scale * std::numeric_limits<double>::epsilon();
}

// The generated trains: 2, 4 and 3 gears, teeth and driver range drawn in this order from one
// fixed rng sequence (the cases of the single test before session 66). Each train is its own
// ctest entry (session 66: the three took 117-131 s user in one entry, over the 30 s rule; the
// 4-gear train alone takes about 110 s, see docs/performance.md "Session 66 (chaintest66)").
struct GeneratedTrain {
  unsigned gears, even, odd;
  double from;
};

std::vector<GeneratedTrain> generated_trains() {
  std::mt19937 rng(20261128);
  std::uniform_int_distribution<unsigned> teeth(8, 12);
  std::uniform_real_distribution<double> start(0, 2 * std::numbers::pi);
  std::vector<GeneratedTrain> trains;
  for (unsigned gears : {2u, 4u, 3u}) {
    unsigned even = teeth(rng), odd = teeth(rng);
    // range ends with few bits (exact rationals either way)
    double from = std::ldexp(std::round(std::ldexp(start(rng), 10)), -10);
    trains.push_back({gears, even, odd, from});
  }
  return trains;
}

class ToleranceChainKernel : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ToleranceChainKernel, KernelChainEqualsCSpaceChainOnGeneratedGearTrains) {
  const std::vector<GeneratedTrain> trains = generated_trains();
  ASSERT_LT(GetParam(), trains.size());
  const GeneratedTrain& train = trains[GetParam()];
  const unsigned gears = train.gears, even = train.even, odd = train.odd;
  const double from = train.from;
  {
    std::string text = test_gears::gear_train(gears, even, odd);
    SCOPED_TRACE(std::to_string(gears) + " gears, " + std::to_string(even) + "/" + std::to_string(odd) +
                 " teeth, from " + std::to_string(from));
    ToleranceOptions options = options_for(from, 0.4, 0);
    ToleranceOptions with_mc = options;
    with_mc.monte_carlo = 30;
    // The certified band of a position is a function of its inputs (session 67): the lookup below
    // replays the kernel run's band where its inputs are the kernel path's bit for bit
    // (ChainBandMemo), instead of computing it a second time (the 4-gear train's hand-over
    // position: 127 sub-boxes of the tolerance box).
    auto memo = std::make_shared<tolerance_detail::ChainBandMemo>();
    ChainPaths kernel_path;
    kernel_path.band_memo = memo;
    ToleranceResult kernel = tolerance_detail::analyze_chain(text, with_mc, kernel_path);
    for (const std::string& note : kernel.notes)
      EXPECT_EQ(note.find("not unique"), std::string::npos) << "the kernel path fell back: " << note;
    std::size_t held = 0;
    for (const VariationSample& s : kernel.samples) held += s.contact;
    // the train is held somewhere (otherwise nothing was compared): before session 66 checked
    // over the three trains together (held_total > positions_total / 4), now on each train
    EXPECT_GT(held, kernel.samples.size() / 4);
    ASSERT_TRUE(kernel.monte_carlo.has_value());
    EXPECT_EQ(kernel.monte_carlo->outside_certified, 0u);
    EXPECT_EQ(kernel.monte_carlo->not_certified, 0u);
    // sampled at every held position, the band bounded or not (session 26)
    EXPECT_EQ(kernel.monte_carlo->evaluations, 30 * held);

    // Oracle 1: the C-space lookup at the same nominal motion, bit for bit.
    // (train 0, the cheapest: the lookup computes its own bands, so that the C-space lookup's band
    // computation is compared with the kernel path's, not replayed)
    ChainPaths lookup;
    lookup.cspace_lookup = true;
    if (GetParam() != 0) lookup.band_memo = memo;
    ToleranceResult oracle = tolerance_detail::analyze_chain(text, options, lookup);
    std::vector<std::string> found = differences(kernel, oracle);
    EXPECT_TRUE(found.empty()) << found.size() << " differences, first: " << found.front();
    // every held position's band replayed: the lookup's inputs to it (each pair's contact curve,
    // chart values, sensitivities and slopes) are the kernel path's, bit for bit
    EXPECT_EQ(memo->replayed, GetParam() != 0 ? held : 0u);
    // The mutated lookups on the first generated train (the first held one before session 66:
    // every train is now required to be held, so it is the same train).
    if (GetParam() == 0) {
      ASSERT_GT(held, 0u) << "the mutations need a held train";
      ChainPaths wrong_branch;
      wrong_branch.mutate_lookup = [](std::size_t, std::size_t, CurveSlice& curve) {
        curve.free_half_turn = !curve.free_half_turn;
      };
      EXPECT_FALSE(differences(tolerance_detail::analyze_chain(text, options, wrong_branch), oracle).empty())
          << "a lookup in the follower's other chart was not caught";
      ChainPaths wrong_flank;
      wrong_flank.mutate_lookup = [](std::size_t, std::size_t, CurveSlice& curve) { curve.second.edge ^= 1; };
      EXPECT_FALSE(differences(tolerance_detail::analyze_chain(text, options, wrong_flank), oracle).empty())
          << "a lookup of the neighbouring flank was not caught";
    }

    // Oracle 2: the chain before session 13 (C-space slicer kinematics). Only its nominal
    // motion and regions are compared: its certified band (as costly as the kernel run's, and
    // compared with it nowhere here) is not computed (session 51).
    ChainPaths before;
    before.kernel_kinematics = false;
    before.certified_band = false;
    ToleranceResult old = tolerance_detail::analyze_chain(text, options, before);
    ASSERT_EQ(kernel.samples.size(), old.samples.size());
    for (std::size_t i = 0; i < old.samples.size(); ++i) {
      SCOPED_TRACE("position " + std::to_string(i));
      EXPECT_EQ(kernel.samples[i].driver, old.samples[i].driver);
      EXPECT_EQ(kernel.samples[i].contact, old.samples[i].contact);
      EXPECT_TRUE(within_ulps(kernel.samples[i].nominal, old.samples[i].nominal, 8))
          << kernel.samples[i].nominal << " / " << old.samples[i].nominal;
    }
    ASSERT_EQ(kernel.regions.size(), old.regions.size());
    for (std::size_t r = 0; r < old.regions.size(); ++r) {
      EXPECT_EQ(kernel.regions[r].contact, old.regions[r].contact);
      EXPECT_TRUE(kernel.regions[r].first == old.regions[r].first && kernel.regions[r].second == old.regions[r].second);
      EXPECT_EQ(kernel.regions[r].first_sample, old.regions[r].first_sample);
      EXPECT_EQ(kernel.regions[r].last_sample, old.regions[r].last_sample);
    }
  }
}

std::string train_name(const ::testing::TestParamInfo<std::size_t>& info) {
  const GeneratedTrain train = generated_trains()[info.param];
  return "train" + std::to_string(info.param) + "_" + std::to_string(train.gears) + "_gears";
}

INSTANTIATE_TEST_SUITE_P(Generated, ToleranceChainKernel, ::testing::Values(0, 1, 2), train_name);

}  // namespace
}  // namespace hipair
