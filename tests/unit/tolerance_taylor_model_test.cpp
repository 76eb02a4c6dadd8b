// First-order Taylor models (src/tolerance/taylor_model.hpp; session 21). Generated tests:
// (1) random functions built from every operation of number_traits (+ - * /, sqrt, sin, cos,
//     tan, atan2, |x|, min, max) over random boxes: at thousands of sampled points of each box,
//     the value there (certified: MPFI/outward-rounded interval evaluation at the point, a few
//     ulps wide) meets the Taylor model's form at that point, C + sum A_i xi_i + R, and its range;
//     and on correlated expressions the Taylor model's range is narrower than plain interval
//     evaluation over the box;
// (2) the first gear mesh of examples/models/gear-train.json (gear-A and gear-B's tooth edges
//     from module, pressure angle, flank radius, ...), on random sub-boxes of its tolerance box:
//     values and partial derivatives as jets of Taylor models contain those at sampled points
//     (interval jets at the point), and are far narrower than interval jets over the box (the
//     dependency problem session 20 diagnosed);
// (3) the certified band of a three-gear chain with the Taylor-model partials holds every Monte
//     Carlo sample and is narrower than with interval jets only.
#include "model/parametric/parametric.hpp"
#include "tolerance/jet.hpp"
#include "tolerance/taylor_model.hpp"
#include "gear_train_models.hpp"
#include "random_expression.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using model_detail::Arithmetic;
using tolerance_detail::Jet;
using tolerance_detail::TaylorModel1;
using test::Expression;
using test::RandomBox;
using test::random_box;
using test::random_expression;
using test::evaluate;

bool meets(const Interval& a, const Interval& b) { return a.lo <= b.hi && b.lo <= a.hi; }
bool finite(const Interval& a) { return std::isfinite(a.lo) && std::isfinite(a.hi); }

// The Taylor model's form at the point x of the box (each xi_i = (x_i - c_i) / h_i enclosed).
Interval form_at(const TaylorModel1& t, const std::vector<TaylorModel1>& variables, const std::vector<double>& x) {
  Interval value = t.constant + t.remainder;
  for (std::size_t i = 0; i < t.coefficients.size(); ++i) {
    const TaylorModel1& v = variables[i];
    Interval xi = (Interval::point(x[i]) - v.constant) / v.coefficients[i];
    value = value + t.coefficients[i] * xi;
  }
  return value;
}

TEST(ToleranceTaylorModel, RandomFunctionsAreEnclosedAtSampledPointsOfTheBox) {
  std::mt19937_64 random(21);
  std::size_t cases = 0, refused = 0, points = 0, narrower = 0, half = 0, compared = 0;
  double width_taylor = 0, width_interval = 0;
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    std::size_t n = 2 + trial % 4;
    Expression e = random_expression(random, n, 4 + trial % 9);
    RandomBox box = random_box(random, n);
    std::vector<TaylorModel1> tx(n);
    std::vector<Interval> ix(n);
    for (std::size_t i = 0; i < n; ++i) {
      tx[i] = TaylorModel1::over(box.lo[i], box.hi[i], i);
      ix[i] = Interval(box.lo[i], box.hi[i]);
    }
    TaylorModel1 t;
    try {
      t = evaluate(e, tx);
    } catch (const NumericError&) {
      ++refused;   // |x|, min, max or atan2 undecided over the box: the caller falls back
      continue;
    }
    ++cases;
    Interval range = t.range(), plain = evaluate(e, ix);
    // (expressions that vary over the box; a constant one is a few ulps wide either way)
    if (finite(range) && finite(plain) && plain.width() > 1e-9 * (1 + std::fabs(plain.lo) + std::fabs(plain.hi))) {
      ++compared;
      width_taylor += range.width();
      width_interval += plain.width();
      if (range.width() <= 1.01 * plain.width()) ++narrower;
      if (range.width() <= 0.5 * plain.width()) ++half;
    }
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int s = 0; s < 250; ++s) {
      std::vector<double> x(n);
      std::vector<Interval> px(n);
      for (std::size_t i = 0; i < n; ++i) {
        // corners and edges of the box too
        double u = s < 4 ? ((s >> (i % 2)) & 1) : unit(random);
        x[i] = box.lo[i] + u * (box.hi[i] - box.lo[i]);
        x[i] = std::min(std::max(x[i], box.lo[i]), box.hi[i]);
        px[i] = Interval::point(x[i]);
      }
      Interval value = evaluate(e, px);
      if (!finite(value)) continue;
      ++points;
      ASSERT_TRUE(meets(form_at(t, tx, x), value)) << "point " << s << ": value [" << value.lo << ", " << value.hi
                                                   << "], form [" << form_at(t, tx, x).lo << ", " << form_at(t, tx, x).hi << "]";
      ASSERT_TRUE(meets(range, value));
    }
  }
  std::printf("random functions: %zu cases (%zu refused), %zu points; of %zu varying ones, the range within 1 %% of "
              "interval evaluation or narrower in %zu, at most half as wide in %zu; total width %.3g against %.3g\n",
              cases, refused, points, compared, narrower, half, width_taylor, width_interval);
  EXPECT_GE(cases, 250u);
  EXPECT_GE(points, 60000u);
  // Where an expression uses a variable once, first order is interval evaluation's equal (plus
  // second-order remainders); where it reuses one (correlation), narrower.
  EXPECT_GE(narrower, compared * 4 / 5);
  EXPECT_GE(half, compared / 10);
  EXPECT_LT(width_taylor, width_interval);
}

TEST(ToleranceTaylorModel, CorrelatedExpressionsAreNarrowerThanIntervals) {
  // expressions whose plain interval evaluation over the box loses the correlation of x and y
  using A = Arithmetic<TaylorModel1>;
  using I = Arithmetic<Interval>;
  std::mt19937_64 random(211);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    RandomBox box = random_box(random, 2);
    TaylorModel1 x = TaylorModel1::over(box.lo[0], box.hi[0], 0), y = TaylorModel1::over(box.lo[1], box.hi[1], 1);
    Interval ix(box.lo[0], box.hi[0]), iy(box.lo[1], box.hi[1]);
    std::vector<std::pair<Interval, Interval>> pairs{
        {(x - x * 1).range(), ix - ix},
        {((x + y) * (x - y) - x * x + y * y).range(), (ix + iy) * (ix - iy) - ix * ix + iy * iy},
        {(A::sin(x) * A::sin(x) + A::cos(x) * A::cos(x)).range(), I::sin(ix) * I::sin(ix) + I::cos(ix) * I::cos(ix)},
        {(A::atan2(y + 3, x + 5) - A::atan2(y + 3, x + 5)).range(), I::atan2(iy + 3, ix + 5) - I::atan2(iy + 3, ix + 5)},
        {(x / (A::sqrt(x * x + 1)) - x * A::sqrt(x * x + 1) / (x * x + 1)).range(),
         ix / I::sqrt(ix * ix + 1) - ix * I::sqrt(ix * ix + 1) / (ix * ix + 1)}};
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      SCOPED_TRACE("expression " + std::to_string(k));
      EXPECT_LT(pairs[k].first.width(), 0.5 * pairs[k].second.width());
      EXPECT_TRUE(pairs[k].first.contains(k == 2 ? 1.0 : 0.0));   // the exact value, an identity
    }
  }
}

TEST(ToleranceTaylorModel, UndecidableComparisonsThrow) {
  TaylorModel1 x = TaylorModel1::over(-1.0, 1.0, 0);
  using A = Arithmetic<TaylorModel1>;
  EXPECT_THROW(A::abs(x), NumericError);
  EXPECT_THROW(A::min(x, TaylorModel1(0)), NumericError);
  EXPECT_THROW(A::max(x, TaylorModel1(0)), NumericError);
  EXPECT_THROW(A::sqrt(x), NumericError);
  EXPECT_THROW(TaylorModel1(1) / x, NumericError);
  EXPECT_THROW(A::atan2(x, x - 2), NumericError);   // meets the cut along the negative x-axis
  // decided ones do not
  EXPECT_NO_THROW(A::abs(x + 2));
  EXPECT_NO_THROW(A::atan2(x, x + 3));
}

// The first gear mesh of gear-train.json: gear-A's and gear-B's tooth edges.
TEST(ToleranceTaylorModel, GearMeshGeometryPartialsOverSubBoxesHoldAndAreNarrowerThanIntervalJets) {
  auto model = std::make_shared<const model_detail::ParametricModel>(
      model_detail::ParametricModel::read_file(std::filesystem::path(HIPAIR_EXAMPLES) / "gear-train.json"));
  const Model& nominal = model->nominal();
  std::size_t n = nominal.parameters.size();
  using DJet = Jet<double>;
  using IJet = Jet<Interval>;
  using TJet = Jet<TaylorModel1>;
  // the parameters the two gears' geometry depends on (non-zero partial derivatives at nominal)
  std::vector<DJet> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = DJet::variable(0.0, i, n);
  std::vector<bool> depends(n, false);
  auto mark = [&](const DJet& q) {
    for (std::size_t i = 0; i < q.gradient.size(); ++i) depends[i] = depends[i] || q.gradient[i] != 0;
  };
  const std::size_t edges = 12;   // the first teeth of each gear: both flanks, tip and root arcs
  for (std::size_t part : {0u, 1u}) {
    model_detail::PartGeometry<DJet> g = model->part_geometry(part, d);
    for (std::size_t e = 0; e < edges && e < g.loops[0].size(); ++e) {
      for (const auto* v : {&g.loops[0][e].source, &g.loops[0][e].target, &g.loops[0][e].center}) {
        mark(v->x);
        mark(v->y);
      }
      mark(g.loops[0][e].radius_squared);
    }
  }
  std::vector<std::size_t> active;
  for (std::size_t i = 0; i < n; ++i)
    if (depends[i]) active.push_back(i);
  ASSERT_GE(active.size(), 10u);
  std::size_t k = active.size();
  std::mt19937_64 random(2121);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double width_taylor = 0, width_interval = 0;
  std::size_t quantities = 0, points = 0;
  for (int trial = 0; trial < 8; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    double scale = std::ldexp(1.0, -(trial % 4));   // 1, 1/2, 1/4, 1/8 of the tolerance box
    std::vector<double> lo(n), hi(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Parameter& p = nominal.parameters[i];
      double a = Rational(p.range.lo - p.nominal).get_d(), b = Rational(p.range.hi - p.nominal).get_d();
      double w = scale * (b - a), start = a + (b - a - w) * unit(random);
      lo[i] = start;
      hi[i] = start + w;
    }
    std::vector<IJet> ij(n);
    std::vector<TJet> tj(n);
    std::vector<TaylorModel1> variables(k);
    for (std::size_t i = 0; i < n; ++i) {
      ij[i] = IJet(Interval(lo[i], hi[i]));
      tj[i] = TJet(TaylorModel1(Interval(lo[i], hi[i])));
    }
    for (std::size_t a = 0; a < k; ++a) {
      std::size_t i = active[a];
      ij[i] = IJet::variable(Interval(lo[i], hi[i]), a, k);
      variables[a] = TaylorModel1::over(lo[i], hi[i], a);
      tj[i] = TJet::variable(variables[a], a, k);
    }
    // every coordinate of the edges: value and partials, interval jets and Taylor-model jets
    auto flatten = [&](auto&& geometry, auto& out) {
      for (std::size_t e = 0; e < edges && e < geometry.loops[0].size(); ++e) {
        const auto& edge = geometry.loops[0][e];
        for (const auto* v : {&edge.source, &edge.target, &edge.center}) {
          out.push_back(v->x);
          out.push_back(v->y);
        }
        out.push_back(edge.radius_squared);
      }
    };
    std::vector<IJet> iq;
    std::vector<TJet> tq;
    for (std::size_t part : {0u, 1u}) {
      flatten(model->part_geometry(part, ij), iq);
      flatten(model->part_geometry(part, tj), tq);
    }
    ASSERT_EQ(iq.size(), tq.size());
    for (std::size_t q = 0; q < tq.size(); ++q)
      for (std::size_t a = 0; a < k; ++a) {
        Interval t = tq[q].partial(a).range(), i = iq[q].partial(a);
        if (!finite(t) || !finite(i)) continue;
        ++quantities;
        width_taylor += t.width();
        width_interval += i.width();
      }
    // sampled points of the box: the interval jets at the point meet the Taylor models' forms
    for (int s = 0; s < 40; ++s) {
      std::vector<IJet> pj(n);
      std::vector<double> x(k);
      for (std::size_t i = 0; i < n; ++i) {
        double v = lo[i] + unit(random) * (hi[i] - lo[i]);
        pj[i] = IJet(Interval::point(std::min(std::max(v, lo[i]), hi[i])));
      }
      for (std::size_t a = 0; a < k; ++a) {
        std::size_t i = active[a];
        x[a] = pj[i].value.lo;
        pj[i] = IJet::variable(pj[i].value, a, k);
      }
      std::vector<IJet> pq;
      for (std::size_t part : {0u, 1u}) flatten(model->part_geometry(part, pj), pq);
      for (std::size_t q = 0; q < pq.size(); ++q) {
        ++points;
        ASSERT_TRUE(meets(form_at(tq[q].value, variables, x), pq[q].value)) << "quantity " << q;
        for (std::size_t a = 0; a < k; ++a)
          ASSERT_TRUE(meets(form_at(tq[q].partial(a), variables, x), pq[q].partial(a))) << "quantity " << q << " partial " << a;
      }
    }
  }
  std::printf("gear-A/gear-B geometry: %zu parameters, %zu finite partials over sub-boxes; total width %.4g (Taylor "
              "models) against %.4g (interval jets), ratio %.3g; %zu quantities checked at points\n",
              k, quantities, width_taylor, width_interval, width_taylor / width_interval, points);
  RecordProperty("width_ratio", std::to_string(width_taylor / width_interval));
  EXPECT_LT(width_taylor, 0.2 * width_interval);
}

// Three gears (gear-train-3), driver 0 .. 0.3 rad: the band with Taylor-model partials holds
// every Monte Carlo sample and is narrower than with interval jets only.
TEST(ToleranceTaylorModel, ChainBandWithTaylorPartialsHoldsMonteCarloAndIsNarrower) {
  std::string text = test_gears::gear_train(3);
  auto band = [&](bool taylor, std::size_t monte_carlo) {
    ToleranceOptions options;
    options.driver = "gear-A";
    options.chain = true;
    options.range = std::make_pair(Rational(0), Rational(3, 10));
    options.positions = 120;
    options.threads = 2;
    options.monte_carlo = monte_carlo;
    options.seed = 21;
    options.taylor_partials = taylor;
    return analyze_tolerances_text(text, options);
  };
  ToleranceResult with = band(true, 300), without = band(false, 0);
  ASSERT_TRUE(with.monte_carlo.has_value());
  EXPECT_EQ(with.monte_carlo->outside_certified, 0u);
  EXPECT_EQ(with.monte_carlo->not_certified, 0u);
  ASSERT_EQ(with.samples.size(), without.samples.size());
  double width_with = 0, width_without = 0;
  std::size_t bounded = 0;
  for (std::size_t i = 0; i < with.samples.size(); ++i) {
    const VariationSample& a = with.samples[i];
    const VariationSample& b = without.samples[i];
    if (!a.contact) continue;
    double wa = a.certified.upper - a.certified.lower, wb = b.certified.upper - b.certified.lower;
    if (!std::isfinite(wa) || !std::isfinite(wb)) continue;
    ++bounded;
    width_with += wa;
    width_without += wb;
    // the certified band contains the linearised one's centre: the nominal output
    EXPECT_LE(a.certified.lower, a.nominal);
    EXPECT_GE(a.certified.upper, a.nominal);
  }
  std::printf("gear-train-3, 0..0.3 rad: %zu bounded positions, total certified width %.4g (Taylor) against %.4g\n",
              bounded, width_with, width_without);
  EXPECT_GT(bounded, 5u);
  EXPECT_LT(width_with, 0.6 * width_without);
}

}  // namespace
}  // namespace hipair
