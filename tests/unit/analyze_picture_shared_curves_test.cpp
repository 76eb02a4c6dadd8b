// `hipair analyze` draws each pair's C-space after its analysis, with the contact curves the
// analysis's kernel slicers formed (hipair::SharedContactCurves): the curves and the pictures
// must be those of a fresh build, on every example model and on generated parameter sets.
#include "curves/contact_curves.hpp"
#include "render/cspace_svg.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/shared_curves.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

// The picture `hipair analyze` draws for a pair's path over a whole exact space (pairs of up to
// 120 boundary edges), with the path on it; nullopt when the builder refuses the pair.
std::optional<std::string> picture(const Model& model, const PairPath& path) {
  try {
    CSpace space = CSpace::build(model, path.x_part, path.y_part);
    render::CSpaceSvgOptions options;
    for (const PathPoint& point : path.points) options.path.push_back({point.x, point.y, point.contact});
    options.title = "exact C-space of " + path.pair + " with the motion path";
    return render::cspace_svg(space, options);
  } catch (const GeometryError&) {
  } catch (const NumericError&) {
  }
  return std::nullopt;
}

std::size_t boundary_edges(const Model& model, const PairPath& path) {
  std::size_t edges = 0;
  for (const std::string& name : {path.x_part, path.y_part})
    if (auto part = model.find_part(name))
      for (const Loop& loop : model.parts[*part].loops) edges += loop.edges.size();
  return edges;
}

struct Outcome {
  std::size_t pictures = 0;   // pictures compared
  std::size_t reused = 0;     // curves the pictures took from the analysis
};

// The analysis (a part of a turn) and then every pair's picture with the analysis's curves
// shared, each against the picture of a fresh build outside any sharing.
Outcome compare_pictures(const Model& model, const std::string& what) {
  Outcome outcome;
  KinematicsOptions options;
  options.cycles = Rational(1, 3);
  options.steps_per_cycle = 180;
  options.reversal = false;
  std::vector<PairPath> paths;
  std::vector<std::optional<std::string>> shared;
  {
    SharedContactCurves scope;
    KinematicsResult result;
    try {
      result = analyze_kinematics(model, options);
    } catch (const Error& error) {
      ADD_FAILURE() << what << ": the analysis failed: " << error.what();
      return outcome;
    }
    for (const PairPath& path : result.paths) {
      if (path.y_part.empty() || boundary_edges(model, path) > 120) continue;
      paths.push_back(path);
      shared.push_back(picture(model, path));
    }
    outcome.reused = scope.reused();
  }
  for (std::size_t k = 0; k < paths.size(); ++k) {
    std::optional<std::string> fresh = picture(model, paths[k]);
    EXPECT_EQ(fresh.has_value(), shared[k].has_value()) << what << " " << paths[k].pair;
    if (!fresh || !shared[k]) continue;
    EXPECT_EQ(*fresh, *shared[k]) << what << " " << paths[k].pair << ": the picture from shared curves differs";
    ++outcome.pictures;
  }
  return outcome;
}

TEST(AnalyzePictureSharedCurves, PicturesEqualFreshBuildsOnEveryExample) {
  std::size_t pictures = 0;
  for (const char* name : {"geneva.json", "ratchet.json", "escapement.json", "cam-follower.json",
                           "cam-follower-lever.json", "cam-drive.json", "scotch-yoke.json", "two-pin-wedge.json",
                           "lift-chain.json", "geneva-drive.json", "geneva-template.json", "cam-shim-stack.json"}) {
    std::filesystem::path file = example(name);
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " missing";
    Model model = read_model_file(file);
    Outcome outcome = compare_pictures(model, name);
    pictures += outcome.pictures;
    if (std::string(name) == "geneva.json" || std::string(name) == "ratchet.json") {
      EXPECT_EQ(outcome.pictures, 1u) << name;
      // (the analysis's third of a turn forms ≈ 180 of Geneva's curves, ≈ 45 of the ratchet's)
      // (Geneva: 70 since the initial state slices windows, session 35: fewer strip curves formed)
      EXPECT_GT(outcome.reused, std::string(name) == "geneva.json" ? 50u : 20u) << name << ": the picture formed its curves again";
    }
  }
  EXPECT_GE(pictures, 10u);
}

// Parameter sets drawn inside the tolerances (random rationals), each analysed and drawn with
// shared curves against fresh builds; and one process holding several of them at once: a
// generator never takes the curves of a different model.
TEST(AnalyzePictureSharedCurves, PicturesEqualFreshBuildsOnGeneratedParameterSets) {
  std::mt19937_64 random(20261201);
  struct Varied {
    const char* model;
    std::vector<const char*> parameters;
  };
  for (const Varied& varied : {Varied{"geneva.json", {"pin-radius", "pin-center", "outer-arc-radius"}},
                               Varied{"ratchet.json", {"tip-radius", "root-radius", "nose-clearance"}}}) {
    std::filesystem::path file = example(varied.model);
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " missing";
    Model nominal = read_model_file(file);
    for (int set = 0; set < 3; ++set) {
      ReadOptions read;
      std::string what = varied.model;
      for (const char* name : varied.parameters) {
        const Parameter* parameter = nominal.find_parameter(name);
        ASSERT_NE(parameter, nullptr) << name;
        ASSERT_LT(parameter->range.lo, parameter->range.hi) << name;
        // lo + (hi - lo) k/1000, k in [0, 1000]
        long k = std::uniform_int_distribution<long>(0, 1000)(random);
        Rational value = parameter->range.lo + (parameter->range.hi - parameter->range.lo) * Rational(k, 1000);
        read.parameter_values[name] = value;
        what += std::string(" ") + name + "=" + value.get_str();
      }
      Model model = read_model_file(file, read);
      Outcome outcome = compare_pictures(model, what);
      EXPECT_EQ(outcome.pictures, 1u) << what;
      EXPECT_GT(outcome.reused, std::string(varied.model) == "geneva.json" ? 50u : 20u) << what;
    }
  }
}

// The curves a generator takes from the scope are those it would form: every chart of Geneva
// and the ratchet, generated fresh, then by two generators in one scope (the second takes the
// first one's), curve for curve (polynomial, validity, corner-entry atoms, label, features).
// Without a scope, or for another model or pair, nothing is taken.
TEST(AnalyzePictureSharedCurves, SharedCurvesAreTheCurvesAGeneratorForms) {
  using namespace cspace;
  auto same = [](const std::vector<ContactCurve>& a, const std::vector<ContactCurve>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k) {
      const ContactCurve &p = a[k], &q = b[k];
      if (!(p.first == q.first) || !(p.second == q.second) || p.type != q.type || p.label != q.label ||
          p.blocked_sign != q.blocked_sign || !(p.polynomial.coefficients == q.polynomial.coefficients) ||
          p.validity.size() != q.validity.size() || p.corner_entry.size() != q.corner_entry.size())
        return false;
      for (std::size_t c = 0; c < p.validity.size(); ++c) {
        if (p.validity[c].atoms.size() != q.validity[c].atoms.size()) return false;
        for (std::size_t i = 0; i < p.validity[c].atoms.size(); ++i)
          if (!(p.validity[c].atoms[i].coefficients == q.validity[c].atoms[i].coefficients)) return false;
      }
      for (std::size_t c = 0; c < p.corner_entry.size(); ++c)
        if (!(p.corner_entry[c].coefficients == q.corner_entry[c].coefficients)) return false;
    }
    return true;
  };
  for (const char* name : {"geneva.json", "ratchet.json"}) {
    std::filesystem::path file = example(name);
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " missing";
    Model model = read_model_file(file);
    ASSERT_FALSE(model.pairs.empty());
    PairAxes axes = pair_axes(model, model.pairs[0].first, model.pairs[0].second);
    ChartLayout layout = chart_layout(model, axes);
    ASSERT_EQ(axes.dimension(), 2);
    std::vector<std::vector<ContactCurve>> fresh;
    {
      CurveGenerator generator(model, axes);
      for (const ChartAxis& x : layout.x_charts)
        for (const ChartAxis& y : layout.y_charts) fresh.push_back(generator.generate(x, y));
    }
    std::size_t curves = 0;
    for (const auto& chart : fresh) curves += chart.size();
    ASSERT_GT(curves, 20u) << name;
    {
      // without a scope nothing is shared
      CurveGenerator first(model, axes), second(model, axes);
      for (const ChartAxis& x : layout.x_charts)
        for (const ChartAxis& y : layout.y_charts) first.generate(x, y);
      std::size_t k = 0;
      for (const ChartAxis& x : layout.x_charts)
        for (const ChartAxis& y : layout.y_charts) EXPECT_TRUE(same(second.generate(x, y), fresh[k++])) << name;
    }
    SharedContactCurves scope;
    // a copy of the model (equal, another object): the same group
    Model copy = model;
    CurveGenerator first(model, axes), second(copy, axes);
    // the first generator forms the curves on the charts' halves (other boxes, the same curves)
    for (const ChartAxis& x : layout.x_charts)
      for (const ChartAxis& y : layout.y_charts) {
        ChartAxis half = x;
        half.hi = (x.lo + x.hi) / 2;
        first.generate(half, y);
      }
    std::size_t before = scope.reused();
    std::size_t k = 0;
    for (const ChartAxis& x : layout.x_charts)
      for (const ChartAxis& y : layout.y_charts) EXPECT_TRUE(same(second.generate(x, y), fresh[k++])) << name;
    EXPECT_GT(scope.reused(), before) << name;
    EXPECT_EQ(scope.groups(), 1u) << name;
    // another pair order and another blocked-space setting are other groups, each its own curves
    PairAxes swapped = pair_axes(model, model.pairs[0].second, model.pairs[0].first);
    CurveGenerator other_pair(model, swapped);
    CurveOptions no_cull;
    no_cull.cull_blocked_space = false;
    CurveGenerator other_setting(model, axes, no_cull);
    EXPECT_EQ(scope.groups(), 3u) << name;
    std::size_t reused = scope.reused();
    ChartLayout swapped_layout = chart_layout(model, swapped);
    std::size_t swapped_curves = other_pair.generate(swapped_layout.x_charts[0], swapped_layout.y_charts[0]).size();
    EXPECT_EQ(scope.reused(), reused) << name;
    // (a generator made by generate_contact_curves in the scope takes other_pair's curves)
    EXPECT_EQ(swapped_curves,
              generate_contact_curves(model, swapped, swapped_layout.x_charts[0], swapped_layout.y_charts[0]).size());
    EXPECT_GT(scope.reused(), reused) << name;
  }
  // a changed model is another group
  Model geneva = read_model_file(example("geneva.json"));
  ReadOptions read;
  read.parameter_values["pin-radius"] = Rational(451, 100);
  Model changed = read_model_file(example("geneva.json"), read);
  SharedContactCurves scope;
  PairAxes axes = pair_axes(geneva, geneva.pairs[0].first, geneva.pairs[0].second);
  ChartLayout layout = chart_layout(geneva, axes);
  CurveGenerator first(geneva, axes);
  first.generate(layout.x_charts[0], layout.y_charts[0]);
  CurveGenerator second(changed, axes);
  std::vector<ContactCurve> curves = second.generate(layout.x_charts[0], layout.y_charts[0]);
  EXPECT_EQ(scope.groups(), 2u);
  EXPECT_EQ(scope.reused(), 0u);
  EXPECT_TRUE(same(curves, generate_contact_curves(changed, axes, layout.x_charts[0], layout.y_charts[0])));
  // nested scopes: the innermost serves, and they may end in any order
  auto outer = std::make_unique<SharedContactCurves>();
  auto inner = std::make_unique<SharedContactCurves>();
  CurveGenerator(geneva, axes).generate(layout.x_charts[0], layout.y_charts[0]);
  EXPECT_EQ(inner->groups(), 1u);
  EXPECT_EQ(outer->groups(), 0u);
  outer.reset();   // not the innermost: unlinked from the chain
  CurveGenerator(geneva, axes).generate(layout.x_charts[0], layout.y_charts[0]);
  EXPECT_EQ(inner->groups(), 1u);
  EXPECT_GT(inner->reused(), 0u);
  inner.reset();   // back to `scope`, made first in this test
  std::size_t before = scope.reused();
  CurveGenerator(geneva, axes).generate(layout.x_charts[0], layout.y_charts[0]);
  EXPECT_GT(scope.reused(), before);
}

}  // namespace
}  // namespace hipair
