// Sensitivities of the follower on a contact curve (the tolerance solver's implicit
// differentiation over the parametric model) equal central finite differences of exact
// recomputations — the model rebuilt exactly at p +- h for a rational step h and the contact
// root isolated exactly — for every one of the Geneva pair's 26 parameters, within the bound
// h^2 + 2e-10 / h that the step and the rebuilds' recorded roundings give.
#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/solver.hpp"
#include "tolerance_geneva_curve.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace hipair {
namespace {

using model_detail::ParametricModel;

// The exact (squared) pin / wall contact function of a model at rational chart coordinates.
Rational exact_contact(const Model& model, const tolerance_detail::CurveSlice& c, const Rational& x, const Rational& y) {
  using V = kernels::Vector<Rational>;
  auto v = [](const Point& p) { return V{p.x, p.y}; };
  const Edge& pin = model.parts[c.first.part].loops[c.first.loop].edges[c.first.edge];
  const Edge& wall = model.parts[c.second.part].loops[c.second.loop].edges[c.second.edge];
  auto a = kernels::rotation_pose_from_half_tangent(v(model.parts[0].motion.pivot), x, c.fixed_half_turn);
  auto b = kernels::rotation_pose_from_half_tangent(v(model.parts[1].motion.pivot), y, c.free_half_turn);
  Rational dx = wall.target.x - wall.source.x, dy = wall.target.y - wall.source.y;
  return kernels::arc_segment_squared(a, v(pin.center), Rational(pin.radius_squared * (dx * dx + dy * dy)), b,
                                      v(wall.source), v(wall.target));
}

Rational exact_root(const Model& model, const tolerance_detail::CurveSlice& c, Rational lo, Rational hi) {
  int sign_lo = sgn(exact_contact(model, c, c.fixed_value, lo));
  EXPECT_NE(sign_lo, sgn(exact_contact(model, c, c.fixed_value, hi)));
  for (int i = 0; i < 100; ++i) {
    Rational mid = (lo + hi) / 2;
    int s = sgn(exact_contact(model, c, c.fixed_value, mid));
    if (s == 0) return mid;
    if (s == sign_lo) lo = mid; else hi = mid;
  }
  return (lo + hi) / 2;
}

TEST(ToleranceSensitivity, EveryGenevaSensitivityEqualsFiniteDifferencesOfExactRebuilds) {
  auto model = std::make_shared<const ParametricModel>(
      ParametricModel::read_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"));
  const Model& nominal = model->nominal();
  tolerance_detail::CurveSolver solver(model);
  tolerance_detail::CurveSlice curve = test::geneva_pin_wall_curve(nominal);
  for (const char* driver : {"-1/5", "-1/20", "1/10"}) {   // chart t = tan((theta - pi)/2)
    SCOPED_TRACE(driver);
    curve.fixed_value = Rational(driver);
    // The wheel on the curve: scan the wheel's chart for a sign change, then refine.
    Rational lo, hi;
    bool found = false;
    for (int j = -60; j < 60 && !found; ++j) {
      Rational a(j, 100), b(j + 1, 100);
      if (sgn(exact_contact(nominal, curve, curve.fixed_value, a)) * sgn(exact_contact(nominal, curve, curve.fixed_value, b)) < 0) {
        lo = a;
        hi = b;
        found = true;
      }
    }
    ASSERT_TRUE(found);
    double v = exact_root(nominal, curve, lo, hi).get_d();
    std::vector<double> s = solver.sensitivities(curve, v);
    ASSERT_EQ(s.size(), nominal.parameters.size());
    Rational h(1, 10000);
    double bound = h.get_d() * h.get_d() + 2e-10 / h.get_d();
    std::size_t significant = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      SCOPED_TRACE(nominal.parameters[i].name);
      auto rebuilt = [&](const Rational& delta) {
        std::vector<Rational> d(s.size(), Rational(0));
        d[i] = delta;
        return exact_root(model->exact_model(d), curve, Rational(v) - Rational(1, 50), Rational(v) + Rational(1, 50));
      };
      double difference = Rational((rebuilt(h) - rebuilt(-h)) / (2 * h)).get_d();
      EXPECT_NEAR(s[i], difference, bound);
      significant += std::fabs(s[i]) > 100 * bound;
    }
    EXPECT_GE(significant, 8u) << "most parameters move the pin / wall contact";
  }
}

}  // namespace
}  // namespace hipair
