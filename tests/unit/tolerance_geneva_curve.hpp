// The Geneva pair's pin / slot 1 wall R contact curve as the tolerance solver takes it (the
// driver's chart held near pi: the pin in slot 1), shared by the solver's tests; Geneva's
// parametric model, a solver set as the assembly chains set it and the driver held over a range
// about its position (session 71: the set-up tolerance_free_side_test.cpp and
// tolerance_contact_constant_test.cpp repeated).
#pragma once

#include "model/parametric/parametric.hpp"
#include "tolerance/solver.hpp"

#include <hipair/model.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <vector>

#include "test_paths.hpp"

namespace hipair::test {

/// examples/models/geneva.json's parametric model.
inline std::shared_ptr<const model_detail::ParametricModel> geneva_parametric() {
  return std::make_shared<const model_detail::ParametricModel>(
      model_detail::ParametricModel::read_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"));
}

/// A solver of `model` as the assembly chains set it: first-order enclosures, Taylor-model partials.
inline tolerance_detail::CurveSolver chain_solver(std::shared_ptr<const model_detail::ParametricModel> model) {
  tolerance_detail::CurveSolver solver(std::move(model));
  solver.set_second_order(false);
  solver.set_taylor_partials(true);
  return solver;
}

/// `curve` with the driver held over about [t0 - half, t0 + half], t0 its position, the ends
/// rounded outwards to multiples of 2^-20 (dyadic: exact as doubles and as rationals), and the
/// wheel's spread over it from its nominal slope there (as the chains' slices take it). `v`, the
/// wheel's position, is refined by the solver's sensitivities as they do.
inline tolerance_detail::CurveSlice held_over(const tolerance_detail::CurveSolver& solver,
                                              const tolerance_detail::CurveSlice& curve, double& v, double half) {
  double slope = 0;
  solver.sensitivities(curve, v, &slope);
  const double t0 = curve.fixed_value.get_d();
  tolerance_detail::CurveSlice held = curve;
  held.fixed_range = tolerance_detail::Interval(std::ldexp(std::floor(std::ldexp(t0 - half, 20)), -20),
                                                std::ldexp(std::ceil(std::ldexp(t0 + half, 20)), -20));
  held.fixed_spread = std::fabs(slope) * held.fixed_range->width();
  return held;
}

inline tolerance_detail::CurveSlice geneva_pin_wall_curve(const Model& nominal) {
  tolerance_detail::CurveSlice curve;
  curve.first = FeatureIdentity{0, 0, 0, FeatureKind::arc};   // driver pin
  for (std::size_t e = 0; e < nominal.parts[1].loops[0].edges.size(); ++e)
    if (nominal.parts[1].loops[0].edges[e].label == "slot 1 wall R")
      curve.second = FeatureIdentity{1, 0, e, FeatureKind::segment};
  curve.fixed_part = 0;
  curve.free_part = 1;
  curve.fixed_half_turn = true;   // the driver near pi: the pin in slot 1
  curve.free_half_turn = false;
  return curve;
}

/// One generated case of the pin / slot 1 wall R curve: a random driver position (chart value
/// in [-0.25, 0.1]), the wheel's nominal root there and its sensitivities, and a random
/// sub-box of 1/4 ... 64 x the tolerance box. False when the nominal root is not found.
struct GenevaBoxCase {
  tolerance_detail::CurveSlice curve;
  double v = 0;
  std::vector<double> sensitivity;
  tolerance_detail::Box box;
};
inline bool generate_geneva_box_case(const tolerance_detail::CurveSolver& solver, const Model& nominal,
                                     std::mt19937_64& random, GenevaBoxCase& out) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  out.curve = geneva_pin_wall_curve(nominal);
  out.curve.fixed_value = Rational(static_cast<long>(std::floor(-2500 + 3500 * unit(random))), 10000);
  std::size_t n = nominal.parameters.size();
  // The wheel on the curve: the first certified sign change of the nominal contact function.
  std::vector<double> zero(n, 0.0);
  tolerance_detail::Interval root;
  bool found = false;
  for (int j = -60; j < 60 && !found; ++j)
    found = solver.certified_point_root(out.curve, zero, tolerance_detail::Interval(j / 100.0, (j + 1) / 100.0), root);
  if (!found) return false;
  out.v = root.middle();
  out.sensitivity = solver.sensitivities(out.curve, out.v);
  double scale = std::pow(2.0, static_cast<int>(unit(random) * 9) - 2);   // 1/4 .. 64
  out.box = tolerance_detail::Box{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  for (std::size_t i = 0; i < n; ++i) {
    const Parameter& p = nominal.parameters[i];
    double lo = Rational(p.range.lo - p.nominal).get_d(), hi = Rational(p.range.hi - p.nominal).get_d();
    double a = unit(random), b = unit(random);   // a random sub-interval of the scaled range
    out.box.lo[i] = scale * (lo + (hi - lo) * std::min(a, b));
    out.box.hi[i] = scale * (lo + (hi - lo) * std::max(a, b));
  }
  return true;
}

/// Probe `k` of a case's box: its lower (0) and upper (1) corners, the corners where the
/// linearised root is least (2) and greatest (3: each parameter at the end its sensitivity points
/// to), a random vector of the box beyond.
inline std::vector<double> box_probe(const GenevaBoxCase& c, int k, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> point(c.box.lo.size());
  for (std::size_t i = 0; i < point.size(); ++i) {
    double at = k < 2 ? double(k) : k < 4 ? double((c.sensitivity[i] > 0) == (k == 3)) : unit(random);
    point[i] = c.box.lo[i] + (c.box.hi[i] - c.box.lo[i]) * at;
  }
  return point;
}

}  // namespace hipair::test
