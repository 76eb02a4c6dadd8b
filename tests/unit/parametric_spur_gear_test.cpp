// The generic (double / interval / Jet) form of the spur_gear template with flank_radius
// (src/model/parametric/parametric.hpp spur_flank, spur_gear_edge; docs/tolerance.md "The
// parametric model"): on generated gears (random tooth counts, modules, flank radii, pressure
// angles, phases, centres, every dimension toleranced), at random deviation vectors inside the
// box, the interval form encloses every vertex of the exact expansion (ParametricModel::
// exact_model: the template expanded exactly, its unit vectors and flank ends rounded within
// 1e-12) and the double form agrees with it within those roundings; the Jet form's derivatives
// equal central differences of exact expansions. The two-arc involute fit (no flank_radius)
// has its own generic form since session 57 (parametric_templates_test.cpp).
#include "generic_form_check.hpp"
#include "tolerance/jet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <type_traits>
#include <utility>

namespace hipair {
namespace {

using model_detail::ParametricModel;

// A gear of z teeth, module m (pitch radius m z / 2), addendum m, dedendum 1.25 m, flank radius
// between 1.3 and 3 times the involute's curvature at the pitch point (r sin alpha): the range
// in which the template's flank reaches the tip circle without pointed teeth for z >= 10.
std::string generated_gear(std::mt19937& rng, bool with_flank_radius = true) {
  std::uniform_int_distribution<int> teeth(10, 40), modulus(1, 4), pressure(16, 24), phase(-180, 180),
      offset(-20, 20), factor(13, 30);
  int z = teeth(rng), m = modulus(rng), a = pressure(rng);
  double rp = m * z / 2.0;
  double rf = rp * std::sin(a * M_PI / 180) * factor(rng) / 10.0;
  std::string flank = with_flank_radius ? R"(, "flank_radius": "fr")" : "";
  return R"({"hipair": 1, "name": "gear", "units": {"length": "mm", "angle": "deg"},
  "parameters": {"m": {"nominal": )" + std::to_string(m) + R"(, "tolerance": 0.001},
                 "z": {"nominal": )" + std::to_string(z) + R"(},
                 "fr": {"nominal": )" + std::to_string(std::round(rf * 100) / 100) + R"(, "tolerance": [-0.01, 0.03]},
                 "alpha": {"nominal": )" + std::to_string(a) + R"(, "tolerance": 0.2, "angle": true},
                 "thin": {"nominal": 0.05, "tolerance": 0.02},
                 "phase": {"nominal": )" + std::to_string(phase(rng)) + R"(, "tolerance": 0.1, "angle": true},
                 "cx": {"nominal": )" + std::to_string(offset(rng)) + R"(, "tolerance": 0.01}},
  "parts": [{"name": "gear", "motion": {"rotation": {"pivot": ["cx", 3]}},
             "features": [{"spur_gear": {"center": ["cx", 3], "teeth": "z", "pitch_radius": "m * z / 2",
                           "addendum": "m", "dedendum": "1.25 * m", "tooth_thickness": "pi * m / 2 - thin",
                           "pressure_angle": "alpha", "phase": "phase")" + flank + R"(}}]}],
  "pairs": []})";
}

std::vector<Rational> random_deviations(const ParametricModel& model, std::mt19937& rng) {
  std::uniform_int_distribution<int> u(0, 1000);
  std::vector<Rational> deviations(model.parameter_count(), Rational(0));
  for (std::size_t i = 0; i < deviations.size(); ++i) {
    const Parameter& p = model.nominal().parameters[i];
    if (p.range.lo != p.range.hi)
      deviations[i] = p.range.lo - p.nominal + Rational(u(rng), 1000) * (p.range.hi - p.range.lo);
  }
  return deviations;
}

TEST(ParametricSpurGear, GenericFormAgreesWithTheExactFormOnGeneratedGears) {
  std::mt19937 rng(17);
  for (int round = 0; round < 20; ++round) {
    std::string text = generated_gear(rng);
    SCOPED_TRACE(text);
    ParametricModel model = ParametricModel::read(text);
    ASSERT_TRUE(model.generic()) << model.exact_only_feature();
    for (int trial = 0; trial < 3; ++trial) test_generic::expect_generic_form_agrees(model, random_deviations(model, rng));
  }
}

// part_geometry computes a gear's canonical flank once for all its edges (session 32): every
// edge is bit for bit the edge_value that computes the flank itself, in doubles, intervals and
// Jets of intervals, on generated gears (reversed loops among them: the wheel's rotation sense)
// at random deviation vectors.
template <class T>
void expect_same(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, double>) {
    EXPECT_EQ(a, b);
  } else if constexpr (std::is_same_v<T, kernels::Interval>) {
    EXPECT_EQ(a.lo, b.lo);
    EXPECT_EQ(a.hi, b.hi);
  } else {
    expect_same(a.value, b.value);
    ASSERT_EQ(a.gradient.size(), b.gradient.size());
    for (std::size_t i = 0; i < a.gradient.size(); ++i) expect_same(a.gradient[i], b.gradient[i]);
  }
}

template <class T>
void expect_part_geometry_is_edge_by_edge(const ParametricModel& model, const std::vector<T>& deviations) {
  std::vector<T> parameters = model.parameter_values(deviations);
  for (std::size_t k = 0; k < model.nominal().parts.size(); ++k) {
    model_detail::PartGeometry<T> geometry = model.part_geometry(k, deviations);
    ASSERT_EQ(geometry.loops.size(), model.nominal().parts[k].loops.size());
    for (std::size_t l = 0; l < geometry.loops.size(); ++l)
      for (std::size_t e = 0; e < geometry.loops[l].size(); ++e) {
        model_detail::EdgeValue<T> one = model.edge_value(k, l, e, parameters);
        const model_detail::EdgeValue<T>& shared = geometry.loops[l][e];
        EXPECT_EQ(one.arc, shared.arc);
        EXPECT_EQ(one.ccw, shared.ccw);
        for (auto [x, y] : {std::pair{&one.source, &shared.source}, std::pair{&one.target, &shared.target},
                            std::pair{&one.center, &shared.center}}) {
          expect_same(x->x, y->x);
          expect_same(x->y, y->y);
        }
        expect_same(one.radius_squared, shared.radius_squared);
      }
  }
}

TEST(ParametricSpurGear, PartGeometrySharesTheFlankWithTheSameValues) {
  std::mt19937 rng(32);
  for (int round = 0; round < 12; ++round) {
    const std::string gear = generated_gear(rng);
    SCOPED_TRACE("gear " + std::to_string(round) + ": " + gear);
    const ParametricModel model = ParametricModel::read(gear);
    std::vector<Rational> deviations = random_deviations(model, rng);
    ASSERT_TRUE(model.generic()) << model.exact_only_feature();
    std::size_t n = deviations.size();
    std::vector<double> point(n);
    std::vector<kernels::Interval> box(n);
    std::vector<tolerance_detail::Jet<kernels::Interval>> jets(n);
    for (std::size_t i = 0; i < n; ++i) {
      point[i] = deviations[i].get_d();
      box[i] = kernels::Interval(point[i] - 1e-4, point[i] + 1e-4);
      jets[i] = tolerance_detail::Jet<kernels::Interval>::variable(box[i], i, n);
    }
    expect_part_geometry_is_edge_by_edge(model, point);
    expect_part_geometry_is_edge_by_edge(model, box);
    expect_part_geometry_is_edge_by_edge(model, jets);
    if (HasFailure()) return;
  }
}

// Until session 57 the two-arc involute fit (no flank_radius) had the exact form only; its
// generic form is tested by ParametricTemplates.* (parametric_templates_test.cpp).
TEST(ParametricSpurGear, TheInvoluteFitWithoutFlankRadiusHasTheGenericForm) {
  std::mt19937 rng(5);
  ParametricModel model = ParametricModel::read(generated_gear(rng, false));
  EXPECT_TRUE(model.generic()) << model.exact_only_feature();
}

// Derivatives of every vertex and arc centre with respect to every parameter (Jet<double>)
// against central differences of exact expansions at +- h: within h^2 |x'''| / 6 (|x'''| <= 1e3
// mm for these radii and angles) + 2 x 1e-9 / h (the exact form's roundings, as above).
TEST(ParametricSpurGear, DerivativesEqualFiniteDifferencesOfExactExpansions) {
  std::mt19937 rng(41);
  for (int round = 0; round < 3; ++round) {
    ParametricModel model = ParametricModel::read(generated_gear(rng));
    std::size_t n = model.parameter_count();
    auto geometry = test_generic::nominal_jets(model);
    Rational h(1, 10000);
    double bound = 1e3 * h.get_d() * h.get_d() / 6 + 2e-9 / h.get_d();
    for (std::size_t i = 0; i < n; ++i) {
      const Parameter& p = model.nominal().parameters[i];
      if (p.range.lo == p.range.hi) continue;
      auto [a, b] = test_generic::exact_models_around(model, i, h);
      const auto& ea = a.parts[0].loops[0].edges;
      const auto& eb = b.parts[0].loops[0].edges;
      ASSERT_EQ(ea.size(), geometry.loops[0].size());
      for (std::size_t e = 0; e < ea.size(); ++e) {
        auto difference = [&](const Rational& x, const Rational& y) { return Rational((x - y) / (2 * h)).get_d(); };
        const auto& g = geometry.loops[0][e];
        EXPECT_NEAR(g.target.x.partial(i), difference(ea[e].target.x, eb[e].target.x), bound) << p.name << " edge " << e;
        EXPECT_NEAR(g.target.y.partial(i), difference(ea[e].target.y, eb[e].target.y), bound) << p.name << " edge " << e;
        if (ea[e].kind == Edge::Kind::arc) {
          EXPECT_NEAR(g.center.x.partial(i), difference(ea[e].center.x, eb[e].center.x), bound) << p.name << " edge " << e;
          EXPECT_NEAR(g.center.y.partial(i), difference(ea[e].center.y, eb[e].center.y), bound) << p.name << " edge " << e;
        }
      }
    }
  }
}

}  // namespace
}  // namespace hipair
