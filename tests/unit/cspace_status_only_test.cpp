// Status-only first-crossing answers (hipair/crossing_before.hpp, StatusOnlyCrossings; the
// simulator's nudge asks its point queries in such a scope, simulation/nudge_check.hpp):
//  - on generated configurations of the example spaces and the degenerate corpus' zero-clearance
//    pairs — on a contact edge's double, a few ulps or 1e-15 ... 1e-9 off it, at random chart
//    points — asked as points (u_end = u_begin, the nudge's query) and as short quintic motions,
//    the status-only answer has the full answer's status, u bracket, grazing flag and cells, and
//    no description (no features, chart point, point or normal); where no description was
//    skipped it is the full answer field for field;
//  - the simulator's runs with status-only nudges are bit for bit those without (escapement,
//    ratchet, cam follower).
#include "cspace_test_support.hpp"
#include "simulation/nudge_check.hpp"
#include "simulation_side_by_side.hpp"
#include "test_paths.hpp"

#include <hipair/crossing_before.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <array>
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

std::string status_of(const MotionCrossing& c) {
  std::ostringstream out;
  out << "status " << static_cast<int>(c.status) << " u [" << c.u_lower << ", " << c.u_upper << "] grazing " << c.grazing
      << " left " << (c.cell_left.valid() ? static_cast<long>(c.cell_left.index()) : -1L) << " entered "
      << (c.cell_entered.valid() ? static_cast<long>(c.cell_entered.index()) : -1L);
  return out.str();
}

struct Counts {
  int queries = 0, in_contact = 0, grazing = 0, free = 0, skipped = 0, described = 0;
};

void compare(const CSpace& space, int count, std::uint64_t seed, Counts& counts) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<std::size_t> edges = test::real_edges(space);
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    std::size_t chart_index = 0;
    double x0 = 0, y0 = 0;
    if (!edges.empty() && random() % 4 != 0) {
      const CSpaceEdge& edge = space.edges()[edges[random() % edges.size()]];
      chart_index = edge.chart;
      x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
      if (two) {
        try {
          y0 = space.evaluate(static_cast<std::size_t>(&edge - space.edges().data()), x0).value;
        } catch (const GeometryError&) {
          continue;
        }
        const int mode = static_cast<int>(random() % 3);
        if (mode == 1) {
          int k = static_cast<int>(random() % 13) - 6;
          for (int j = 0; j < std::abs(k); ++j) y0 = std::nextafter(y0, k > 0 ? 1e300 : -1e300);
        } else if (mode == 2) {
          y0 += sym(random) * std::pow(10.0, -15 + 6 * unit(random));
        }
      }
    } else {
      ChartPoint p = test::random_tile_point(space, random);
      chart_index = p.chart;
      x0 = p.x.get_d();
      y0 = p.y.get_d();
    }
    const CSpaceChart& chart = space.charts()[chart_index];
    const bool point = random() % 3 != 0;
    const double speed = std::pow(10.0, -12 + 11 * unit(random));
    auto axis = [&](AxisKind kind, bool half_turn, double start) {
      std::vector<double> c{test::part_value(kind, half_turn, start)};
      if (!point) {
        c.push_back(sym(random) * speed);
        for (int k = 2; k <= 5; ++k) c.push_back(random() % 3 == 0 ? 0.0 : sym(random) * speed * speed);
      }
      return test::axis_path(kind, c);
    };
    MotionPath path;
    path.x = axis(chart.x_kind, chart.x_half_turn, x0);
    if (two) path.y = axis(chart.y_kind, chart.y_half_turn, y0);
    if (point) path.u_end = path.u_begin;
    auto ask = [&](bool status_only, MotionCrossing& out) -> std::string {
      std::optional<StatusOnlyCrossings> scope;
      if (status_only) scope.emplace();
      try {
        out = space.first_crossing(path);
      } catch (const Error& e) {
        return std::string("error: ") + e.what();
      }
      return "";
    };
    MotionCrossing full, quick;
    std::string full_error, quick_error;
    const std::size_t before = skipped_descriptions();
    if (random() % 2 == 0) {
      full_error = ask(false, full);
      quick_error = ask(true, quick);
    } else {
      quick_error = ask(true, quick);
      full_error = ask(false, full);
    }
    const bool skipped = skipped_descriptions() != before;
    const std::string where = space.first_part() + ":" + space.second_part() + " query " + std::to_string(i) +
                              (point ? " (point)" : " (motion)");
    ASSERT_EQ(quick_error, full_error) << where;
    if (!full_error.empty()) continue;
    ASSERT_EQ(status_of(quick), status_of(full)) << where;
    ASSERT_FALSE(status_only_crossings()) << "the scope must close";
    if (skipped) {
      const MotionCrossing blank;
      auto unset = [](const std::array<CertifiedRange, 2>& got, const std::array<CertifiedRange, 2>& none) {
        for (std::size_t k = 0; k < 2; ++k)
          if (!(got[k].lower == none[k].lower && got[k].upper == none[k].upper)) return false;
        return true;
      };
      EXPECT_TRUE(quick.features.empty() && quick.chart == blank.chart && unset(quick.chart_point, blank.chart_point) &&
                  unset(quick.point, blank.point) && unset(quick.normal, blank.normal))
          << where << ": a status-only answer carries a description";
      ++counts.skipped;
    } else {
      ASSERT_EQ(test::describe_crossing(space, quick), test::describe_crossing(space, full)) << where;
    }
    ++counts.queries;
    if (full.status == CrossingStatus::starts_in_contact) ++counts.in_contact;
    if (full.grazing) ++counts.grazing;
    if (full.status == CrossingStatus::none) ++counts.free;
    if (!full.features.empty()) ++counts.described;   // the full answers are described
  }
}

TEST(CSpaceStatusOnly, AnswersHaveTheFullAnswersStatus) {
  Counts counts;
  std::uint64_t seed = 4720;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    compare(*space, 150, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate/zero-clearance.json");
  for (const PairBuild& pair : CSpace::build_pairs(model)) {
    if (pair.status != PairBuild::Status::built) continue;
    compare(*pair.space, 100, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("status-only: %d queries (%d in contact, %d grazing, %d free) equal; %d descriptions skipped, %d full "
              "answers described\n",
              counts.queries, counts.in_contact, counts.grazing, counts.free, counts.skipped, counts.described);
  EXPECT_GE(counts.queries, 800);
  EXPECT_GE(counts.in_contact, 100);
  EXPECT_GE(counts.grazing, 20);
  EXPECT_GE(counts.free, 100);
  EXPECT_GE(counts.skipped, 100);
  EXPECT_GE(counts.described, 100);
}

TEST(SimulationStatusOnlyNudges, RunsEqualTheRunsWithoutThem) {
  const std::size_t before = skipped_descriptions();
  const test::SideBySide total =
      test::runs_side_by_side<simulation::status_only_nudges>(HIPAIR_EXAMPLES,
                                                              {{"escapement.json", 0.5, 1e-3},
                                                               {"escapement.json", 0.1, 1e-6},
                                                               {"ratchet.json", 0.2, 1e-6},
                                                               {"cam-follower.json", 0.3, 1e-6}},
                                                              100000);
  const std::size_t steps = total.steps, events = total.events;
  const std::size_t skipped = skipped_descriptions() - before;
  std::printf("status-only nudges: %zu steps, %zu events equal; %zu descriptions skipped\n", steps, events, skipped);
  EXPECT_GT(events, 50u);
  EXPECT_GT(skipped, 20u);
}

}  // namespace
}  // namespace hipair
