// The builder's chart-at-a-time input (PairInput::make_chart: a chart's curves are produced
// when the builder reaches it, so only one chart's curves are alive) gives the same C-space as
// the whole input, and the feature pairs are indexed by (first, second, type) in the order met.
#include "cspace/builder_impl.hpp"
#include "cspace_topology_compare.hpp"

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

namespace hipair::cspace {
namespace {

// 20y - k (coefficients[i][j] of x^i y^j)
IntegerPolynomial2 line(long k) {
  IntegerPolynomial2 f;
  f.coefficients = {{mpz_class(-k), mpz_class(20)}};
  return f;
}

// Horizontal lines 20y = k (k odd, inside the chart's y-range) with feature pairs drawn from
// a few keys, in a grid of translation tiles; the lines with k = 1 (mod 4) are contact lines
// (the kind flips across them), the others spurious, so every chart has real and spurious edges.
struct Grid {
  std::size_t columns = 3, rows = 2;
  std::vector<std::vector<ContactCurve>> curves;   // per chart
  std::vector<std::vector<long>> contact_k;        // per chart: the k of its contact lines
};

Grid random_grid(unsigned seed) {
  std::mt19937_64 random(seed);
  Grid grid;
  for (std::size_t c = 0; c < grid.columns * grid.rows; ++c) {
    const long row = static_cast<long>(c / grid.columns);
    grid.curves.emplace_back();
    grid.contact_k.emplace_back();
    for (long k = 20 * (row - 1) + 1; k < 20 * row; k += 2) {
      if (random() % 3 == 0) continue;
      ContactCurve curve;
      curve.polynomial = line(k);
      curve.first = FeatureRef{random() % 2, 0, random() % 3, FeatureKind::vertex};
      curve.second = FeatureRef{2, 0, random() % 2, FeatureKind::segment};
      curve.type = random() % 2 ? ContactType::vertex_segment : ContactType::segment_vertex;
      curve.label = "line " + std::to_string(k);
      grid.curves.back().push_back(std::move(curve));
      if (((k % 4) + 4) % 4 == 1) grid.contact_k.back().push_back(k);
    }
  }
  return grid;
}

ChartInput chart_of(const Grid& grid, std::size_t c) {
  ChartInput chart;
  const long column = static_cast<long>(c % grid.columns), row = static_cast<long>(c / grid.columns);
  chart.x_index = static_cast<std::size_t>(column);
  chart.y_index = static_cast<std::size_t>(row);
  chart.x = ChartAxis{ChartAxis::Kind::translation, false, Rational(column - 1), Rational(column)};
  chart.y = ChartAxis{ChartAxis::Kind::translation, false, Rational(row - 1), Rational(row)};
  chart.curves = grid.curves[c];
  // blocked where an odd number of the chart's contact lines lie below
  chart.classify = [lines = grid.contact_k[c]](const ChartPoint& q) {
    int below = 0;
    for (long k : lines) {
      Rational line(k, 20);
      if (line == q.y) return Overlap::touching;
      if (line < q.y) ++below;
    }
    return below % 2 == 1 ? Overlap::overlapping : Overlap::apart;
  };
  return chart;
}

PairInput pair_input() {
  PairInput input;
  input.first_part = input.x_part = "a";
  input.second_part = input.y_part = "b";
  input.part_names = {"a", "a'", "b"};
  return input;
}

using Key = std::tuple<std::size_t, std::size_t, std::size_t, FeatureKind, std::size_t, std::size_t, std::size_t,
                       FeatureKind, ContactKind>;

Key key_of(const FeaturePair& pair) {
  return {pair.first.part,  pair.first.loop,  pair.first.edge,  pair.first.kind, pair.second.part,
          pair.second.loop, pair.second.edge, pair.second.kind, pair.kind};
}

TEST(BuilderStreamed, ChartAtATimeGivesTheSameSpaceAsWholeInput) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    Grid grid = random_grid(seed);
    const std::size_t count = grid.columns * grid.rows;
    PairInput whole = pair_input();
    for (std::size_t c = 0; c < count; ++c) whole.charts.push_back(chart_of(grid, c));
    CSpace a = build_cspace(std::move(whole), {});

    PairInput streamed = pair_input();
    streamed.chart_count = count;
    std::vector<std::size_t> requested;
    streamed.make_chart = [&](std::size_t c, PairInput& building) {
      requested.push_back(c);
      building.curve_statistics.feature_pairs_considered += 1;
      return chart_of(grid, c);
    };
    CSpace b = build_cspace(std::move(streamed), {});

    std::vector<std::size_t> in_order(count);
    for (std::size_t c = 0; c < count; ++c) in_order[c] = c;
    EXPECT_EQ(requested, in_order) << "each chart once, in order";
    EXPECT_EQ(b.statistics().feature_pairs_considered, count) << "statistics added while streaming are reported";
    EXPECT_EQ(b.statistics().charts, count);

    ASSERT_EQ(a.feature_pairs().size(), b.feature_pairs().size()) << "seed " << seed;
    for (std::size_t i = 0; i < a.feature_pairs().size(); ++i)
      EXPECT_EQ(key_of(a.feature_pairs()[i]), key_of(b.feature_pairs()[i]));
    ASSERT_NO_FATAL_FAILURE(hipair::test::expect_same_topology(a, b, "seed " + std::to_string(seed)));
    // the oracle agrees with the located kind at random rational points of both
    std::mt19937_64 random(seed);
    for (int i = 0; i < 300; ++i) {
      std::size_t c = random() % count;
      const CSpaceChart& chart = a.charts()[c];
      Rational x = chart.x_lo + Rational(static_cast<long>(random() % 997) + 1, 999);
      Rational y = chart.y_lo + Rational(static_cast<long>(random() % 997) + 1, 999);
      Location la = a.locate(hipair::ChartPoint{c, x, y}), lb = b.locate(hipair::ChartPoint{c, x, y});
      EXPECT_EQ(la.kind, lb.kind);
      Overlap expected = chart_of(grid, c).classify(ChartPoint{x, y});
      if (la.kind == Location::Kind::free) EXPECT_EQ(expected, Overlap::apart);
      if (la.kind == Location::Kind::blocked) EXPECT_EQ(expected, Overlap::overlapping);
    }
  }
}

TEST(BuilderStreamed, FeaturePairsAreOnePerKeyInTheOrderMet) {
  for (unsigned seed = 11; seed <= 16; ++seed) {
    Grid grid = random_grid(seed);
    PairInput input = pair_input();
    for (std::size_t c = 0; c < grid.curves.size(); ++c) input.charts.push_back(chart_of(grid, c));
    CSpace space = build_cspace(std::move(input), {});
    // brute force: the distinct keys of the curves in chart order (every line crosses its
    // chart, so every curve is kept)
    std::vector<Key> expected;
    std::map<std::string, Key> label_key;   // per chart and label: its key
    for (std::size_t c = 0; c < grid.curves.size(); ++c)
      for (const ContactCurve& curve : grid.curves[c]) {
        Key key{curve.first.part,  curve.first.loop,  curve.first.edge,  curve.first.kind,        curve.second.part,
                curve.second.loop, curve.second.edge, curve.second.kind, public_kind(curve.type)};
        if (std::find(expected.begin(), expected.end(), key) == expected.end()) expected.push_back(key);
      }
    ASSERT_EQ(space.feature_pairs().size(), expected.size()) << "seed " << seed;
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(key_of(space.feature_pairs()[i]), expected[i]);
    // every edge inside a chart along a line carries exactly that line's feature pair
    std::size_t along = 0;
    for (const CSpaceEdge& edge : space.edges()) {
      if (edge.role == EdgeRole::seam || edge.role == EdgeRole::limit || edge.vertical) continue;
      ASSERT_EQ(edge.curves.size(), 1u);
      const double y = 0.5 * (edge.y_chart.lower + edge.y_chart.upper);
      const long k = std::lround(20 * y);
      const CSpaceChart& chart = space.charts()[edge.chart];
      const std::size_t c = static_cast<std::size_t>(std::lround(chart.x_lo.get_d()) + 1 +
                                                     static_cast<long>(grid.columns) * (std::lround(chart.y_lo.get_d()) + 1));
      const ContactCurve* line = nullptr;
      for (const ContactCurve& curve : grid.curves[c])
        if (curve.label == "line " + std::to_string(k)) line = &curve;
      ASSERT_NE(line, nullptr);
      Key key{line->first.part,  line->first.loop,  line->first.edge,  line->first.kind,        line->second.part,
              line->second.loop, line->second.edge, line->second.kind, public_kind(line->type)};
      EXPECT_EQ(key_of(space.feature_pairs()[edge.curves[0]]), key);
      ++along;
    }
    EXPECT_GT(along, 0u);
  }
}

}  // namespace
}  // namespace hipair::cspace
