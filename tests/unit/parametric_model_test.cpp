// The parametric model (issue 10 item 3): the recorded formulas reproduce the model read, the
// exact form at a parameter vector equals a re-read with the values overridden, the generic
// forms (double, intervals, AutoDiff) agree with it, and AutoDiff derivatives of a Geneva
// contact curve equal central finite differences of exact rebuilds.
#include "generic_form_check.hpp"
#include "model/parametric/number_traits.hpp"
#include "model/parametric/parametric.hpp"
#include "tolerance/contact_function.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <random>

namespace hipair {
namespace {

using model_detail::AutoDiff;
using model_detail::ParametricModel;
namespace fs = std::filesystem;

fs::path example(const std::string& name) { return fs::path(HIPAIR_EXAMPLES) / name; }

void expect_same_geometry(const Model& a, const Model& b) {
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    ASSERT_EQ(a.parts[k].loops.size(), b.parts[k].loops.size());
    EXPECT_TRUE(a.parts[k].motion.pivot == b.parts[k].motion.pivot);
    EXPECT_TRUE(a.parts[k].motion.direction == b.parts[k].motion.direction);
    for (std::size_t l = 0; l < a.parts[k].loops.size(); ++l) {
      const auto& x = a.parts[k].loops[l].edges;
      const auto& y = b.parts[k].loops[l].edges;
      ASSERT_EQ(x.size(), y.size());
      for (std::size_t e = 0; e < x.size(); ++e) {
        EXPECT_TRUE(x[e].source == y[e].source) << a.parts[k].name << " loop " << l << " edge " << e;
        EXPECT_TRUE(x[e].target == y[e].target);
        EXPECT_EQ(x[e].ccw, y[e].ccw);
        EXPECT_EQ(x[e].label, y[e].label);
        if (x[e].is_arc()) {
          EXPECT_TRUE(x[e].center == y[e].center);
          EXPECT_EQ(x[e].radius_squared, y[e].radius_squared);
        }
      }
    }
  }
}

TEST(ParametricModel, EveryExampleIsReproducedAtTheNominalVector) {
  for (const auto& entry : fs::directory_iterator(HIPAIR_EXAMPLES)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ParametricModel model = ParametricModel::read_file(entry.path());
    Model read = read_model_file(entry.path());
    expect_same_geometry(model.exact_model(std::vector<Rational>(model.parameter_count(), Rational(0))), read);
  }
}

// Random rational deviations inside the tolerance box: the exact form equals read_model with the
// values overridden (the same rounding of directions, the same orientation and labels).
TEST(ParametricModel, ExactFormEqualsAReReadWithOverriddenValues) {
  for (const char* name : {"geneva.json", "cam-follower.json", "geneva-template.json"}) {
    SCOPED_TRACE(name);
    ParametricModel model = ParametricModel::read_file(example(name));
    std::mt19937_64 random(12);
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<Rational> deviations(model.parameter_count(), Rational(0));
      ReadOptions options;
      for (std::size_t i = 0; i < model.parameter_count(); ++i) {
        const Parameter& p = model.nominal().parameters[i];
        if (model.derived(i) || p.range.lo == p.range.hi) continue;
        Rational u(static_cast<long>(random() % 1001), 1000);
        Rational value = p.range.lo + u * (p.range.hi - p.range.lo);
        deviations[i] = value - p.nominal;
        options.parameter_values[p.name] = value;
      }
      std::optional<Model> reread;
      try {
        reread = read_model_file(example(name), options);
      } catch (const ModelError&) {
      }
      if (!reread) {  // invalid there (a template's slots no longer fit): the exact form agrees
        EXPECT_THROW(model.exact_model(deviations), ModelError);
        continue;
      }
      expect_same_geometry(model.exact_model(deviations), *reread);
    }
  }
}

// The generic forms at a vector enclose (intervals) and approximate (double, AutoDiff values)
// the exact geometry up to the reader's recorded roundings (10^-12 per direction).
TEST(ParametricModel, GenericFormsAgreeWithTheExactForm) {
  ParametricModel model = ParametricModel::read_file(example("geneva.json"));
  ASSERT_TRUE(model.generic());
  std::size_t n = model.parameter_count();
  std::vector<Rational> deviations(n);
  for (std::size_t i = 0; i < n; ++i) deviations[i] = Rational(static_cast<long>(i % 5) - 2, 200000);
  test_generic::expect_generic_form_agrees(model, deviations);
}

// ---------------------------------------------------------------- Geneva contact derivative

struct GenevaContact {
  FeatureIdentity pin, wall;
};

GenevaContact pin_and_wall(const Model& model) {
  GenevaContact c;
  c.pin = FeatureIdentity{0, 0, 0, FeatureKind::arc};
  const Part& wheel = model.parts[1];
  for (std::size_t e = 0; e < wheel.loops[0].edges.size(); ++e)
    if (wheel.loops[0].edges[e].label == "slot 1 wall R") c.wall = FeatureIdentity{1, 0, e, FeatureKind::segment};
  return c;
}

// Exact contact function (squared form, rational) of the pin against the wall of an exactly
// read model, at rational chart coordinates.
bool half_x = false, half_y = false;   // the charts of the contact point found below

Rational exact_contact(const Model& model, const GenevaContact& c, const Rational& x, const Rational& y) {
  using V = kernels::Vector<Rational>;
  auto v = [](const Point& p) { return V{p.x, p.y}; };
  const Edge& pin = model.parts[0].loops[0].edges[c.pin.edge];
  const Edge& wall = model.parts[1].loops[0].edges[c.wall.edge];
  auto a = kernels::rotation_pose_from_half_tangent(v(model.parts[0].motion.pivot), x, half_x);
  auto b = kernels::rotation_pose_from_half_tangent(v(model.parts[1].motion.pivot), y, half_y);
  Point d{wall.target.x - wall.source.x, wall.target.y - wall.source.y};
  Rational product2 = pin.radius_squared * (d.x * d.x + d.y * d.y);
  return kernels::arc_segment_squared(a, v(pin.center), product2, b, v(wall.source), v(wall.target));
}

// The wheel's chart coordinate y on the contact curve at driver chart x, exactly, by bisection
// on [lo, hi] (a sign change of the exact contact function), to 2^-90.
Rational exact_root(const Model& model, const GenevaContact& c, const Rational& x, Rational lo, Rational hi) {
  int sign_lo = sgn(exact_contact(model, c, x, lo));
  for (int i = 0; i < 90; ++i) {
    Rational mid = (lo + hi) / 2;
    int s = sgn(exact_contact(model, c, x, mid));
    if (s == 0) return mid;
    if (s == sign_lo) lo = mid; else hi = mid;
  }
  return (lo + hi) / 2;
}

TEST(ParametricModel, GenevaContactDerivativesEqualFiniteDifferencesOfExactRebuilds) {
  ParametricModel model = ParametricModel::read_file(example("geneva.json"));
  const Model& nominal = model.nominal();
  GenevaContact c = pin_and_wall(nominal);
  ASSERT_EQ(c.wall.part, 1u);
  std::size_t n = model.parameter_count();
  std::size_t pin_radius = static_cast<std::size_t>(nominal.find_parameter("pin-radius") - nominal.parameters.data());
  std::size_t slot_offset =
      static_cast<std::size_t>(nominal.find_parameter("slot-axis-angular-off") - nominal.parameters.data());
  // A point of the curve: scan the driver chart for a valid root (double), then take it exactly.
  auto ga = model.part_geometry<double>(0, std::vector<double>(n, 0.0));
  auto gb = model.part_geometry<double>(1, std::vector<double>(n, 0.0));
  Rational x, y_lo, y_hi;
  bool found = false;
  for (int h = 0; h < 4 && !found; ++h)
  for (int i = -90; i <= 90 && !found; ++i) {
    half_x = h & 1;
    half_y = (h & 2) != 0;
    double xd = i / 100.0;
    auto a = tolerance_detail::pose_of(nominal.parts[0].motion, ga, xd, half_x);
    for (int j = -100; j < 100 && !found; ++j) {
      double y0 = j / 100.0, y1 = (j + 1) / 100.0;
      auto f = [&](double y) {
        auto b = tolerance_detail::pose_of(nominal.parts[1].motion, gb, y, half_y);
        return tolerance_detail::contact_function(ga, c.pin, a, gb, c.wall, b);
      };
      if (f(y0) * f(y1) >= 0) continue;
      auto b = tolerance_detail::pose_of(nominal.parts[1].motion, gb, 0.5 * (y0 + y1), half_y);
      const auto& pin = ga.loops[0][0];
      const auto& wall = gb.loops[0][c.wall.edge];
      auto validity = kernels::arc_segment_validity(a, pin.center, kernels::ArcSector<double>{{1, 0}, {1, 0}, false, true},
                                                    b, wall.source, wall.target);
      if (kernels::evaluate_validity(validity, [](double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }) != 1) continue;
      x = Rational(i, 100);
      y_lo = Rational(j, 100);
      y_hi = Rational(j + 1, 100);
      found = true;
    }
  }
  ASSERT_TRUE(found) << "no valid pin/wall contact on the driver chart";
  Rational y = exact_root(nominal, c, x, y_lo, y_hi);

  // AutoDiff over the parameters and y: dy/dp = -F_p / F_y.
  std::vector<AutoDiff> deviations(n);
  for (std::size_t i = 0; i < n; ++i) deviations[i] = AutoDiff(0.0, Eigen::VectorXd::Unit(n + 1, i));
  auto ad_a = model.part_geometry<AutoDiff>(0, deviations);
  auto ad_b = model.part_geometry<AutoDiff>(1, deviations);
  AutoDiff xa(x.get_d(), Eigen::VectorXd::Zero(n + 1));
  AutoDiff ya(y.get_d(), Eigen::VectorXd::Unit(n + 1, n));
  AutoDiff f = tolerance_detail::contact_function(ad_a, c.pin, tolerance_detail::pose_of(nominal.parts[0].motion, ad_a, xa, half_x),
                                                  ad_b, c.wall, tolerance_detail::pose_of(nominal.parts[1].motion, ad_b, ya, half_y));
  double fy = f.derivatives()[static_cast<Eigen::Index>(n)];
  ASSERT_GT(std::fabs(fy), 1e-6);
  EXPECT_LT(std::fabs(f.value() / fy), 1e-12);   // (x, y) is on the curve

  for (std::size_t i : {pin_radius, slot_offset}) {
    SCOPED_TRACE(nominal.parameters[i].name);
    double derivative = -f.derivatives()[static_cast<Eigen::Index>(i)] / fy;
    // Central difference of exact rebuilds at the rational step h:
    //   |FD - y'| <= h^2 max|y'''| / 6 + (rounding of each rebuild) / h.
    // The rebuilds round directions to 10^-12 rad (<= 10^-10 mm at these radii; |dy/dmm| < 1
    // here), and |y'''| < 6 for this curve at this scale: bound = h^2 + 2e-10 / h.
    Rational h(1, 10000);
    auto rebuilt_root = [&](const Rational& delta) {
      std::vector<Rational> d(n, Rational(0));
      d[i] = delta;
      Model rebuilt = model.exact_model(d);
      return exact_root(rebuilt, c, x, y - Rational(1, 100), y + Rational(1, 100));
    };
    Rational difference = (rebuilt_root(h) - rebuilt_root(-h)) / (2 * h);
    double bound = h.get_d() * h.get_d() + 2e-10 / h.get_d();
    EXPECT_NEAR(derivative, difference.get_d(), bound);
    EXPECT_GT(std::fabs(derivative), 100 * bound) << "the derivative should be significant";
  }
}

}  // namespace
}  // namespace hipair
