// The parts' inscribed disks of the curve generator's blocked-space cull, computed once per part
// and shared by every generator of a part with the same loops (src/curves/contact_curves.cpp,
// session 34). Generated rotating pairs of rational star polygons (four to six vertices; some
// models share a part's loops exactly, others have parts of the same vertex counts and other
// shapes, or the same shape moved by 1/64 or scaled by 10^-30 / 10^40), each chart pair's
// selection (CurveGenerator::select: the broad phase and the cull) taken in one sequence with
// the memo warm, then again with the memo emptied before each model: the same selections. And
// the sharing itself: a part met again is not computed again.
#include "curves/contact_curves.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string text(const Rational& q) { return '"' + q.get_str() + '"'; }

// 10^e as an exact rational (e of either sign)
Rational ten_to(int e) {
  Rational r(1);
  for (int i = 0; i < (e < 0 ? -e : e); ++i) r = e < 0 ? Rational(r / 10) : Rational(r * 10);
  return r;
}

// A star polygon's vertices around the origin on a 1/q grid (simple: increasing angles).
std::vector<std::pair<Rational, Rational>> star(std::mt19937_64& random, int k, long q) {
  std::vector<std::pair<Rational, Rational>> points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * 3.141592653589793 * (i + 0.2 + 0.6 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = 0.45 + 0.55 * static_cast<double>(random() % 1000) / 1000.0;
    points.emplace_back(Rational(static_cast<long>(std::lround(static_cast<double>(q) * r * std::cos(angle))), q),
                        Rational(static_cast<long>(std::lround(static_cast<double>(q) * r * std::sin(angle))), q));
  }
  for (auto& p : points) {
    p.first.canonicalize();
    p.second.canonicalize();
  }
  return points;
}

std::string loop_text(const std::vector<std::pair<Rational, Rational>>& points, const Rational& dx, const Rational& scale) {
  auto x = [&](const Rational& v) { return text(Rational((v + dx) * scale)); };
  auto y = [&](const Rational& v) { return text(Rational(v * scale)); };
  std::string out = "{ \"start\": [" + x(points[0].first) + ", " + y(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    out += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + x(p.first) + ", " + y(p.second) + "] }";
  }
  return out + "] }";
}

struct Shape {
  std::vector<std::pair<Rational, Rational>> points;
};

// Part a about the origin, part b about (d, 0); lengths times `scale`.
// (a's loop moved by shift_a, b's by d + shift_b)
Model pair_model(const Shape& a, const Shape& b, const Rational& d, const Rational& scale, const Rational& shift_a,
                 const Rational& shift_b = Rational(0)) {
  std::string model = R"({ "hipair": 1, "name": "stars", "units": { "length": "mm", "angle": "deg" }, "parts": [
    { "name": "a", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" +
                      loop_text(a.points, shift_a, scale) + R"( ] },
    { "name": "b", "motion": { "rotation": { "pivot": [)" + text(Rational(d * scale)) + R"(, 0] } }, "loops": [ )" +
                      loop_text(b.points, Rational(d + shift_b), scale) + R"( ] } ],
    "pairs": [ { "parts": ["a", "b"] } ] })";
  return read_model(model);
}

using Selections = std::vector<std::vector<cspace::CurveGenerator::FeaturePair>>;

Selections selections(const Model& model) {
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  cspace::CurveGenerator generator(model, axes);
  Selections out;
  for (const cspace::ChartAxis& x : layout.x_charts)
    for (const cspace::ChartAxis& y : layout.y_charts) out.push_back(generator.select(x, y));
  return out;
}

TEST(InscribedDiskMemo, SharedDisksGiveTheSelectionsOfDisksComputedAfresh) {
  std::mt19937_64 random(3401);
  std::vector<Model> models;
  for (int scale : {0, -30, 40}) {
    for (int group = 0; group < 3; ++group) {
      int k = 4 + static_cast<int>(random() % 3);
      Shape shared{star(random, k, 16)};
      for (int n = 0; n < 4; ++n) {
        Rational d = Rational(static_cast<long>(18 + random() % 9), 16);
        d.canonicalize();
        // n = 0, 1: the shared part again (with another partner); n = 2: another shape of as
        // many vertices; n = 3: the shared shape moved by 1/64
        Shape a = n == 2 ? Shape{star(random, k, 16)} : shared;
        Shape b{star(random, k, 16)};
        models.push_back(pair_model(a, b, d, ten_to(scale), n == 3 ? Rational(1, 64) : Rational(0)));
      }
    }
  }
  cspace::clear_inscribed_disk_memo();
  std::vector<Selections> warm;
  for (const Model& model : models) warm.push_back(selections(model));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < models.size(); ++i) {
    cspace::clear_inscribed_disk_memo();
    Selections fresh = selections(models[i]);
    EXPECT_EQ(warm[i], fresh) << "model " << i;
    for (const auto& s : fresh) kept += s.size();
  }
  EXPECT_GT(kept, 0u);
}

TEST(InscribedDiskMemo, APartMetAgainIsNotComputedAgain) {
  std::mt19937_64 random(3402);
  Shape a{star(random, 5, 16)}, b{star(random, 5, 16)}, c{star(random, 5, 16)};
  Model first = pair_model(a, b, Rational(3, 2), Rational(1), Rational(0));
  Model second = pair_model(a, c, Rational(3, 2), Rational(1), Rational(0));    // a again
  // both again, roles swapped: part a has first's b loop, part b first's a loop
  Model third = pair_model(b, a, Rational(3, 2), Rational(1), Rational(3, 2), Rational(-3, 2));
  cspace::clear_inscribed_disk_memo();
  std::size_t before = cspace::inscribed_disk_parts_computed();
  selections(first);
  EXPECT_EQ(cspace::inscribed_disk_parts_computed() - before, 2u);
  selections(second);
  EXPECT_EQ(cspace::inscribed_disk_parts_computed() - before, 3u);
  selections(third);
  EXPECT_EQ(cspace::inscribed_disk_parts_computed() - before, 3u);
}

}  // namespace
}  // namespace hipair
