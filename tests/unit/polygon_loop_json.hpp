// Test helper: a polygon (exact rational vertices) as a model loop of line_to edges.
#pragma once

#include <hipair/rational.hpp>

#include <string>
#include <utility>
#include <vector>

namespace hipair::test_loops {

using Points = std::vector<std::pair<Rational, Rational>>;

inline std::string text(const Rational& q) { return "\"" + q.get_str() + "\""; }

inline std::string loop_json(const Points& points) {
  std::string out = "{ \"start\": [" + text(points[0].first) + ", " + text(points[0].second) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    out += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + text(p.first) + ", " + text(p.second) + "] }";
  }
  return out + "] }";
}

}  // namespace hipair::test_loops
