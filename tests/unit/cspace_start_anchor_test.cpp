// CSpace::first_crossing's start anchors (src/cspace/cspace_queries.cpp, StartAnchor; switch
// cspace::start_anchors() in src/cspace/angle_filter.hpp): a query answering `none` remembers its
// last stretch's box when no curve of the chart vanishes on it, and a later start inside it is
// located in that free cell without the exact ray shooting. Generated chains of motions as the
// simulator makes them (each step starts where the last one ended, rounded to doubles; point
// queries at the step's start as the nudge makes them; now and then a jump to a random
// configuration, a move of one coordinate, or to another space) must give, query by query, the answers of the same chain
// with the anchors off (every start located exactly).
#include "cspace/angle_filter.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

using Switch = test::FlagSwitch<&cspace::start_anchors>;
using test::describe_crossing;
using test::axis_path;


double end_value(const std::vector<double>& c) {
  Rational v(0);
  for (std::size_t i = c.size(); i-- > 0;) v = v * 1 + Rational(c[i]);
  return v.get_d();
}

// One generated chain of queries on the spaces, as (space, path) in order.
struct Query {
  const CSpace* space;
  MotionPath path;
};

std::vector<Query> chain(const std::vector<const CSpace*>& spaces, int count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::vector<Query> queries;
  std::vector<std::array<double, 2>> at(spaces.size());
  auto jump = [&](std::size_t s) {
    const CSpace& space = *spaces[s];
    const CSpaceChart& chart = space.charts()[random() % space.charts().size()];
    auto part = [&](AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
      double t = lo.get_d() + (hi.get_d() - lo.get_d()) * unit(random);
      return kind == AxisKind::translation ? t : (half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t);
    };
    at[s][0] = part(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi);
    at[s][1] = space.dimension() == 2 ? part(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi) : 0;
  };
  for (std::size_t s = 0; s < spaces.size(); ++s) jump(s);
  for (int i = 0; i < count; ++i) {
    std::size_t s = random() % spaces.size();
    const CSpace& space = *spaces[s];
    const CSpaceChart& chart0 = space.charts().front();
    if (random() % 10 == 0) jump(s);
    // or a move of one coordinate only (a start beside the last step's box: inside its range
    // of the other coordinate)
    else if (random() % 4 == 0) at[s][random() % space.dimension()] += sym(random) * std::pow(10.0, -3 + 3 * unit(random));
    double scale = std::pow(10.0, -5 + 4 * unit(random));
    std::vector<double> x{at[s][0], scale * sym(random), scale * 0.3 * sym(random), scale * 0.05 * sym(random)};
    std::vector<double> y{at[s][1], scale * sym(random), scale * 0.3 * sym(random), scale * 0.05 * sym(random)};
    if (random() % 3 == 0) {   // a point query at the start (the nudge's)
      Query point{&space, {}};
      point.path.x = axis_path(chart0.x_kind, {x[0]});
      if (space.dimension() == 2) point.path.y = axis_path(chart0.y_kind, {y[0]});
      queries.push_back(std::move(point));
    }
    Query motion{&space, {}};
    motion.path.x = axis_path(chart0.x_kind, x);
    if (space.dimension() == 2) motion.path.y = axis_path(chart0.y_kind, y);
    queries.push_back(std::move(motion));
    // the next step starts where this one ended, in doubles (a crossing: a jump)
    at[s][0] = end_value(x);
    at[s][1] = space.dimension() == 2 ? end_value(y) : 0;
  }
  return queries;
}

std::vector<std::string> answers(const std::vector<Query>& queries, bool anchors, std::size_t& anchored) {
  Switch use(anchors);
  std::size_t before = cspace::anchored_starts();
  std::vector<std::string> result;
  for (const Query& q : queries) {
    try {
      result.push_back(describe_crossing(*q.space, q.space->first_crossing(q.path)));
    } catch (const Error& e) {
      result.push_back(std::string("error: ") + e.what());
    }
  }
  anchored = cspace::anchored_starts() - before;
  return result;
}

void check(const std::vector<Query>& queries, std::size_t& anchored_total, std::size_t& none_total) {
  std::size_t anchored = 0, unused = 0;
  std::vector<std::string> with = answers(queries, true, anchored);
  std::vector<std::string> without = answers(queries, false, unused);
  ASSERT_EQ(unused, 0u) << "the switch must turn the anchors off";
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    ASSERT_EQ(with[i], without[i]) << "query " << i;
    none_total += with[i].rfind("status 0 ", 0) == 0;
  }
  anchored_total += anchored;
}

TEST(CSpaceStartAnchor, ChainsOfMotionsGiveTheAnswersOfExactStartLocation) {
  std::size_t anchored = 0, none = 0;
  Model geneva = read_model_file(example("geneva-drive.json"));
  Model cam = read_model_file(example("cam-follower.json"));
  std::vector<std::unique_ptr<CSpace>> owned = test::example_spaces();
  std::vector<const CSpace*> spaces;
  for (const auto& s : owned) spaces.push_back(s.get());
  for (std::uint64_t seed : {3u, 5u, 7u}) {
    check(chain(spaces, 800, seed), anchored, none);
    ASSERT_FALSE(HasFatalFailure()) << "seed " << seed;
  }
  // a space freed and another one built (possibly at the same address): anchors of the freed
  // one must never match
  for (int round = 0; round < 3; ++round) {
    auto fresh = std::make_unique<CSpace>(CSpace::build(round % 2 ? cam : geneva, round % 2 ? "cam" : "driver",
                                                        round % 2 ? "follower" : "wheel"));
    check(chain({fresh.get()}, 300, 11 + round), anchored, none);
    ASSERT_FALSE(HasFatalFailure()) << "round " << round;
  }
  std::printf("anchored starts %zu, free answers %zu\n", anchored, none);
  RecordProperty("anchored", static_cast<int>(anchored));
  EXPECT_GE(anchored, 500u);   // the anchors are used
  EXPECT_GE(none, 1500u);
}

// The anchor's box must hold no curve at all, not only none that the path meets: a motion that
// leaves a contact curve (excluded by the mean-value form, one stretch) has a box that the
// curve crosses beside the path, near its start corner. Generated: a random motion up to its
// first crossing; from a point just before it, a motion away from the curve (back and
// sideways); then a start at a corner of that motion's box (or of its last halves' boxes), which
// for many of the cases lies on the other side of the curve (blocked, or another free cell).
// Each such start must be answered as with the anchors off (exact location), and none of those
// on the other side may be anchored.
TEST(CSpaceStartAnchor, StartsBesideACurveCrossingTheLastBoxAreLocatedExactly) {
  std::vector<std::unique_ptr<CSpace>> owned = test::example_spaces();
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::size_t cases = 0, other_side = 0, anchored_other_side = 0;
  for (const auto& owned_space : owned) {
    const CSpace& space = *owned_space;
    if (space.dimension() != 2) continue;
    const CSpaceChart& chart0 = space.charts().front();
    auto line = [&](std::array<double, 2> from, std::array<double, 2> by) {
      MotionPath path;
      path.x = axis_path(chart0.x_kind, {from[0], by[0]});
      path.y = axis_path(chart0.y_kind, {from[1], by[1]});
      return path;
    };
    auto point = [&](std::array<double, 2> at) {
      MotionPath path;
      path.x = axis_path(chart0.x_kind, {at[0]});
      path.y = axis_path(chart0.y_kind, {at[1]});
      return path;
    };
    auto ask = [&](const MotionPath& path, bool anchors) {
      Switch use(anchors);
      try {
        return describe_crossing(space, space.first_crossing(path));
      } catch (const Error& e) {
        return std::string("error: ") + e.what();
      }
    };
    for (int attempt = 0; attempt < 400; ++attempt) {
      // a random motion to its first crossing
      const CSpaceChart& chart = space.charts()[random() % space.charts().size()];
      auto part = [&](AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
        double t = lo.get_d() + (hi.get_d() - lo.get_d()) * unit(random);
        return kind == AxisKind::translation ? t : (half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t);
      };
      std::array<double, 2> from{part(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi),
                                 part(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi)};
      double scale = std::pow(10.0, -1 + 1.3 * unit(random));
      std::array<double, 2> v{scale * sym(random), scale * sym(random)};
      MotionCrossing hit;
      {
        Switch off(false);
        try {
          // longer until it crosses
          for (int longer = 0; longer < 4; ++longer, v = {4 * v[0], 4 * v[1]}) {
            hit = space.first_crossing(line(from, v));
            if (hit.status != CrossingStatus::none) break;
          }
        } catch (const Error&) {
          continue;
        }
      }
      if (hit.status != CrossingStatus::crossing || hit.u_lower <= 0) continue;
      // a point just before the crossing (a little back along the motion), in doubles
      double u = hit.u_lower.get_d() * (1 - std::pow(10.0, -6 + 5 * unit(random)));
      std::array<double, 2> p{from[0] + v[0] * u, from[1] + v[1] * u};
      // away from the curve: back along the motion, and sideways
      double length = std::hypot(v[0], v[1]) * std::pow(10.0, -4 + 3 * unit(random));
      double phi = 1.4 * sym(random), n = std::hypot(v[0], v[1]);
      std::array<double, 2> back{-v[0] / n, -v[1] / n}, side{-back[1], back[0]};
      std::array<double, 2> d{length * (std::cos(phi) * back[0] + std::sin(phi) * side[0]),
                              length * (std::cos(phi) * back[1] + std::sin(phi) * side[1])};
      MotionPath away = line(p, d);
      std::string away_off = ask(away, false);
      if (away_off.rfind("status 0 ", 0) != 0) continue;   // only motions answered `none`
      MotionCrossing away_crossing;
      {
        Switch off(false);
        away_crossing = space.first_crossing(away);
      }
      // starts at the corners of the box of the motion's last 2^-k (k = 0..3), a little inside
      for (int k = 0; k < 4; ++k)
        for (int corner = 0; corner < 2; ++corner) {
          double lo = 1 - std::ldexp(1.0, -k);
          double near = lo + (1 - lo) * 0.001, far = lo + (1 - lo) * 0.999;
          std::array<double, 2> q{p[0] + d[0] * (corner ? near : far), p[1] + d[1] * (corner ? far : near)};
          MotionPath start = point(q);
          std::string exact = ask(start, false);
          MotionCrossing located;
          {
            Switch off(false);
            try {
              located = space.first_crossing(start);
            } catch (const Error&) {
              continue;
            }
          }
          bool beyond = located.status != CrossingStatus::none || located.cell_left != away_crossing.cell_left;
          // the motion again with the anchors on (it leaves, or not, its anchor), then the start
          ASSERT_EQ(ask(away, true), away_off) << "attempt " << attempt;
          std::size_t before = cspace::anchored_starts();
          std::string anchored = ask(start, true);
          std::size_t used = cspace::anchored_starts() - before;
          ++cases;
          other_side += beyond;
          if (beyond) anchored_other_side += used;
          ASSERT_EQ(anchored, exact) << "attempt " << attempt << " k " << k << " corner " << corner << " at (" << q[0]
                                     << ", " << q[1] << ")";
        }
    }
  }
  std::printf("corner starts %zu, on the other side of a curve %zu, anchored there %zu\n", cases, other_side,
              anchored_other_side);
  EXPECT_EQ(anchored_other_side, 0u);
  EXPECT_GE(other_side, 50u);   // the case is exercised: starts beside a curve inside the box
}

}  // namespace
}  // namespace hipair
