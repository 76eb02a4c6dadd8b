// contact_frame_ranges (include/hipair/contact_frame_doubles.hpp, src/cspace/cspace_queries.cpp):
// CSpace::contact_frame at a configuration given by doubles, without rationals. The oracle is
// contact_frame itself at the part coordinates whose exact values are those doubles
// (PartCoordinate{kind, Rational(value)}): every answer (throws / none / the point's and the unit
// normal's enclosures, bound for bound) must be equal. Generated configurations on the example
// spaces (rotating and translating axes, 2-D and 1-D): whole-turn angles as the simulator makes
// them (tan(a/2), a half turn past 1e15), chart bounds as doubles and their neighbours (the chart
// tests at and next to a bound, on seam charts through -1/t), tiny and huge tangents (the
// quotient's fallback range), zero and -0, half turns, and a kind its axis refuses.
//
// Also: the simulator's runs with the route on and off side by side, bit for bit
// (switch simulation::frame_doubles(), src/simulation/frame_cache.hpp).
#include "cspace_test_support.hpp"
#include "simulation/frame_cache.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/contact_frame_doubles.hpp>
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair {
namespace {

std::string ranges_text(const std::array<CertifiedRange, 2>& point, const std::array<CertifiedRange, 2>& normal) {
  std::ostringstream out;
  for (const auto* ranges : {&point, &normal})
    for (const CertifiedRange& r : *ranges) out << " [" << test::bits_of(r.lower) << ", " << test::bits_of(r.upper) << "]";
  return out.str();
}

std::string oracle_text(const CSpace& space, FeatureId f, const DoubleCoordinate& x, const DoubleCoordinate& y) {
  auto part = [](const DoubleCoordinate& d) {
    return PartCoordinate{d.kind, d.kind == PartCoordinate::Kind::half_turn ? Rational(0) : Rational(d.value)};
  };
  std::optional<Contact> c;
  try {
    c = space.contact_frame(f, part(x), part(y));
  } catch (const GeometryError& e) {
    return std::string("throws ") + e.what();
  }
  if (!c) return "none";
  return ranges_text(c->point_range, c->normal);
}

std::string doubles_text(const CSpace& space, FeatureId f, const DoubleCoordinate& x, const DoubleCoordinate& y) {
  std::optional<FrameRanges> r;
  try {
    r = contact_frame_ranges(space, f, x, y);
  } catch (const GeometryError& e) {
    return std::string("throws ") + e.what();
  }
  if (!r) return "none";
  return ranges_text(r->point_range, r->normal);
}

// A double near a chart value v of a chart axis: v itself, or a neighbour a few ulps off.
double near(double v, std::mt19937_64& random) {
  int steps = static_cast<int>(random() % 7) - 3;
  for (; steps > 0; --steps) v = std::nextafter(v, std::numeric_limits<double>::infinity());
  for (; steps < 0; ++steps) v = std::nextafter(v, -std::numeric_limits<double>::infinity());
  return v;
}

// A part coordinate (as the simulator makes it) for an axis of `kind` of `space`'s charts.
DoubleCoordinate generated(const CSpace& space, bool y_axis, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const CSpaceChart& chart = charts[random() % charts.size()];
  const AxisKind kind = y_axis ? chart.y_kind : chart.x_kind;
  const bool half_turn = y_axis ? chart.y_half_turn : chart.x_half_turn;
  const Rational& lo = y_axis ? chart.y_lo : chart.x_lo;
  const Rational& hi = y_axis ? chart.y_hi : chart.x_hi;
  DoubleCoordinate c;
  const unsigned pick = random() % 10;
  if (kind == AxisKind::translation) {
    c.kind = PartCoordinate::Kind::offset;
    if (pick == 9) {   // a kind the axis refuses: contact_frame throws
      c.kind = PartCoordinate::Kind::half_angle_tangent;
      c.value = unit(random);
    } else if (pick < 4) {
      c.value = near((random() % 2 ? lo : hi).get_d(), random);
    } else if (pick == 4) {
      c.value = random() % 2 ? 0.0 : -0.0;
    } else {
      const double a = lo.get_d(), b = hi.get_d();
      c.value = a + (b - a) * (0.5 + 0.6 * unit(random));
    }
    return c;
  }
  c.kind = PartCoordinate::Kind::half_angle_tangent;
  if (pick < 4) {
    // at or next to a bound; on a half-turn chart the bound is -1/t: t = -1/bound
    double b = (random() % 2 ? lo : hi).get_d();
    if (half_turn) b = b == 0 ? 1e300 : -1 / b;
    c.value = near(b, random);
  } else if (pick == 4) {
    c.value = random() % 2 ? 0.0 : -0.0;
  } else if (pick == 5) {
    c.value = std::ldexp(unit(random), static_cast<int>(random() % 1200) - 600);   // tiny and huge tangents
  } else if (pick == 6) {
    c.kind = PartCoordinate::Kind::half_turn;
  } else if (pick == 7 && random() % 4 == 0) {
    c.kind = PartCoordinate::Kind::offset;   // refused by a rotation axis
    c.value = unit(random);
  } else {
    // the simulator's coordinate: tan of half the angle, a half turn past 1e15
    const double a = std::remainder(4 * std::numbers::pi * unit(random), 2 * std::numbers::pi);
    const double t = std::tan(a / 2);
    if (!std::isfinite(t) || std::abs(t) > 1e15) c.kind = PartCoordinate::Kind::half_turn;
    else c.value = t;
  }
  return c;
}

TEST(CSpaceFrameDoubles, RangesEqualContactFrameAtTheSameRationals) {
  std::mt19937_64 random(20261203);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  const std::size_t fallbacks_before = contact_frame_ranges_fallbacks();
  std::size_t compared = 0, defined = 0, thrown = 0, mismatches = 0;
  for (int query = 0; query < 6000; ++query) {
    const CSpace& space = *spaces[random() % spaces.size()];
    const DoubleCoordinate x = generated(space, false, random);
    const DoubleCoordinate y = space.dimension() == 2 ? generated(space, true, random) : DoubleCoordinate{};
    for (int k = 0; k < 4; ++k) {
      FeatureId f(random() % space.feature_pairs().size());
      const std::string oracle = oracle_text(space, f, x, y);
      const std::string fast = doubles_text(space, f, x, y);
      if (fast != oracle && ++mismatches <= 3)
        ADD_FAILURE() << "query " << query << " feature " << f.index() << " x kind " << static_cast<int>(x.kind) << " "
                      << test::bits_of(x.value) << " y kind " << static_cast<int>(y.kind) << " "
                      << test::bits_of(y.value) << ": '" << fast << "' against '" << oracle << "'";
      ++compared;
      if (oracle.rfind(" [", 0) == 0) ++defined;
      if (oracle.rfind("throws", 0) == 0) ++thrown;
    }
  }
  const std::size_t fallbacks = contact_frame_ranges_fallbacks() - fallbacks_before;
  std::printf("frame doubles: %zu answers, %zu differ (%zu frames, %zu throws); %zu answered by contact_frame\n",
              compared, mismatches, defined, thrown, fallbacks);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(defined, compared / 4);
  EXPECT_GT(thrown, 0u);
  EXPECT_LT(fallbacks, compared / 4);
}

TEST(CSpaceFrameDoubles, SimulationRunsEqualTheRunsWithoutIt) {
  const std::size_t misses_before = simulation::frame_cache_misses(), fallbacks_before = contact_frame_ranges_fallbacks();
  const test::SideBySide total =
      test::runs_side_by_side<simulation::frame_doubles>(HIPAIR_EXAMPLES,
                                                         {{"escapement.json", 0.5, 1e-3},
                                                          {"escapement.json", 0.1, 1e-6},
                                                          {"ratchet.json", 0.2, 1e-6},
                                                          {"cam-follower.json", 0.3, 1e-6},
                                                          {"scotch-yoke.json", 0.3, 1e-6}},
                                                         100000);
  const std::size_t steps = total.steps, events = total.events;
  // frames made (the runs with the route and without it alike: half each), and how many of the
  // route's were answered by contact_frame
  const std::size_t made = simulation::frame_cache_misses() - misses_before;
  const std::size_t fallbacks = contact_frame_ranges_fallbacks() - fallbacks_before;
  std::printf("frame doubles: %zu steps, %zu events equal; %zu frames made by the route, %zu of them by contact_frame\n",
              steps, events, made / 2, fallbacks);
  EXPECT_GT(made / 2, 1000u);
  EXPECT_LT(fallbacks, made / 20);
  EXPECT_GT(events, 50u);
}

}  // namespace
}  // namespace hipair
