// Shared pieces of the first_crossing tests that compare a switch's answers (start filter, scan
// memo, angle memo, the stopped query, the path memo, the dyadic sums): the exact description of
// an answer, the starts they generate near contact edges and on chart sides, and generated
// quintic motions.
#pragma once

#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::test {

// The answer to `path` on `space`, described exactly ("throws: ..." where it throws).
inline std::string crossing_answer(const CSpace& space, const MotionPath& path) {
  try {
    return describe_crossing(space, space.first_crossing(path));
  } catch (const GeometryError& e) {
    return std::string("throws: ") + e.what();
  }
}

// A coordinate moved off where it was: by -4 ... 4 ulps, or by +-(1e-15 ... 1e-3).
inline void move_off(double& value, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  if (random() % 2 == 0) {
    int k = static_cast<int>(random() % 9) - 4;
    for (int j = 0; j < std::abs(k); ++j) value = std::nextafter(value, k > 0 ? 1e300 : -1e300);
  } else {
    value += sym(random) * std::pow(10.0, -15 + 12 * unit(random));
  }
}

// A point (chart values) of the edge e's interior, x at 2 % ... 98 % of its x-range: false where
// the edge is vertical (nothing changed) or its ordinate cannot be evaluated there (c and x0 set).
inline bool onto_edge(const CSpace& space, std::size_t e, std::mt19937_64& random, std::size_t& c, double& x0, double& y0) {
  std::uniform_real_distribution<double> unit(0, 1);
  const CSpaceEdge& edge = space.edges()[e];
  if (edge.vertical) return false;
  c = edge.chart;
  x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
  try {
    y0 = space.evaluate(e, x0).value;
  } catch (const GeometryError&) {
    return false;
  }
  return true;
}

// x or y (chart values) put on one of the chart's sides (x only in a 1-D space).
inline void to_chart_side(const CSpaceChart& chart, bool two, double& x, double& y, std::mt19937_64& random) {
  bool on_x = !two || random() % 2 == 0;
  double side = (random() % 2 == 0) ? (on_x ? chart.x_lo : chart.y_lo).get_d() : (on_x ? chart.x_hi : chart.y_hi).get_d();
  (on_x ? x : y) = side;
}

// The tests' motion from the part values (qx0, qy0) by (vx, vy), bent by `bend` (x quadratic,
// y cubic, the same end); a point path when `point`.
inline MotionPath bent_motion(const CSpaceChart& chart, bool two, double qx0, double qy0, double vx, double vy,
                              double bend, bool point) {
  MotionPath path;
  path.x = axis_path(chart.x_kind, {qx0, vx * (1 - bend), vx * bend, 0});
  if (two) path.y = axis_path(chart.y_kind, {qy0, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
  if (point) path.u_end = path.u_begin;
  return path;
}

// A motion on `space`: from a random point of a random chart, either toward a random point of a
// real edge and past it (kind 0, two thirds: a crossing from a free start), or in a random
// direction by 10^-3 ... 1 (kind 1);
// a cubic in u through both ends with a random bend.
inline MotionPath random_motion(const CSpace& space, std::mt19937_64& random, int& kind, std::size_t& chart_index) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const bool two = space.dimension() == 2;
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  kind = real_edges.empty() || random() % 3 == 0 ? 1 : 0;
  std::size_t c = random() % space.charts().size();
  double x1 = 0, y1 = 0;
  if (kind == 0) {
    const std::size_t e = real_edges[random() % real_edges.size()];
    const CSpaceEdge& edge = space.edges()[e];
    c = edge.chart;
    double x = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
    double y = 0;
    if (two) {
      try {
        y = space.evaluate(e, x).value;
      } catch (const GeometryError&) {
        kind = 1;
      }
    } else {
      x = edge.x_chart.lower;
    }
    x1 = x;
    y1 = y;
  }
  const CSpaceChart& chart = space.charts()[c];
  double x0 = chart.x_lo.get_d() + (chart.x_hi.get_d() - chart.x_lo.get_d()) * unit(random);
  double y0 = two ? chart.y_lo.get_d() + (chart.y_hi.get_d() - chart.y_lo.get_d()) * unit(random) : 0;
  if (kind == 0) {
    double past = 1 + 0.5 * unit(random);
    x1 = x0 + (x1 - x0) * past;
    y1 = y0 + (y1 - y0) * past;
  } else {
    double scale = std::pow(10.0, -3 + 3 * unit(random));
    x1 = x0 + sym(random) * scale;
    y1 = y0 + sym(random) * scale;
  }
  double qx0 = part_value(chart.x_kind, chart.x_half_turn, x0);
  double qx1 = part_value(chart.x_kind, chart.x_half_turn, x1);
  double qy0 = two ? part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
  double qy1 = two ? part_value(chart.y_kind, chart.y_half_turn, y1) : 0;
  double bend = (random() % 3 == 0) ? 0.0 : 0.3 * sym(random);
  double vx = qx1 - qx0, vy = qy1 - qy0;
  MotionPath path;
  path.x = axis_path(chart.x_kind, {qx0, vx * (1 - bend), vx * bend, 0});
  if (two) path.y = axis_path(chart.y_kind, {qy0, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
  chart_index = c;
  return path;
}

// A start (chart values) on `space`: anywhere, a few ulps or 1e-15 ... 1e-3 off a real edge, or
// on a chart's side.
inline void pick_start(const CSpace& space, std::mt19937_64& random, std::size_t& c, double& x0, double& y0) {
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const bool two = space.dimension() == 2;
  c = random() % charts.size();
  x0 = charts[c].x_lo.get_d() + (charts[c].x_hi.get_d() - charts[c].x_lo.get_d()) * unit(random);
  y0 = two ? charts[c].y_lo.get_d() + (charts[c].y_hi.get_d() - charts[c].y_lo.get_d()) * unit(random) : 0;
  const int kind = static_cast<int>(random() % 3);
  if (kind == 1 && two) {
    std::size_t e = random() % space.edges().size();
    if (!space.edges()[e].real || !onto_edge(space, e, random, c, x0, y0)) return;
    move_off(random() % 2 == 0 ? y0 : x0, random);
  } else if (kind == 2) {
    to_chart_side(charts[c], two, x0, y0, random);
  }
}

// A generated start on a random one of `spaces`: chart c's values (x0, y0) from
// pick(space, random, c, x0, y0), and the parts' values there.
struct PartStart {
  const CSpace* space = nullptr;
  std::size_t chart = 0;
  bool two = false;
  double qx0 = 0, qy0 = 0;
};
template <class Pick>
PartStart part_start(const std::vector<std::unique_ptr<CSpace>>& spaces, std::mt19937_64& random, Pick&& pick) {
  PartStart s;
  s.space = spaces[random() % spaces.size()].get();
  double x0 = 0, y0 = 0;
  pick(*s.space, random, s.chart, x0, y0);
  const CSpaceChart& chart = s.space->charts()[s.chart];
  s.two = s.space->dimension() == 2;
  s.qx0 = part_value(chart.x_kind, chart.x_half_turn, x0);
  s.qy0 = s.two ? part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
  return s;
}

// A generated motion (random_motion) on a random one of `spaces` (index s), and first_crossing's
// answer to it (the oracle of the tests that stop or limit the query).
struct GeneratedQuery {
  std::size_t s = 0;
  int kind = 0;
  MotionPath path;
  MotionCrossing answer;
};
// false where the query throws
inline bool random_query(const std::vector<std::unique_ptr<CSpace>>& spaces, std::mt19937_64& random, GeneratedQuery& q) {
  q.s = random() % spaces.size();
  std::size_t chart = 0;
  q.path = random_motion(*spaces[q.s], random, q.kind, chart);
  try {
    q.answer = spaces[q.s]->first_crossing(q.path);
  } catch (const GeometryError&) {
    return false;
  }
  return true;
}

// A generated motion of the crossing-query tests (cspace_crossing_path_memo_test.cpp,
// cspace_dyadic_sums_test.cpp): a quintic in the part coordinates — the simulator's step paths —
// starting on a contact edge (`edges`: real_edges(space)), a few ulps or 1e-15 ... 1e-9 off it,
// along its tangent with a random bend, or at a random chart point, at a speed 1e-12 ... 10 chart
// units. Nothing where the sampled edge has no derivative there. Draws from `random` in one fixed
// order, so a seed names the same motions in every test.
struct GeneratedMotion {
  MotionPath path;
  double speed = 0, x0 = 0, y0 = 0;
  std::size_t chart = 0;
};

inline std::optional<GeneratedMotion> generated_motion(const CSpace& space, const std::vector<std::size_t>& edges,
                                                       std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const bool two = space.dimension() == 2;
  GeneratedMotion m;
  m.speed = std::pow(10.0, -12 + 13 * unit(random));
  double sx = sym(random), sy = sym(random);
  if (!edges.empty() && random() % 4 != 0) {
    const CSpaceEdge& edge = space.edges()[edges[random() % edges.size()]];
    m.chart = edge.chart;
    m.x0 = edge.x_chart.lower + (edge.x_chart.upper - edge.x_chart.lower) * (0.02 + 0.96 * unit(random));
    if (two) {
      try {
        const std::size_t e = static_cast<std::size_t>(&edge - space.edges().data());
        m.y0 = space.evaluate(e, m.x0).value;
        EdgeDerivatives d = space.derivatives(EdgeId(e), Rational(m.x0));
        sx = 1;
        sy = 0.5 * (d.dy.lower + d.dy.upper);
      } catch (const GeometryError&) {
        return std::nullopt;
      }
      if (!std::isfinite(sy)) return std::nullopt;
      if (random() % 2 == 0) {
        int k = static_cast<int>(random() % 13) - 6;
        for (int j = 0; j < std::abs(k); ++j) m.y0 = std::nextafter(m.y0, k > 0 ? 1e300 : -1e300);
      } else {
        m.y0 += sym(random) * std::pow(10.0, -15 + 6 * unit(random));
      }
    }
    if (random() % 2 == 0) {
      sx = -sx;
      sy = -sy;
    }
  } else {
    ChartPoint p = random_tile_point(space, random);
    m.chart = p.chart;
    m.x0 = p.x.get_d();
    m.y0 = p.y.get_d();
  }
  const CSpaceChart& chart = space.charts()[m.chart];
  auto axis = [&](AxisKind kind, bool half_turn, double start, double direction) {
    std::vector<double> c{part_value(kind, half_turn, start), direction * m.speed};
    for (int k = 2; k <= 5; ++k) c.push_back(random() % 3 == 0 ? 0.0 : sym(random) * m.speed * m.speed);
    return axis_path(kind, c);
  };
  m.path.x = axis(chart.x_kind, chart.x_half_turn, m.x0, sx);
  if (two) m.path.y = axis(chart.y_kind, chart.y_half_turn, m.y0, sy);
  return m;
}

// What switch_answers_equal saw: motions asked, their answers' kinds, the counter's increase.
struct SwitchCounts {
  int motions = 0, crossing = 0, none = 0, other = 0;
  std::size_t hits = 0;
};

// `count` generated motions on `space` (seed `seed`), each asked with the switch Flag on and off
// in a random order: the two answers equal field for field, Counter unchanged with the switch off
// (and its whole increase made with it on).
template <bool& (*Flag)(), std::size_t& (*Counter)()>
void switch_answers_equal(const CSpace& space, int count, std::uint64_t seed, SwitchCounts& counts) {
  std::mt19937_64 random(seed);
  const std::vector<std::size_t> edges = real_edges(space);
  for (int i = 0; i < count; ++i) {
    std::optional<GeneratedMotion> motion = generated_motion(space, edges, random);
    if (!motion) continue;
    const std::size_t before = Counter();
    std::size_t on_hits = 0;
    auto [with, without] = on_and_off<Flag>(random, [&](bool on) {
      const std::size_t start = Counter();
      std::string answer = crossing_answer(space, motion->path);
      if (on) on_hits = Counter() - start;
      else EXPECT_EQ(Counter(), start) << "the switch must turn it off";
      return answer;
    });
    ASSERT_EQ(with, without) << space.first_part() << ":" << space.second_part() << " motion " << i << " speed "
                             << motion->speed << " from (" << motion->x0 << ", " << motion->y0 << ") in chart "
                             << motion->chart;
    ASSERT_EQ(Counter() - before, on_hits);
    ++counts.motions;
    counts.hits += on_hits;
    if (with.rfind("status 1 ", 0) == 0) ++counts.crossing;
    else if (with.rfind("status 0 ", 0) == 0) ++counts.none;
    else ++counts.other;
  }
}

// switch_answers_equal on each of the example spaces (example_spaces()), seeds seed + 1, + 2, ...
template <bool& (*Flag)(), std::size_t& (*Counter)()>
void switch_answers_equal_on_examples(int count, std::uint64_t seed, SwitchCounts& counts) {
  for (const std::unique_ptr<CSpace>& space : example_spaces()) {
    switch_answers_equal<Flag, Counter>(*space, count, ++seed, counts);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace hipair::test
