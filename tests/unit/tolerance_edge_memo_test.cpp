// The Taylor-model edge memo (src/tolerance/edge_memo.hpp, session 41): an edge (or a part's
// axes) taken from the memo is, field for field and bit for bit, the one the parametric model
// evaluates over the same box with the same jet variables, on generated gear trains (2…4 gears,
// random even tooth counts) and generated boxes: sub-boxes split along random parameters (the
// band's subdivision: the splits the memo's hits come from), ends m·2^e with e in −300…300
// (evaluations that throw must throw both ways), −0 against +0 ends, random active sets whose
// variable indices move between calls. The reference builds its jets itself (the solver's form
// before the memo) and calls ParametricModel::edge_value / motion_value directly.
#include "model/parametric/parametric.hpp"
#include "tolerance/edge_memo.hpp"
#include "tolerance/solver.hpp"

#include "gear_train_models.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using model_detail::EdgeValue;
using model_detail::ParametricModel;
using tolerance_detail::Box;
using tolerance_detail::Jet;
using tolerance_detail::TaylorEdgeMemo;
using tolerance_detail::TaylorModel1;
using TaylorJet = Jet<TaylorModel1>;

// The jets of the solver's taylor_geometry before session 41, written out again here.
std::vector<TaylorJet> reference_jets(const Box& box, const std::vector<std::size_t>& active) {
  std::vector<TaylorJet> jets;
  for (std::size_t i = 0; i < box.lo.size(); ++i) {
    std::size_t a = 0;
    while (a < active.size() && active[a] != i) ++a;
    if (a < active.size()) {
      jets.push_back(TaylorJet::variable(TaylorModel1::over(box.lo[i], box.hi[i], a), a, active.size() + 1));
    } else if (box.hi[i] > box.lo[i]) {
      jets.emplace_back(TaylorModel1(Interval(box.lo[i], box.hi[i])));
    } else {
      jets.emplace_back(TaylorModel1(Interval::point(box.lo[i])));
    }
  }
  return jets;
}

std::string bits(const Interval& x) {
  return std::to_string(std::bit_cast<std::uint64_t>(x.lo)) + ":" + std::to_string(std::bit_cast<std::uint64_t>(x.hi));
}
std::string bits(const TaylorModel1& t) {
  std::string s = bits(t.constant) + "|" + std::to_string(t.coefficients.size()) + "[";
  for (const Interval& c : t.coefficients) s += bits(c) + ",";
  return s + "]" + bits(t.remainder);
}
std::string bits(const TaylorJet& j) {
  std::string s = bits(j.value) + "{" + std::to_string(j.gradient.size()) + ":";
  for (const TaylorModel1& g : j.gradient) s += bits(g) + ";";
  return s + "}";
}
std::string bits(const kernels::Vector<TaylorJet>& v) { return bits(v.x) + " / " + bits(v.y); }
std::string bits(const EdgeValue<TaylorJet>& e) {
  return std::string(e.arc ? "arc " : "segment ") + (e.ccw ? "ccw " : "cw ") + bits(e.source) + " -> " + bits(e.target) +
         " centre " + bits(e.center) + " r2 " + bits(e.radius_squared);
}

class Boxes {
 public:
  explicit Boxes(unsigned seed) : random_(seed) {}
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  // m 2^e, e in -300…300 (one in three), else a tolerance-sized deviation
  double end() {
    double m = std::uniform_real_distribution<double>(-1.0, 1.0)(random_);
    if (pick(3) == 0) return std::ldexp(m, pick(601) - 300);
    return m * 0.01;
  }
  Box box(std::size_t n) {
    Box b;
    int style = pick(4);
    for (std::size_t i = 0; i < n; ++i) {
      double a = 0, c = 0;
      if (style == 0) {   // the model's tolerance box shape: symmetric about 0
        a = std::ldexp(1.0, -pick(12)) * 0.01;
        b.lo.push_back(-a);
        b.hi.push_back(a);
        continue;
      }
      a = end();
      c = pick(5) == 0 ? a : end();   // some do not vary
      if (pick(8) == 0) a = pick(2) ? -0.0 : 0.0, c = pick(2) ? -0.0 : 0.0;
      b.lo.push_back(std::min(a, c));
      b.hi.push_back(std::max(a, c));
    }
    return b;
  }
  std::vector<std::size_t> active(const Box& b, const std::vector<std::uint32_t>& reads) {
    std::vector<std::size_t> a;
    int style = pick(3);
    for (std::size_t i = 0; i < b.lo.size(); ++i) {
      if (!(b.hi[i] > b.lo[i])) continue;
      bool read = std::find(reads.begin(), reads.end(), i) != reads.end();
      if (style == 0 ? read : style == 1 ? pick(2) == 0 : pick(6) != 0) a.push_back(i);
    }
    return a;
  }

 private:
  std::mt19937_64 random_;
};

TEST(ToleranceEdgeMemo, EdgesAndAxesFromTheMemoEqualTheModelsEvaluationBitForBit) {
  Boxes gen(41);
  std::size_t compared = 0, thrown = 0, subdivided_hits = 0, moved_indices = 0;
  for (int train = 0; train < 6; ++train) {
    unsigned gears = 2 + static_cast<unsigned>(gen.pick(3));
    unsigned even = 8 + 2 * static_cast<unsigned>(gen.pick(6)), odd = 8 + 2 * static_cast<unsigned>(gen.pick(6));
    auto model = std::make_shared<const ParametricModel>(ParametricModel::read(test_gears::gear_train(gears, even, odd)));
    std::size_t n = model->parameter_count();
    TaylorEdgeMemo memo(model);
    for (int trial = 0; trial < 5; ++trial) {
      // an edge of one gear (or its axes), the other gear's edge in the same boxes
      std::size_t part = static_cast<std::size_t>(gen.pick(static_cast<int>(gears)));
      FeatureIdentity f{part, 0, static_cast<std::size_t>(gen.pick(4 * static_cast<int>(part % 2 == 0 ? even : odd)))};
      bool axes = gen.pick(5) == 0;
      std::vector<std::uint32_t> reads = axes ? memo.motion_reads(part) : memo.edge_reads(f);
      ASSERT_FALSE(reads.empty());
      std::vector<Box> pending{gen.box(n)};
      std::optional<std::vector<std::size_t>> active;
      for (int step = 0; step < 12 && !pending.empty(); ++step) {
        Box b = pending.back();
        pending.pop_back();
        // the band's case: the same variables along a curve's subdivision; sometimes new ones
        if (!active || gen.pick(4) == 0) active = gen.active(b, reads);
        // the memo against the evaluation over b with the variables `vars`
        auto check = [&](const std::vector<std::size_t>& vars, const char* what) {
          std::size_t hits = memo.hits();
          std::optional<std::string> expected, got;
          std::vector<TaylorJet> values;
          try {
            values = model->parameter_values(reference_jets(b, vars));
            if (axes) {
              kernels::Vector<TaylorJet> pivot, direction;
              model->motion_value(part, values, pivot, direction);
              expected = bits(pivot) + " axis " + bits(direction);
            } else {
              expected = bits(model->edge_value(f.part, f.loop, f.edge, values));
            }
          } catch (const NumericError&) {
          }
          bool asked = false;
          auto parameters = [&]() -> const std::vector<TaylorJet>& {
            asked = true;
            values = model->parameter_values(tolerance_detail::taylor_deviations(b, vars));
            return values;
          };
          try {
            if (axes) {
              kernels::Vector<TaylorJet> pivot, direction;
              memo.motion(part, b, vars, parameters, pivot, direction);
              got = bits(pivot) + " axis " + bits(direction);
            } else {
              got = bits(memo.edge(f, b, vars, parameters));
            }
          } catch (const NumericError&) {
          }
          ASSERT_EQ(expected.has_value(), got.has_value()) << "train " << train << " trial " << trial << " step " << step << " " << what;
          if (!expected) ++thrown;
          else ASSERT_TRUE(*expected == *got) << "train " << train << " trial " << trial << " step " << step << " " << what
                                              << ": the memo's " << (axes ? "axes" : "edge")
                                              << " differ from the evaluation (first 300 characters)\n"
                                              << expected->substr(0, 300) << "\n" << got->substr(0, 300);
          if (memo.hits() > hits) {
            EXPECT_FALSE(asked);
            if (step > 0) ++subdivided_hits;
          }
          ++compared;
        };
        check(*active, "");
        if (::testing::Test::HasFatalFailure()) return;
        // the same box with every varying parameter a variable, and with only the read ones: the
        // read parameters' variable indices move (the key must tell them apart)
        if (gen.pick(3) == 0) {
          std::vector<std::size_t> all, only_read;
          for (std::size_t i = 0; i < n; ++i) {
            if (!(b.hi[i] > b.lo[i])) continue;
            all.push_back(i);
            if (std::find(reads.begin(), reads.end(), i) != reads.end()) only_read.push_back(i);
          }
          check(all, "(all varying as variables)");
          if (::testing::Test::HasFatalFailure()) return;
          check(only_read, "(the read ones as variables)");
          if (::testing::Test::HasFatalFailure()) return;
          // as many variables, the read ones' indices moved by one: a parameter not read before
          // the last read one, then one after it
          std::optional<std::size_t> before, after;
          for (std::size_t i : all) {
            if (std::find(reads.begin(), reads.end(), i) != reads.end()) continue;
            if (!only_read.empty() && i < only_read.back()) before = i;
            if (!only_read.empty() && i > only_read.back() && !after) after = i;
          }
          if (before && after) {
            for (std::size_t extra : {*before, *after}) {
              std::vector<std::size_t> vars = only_read;
              vars.insert(std::upper_bound(vars.begin(), vars.end(), extra), extra);
              check(vars, "(the read ones' indices moved)");
              if (::testing::Test::HasFatalFailure()) return;
            }
            ++moved_indices;
          }
        }
        // halves along a random varying parameter, read or not
        std::vector<std::size_t> varying;
        for (std::size_t i = 0; i < n; ++i)
          if (b.hi[i] > b.lo[i]) varying.push_back(i);
        if (varying.empty()) continue;
        std::size_t split = gen.pick(2) == 0 ? varying[static_cast<std::size_t>(gen.pick(static_cast<int>(varying.size())))]
                                              : reads[static_cast<std::size_t>(gen.pick(static_cast<int>(reads.size())))];
        if (!(b.hi[split] > b.lo[split])) split = varying.front();
        auto [left, right] = tolerance_detail::halves(b, split);
        pending.push_back(right);
        pending.push_back(left);
        if (gen.pick(6) == 0) pending.push_back(b);   // the same box again: a hit
      }
    }
  }
  // every case reached: comparisons, throws, hits along subdivisions, moved variable indices
  const std::size_t counts[] = {compared, thrown, subdivided_hits, moved_indices}, floors[] = {300, 5, 20, 5};
  for (int c = 0; c < 4; ++c) EXPECT_GT(counts[c], floors[c]) << "case " << c;
}

// What an edge reads: every parameter whose box ends change the edge's evaluation is among its
// reads (a parameter outside them, moved alone, leaves the evaluation the same bit for bit).
TEST(ToleranceEdgeMemo, AParameterOutsideAnEdgesReadsDoesNotChangeIt) {
  Boxes gen(4141);
  auto model = std::make_shared<const ParametricModel>(ParametricModel::read(test_gears::gear_train(3, 10, 12)));
  std::size_t n = model->parameter_count();
  TaylorEdgeMemo memo(model);
  std::size_t moved = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::size_t part = static_cast<std::size_t>(gen.pick(3));
    FeatureIdentity f{part, 0, static_cast<std::size_t>(gen.pick(40))};
    std::vector<std::uint32_t> reads = memo.edge_reads(f);
    Box b;
    for (std::size_t i = 0; i < n; ++i) {
      b.lo.push_back(-0.001);
      b.hi.push_back(0.001);
    }
    std::vector<std::size_t> active;
    for (std::uint32_t i : reads) active.push_back(i);
    std::string base = bits(model->edge_value(f.part, f.loop, f.edge, model->parameter_values(reference_jets(b, active))));
    for (std::size_t i = 0; i < n; ++i) {
      if (std::find(reads.begin(), reads.end(), i) != reads.end()) continue;
      Box c = b;
      c.lo[i] = -0.003;
      c.hi[i] = 0.0005;
      ASSERT_TRUE(base == bits(model->edge_value(f.part, f.loop, f.edge, model->parameter_values(reference_jets(c, active)))))
          << "parameter " << i << " (not among the edge's reads) moves edge " << f.edge << " of part " << part;
      ++moved;
    }
  }
  EXPECT_GT(moved, 100u);
}

}  // namespace
}  // namespace hipair
