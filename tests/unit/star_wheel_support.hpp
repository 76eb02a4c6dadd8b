// Geneva with generated star wheels, shared by the half-turn tests (cspace_half_turn_symmetry_test.cpp,
// cspace_twin_chart_test.cpp).
#pragma once

#include "model/exact_trig.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair::test {

inline Model geneva() { return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"); }

inline std::size_t part_index(const Model& model, const std::string& name) {
  for (std::size_t i = 0; i < model.parts.size(); ++i)
    if (model.parts[i].name == name) return i;
  return no_index;
}

/// `along` u plus `across` its left normal (-u.y, u.x).
inline Point at(const Point& u, const Rational& along, const Rational& across) {
  Point p{Rational(along * u.x - across * u.y), Rational(along * u.y + across * u.x)};
  p.x.canonicalize();
  p.y.canonicalize();
  return p;
}

/// A star wheel of `arms` rectangular arms about the origin (Geneva's wheel pivot), one loop of
/// segments, counter-clockwise. Arm k points along phi_k = 2 pi k / arms - pi + pi / arms (+ a
/// random turn), its direction an exact rational unit vector from a dyadic half-angle tangent;
/// with an even count and `symmetric`, arm k + arms/2 is arm k's exact negation.
inline Loop star_wheel(std::mt19937_64& random, int arms, bool symmetric) {
  const double turn = std::uniform_real_distribution<double>(-0.2, 0.2)(random);
  const Rational inner(std::uniform_int_distribution<long>(36, 44)(random), 2);    // 18..22
  const Rational outer(std::uniform_int_distribution<long>(110, 124)(random), 2);  // 55..62
  const Rational half_width(std::uniform_int_distribution<long>(8, 12)(random), 2);
  std::vector<Point> units(arms);
  for (int k = 0; k < arms; ++k) {
    if (symmetric && arms % 2 == 0 && k >= arms / 2) {
      const Point& u = units[k - arms / 2];
      units[k] = Point{Rational(-u.x), Rational(-u.y)};
      continue;
    }
    const double phi = 2 * std::numbers::pi * k / arms - std::numbers::pi + std::numbers::pi / arms + turn;
    Rational t(static_cast<long>(std::llround(std::tan(phi / 2) * 1048576.0)), 1048576);
    t.canonicalize();
    units[k] = model_detail::unit_from_half_tangent(t);
  }
  std::vector<Point> corners;
  const Rational minus_half_width(-half_width);
  for (const Point& u : units) {
    const std::pair<Rational, Rational> ends[4] = {
        {inner, minus_half_width}, {outer, minus_half_width}, {outer, half_width}, {inner, half_width}};
    for (const auto& [along, across] : ends) corners.push_back(at(u, along, across));
  }
  Loop loop;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    Edge e;
    e.kind = Edge::Kind::segment;
    e.source = corners[i];
    e.target = corners[(i + 1) % corners.size()];
    loop.edges.push_back(e);
  }
  return loop;
}

/// Geneva with its wheel replaced by `wheel`.
inline Model with_wheel(const Loop& wheel) {
  Model model = geneva();
  Part& part = model.parts[part_index(model, "wheel")];
  part.loops = {wheel};
  part.features.clear();
  return model;
}

}  // namespace hipair::test
