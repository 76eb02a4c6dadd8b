// first_crossing's carried region (src/cspace/carried_region.hpp, switch
// cspace::carried_regions()): walks on the example spaces and the degenerate ones — each motion
// starts where the last one ended (as the simulator's steps do), 10^-4 ... 10^-1 of the chart's
// width long, a third of them point paths (the nudge's questions) — so that regions are made,
// used, and replaced as the walk goes from cell to cell (free and blocked). Every answer, every
// field (test::crossing_answer), equals the answer without the region.
#include "cspace/angle_filter.hpp"
#include "cspace/carried_region.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

struct Tally {
  std::size_t compared = 0, in_contact = 0, mismatches = 0;
};

void walk(const CSpace& space, int count, std::uint64_t seed, const std::string& name, Tally& tally) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const bool two = space.dimension() == 2;
  std::size_t c = random() % charts.size();
  auto inside = [](double v, double lo, double hi) { return std::min(std::max(v, lo + 1e-9 * (hi - lo)), hi - 1e-9 * (hi - lo)); };
  const CSpaceChart* chart = &charts[c];
  double x = chart->x_lo.get_d() + (chart->x_hi.get_d() - chart->x_lo.get_d()) * unit(random);
  double y = two ? chart->y_lo.get_d() + (chart->y_hi.get_d() - chart->y_lo.get_d()) * unit(random) : 0;
  for (int i = 0; i < count; ++i) {
    if (random() % 50 == 0) {   // now and then a jump to another chart and place
      c = random() % charts.size();
      chart = &charts[c];
      x = chart->x_lo.get_d() + (chart->x_hi.get_d() - chart->x_lo.get_d()) * unit(random);
      y = two ? chart->y_lo.get_d() + (chart->y_hi.get_d() - chart->y_lo.get_d()) * unit(random) : 0;
    }
    const double w = chart->x_hi.get_d() - chart->x_lo.get_d(), h = two ? chart->y_hi.get_d() - chart->y_lo.get_d() : 0;
    const bool point = random() % 3 == 0;
    const double scale = std::pow(10.0, -4 + 3 * unit(random));
    double x1 = point ? x : inside(x + sym(random) * scale * w, chart->x_lo.get_d(), chart->x_hi.get_d());
    double y1 = point || !two ? y : inside(y + sym(random) * scale * h, chart->y_lo.get_d(), chart->y_hi.get_d());
    double qx0 = test::part_value(chart->x_kind, chart->x_half_turn, x);
    double qx1 = test::part_value(chart->x_kind, chart->x_half_turn, x1);
    double qy0 = two ? test::part_value(chart->y_kind, chart->y_half_turn, y) : 0;
    double qy1 = two ? test::part_value(chart->y_kind, chart->y_half_turn, y1) : 0;
    double bend = (point || random() % 2 == 0) ? 0.0 : 0.3 * sym(random);
    MotionPath path = test::bent_motion(*chart, two, qx0, qy0, qx1 - qx0, qy1 - qy0, bend, point);
    std::ostringstream what;
    what.precision(17);
    what << name << " " << space.first_part() << ":" << space.second_part() << " step " << i << " chart " << c << " from "
         << x << ", " << y << " to " << x1 << ", " << y1 << (point ? " (point)" : "");
    auto [on, off] =
        test::on_and_off<&cspace::carried_regions>(random, [&](bool region) {
          if (region) return test::crossing_answer(space, path);
          // the oracle reads no state the runs with the region left (start anchors, anchor boxes)
          test::FlagSwitch<&cspace::start_anchors> anchors(false);
          test::FlagSwitch<&cspace::anchor_boxes> boxes(false);
          return test::crossing_answer(space, path);
        });
    if (on != off && ++tally.mismatches <= 3) ADD_FAILURE() << what.str() << "\n with the region:    " << on << "\n without the region: " << off;
    ++tally.compared;
    if (on.rfind("status 2 ", 0) == 0) ++tally.in_contact;
    x = x1;
    y = y1;
  }
}

TEST(CSpaceCarriedRegion, WalksAnswerAsWithoutTheRegion) {
  Tally tally;
  const std::size_t hits_before = cspace::carried_region_hits(), made_before = cspace::carried_regions_made();
  std::uint64_t seed = 4401;
  {
    std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
    for (const auto& space : spaces) {
      walk(*space, 1500, seed++, "example", tally);
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  for (const char* name : {"zero-clearance.json", "tangent-circles.json", "concentric-arcs.json", "coincident-edges.json",
                           "collinear-edges.json", "interval-contact.json", "vertex-on-vertex.json"}) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate" / name);
    for (const PairBuild& pair : CSpace::build_pairs(model)) {
      if (pair.status != PairBuild::Status::built) continue;
      walk(*pair.space, 400, seed++, name, tally);
      ASSERT_FALSE(HasFatalFailure());
    }
  }
  const std::size_t hits = cspace::carried_region_hits() - hits_before, made = cspace::carried_regions_made() - made_before;
  std::printf("carried region: %zu walk steps compared (%zu starting in contact), %zu differ; %zu regions made, %zu boxes inside one\n",
              tally.compared, tally.in_contact, tally.mismatches, made, hits);
  EXPECT_EQ(tally.mismatches, 0u) << "answers that differ";
  EXPECT_GT(made, 100u);
  EXPECT_GT(hits, 100u);
}

}  // namespace
}  // namespace hipair
