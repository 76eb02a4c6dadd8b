// Session 49 (fast49): a feature pair's curve carried from one half-turn chart kind to another
// by reflection (src/curves/half_turn_memo.hpp: x^(2k) N(-1/x) with k the quantity's degree in
// the rotation triple less the (1 + t^2) factors normalisation removed) instead of formed again.
// Compared with the generator with the memo off (every chart forms its curves), curve for curve:
// features, type, label, blocked side, the normalised polynomial, every validity atom and every
// corner-entry atom, on the examples with rotating parts (1-D and 2-D spaces, rotation against
// translation, arcs of rational and irrational radius products) and on generated spur-gear pairs,
// the charts taken in layout order and in reverse (the memo reflects in x, in y and in both, from
// either kind). The memo must have answered. And a model whose validity atoms are constants in
// one kind and multiples of x^2 in the other (formed anew, not reflected).
#include "curves/contact_curves.hpp"
#include "curves/half_turn_memo.hpp"
#include "spur_gear_pairs.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string polynomial_text(const cspace::IntegerPolynomial2& p) {
  std::ostringstream out;
  for (const auto& row : p.coefficients) {
    out << "[";
    for (const mpz_class& c : row) out << c.get_str() << " ";
    out << "]";
  }
  return out.str();
}

// Everything of a curve, as text (a difference names itself in the failure message).
std::string curve_text(const cspace::ContactCurve& curve) {
  std::ostringstream out;
  out << curve.label << " | " << curve.first.part << ":" << static_cast<int>(curve.first.kind) << ":" << curve.first.loop
      << ":" << curve.first.edge << " / " << curve.second.part << ":" << static_cast<int>(curve.second.kind) << ":"
      << curve.second.loop << ":" << curve.second.edge << " | type " << static_cast<int>(curve.type) << " sign "
      << curve.blocked_sign << " | f " << polynomial_text(curve.polynomial) << " | validity";
  for (const cspace::ValidityClause& clause : curve.validity) {
    out << " {";
    for (const auto& atom : clause.atoms) out << polynomial_text(atom) << ";";
    out << "}";
  }
  out << " | entry";
  for (const auto& atom : curve.corner_entry) out << " " << polynomial_text(atom);
  return out.str();
}

// Every pair (i < j) of the model with a C-space: the curves of each chart, with the memo on
// (one generator, charts in `order`) and off (another generator), compared.
void expect_reflected_curves_formed(const Model& model, const std::string& name, bool reverse, std::size_t& curves,
                                    std::size_t& charts, const cspace::CurveOptions& options = {}) {
  for (std::size_t i = 0; i < model.parts.size(); ++i)
    for (std::size_t j = i + 1; j < model.parts.size(); ++j) {
      cspace::PairAxes axes;
      try {
        axes = cspace::pair_axes(model, i, j);
      } catch (const std::exception&) {
        continue;   // no C-space for this pair (neither part moves)
      }
      if (axes.dimension() == 0) continue;
      const cspace::ChartLayout layout = cspace::chart_layout(model, axes);
      std::vector<std::pair<cspace::ChartAxis, cspace::ChartAxis>> boxes;
      const std::vector<cspace::ChartAxis> no_y(1);
      for (const cspace::ChartAxis& x : layout.x_charts)
        for (const cspace::ChartAxis& y : layout.y_charts.empty() ? no_y : layout.y_charts) boxes.emplace_back(x, y);
      if (reverse) std::reverse(boxes.begin(), boxes.end());
      const cspace::CurveGenerator remembering(model, axes, options), plain(model, axes, options);
      for (const auto& [x, y] : boxes) {
        cspace::half_turn_memo_switch() = true;
        const std::vector<cspace::ContactCurve> with = remembering.generate(x, y);
        cspace::half_turn_memo_switch() = false;
        const std::vector<cspace::ContactCurve> without = plain.generate(x, y);
        cspace::half_turn_memo_switch() = true;
        SCOPED_TRACE(name + " parts " + std::to_string(i) + ", " + std::to_string(j) + " chart " +
                     (x.half_turn ? "pi" : "0") + "/" + (y.half_turn ? "pi" : "0"));
        ASSERT_EQ(with.size(), without.size());
        for (std::size_t k = 0; k < with.size(); ++k) EXPECT_EQ(curve_text(with[k]), curve_text(without[k])) << "curve " << k;
        curves += with.size();
        ++charts;
      }
    }
}

// An arm turning about the origin with a vertex at (10, 0), against a fixed block whose lower edge
// runs from (-10, 5) to (10, 5), reached in both half-turn charts: the vertex-on-edge validity
// atoms are 200 (w + c) and 200 (w - c) in the rotation triple, the constant 400 (a clause that
// always holds, dropped) and 400 x^2 in the chart at 0, the other way round in the chart at pi.
// A reflection of one kind's curve would keep the atom x^2 as the constant 1 and miss the other:
// the memo must form the curve anew.
const char* const half_turn_constant_model = R"({
  "hipair": 1, "name": "half-turn-constant", "units": { "length": "mm", "angle": "deg" },
  "parts": [
    { "name": "arm", "motion": { "rotation": { "pivot": [0, 0] } },
      "loops": [ { "start": [10, 0], "edges": [ { "line_to": [0, 2] }, { "line_to": [0, -2] }, { "line_to": [10, 0] } ] } ] },
    { "name": "block", "motion": "fixed",
      "loops": [ { "start": [-10, 5], "edges": [ { "line_to": [10, 5] }, { "line_to": [10, 10] }, { "line_to": [-10, 10] },
                                               { "line_to": [-10, 5] } ] } ] }
  ]
})";

TEST(HalfTurnMemo, ConstantsOfOneChartKindAreNotReflected) {
  const Model model = read_model(half_turn_constant_model);
  std::size_t curves = 0, charts = 0;
  cspace::CurveOptions without_cull;
  without_cull.cull_blocked_space = false;
  for (bool reverse : {false, true}) {
    expect_reflected_curves_formed(model, "half-turn constant", reverse, curves, charts);
    expect_reflected_curves_formed(model, "half-turn constant, no cull", reverse, curves, charts, without_cull);
  }
  EXPECT_EQ(charts, 8u);
  EXPECT_GT(curves, 0u);
}

TEST(HalfTurnMemo, ReflectedCurvesAreTheFormedCurves) {
  const std::size_t hits_before = cspace::half_turn_memo_hits();
  std::size_t curves = 0, charts = 0;
  for (const char* example : {"geneva.json", "ratchet.json", "escapement.json", "scotch-yoke.json", "lever-stop.json",
                              "cam-follower-lever.json", "film-advance.json", "geneva-drive.json"}) {
    const std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / example;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const Model model = read_model_file(path);
    for (bool reverse : {false, true}) expect_reflected_curves_formed(model, example, reverse, curves, charts);
  }
  std::mt19937_64 random(4901);
  for (int trial = 0; trial < 2; ++trial) {
    std::string name;
    const Model model = test_gears::spur_gear_pair(random, 5 + static_cast<long>(random() % 4), 5 + static_cast<long>(random() % 4), name);
    expect_reflected_curves_formed(model, name, trial == 1, curves, charts);
  }
  EXPECT_GT(charts, 40u);
  EXPECT_GT(curves, 1000u);
  EXPECT_GT(cspace::half_turn_memo_hits() - hits_before, curves / 5);   // the memo answered
}

}  // namespace
}  // namespace hipair
