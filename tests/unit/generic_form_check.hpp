// Shared check of the parametric model's generic forms against its exact form (used by
// parametric_model_test.cpp and parametric_ratchet_test.cpp).
#pragma once

#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/jet.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace hipair::test_generic {

/// At `deviations`, the interval form encloses every vertex of the exact form (exact_model) and
/// the double form agrees with it, within `slack` (the exact form's rounded unit vectors:
/// <= 1e-12 rad x 100 mm = 1e-10 mm; 1e-9 is used); the interval form is narrow (< 1e-9).
inline void expect_generic_form_agrees(const model_detail::ParametricModel& model,
                                       const std::vector<Rational>& deviations) {
  std::size_t n = model.parameter_count();
  Model exact = model.exact_model(deviations);
  std::vector<kernels::Interval> box(n);
  std::vector<double> point(n);
  for (std::size_t i = 0; i < n; ++i) {
    box[i] = kernels::Interval::enclose(deviations[i]);
    point[i] = deviations[i].get_d();
  }
  const double slack = 1e-9;
  for (std::size_t k = 0; k < exact.parts.size(); ++k) {
    auto enclosure = model.part_geometry<kernels::Interval>(k, box);
    auto approximate = model.part_geometry<double>(k, point);
    ASSERT_EQ(enclosure.loops.size(), exact.parts[k].loops.size());
    for (std::size_t l = 0; l < exact.parts[k].loops.size(); ++l) {
      ASSERT_EQ(enclosure.loops[l].size(), exact.parts[k].loops[l].edges.size());
      for (std::size_t e = 0; e < exact.parts[k].loops[l].edges.size(); ++e) {
        const Edge& edge = exact.parts[k].loops[l].edges[e];
        const auto& x = enclosure.loops[l][e];
        EXPECT_EQ(x.arc, edge.kind == Edge::Kind::arc);
        EXPECT_LE(x.source.x.lo - slack, edge.source.x.get_d());
        EXPECT_GE(x.source.x.hi + slack, edge.source.x.get_d());
        EXPECT_LE(x.source.y.lo - slack, edge.source.y.get_d());
        EXPECT_GE(x.source.y.hi + slack, edge.source.y.get_d());
        EXPECT_LE(x.target.x.lo - slack, edge.target.x.get_d());
        EXPECT_GE(x.target.x.hi + slack, edge.target.x.get_d());
        EXPECT_LT(x.source.x.width(), 1e-9);
        EXPECT_NEAR(approximate.loops[l][e].target.x, edge.target.x.get_d(), slack);
        EXPECT_NEAR(approximate.loops[l][e].target.y, edge.target.y.get_d(), slack);
        EXPECT_EQ(approximate.loops[l][e].ccw, edge.ccw);
      }
    }
  }
}

/// Part 0's geometry as jets (values and derivatives over every parameter) at the nominal vector.
inline model_detail::PartGeometry<tolerance_detail::Jet<double>> nominal_jets(const model_detail::ParametricModel& model) {
  std::size_t n = model.parameter_count();
  std::vector<tolerance_detail::Jet<double>> jets(n);
  for (std::size_t i = 0; i < n; ++i) jets[i] = tolerance_detail::Jet<double>::variable(0.0, i, n);
  return model.part_geometry<tolerance_detail::Jet<double>>(0, jets);
}

/// The exact forms at deviation +h and -h of parameter i (the others nominal), for central
/// differences.
inline std::pair<Model, Model> exact_models_around(const model_detail::ParametricModel& model, std::size_t i,
                                                   const Rational& h) {
  std::vector<Rational> plus(model.parameter_count(), Rational(0)), minus(model.parameter_count(), Rational(0));
  plus[i] = h;
  minus[i] = -h;
  return {model.exact_model(plus), model.exact_model(minus)};
}

}  // namespace hipair::test_generic
