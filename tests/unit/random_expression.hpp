// Random expressions over every operation of the parametric model's number types (+ - * /,
// sqrt, sin, cos, tan, atan2, |x|, min, max, negation), evaluated in any of them, and random
// narrow boxes: the generated cases of the tolerance jets' tests (Taylor models, Hessian jets).
#pragma once

#include "model/parametric/number_traits.hpp"

#include <hipair/rational.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace hipair::test {

// A random expression: nodes in evaluation order, the last one the result.
struct Node {
  enum Op { variable, constant, add, sub, mul, div, sqrt, sin, cos, tan, atan2, abs, min, max, neg } op;
  std::size_t a = 0, b = 0;   // operands (earlier nodes); `a` the variable's index for `variable`
  int numerator = 0;          // constant = numerator / 8
};
using Expression = std::vector<Node>;

inline Expression random_expression(std::mt19937_64& random, std::size_t variables, std::size_t operations) {
  Expression e;
  for (std::size_t i = 0; i < variables; ++i) e.push_back(Node{Node::variable, i});
  e.push_back(Node{Node::constant, 0, 0, std::uniform_int_distribution<int>(-16, 16)(random)});
  std::uniform_int_distribution<int> op(Node::add, Node::neg);
  for (std::size_t k = 0; k < operations; ++k) {
    std::uniform_int_distribution<std::size_t> pick(0, e.size() - 1);
    // prefer recent nodes so that the expression is deep, and reuse variables (correlation)
    std::size_t a = std::max(pick(random), pick(random)), b = pick(random);
    e.push_back(Node{static_cast<Node::Op>(op(random)), a, b});
  }
  return e;
}

template <class T>
T evaluate(const Expression& e, const std::vector<T>& x) {
  using A = model_detail::Arithmetic<T>;
  std::vector<T> v;
  v.reserve(e.size());
  for (const Node& n : e) {
    switch (n.op) {
      case Node::variable: v.push_back(x[n.a]); break;
      case Node::constant: v.push_back(A::constant(Rational(n.numerator, 8))); break;
      case Node::add: v.push_back(v[n.a] + v[n.b]); break;
      case Node::sub: v.push_back(v[n.a] - v[n.b]); break;
      case Node::mul: v.push_back(v[n.a] * v[n.b]); break;
      // kept in the domain: a / (b^2 + 1/2), sqrt(a^2 + 1/4)
      case Node::div: v.push_back(v[n.a] / (v[n.b] * v[n.b] + A::constant(Rational(1, 2)))); break;
      case Node::sqrt: v.push_back(A::sqrt(v[n.a] * v[n.a] + A::constant(Rational(1, 4)))); break;
      case Node::sin: v.push_back(A::sin(v[n.a])); break;
      case Node::cos: v.push_back(A::cos(v[n.a])); break;
      case Node::tan: v.push_back(A::tan(v[n.a] * A::constant(Rational(1, 4)))); break;
      case Node::atan2: v.push_back(A::atan2(v[n.a], v[n.b])); break;
      case Node::abs: v.push_back(A::abs(v[n.a])); break;
      case Node::min: v.push_back(A::min(v[n.a], v[n.b])); break;
      case Node::max: v.push_back(A::max(v[n.a], v[n.b])); break;
      case Node::neg: v.push_back(-v[n.a]); break;
    }
  }
  return v.back();
}

struct RandomBox {
  std::vector<double> lo, hi;
};
// half widths 2^-12 ... 2^-4 (tolerance boxes are narrow against the values: gear-train's
// parameters' tolerances are 10^-3 ... 10^-2 of them)
inline RandomBox random_box(std::mt19937_64& random, std::size_t n) {
  std::uniform_real_distribution<double> centre(-2.0, 2.0);
  std::uniform_int_distribution<int> exponent(-12, -4);
  RandomBox b;
  for (std::size_t i = 0; i < n; ++i) {
    double c = centre(random), h = std::ldexp(std::uniform_real_distribution<double>(0.5, 1.0)(random), exponent(random));
    b.lo.push_back(c - h);
    b.hi.push_back(c + h);
  }
  return b;
}

}  // namespace hipair::test
