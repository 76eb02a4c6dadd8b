#include "model/exact_trig.hpp"

#include "model/expression.hpp"

#include <mpfr.h>

#include <map>
#include <tuple>

namespace hipair::model_detail {
namespace {

constexpr mpfr_prec_t working_bits = 256;

thread_local RoundingBoundScope* current_scope = nullptr;

Rational half_bound() { return Rational(rounding_bound() / 2); }

// Unit vector of angle a (|a| <= pi/2 + small) via a rounded t = tan(a/2): the simplest
// rational t with |2 atan t - a| <= b, the rounding bound (the window of angles [a - b, a + b]
// mapped through tan(./2), which is increasing there). Taking the whole angle window (not a
// window of fixed width in t) keeps a nearby exact direction reachable after an earlier
// rounding of the angle itself: pi/2 rounded to a rational a' still gives t = 1, (0, 1).
Point unit_small_angle(const mpfr_t angle, const std::string& pointer, const std::string& expression,
                       std::vector<Rounding>& roundings) {
  mpfr_t bound, end;
  mpfr_inits2(working_bits, bound, end, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_q(bound, rounding_bound().get_mpq_t(), MPFR_RNDN);
  Rational ends[2];
  for (int side = 0; side < 2; ++side) {
    (side == 0 ? mpfr_sub : mpfr_add)(end, angle, bound, MPFR_RNDN);
    mpfr_div_ui(end, end, 2, MPFR_RNDN);
    mpfr_tan(end, end, MPFR_RNDN);
    mpfr_get_q(ends[side].get_mpq_t(), end);  // exact value of the 256-bit approximation
  }
  mpfr_clears(bound, end, static_cast<mpfr_ptr>(nullptr));
  // Each 256-bit end is within 2^-245 of the true one (|t| <= 1 + small, a few roundings of
  // relative size 2^-256); shrink the window by 2^-240 on each side.
  Rational t = simplest_rational_between(ends[0] + Rational(1, mpz_class(1) << 240),
                                         ends[1] - Rational(1, mpz_class(1) << 240));
  // The record holds the half-angle tangent used and the bound on the angle it implies.
  roundings.push_back(Rounding{pointer, "direction of " + expression + " (half-angle tangent)", t,
                               rounding_bound()});
  return unit_from_half_tangent(t);
}

Point direction_from_mpfr(mpfr_t angle, const std::string& pointer, const std::string& expression,
                          std::vector<Rounding>& roundings) {
  // Reduce to (-pi, pi].
  mpfr_t pi, reduced;
  mpfr_inits2(working_bits, pi, reduced, static_cast<mpfr_ptr>(nullptr));
  mpfr_const_pi(pi, MPFR_RNDN);
  mpfr_remainder(reduced, angle, pi, MPFR_RNDN);  // now in [-pi/2, pi/2], angle = reduced + k pi
  mpfr_t k;
  mpfr_init2(k, working_bits);
  mpfr_sub(k, angle, reduced, MPFR_RNDN);
  mpfr_div(k, k, pi, MPFR_RNDN);
  mpfr_round(k, k);
  long turns = mpfr_get_si(k, MPFR_RNDN);
  Point unit = unit_small_angle(reduced, pointer, expression, roundings);
  mpfr_clears(pi, reduced, k, static_cast<mpfr_ptr>(nullptr));
  if (turns % 2 != 0) {
    unit.x = -unit.x;
    unit.y = -unit.y;
  }
  return unit;
}

// The directions this thread has made (session 70, growth70): a model repeats its angles (Geneva
// writes each slot flank's "... + 1*pi/4 + pi/2" at several polar points, a template turns
// every tooth by the same pitch multiples), and each direction costs two 256-bit tangents and a
// continued-fraction descent. The direction is a function of the angle's rationals and the
// rounding bound in force only, so a repeated angle takes the unit vector and the rounded
// half-angle tangent made the first time (its Rounding record is written again with this
// call's pointer and text, as the computation writes it). The key is (which function, its
// rationals canonical, the bound); the memo is cleared past 4096 directions.
enum class DirectionKind { angle, pi_multiple, sum };
using DirectionKey = std::tuple<int, Rational, Rational, Rational>;
struct MadeDirection {
  Point unit;
  Rational tangent;   // the rounded half-angle tangent of the Rounding record
};
thread_local std::map<DirectionKey, MadeDirection> made_directions;

// The direction of the angle `make_angle` sets (an mpfr_t of working_bits), through the memo.
template <class MakeAngle>
Point memo_direction(DirectionKind kind, const Rational& first, const Rational& second, MakeAngle make_angle,
                     const std::string& pointer, const std::string& expression, std::vector<Rounding>& roundings) {
  DirectionKey key{static_cast<int>(kind), first, second, rounding_bound()};
  std::get<1>(key).canonicalize();
  std::get<2>(key).canonicalize();
  std::get<3>(key).canonicalize();
  if (auto found = made_directions.find(key); found != made_directions.end()) {
    roundings.push_back(Rounding{pointer, "direction of " + expression + " (half-angle tangent)", found->second.tangent,
                                 rounding_bound()});
    return found->second.unit;
  }
  mpfr_t a;
  mpfr_init2(a, working_bits);
  make_angle(a);
  const std::size_t before = roundings.size();
  Point unit = direction_from_mpfr(a, pointer, expression, roundings);
  mpfr_clear(a);
  if (roundings.size() == before + 1) {   // (always: the direction is rounded once)
    if (made_directions.size() >= 4096) made_directions.clear();
    made_directions.emplace(std::move(key), MadeDirection{unit, roundings.back().value});
  }
  return unit;
}

}  // namespace

Rational default_rounding_bound() { return Rational(1, 1000000000000L); }

Rational smallest_rounding_bound() { return Rational(mpz_class(1), mpz_class("1000000000000000000000000000000")); }

Rational largest_rounding_bound() { return Rational(1, 1000); }

const Rational& rounding_bound() {
  static const Rational fallback = default_rounding_bound();
  return current_scope ? current_scope->bound_ : fallback;
}

bool rounding_bound_overrides_model() { return current_scope && current_scope->overrides_model_; }

RoundingBoundScope::RoundingBoundScope(const Rational& bound, bool overrides_model)
    : previous_(current_scope), bound_(bound), overrides_model_(overrides_model) {
  current_scope = this;
}

RoundingBoundScope::~RoundingBoundScope() { current_scope = previous_; }

Rational simplest_rational_between(const Rational& lo_in, const Rational& hi_in) {
  Rational lo = lo_in, hi = hi_in;  // canonical copies (mpq_class(a, b) is not canonical)
  lo.canonicalize();
  hi.canonicalize();
  if (lo <= 0 && hi >= 0) return Rational(0);
  if (hi < 0) return Rational(-simplest_rational_between(Rational(-hi), Rational(-lo)));
  // 0 < lo <= hi: continued-fraction descent (Stern-Brocot), iterative.
  // Invariant: result = (p0 * x + p1) / (q0 * x + q1) for the simplest x in [a, b].
  // a = an / ad and b = bn / bd with positive denominators, not reduced: each step's new ends are
  // 1 / (b - floor a) = bd / (bn - floor(a) bd) and 1 / (a - floor a) = ad / (an mod ad), the
  // remainders of Euclid's algorithm on the ends, so no gcd is taken (as rationals, every step
  // canonicalised two quotients of numbers of the input's size: ≈ 55 K instructions per call on
  // the 256-bit half-angle tangent windows). The same steps and tests as on the rationals.
  mpz_class an = lo.get_num(), ad = lo.get_den(), bn = hi.get_num(), bd = hi.get_den();
  mpz_class p0 = 1, p1 = 0, q0 = 0, q1 = 1;
  mpz_class floor_a, rest, t;
  for (;;) {
    mpz_fdiv_qr(floor_a.get_mpz_t(), rest.get_mpz_t(), an.get_mpz_t(), ad.get_mpz_t());
    mpz_class value;  // the simplest x is an integer when one lies in [a, b]
    bool integer_found = false;
    if (sgn(rest) == 0) {  // a is the integer floor_a
      value = floor_a;
      integer_found = true;
    } else {
      t = floor_a + 1;  // floor_a + 1 <= bn / bd iff (floor_a + 1) bd <= bn
      t *= bd;
      if (t <= bn) {
        value = floor_a + 1;
        integer_found = true;
      }
    }
    if (integer_found) {
      Rational result(p0 * value + p1, q0 * value + q1);
      result.canonicalize();
      return result;
    }
    // x = floor_a + 1/y with y in [1/(b - floor_a), 1/(a - floor_a)].
    mpz_class np0 = p0 * floor_a + p1, nq0 = q0 * floor_a + q1;
    p1 = p0;
    q1 = q0;
    p0 = np0;
    q0 = nq0;
    // new a = bd / (bn - floor_a bd), new b = ad / rest (rest = an - floor_a ad > 0)
    mpz_submul(bn.get_mpz_t(), floor_a.get_mpz_t(), bd.get_mpz_t());
    an.swap(bd);   // an = bd (old), bd = an (old, no longer needed)
    ad.swap(bn);   // ad = bn - floor_a bd (old), bn = ad (old)
    bd.swap(rest); // bd = rest
  }
}

Rational round_half_tangent(const Rational& tangent) {
  return simplest_rational_between(tangent - half_bound(), tangent + half_bound());
}

Rational round_simplest(const Rational& value) {
  Rational half = rounding_bound_near(abs(value)) / 2;
  return simplest_rational_between(value - half, value + half);
}

Point exact_unit_vector(const Rational& angle, const std::string& pointer,
                        const std::string& expression, std::vector<Rounding>& roundings) {
  if (angle == 0) return Point{Rational(1), Rational(0)};
  return memo_direction(
      DirectionKind::angle, angle, Rational(0), [&](mpfr_t a) { mpfr_set_q(a, angle.get_mpq_t(), MPFR_RNDN); }, pointer,
      expression, roundings);
}

Point exact_unit_vector_pi(const Rational& multiple_of_pi, const std::string& pointer,
                           const std::string& expression, std::vector<Rounding>& roundings) {
  // Exact for multiples of pi/2. (Callers may pass mpq_class(a, b), which is not canonical.)
  Rational multiple = multiple_of_pi;
  multiple.canonicalize();
  Rational twice = 2 * multiple;
  twice.canonicalize();
  if (twice.get_den() == 1) {
    mpz_class quarter = twice.get_num() % 4;
    if (quarter < 0) quarter += 4;
    switch (quarter.get_si()) {
      case 0: return Point{Rational(1), Rational(0)};
      case 1: return Point{Rational(0), Rational(1)};
      case 2: return Point{Rational(-1), Rational(0)};
      default: return Point{Rational(0), Rational(-1)};
    }
  }
  return memo_direction(
      DirectionKind::pi_multiple, multiple, Rational(0),
      [&](mpfr_t a) {
        mpfr_t pi;
        mpfr_init2(pi, working_bits);
        mpfr_const_pi(pi, MPFR_RNDN);
        mpfr_set_q(a, multiple.get_mpq_t(), MPFR_RNDN);
        mpfr_mul(a, a, pi, MPFR_RNDN);
        mpfr_clear(pi);
      },
      pointer, expression, roundings);
}

Point exact_unit_vector_sum(const Rational& phase, const Rational& multiple_of_pi, const std::string& pointer,
                            const std::string& expression, std::vector<Rounding>& roundings) {
  if (phase == 0) return exact_unit_vector_pi(multiple_of_pi, pointer, expression, roundings);
  // A phase whose own direction comes out exact (a quarter turn, rounded or not: 90 degrees)
  // turns the rounded u(pi multiple) exactly: still one rounding, and the same rationals as
  // before this function existed (the ratchet's and the certificate corpus's geometry).
  std::vector<Rounding> phase_rounding;
  Point base = exact_unit_vector(phase, pointer, "phase of " + expression, phase_rounding);
  if (sgn(base.x) == 0 || sgn(base.y) == 0) {
    Point turn = exact_unit_vector_pi(multiple_of_pi, pointer, expression, roundings);
    roundings.insert(roundings.end(), phase_rounding.begin(), phase_rounding.end());
    return Point{turn.x * base.x - turn.y * base.y, turn.x * base.y + turn.y * base.x};
  }
  Rational multiple = multiple_of_pi;
  multiple.canonicalize();
  return memo_direction(
      DirectionKind::sum, phase, multiple,
      [&](mpfr_t a) {
        mpfr_t pi, p;
        mpfr_inits2(working_bits, pi, p, static_cast<mpfr_ptr>(nullptr));
        mpfr_const_pi(pi, MPFR_RNDN);
        mpfr_set_q(a, multiple.get_mpq_t(), MPFR_RNDN);
        mpfr_mul(a, a, pi, MPFR_RNDN);
        mpfr_set_q(p, phase.get_mpq_t(), MPFR_RNDN);
        mpfr_add(a, a, p, MPFR_RNDN);
        mpfr_clears(pi, p, static_cast<mpfr_ptr>(nullptr));
      },
      pointer, expression, roundings);
}

}  // namespace hipair::model_detail
