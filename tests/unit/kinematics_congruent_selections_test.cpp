// Two caches of the kernel slicer (session 16), each checked against the uncached computation
// on generated cases:
//  - OraclePairOverlap: cspace::PairOverlap (both parts' body enclosures, the second part's
//    placement and exact edges prepared once) gives classify_overlap's answer at generated
//    rational chart points of generated gear pairs and of the examples' pairs.
//  - KernelSlicerCongruent: slicers sharing a SelectionMemo reuse the feature-pair selection of
//    an exactly congruent pair (a translate of it: equal CurveGenerator::congruence_key). On
//    generated gear pairs and a translated copy of each (a random rational shift), the copy's
//    slices with the shared selection equal its slices with its own cull; a pair that is not
//    congruent (the copy with its second gear moved 1/2 mm farther) shares nothing and keeps its own
//    slices. And generate_selected(select()) is generate(), curve for curve. Since session 23
//    the memo shares whole strips too: the copy's features (labels, kinds, feature pairs of its
//    own parts) equal those of its own generation.
#include "kinematics/slice.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// The example's spur-gear pair with the given teeth.
Model gear_pair(int teeth_1, int teeth_2) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(teeth_1);
  read.parameter_values["teeth-2"] = Rational(teeth_2);
  read.allow_out_of_tolerance = true;
  return read_model_file(example("spur-gears.json"), read);
}

Point shifted(const Point& p, const Point& by) { return Point{Rational(p.x + by.x), Rational(p.y + by.y)}; }

// Appends a copy of the parts of pair `pair` translated by `by` (the second part by `by` +
// `extra`), and a pair of the two copies; returns its index.
std::size_t add_translated_copy(Model& model, std::size_t pair, const Point& by, const Point& extra, const std::string& tag) {
  const PairSpec spec = model.pairs.at(pair);
  std::size_t first_index = model.parts.size();
  for (std::size_t side = 0; side < 2; ++side) {
    Part part = model.parts.at(side == 0 ? spec.first : spec.second);
    Point move = side == 0 ? by : shifted(by, extra);
    part.name += tag;
    for (Loop& loop : part.loops)
      for (Edge& edge : loop.edges) {
        edge.source = shifted(edge.source, move);
        edge.target = shifted(edge.target, move);
        if (edge.is_arc()) edge.center = shifted(edge.center, move);
      }
    part.motion.pivot = shifted(part.motion.pivot, move);
    model.parts.push_back(std::move(part));
  }
  PairSpec copy;
  copy.first = first_index;
  copy.second = first_index + 1;
  model.pairs.push_back(copy);
  return model.pairs.size() - 1;
}

Rational random_in(const ChartAxis& axis, std::mt19937_64& random) {
  Rational u(static_cast<long>(random() % (1u << 20)), 1L << 20);
  u.canonicalize();
  return Rational(axis.lo + (axis.hi - axis.lo) * u);
}

// Slices a and b agree: the same points (exact values), features, zero-clearance flags and
// interval classes.
void expect_equal(const ChartSlice& a, const ChartSlice& b, const std::string& where) {
  ASSERT_EQ(a.covered_lo, b.covered_lo) << where;
  ASSERT_EQ(a.covered_hi, b.covered_hi) << where;
  ASSERT_EQ(a.points.size(), b.points.size()) << where;
  ASSERT_EQ(a.kinds, b.kinds) << where;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(algebra::compare(a.points[i].value, b.points[i].value), 0) << where << ": point " << i;
    EXPECT_EQ(a.points[i].features, b.points[i].features) << where << ": point " << i;
    EXPECT_EQ(a.points[i].touching, b.points[i].touching) << where << ": point " << i;
  }
}

TEST(OraclePairOverlap, PreparedPartsClassifyAsTheOracleOnGeneratedPoses) {
  std::mt19937_64 random(20261129);
  std::vector<Model> models;
  for (int k = 0; k < 3; ++k) models.push_back(gear_pair(7 + static_cast<int>(random() % 7), 7 + static_cast<int>(random() % 9)));
  for (const char* file : {"geneva.json", "ratchet.json", "cam-follower.json", "scotch-yoke.json", "gear-train.json"})
    models.push_back(read_model_file(example(file)));
  std::size_t counts[3] = {0, 0, 0};
  for (const Model& model : models)
    for (std::size_t p = 0; p < model.pairs.size() && p < 3; ++p) {
      cspace::PairAxes axes;
      try {
        axes = cspace::pair_axes(model, model.pairs[p].first, model.pairs[p].second);
      } catch (const GeometryError&) {
        continue;
      }
      cspace::ChartLayout layout = cspace::chart_layout(model, axes);
      cspace::PairOverlap prepared(model, axes);
      ChartAxis none{ChartAxis::Kind::translation, false, Rational(0), Rational(0)};
      for (std::size_t i = 0; i < layout.x_charts.size(); ++i)
        for (std::size_t j = 0; j < std::max<std::size_t>(1, layout.y_charts.size()); ++j)
          for (int k = 0; k < 40; ++k) {
            const ChartAxis& x = layout.x_charts[i];
            const ChartAxis& y = layout.y_charts.empty() ? none : layout.y_charts[j];
            cspace::ChartPoint q;
            q.x = random_in(x, random);
            q.y = layout.y_charts.empty() ? Rational(0) : random_in(y, random);
            cspace::Overlap expected = cspace::classify_overlap(model, axes, x, y, q);
            ASSERT_EQ(prepared.classify(x, y, q), expected)
                << model.name << " pair " << p << " at " << q.x.get_str() << ", " << q.y.get_str();
            ++counts[static_cast<int>(expected)];
          }
    }
  // the generated poses meet every verdict but touching (a measure-zero set) often
  EXPECT_GT(counts[static_cast<int>(cspace::Overlap::apart)], 100u);
  EXPECT_GT(counts[static_cast<int>(cspace::Overlap::overlapping)], 100u);
}

// Touching configurations: the exact rational points of kernel slices (a zero-clearance fit's
// walls), classified by both at (value, point) and (point, value).
TEST(OraclePairOverlap, PreparedPartsClassifyAsTheOracleAtSlicePoints) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "zero-clearance/scotch-yoke-exact-fit.json");
  std::mt19937_64 random(5);
  std::size_t touching = 0, compared = 0;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    cspace::PairAxes axes = cspace::pair_axes(model, model.pairs[p].first, model.pairs[p].second);
    cspace::ChartLayout layout = cspace::chart_layout(model, axes);
    cspace::PairOverlap prepared(model, axes);
    for (std::size_t follower : {model.pairs[p].first, model.pairs[p].second}) {
      std::unique_ptr<PairSlicer> slicer;
      try {
        slicer = make_kernel_slicer(model, p, follower);
      } catch (const GeometryError&) {
        continue;
      }
      for (std::size_t o = 0; o < std::max<std::size_t>(1, slicer->other_charts().size()); ++o)
        for (std::size_t f = 0; f < slicer->follower_charts().size(); ++f)
          for (int k = 0; k < 10; ++k) {
            Rational value = slicer->other_moves() ? random_in(slicer->other_charts()[o], random) : Rational(0);
            ChartSlice slice = slicer->slice(o, value, f);
            for (const SlicePoint& point : slice.points) {
              if (!point.value.exact) continue;
              for (std::size_t i = 0; i < layout.x_charts.size(); ++i)
                for (std::size_t j = 0; j < std::max<std::size_t>(1, layout.y_charts.size()); ++j) {
                  ChartAxis none{ChartAxis::Kind::translation, false, Rational(0), Rational(0)};
                  const ChartAxis& x = layout.x_charts[i];
                  const ChartAxis& y = layout.y_charts.empty() ? none : layout.y_charts[j];
                  for (bool swap : {false, true}) {
                    cspace::ChartPoint q;
                    q.x = swap ? value : point.value.lower;
                    q.y = layout.y_charts.empty() ? Rational(0) : (swap ? point.value.lower : value);
                    cspace::Overlap expected = cspace::classify_overlap(model, axes, x, y, q);
                    ASSERT_EQ(prepared.classify(x, y, q), expected)
                        << "pair " << p << " at " << q.x.get_str() << ", " << q.y.get_str();
                    touching += expected == cspace::Overlap::touching;
                    ++compared;
                  }
                }
            }
          }
    }
  }
  EXPECT_GT(compared, 0u);
  EXPECT_GT(touching, 0u);
}

TEST(KernelSlicerCongruent, TranslatedGearPairsShareSelectionsWithTheSameSlices) {
  std::mt19937_64 random(1129);
  for (int trial = 0; trial < 2; ++trial) {
    Model model = gear_pair(7 + static_cast<int>(random() % 5), 8 + static_cast<int>(random() % 6));
    auto coordinate = [&] {
      Rational r(static_cast<long>(random() % 20001) - 10000, static_cast<long>(1 + random() % 97));
      r.canonicalize();
      return r;
    };
    const Point by{coordinate(), coordinate()};
    const std::size_t copy = add_translated_copy(model, 0, by, Point{Rational(0), Rational(0)}, "'");
    const std::size_t moved = add_translated_copy(model, 0, by, Point{Rational(1, 2), Rational(0)}, "''");
    auto memo = std::make_shared<SelectionMemo>();
    KernelSlicerOptions shared;
    shared.selections = memo;
    auto original = make_kernel_slicer(model, 0, model.pairs[0].second, shared);
    auto copy_shared = make_kernel_slicer(model, copy, model.pairs[copy].second, shared);
    auto copy_own = make_kernel_slicer(model, copy, model.pairs[copy].second, KernelSlicerOptions{});
    auto moved_shared = make_kernel_slicer(model, moved, model.pairs[moved].second, shared);
    auto moved_own = make_kernel_slicer(model, moved, model.pairs[moved].second, KernelSlicerOptions{});
    std::size_t points = 0;
    std::set<std::pair<std::size_t, std::size_t>> first_slices;
    for (int k = 0; k < 5; ++k) {
      const std::size_t o = random() % original->other_charts().size();
      const std::size_t f = random() % original->follower_charts().size();
      const Rational value = random_in(original->other_charts()[o], random);
      const std::string where = "trial " + std::to_string(trial) + " charts " + std::to_string(o) + "," +
                                std::to_string(f) + " at " + value.get_str();
      original->slice(o, value, f);   // the original pair's selections first
      const std::size_t taken = memo->hits() + memo->strip_hits();
      ChartSlice a = copy_own->slice(o, value, f);
      ChartSlice b = copy_shared->slice(o, value, f);
      expect_equal(a, b, "copy " + where);
      points += a.points.size();
      // the copy's first slice of a chart pair takes what the original just built there (a
      // selection or the whole strip); later slices of the pair may find their strip taken already
      if (first_slices.insert({o, f}).second) EXPECT_GT(memo->hits() + memo->strip_hits(), taken) << where;
      for (const SlicePoint& point : b.points)
        for (std::size_t feature : point.features) {
          ASSERT_LT(feature, copy_shared->features().size());
          EXPECT_EQ(copy_shared->features()[feature].label, copy_own->features()[feature].label);
          const IntegerPolynomial2* p = copy_shared->polynomial(o, f, feature);
          const IntegerPolynomial2* q = copy_own->polynomial(o, f, feature);
          ASSERT_NE(p, nullptr);
          ASSERT_NE(q, nullptr);
          EXPECT_EQ(p->coefficients, q->coefficients) << where;
        }
      const std::size_t selection_hits = memo->hits(), strip_hits = memo->strip_hits();
      expect_equal(moved_own->slice(o, value, f), moved_shared->slice(o, value, f), "moved " + where);
      EXPECT_EQ(memo->hits(), selection_hits) << "moved " << where;
      EXPECT_EQ(memo->strip_hits(), strip_hits) << "moved " << where;
      for (const SlicePoint& point : moved_shared->slice(o, value, f).points)
        for (std::size_t feature : point.features) {
          const ContactFeature& a = moved_shared->features().at(feature);
          const ContactFeature& b = moved_own->features().at(feature);
          EXPECT_EQ(a.label, b.label) << "moved " << where;
          EXPECT_TRUE(a.first == b.first && a.second == b.second) << "moved " << where;
        }
    }
    EXPECT_GT(points, 0u);
    // the copy took the original's whole strips (session 23: the strips' curves, cells and the
    // labels written for the copy's own parts), the moved pair none
    // (a strip taken whole takes its selection with it: no separate selection hit)
    EXPECT_GT(memo->strip_hits(), 0u) << "trial " << trial;
    for (std::size_t feature = 0; feature < copy_own->features().size(); ++feature) {
      if (copy_own->features()[feature].label.empty()) continue;
      ASSERT_LT(feature, copy_shared->features().size()) << "trial " << trial;
      const ContactFeature& a = copy_shared->features()[feature];
      const ContactFeature& b = copy_own->features()[feature];
      EXPECT_EQ(a.label, b.label) << "trial " << trial << " feature " << feature;
      EXPECT_EQ(a.kind, b.kind) << "trial " << trial << " feature " << feature;
      EXPECT_TRUE(a.first == b.first && a.second == b.second) << "trial " << trial << " feature " << feature;
    }
  }
}

TEST(KernelSlicerCongruent, CongruenceKeysOfTheGearTrainAndSelectedGeneration) {
  Model model = read_model_file(example("gear-train.json"));
  ASSERT_GE(model.pairs.size(), 3u);
  std::vector<std::string> keys;
  std::vector<std::unique_ptr<cspace::CurveGenerator>> generators;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    cspace::PairAxes axes = cspace::pair_axes(model, model.pairs[p].first, model.pairs[p].second);
    generators.push_back(std::make_unique<cspace::CurveGenerator>(model, axes));
    keys.push_back(generators.back()->congruence_key());
    EXPECT_FALSE(keys.back().empty());
  }
  // The idler train's meshes: 10 x 12 and 12 x 10 teeth alternate, so no mesh is a translate of
  // its neighbour; the teeth's phases make A:B, B:C, C:D distinct (C's boundary starts half a
  // turn from A's), and each later mesh is a translate of an earlier one (D:E of B:C, ...).
  for (std::size_t p = 0; p + 1 < keys.size(); ++p) EXPECT_FALSE(keys[p] == keys[p + 1]) << "pairs " << p << ", " << p + 1;
  EXPECT_FALSE(keys[0] == keys[2]);
  std::size_t translates = 0;
  for (std::size_t p = 0; p < keys.size(); ++p)
    for (std::size_t q = 0; q < p; ++q)
      if (keys[p] == keys[q]) {
        ++translates;
        break;
      }
  EXPECT_EQ(translates, keys.size() - 3);
  // generate_selected(select()) is generate(), curve for curve, on generated strips
  std::mt19937_64 random(31);
  cspace::PairAxes axes = cspace::pair_axes(model, model.pairs[0].first, model.pairs[0].second);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  for (int k = 0; k < 3; ++k) {
    ChartAxis x = layout.x_charts[random() % layout.x_charts.size()];
    const ChartAxis y = layout.y_charts[random() % layout.y_charts.size()];
    const int cell = static_cast<int>(random() % 64);
    const Rational lo = x.lo, width = Rational(x.hi - x.lo);
    x.lo = lo + width * cell / 64;
    x.hi = lo + width * (cell + 1) / 64;
    std::vector<cspace::ContactCurve> direct = generators[0]->generate(x, y);
    std::vector<cspace::ContactCurve> selected = generators[0]->generate_selected(x, y, generators[0]->select(x, y));
    ASSERT_EQ(direct.size(), selected.size());
    EXPECT_GT(direct.size(), 0u);
    for (std::size_t i = 0; i < direct.size(); ++i) {
      EXPECT_EQ(direct[i].label, selected[i].label);
      EXPECT_EQ(direct[i].polynomial.coefficients, selected[i].polynomial.coefficients);
      EXPECT_EQ(direct[i].validity.size(), selected[i].validity.size());
    }
  }
}

}  // namespace
}  // namespace hipair::kinematics_detail
