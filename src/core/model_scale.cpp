#include "core/model_scale.hpp"

#include <gmp.h>

namespace hipair {

long normalising_shift(const Model& model, const std::vector<std::size_t>& parts) {
  Rational largest = 0;
  auto see = [&](const Rational& value) {
    if (abs(value) > largest) largest = abs(value);
  };
  for (std::size_t index : parts) {
    const Part& part = model.parts.at(index);
    if (part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed) return 0;
    if (part.motion.kind == Motion::Kind::rotation) {
      see(part.motion.pivot.x);
      see(part.motion.pivot.y);
    }
    for (const auto& loop : part.loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          see(p->x);
          see(p->y);
        }
  }
  if (sgn(largest) == 0) return 0;
  long exponent = static_cast<long>(mpz_sizeinbase(largest.get_num_mpz_t(), 2)) -
                  static_cast<long>(mpz_sizeinbase(largest.get_den_mpz_t(), 2));
  if (exponent >= -30 && exponent <= 60) return 0;   // about 1e-9 mm .. 1e18 mm: as is
  return exponent - 6;
}

Model scaled_model(const Model& model, long shift) {
  auto scale = [shift](Rational& value, long power) {
    long bits = shift * power;
    if (bits >= 0)
      mpq_div_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(bits));
    else
      mpq_mul_2exp(value.get_mpq_t(), value.get_mpq_t(), static_cast<mp_bitcnt_t>(-bits));
  };
  auto scale_point = [&](Point& p) {
    scale(p.x, 1);
    scale(p.y, 1);
  };
  Model scaled = model;
  for (Part& part : scaled.parts) {
    for (Loop& loop : part.loops)
      for (Edge& edge : loop.edges) {
        scale_point(edge.source);
        scale_point(edge.target);
        scale_point(edge.center);
        scale(edge.radius_squared, 2);
      }
    scale_point(part.motion.pivot);
    if (part.motion.translation_limits) {
      scale(part.motion.translation_limits->lo, 1);
      scale(part.motion.translation_limits->hi, 1);
    }
    scale(part.initial.offset, 1);
    scale(part.initial.x, 1);
    scale(part.initial.y, 1);
  }
  return scaled;
}

}  // namespace hipair
