// The contact zones of a tolerance analysis (ToleranceResult::zones, the paper's Figure 5)
// against exact contacts of the perturbed models (session 53, hunt53). For random rational
// parameter vectors in the tolerance box (corners and interior points), the model is read
// exactly at those values and its C-space built exactly (CSpace::build: the exact arrangement of
// the pair's contact curves); at each zone's abscissa (the chart coordinate the zone sampled,
// recomputed exactly as the analysis does) the 1-D slice's boundary points carrying the zone's
// feature pair are the exact contacts of that pair there. The one nearest the nominal value
// must lie in the zone's certified bounds [certified_lower, certified_upper] (its nearest double
// within one ulp, mapped to part coordinates, meets them): the zone claims to enclose the contact
// over the whole box. The contact must also exist (a contact curve of a zone's feature pair
// crosses the slice near the nominal point for every vector of these boxes).
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/tolerance.hpp>

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

namespace hipair {
namespace {

// The edge's abscissae as the analysis samples them (src/tolerance/analysis.cpp, zones()).
std::vector<double> zone_abscissae(const CSpaceEdge& edge, std::size_t samples) {
  std::vector<double> out;
  double x0 = edge.x_chart.lower, x1 = edge.x_chart.upper;
  for (std::size_t j = 0; j < samples; ++j) out.push_back(x0 + (x1 - x0) * (static_cast<double>(j) + 0.5) / static_cast<double>(samples));
  return out;
}

void expect_zones_hold_exact_contacts(const std::string& file, int vectors, std::uint64_t seed) {
  SCOPED_TRACE(file);
  const std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
  ToleranceOptions options;
  options.positions = 72;
  options.zone_samples = 5;
  options.threads = 1;
  ToleranceResult result = analyze_tolerances(path, options);
  ASSERT_FALSE(result.zones.empty());
  Model nominal = read_model_file(path);
  ASSERT_FALSE(nominal.pairs.empty());
  // the analysis' pair: the model pair holding the driver and the follower, in its order
  std::string first, second;
  for (const PairSpec& p : nominal.pairs) {
    const std::string& a = nominal.parts[p.first].name;
    const std::string& b = nominal.parts[p.second].name;
    if ((a == result.driver && b == result.follower) || (a == result.follower && b == result.driver)) {
      first = a;
      second = b;
      break;
    }
  }
  ASSERT_FALSE(first.empty());
  CSpace space = CSpace::build(nominal, first, second);
  // per zone: its feature pair and, per stored sample, the exact chart abscissa
  struct Sample {
    std::size_t zone, k;
    Rational x;
    bool x_half_turn, y_half_turn;
    AxisKind y_kind;
  };
  std::vector<Sample> samples;
  for (std::size_t z = 0; z < result.zones.size(); ++z) {
    const ContactZone& zone = result.zones[z];
    ASSERT_LT(zone.edge, space.edges().size());
    const CSpaceEdge& edge = space.edges()[zone.edge];
    ASSERT_FALSE(edge.curves.empty());
    ASSERT_EQ(space.feature_pair(FeatureId(edge.curves.front())).label, zone.contact) << "the nominal C-space differs";
    const CSpaceChart& chart = space.charts()[edge.chart];
    std::vector<double> xs = zone_abscissae(edge, options.zone_samples);
    for (std::size_t k = 0; k < zone.x.size(); ++k) {
      bool found = false;
      for (double xd : xs)
        if ((zone.x_rotates ? chart.x_to_coordinate(xd) : xd) == zone.x[k]) {
          samples.push_back(Sample{z, k, Rational(xd), chart.x_half_turn, chart.y_half_turn, chart.y_kind});
          found = true;
          break;
        }
      ASSERT_TRUE(found) << "zone " << z << " sample " << k;
    }
  }
  ASSERT_FALSE(samples.empty());
  // random parameter vectors of the box: its two extreme corners and random rational points
  std::mt19937_64 random(seed);
  int checked = 0;
  for (int v = 0; v < vectors; ++v) {
    ReadOptions read;
    for (const Parameter& p : nominal.parameters) {
      if (p.range.lo == p.range.hi) continue;
      Rational value;
      if (v == 0) value = p.range.lo;
      else if (v == 1) value = p.range.hi;
      else {
        long q = 1 + static_cast<long>(random() % 97);
        value = p.range.lo + Rational(static_cast<long>(random() % static_cast<unsigned long>(q + 1)), q) * (p.range.hi - p.range.lo);
      }
      value.canonicalize();
      read.parameter_values[p.name] = value;
    }
    SCOPED_TRACE("vector " + std::to_string(v));
    Model perturbed = read_model_file(path, read);
    CSpace exact = CSpace::build(perturbed, first, second);
    for (const Sample& s : samples) {
      const ContactZone& zone = result.zones[s.zone];
      const FeaturePair& want = space.feature_pair(FeatureId(space.edges()[zone.edge].curves.front()));
      double best_distance = INFINITY, best_lo = 0, best_hi = 0;
      for (const Slice& slice : exact.slice(SliceAxis::x, s.x)) {
        const CSpaceChart& chart = exact.charts()[slice.chart];
        if (chart.x_half_turn != s.x_half_turn || chart.y_half_turn != s.y_half_turn) continue;
        for (const Slice::Point& point : slice.points) {
          bool holds = false;
          for (FeatureId f : point.features) {
            const FeaturePair& fp = exact.feature_pair(f);
            holds = holds || (fp.first == want.first && fp.second == want.second);
          }
          if (!holds) continue;
          // the exact contact's ordinate: its nearest double, within one unit in the last place
          const double a = point.at.approximate();
          double lo = std::nextafter(a, -INFINITY), hi = std::nextafter(a, INFINITY);
          double ylo = zone.y_rotates ? chart.y_to_coordinate(lo) : lo;
          double yhi = zone.y_rotates ? chart.y_to_coordinate(hi) : hi;
          double mid = (ylo + yhi) / 2;
          double d = std::abs(mid - zone.nominal[s.k]);
          if (d < best_distance) best_distance = d, best_lo = ylo, best_hi = yhi;
        }
      }
      const double width = zone.certified_upper[s.k] - zone.certified_lower[s.k];
      ASSERT_LT(best_distance, 10 * width + 1e-9)
          << zone.contact << " at x = " << zone.x[s.k] << ": no exact contact of the zone's pair near the nominal " << zone.nominal[s.k] << " (nearest at distance "
          << best_distance << ", [" << best_lo << ", " << best_hi << "]; the zone [" << zone.certified_lower[s.k] << ", "
          << zone.certified_upper[s.k] << "], sample " << s.k << " of " << zone.x.size() << ")";
      // the exact contact's interval meets the zone's certified bounds (1e-12 relative: the
      // doubles of the chart-to-part map)
      const double slack = 1e-12 * (1 + std::abs(zone.nominal[s.k]));
      EXPECT_GE(best_hi, zone.certified_lower[s.k] - slack)
          << zone.contact << " at x = " << zone.x[s.k] << ": exact contact [" << best_lo << ", " << best_hi << "] below the zone ["
          << zone.certified_lower[s.k] << ", " << zone.certified_upper[s.k] << "]";
      EXPECT_LE(best_lo, zone.certified_upper[s.k] + slack)
          << zone.contact << " at x = " << zone.x[s.k] << ": exact contact [" << best_lo << ", " << best_hi << "] above the zone ["
          << zone.certified_lower[s.k] << ", " << zone.certified_upper[s.k] << "]";
      ++checked;
    }
  }
  EXPECT_GE(checked, vectors * static_cast<int>(samples.size()));
}

TEST(ToleranceZoneOracle, CamFollowerZonesHoldTheExactContactsOfTheBox) { expect_zones_hold_exact_contacts("cam-follower.json", 12, 53); }

TEST(ToleranceZoneOracle, ScotchYokeZonesHoldTheExactContactsOfTheBox) { expect_zones_hold_exact_contacts("scotch-yoke.json", 10, 54); }

TEST(ToleranceZoneOracle, GenevaZonesHoldTheExactContactsOfTheBox) { expect_zones_hold_exact_contacts("geneva.json", 3, 55); }

}  // namespace
}  // namespace hipair
