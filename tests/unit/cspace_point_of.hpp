// A motion's configuration at one parameter value as a point motion (the first-crossing tests
// ask a point query at a crossing's parameter to check its answer).
#pragma once

#include <hipair/cspace.hpp>

#include <utility>

namespace hipair::test {

// The path's configuration at u, exactly (a point query's path).
inline MotionPath point_of(const MotionPath& path, const Rational& u) {
  MotionPath point;
  for (auto [from, to] : {std::pair{&path.x, &point.x}, std::pair{&path.y, &point.y}}) {
    to->kind = from->kind;
    Rational v(0);
    for (std::size_t i = from->coefficients.size(); i-- > 0;) v = v * u + from->coefficients[i];
    v.canonicalize();
    to->coefficients = {v};
  }
  return point;
}

}  // namespace hipair::test
