// Certificates for single configurations: interference and clearance, and the helpers shared by
// every producer (model identity, exact maps, self-check).
#include "certificates/producer.hpp"
#include "core/model_scale.hpp"
#include "certify/planar_check.hpp"

#include <hipair/overlap.hpp>

#include "model/interval.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace hipair {
namespace certify_detail {

const Part& part_of(const Model& model, const std::string& name) {
  auto index = model.find_part(name);
  if (!index) throw ModelError("/parts", "no part called '" + name + "'");
  return model.parts[*index];
}

Certificate start_certificate(const Model& model, const CertifyContext& context, ClaimKind claim,
                              const std::string& first, const std::string& second) {
  part_of(model, first);
  part_of(model, second);
  if (first == second) throw ModelError("/pairs", "a pair needs two different parts");
  Certificate c;
  c.claim = claim;
  c.model_name = model.name;
  c.model_file = std::filesystem::path(model.source).filename().string();
  c.content_hash = model.content_hash;
  for (const Parameter& parameter : model.parameters) {
    auto found = context.parameter_values.find(parameter.name);
    bool overridden = found != context.parameter_values.end();
    c.parameters.push_back({parameter.name, overridden ? found->second : parameter.nominal, overridden});
  }
  c.roundings = model.roundings;
  c.first = first;
  c.second = second;
  return c;
}

void self_check(const Certificate& certificate, const Model& model) {
  VerificationResult result = check_certificate(certificate, model);
  if (!result.valid) throw NumericError("the certificate produced does not pass its own check: " + result.reason);
}

verify::ExactMap exact_map(const Part& part, const ExactPosition* position) {
  verify::ExactMap map;
  switch (part.motion.kind) {
    case Motion::Kind::fixed: return map;
    case Motion::Kind::rotation: {
      if (!position) throw ModelError(part.pointer, "no position given for rotating part '" + part.name + "'");
      const Rational& t = position->value;
      Rational w = 1 + t * t;
      int sign = position->half_turn ? -1 : 1;
      map.c = sign * (1 - t * t) / w;
      map.s = sign * 2 * t / w;
      map.pivot = part.motion.pivot;
      return map;
    }
    case Motion::Kind::translation:
      if (!position) throw ModelError(part.pointer, "no position given for translating part '" + part.name + "'");
      map.shift = Point{Rational(position->value * part.motion.direction.x), Rational(position->value * part.motion.direction.y)};
      return map;
    default:
      throw GeometryError("part '" + part.name + "' is not a fixed-axis part: certificates cover fixed, rotating and translating parts");
  }
}

verify::IntervalMap interval_map(const Part& part, const RationalInterval& range) {
  switch (part.motion.kind) {
    case Motion::Kind::fixed: return verify::IntervalMap{};
    case Motion::Kind::rotation: return verify::rotation_over(range);
    case Motion::Kind::translation: return verify::translation_over(part.motion.direction, range);
    default: throw GeometryError("part '" + part.name + "' is not a fixed-axis part");
  }
}

namespace {
// 10^(floor(log10 |value|) - digits + 1): the last of `digits` significant decimal digits of a
// non-zero value (exactly: no double, any magnitude).
Rational decimal_unit(const Rational& value, int digits) {
  Rational magnitude = abs(value);
  long exponent = long(mpz_sizeinbase(magnitude.get_num_mpz_t(), 10)) - long(mpz_sizeinbase(magnitude.get_den_mpz_t(), 10));
  auto power = [](long e) {
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 10, unsigned(std::abs(e)));
    return e >= 0 ? Rational(p) : Rational(1) / Rational(p);
  };
  while (power(exponent) > magnitude) --exponent;
  while (power(exponent + 1) <= magnitude) ++exponent;
  return power(exponent - digits + 1);
}
}  // namespace

long clearance_search_limit(const Part& a, const verify::ExactMap& map_a, const Part& b, const verify::ExactMap& map_b) {
  auto bits = [](const Rational& r) {
    return long(mpz_sizeinbase(r.get_num_mpz_t(), 2) + mpz_sizeinbase(r.get_den_mpz_t(), 2));
  };
  long total = 0;
  for (const verify::ExactMap* map : {&map_a, &map_b})
    for (const Rational* r : {&map->c, &map->s, &map->pivot.x, &map->pivot.y, &map->shift.x, &map->shift.y})
      total += bits(*r);
  for (const Part* part : {&a, &b}) {
    long largest = 0;
    for (const auto& loop : part->loops)
      for (const auto& edge : loop.edges) largest = std::max({largest, bits(edge.source.x), bits(edge.source.y)});
    total += largest;
  }
  return 4096 + 8 * total;
}

std::optional<Rational> claimed_clearance(const Rational& bound, const std::optional<Rational>& asked, const Part& a,
                                          const verify::ExactMap& map_a, const Part& b, const verify::ExactMap& map_b,
                                          const Rational& cap) {
  auto exactly = [&](const Rational& d) {
    return verify::boundary_distance_at_least(verify::place(a, map_a), verify::place(b, map_b), d);
  };
  if (asked) return bound >= *asked || exactly(*asked) ? asked : std::nullopt;
  if (sgn(bound) <= 0) {
    // Apart (the caller decided it exactly) but closer than the 256-bit enclosures resolve (a
    // gap of 1e-80 mm between parts of 50 mm; until session 74 refused as "touch or overlap",
    // hostile74 M1): cap 2^-e for the least e that holds exactly, found by doubling e and then
    // bisecting it (about 2 log2 e exact tests), within a factor 2 of the distance.
    // The doubling stops at e_max = 4096 + 8 S (clearance_search_limit): S the bits of the
    // inputs (both maps' entries, each part's largest vertex coordinate), 8 the degree of a
    // squared distance in them; beyond, a clear refusal (session 75: it had no bound, and a
    // position with a huge number of digits made every exact test of the search larger).
    if (sgn(cap) <= 0) return std::nullopt;
    auto holds = [&](long e) { return exactly(times_power_of_two(cap, -e)); };
    const long e_max = clearance_search_limit(a, map_a, b, map_b);
    long low = 0, high = 1;   // cap 2^-low does not hold (or low = 0), cap 2^-high is tested
    while (!holds(high)) {
      if (high >= e_max)
        throw GeometryError("cannot certify a clearance of '" + a.name + "' and '" + b.name +
                            "': they are apart but closer than 2^-" + std::to_string(e_max) +
                            " times the distance of two of their boundary points, the bound the search for the "
                            "distance takes from the sizes of the positions and coordinates; claim a distance with "
                            "--distance instead");
      low = high;
      high = std::min(2 * high, e_max);
    }
    while (high - low > 1) {
      const long middle = low + (high - low) / 2;
      (holds(middle) ? high : low) = middle;
    }
    return round_down(times_power_of_two(cap, -high), 6);
  }
  // The bound rounded down to 6 digits; when the bound is a hair under the next 6-digit value
  // (an exact distance of 2e-300 mm enclosed as 1.99999...97e-300), that value if it holds
  // exactly: the found distance is then the same at every scale (session 62, hunt62).
  // The exact test (quadratic in the parts' edges, rational) is asked only when the next 6-digit
  // value is within the enclosure's own width of the bound (the bound comes from 256-bit
  // intervals: 2^-192 of it is wider than that); farther up, a tight bound says it fails.
  Rational down = round_down(bound, 6);
  if (down < bound) {
    Rational up = down + decimal_unit(bound, 6);
    mpz_class width_scale;
    mpz_ui_pow_ui(width_scale.get_mpz_t(), 2, 192);
    if ((up - bound) * Rational(width_scale) <= bound && exactly(up)) return up;
  }
  return down;
}

Rational round_down(const Rational& value, int digits) {
  if (sgn(value) == 0) return value;
  Rational unit = decimal_unit(value, digits);
  Rational steps = value / unit;
  mpz_class whole;
  mpz_tdiv_q(whole.get_mpz_t(), steps.get_num_mpz_t(), steps.get_den_mpz_t());
  return Rational(whole) * unit;
}

Rational approximate(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.15g", value);   // a short decimal, readable in certificates
  return parse_rational(text);
}

namespace {

Placement to_placement(const verify::ExactMap& map) { return placement_about(map.pivot, map.c, map.s, map.shift); }

const ExactPosition* position_of(const std::map<std::string, ExactPosition>& positions, const Part& part) {
  auto found = positions.find(part.name);
  return found == positions.end() ? nullptr : &found->second;
}

// A position beyond the part's motion limits is an input error naming the part and its limits,
// decided by the verifier's own test (an angle must be certainly within them: a tangent at a
// limit's irrational neighbourhood is refused too). Until session 32 it reached the self-check
// ("does not pass its own check", exit 3).
void require_within_limits(const Part& part, const ExactPosition& position) {
  bool rotating = part.motion.kind == Motion::Kind::rotation;
  const std::optional<RationalInterval>& limits = rotating ? part.motion.angle_limits : part.motion.translation_limits;
  if (!limits) return;
  bool within = rotating ? verify::certainly_within(limits, verify::angle_of_tangent(position.value, position.half_turn), true)
                         : limits->lo <= position.value && position.value <= limits->hi;
  if (!within)
    throw ModelError(part.pointer, std::string("the ") + (rotating ? "angle" : "offset") + " of '" + part.name + "' (" +
                                       verify::position_text(position) + ") is " + (rotating ? "not certainly within" : "outside") +
                                       " its motion limits [" + to_decimal_string(limits->lo) + ", " +
                                       to_decimal_string(limits->hi) + "]" + (rotating ? " rad" : " mm"));
}

// Only the moving parts of the pair keep a position.
std::map<std::string, ExactPosition> pair_positions(const std::map<std::string, ExactPosition>& positions,
                                                    const Part& a, const Part& b) {
  std::map<std::string, ExactPosition> result;
  for (const Part* part : {&a, &b})
    if (part->motion.kind != Motion::Kind::fixed) {
      const ExactPosition* position = position_of(positions, *part);
      if (!position) throw ModelError(part->pointer, "no position given for moving part '" + part->name + "'");
      ExactPosition copy = *position;
      copy.is_offset = part->motion.kind == Motion::Kind::translation;
      require_within_limits(*part, copy);
      result[part->name] = copy;
    }
  return result;
}

}  // namespace
}  // namespace certify_detail

using namespace certify_detail;

namespace {

// exact_position_from_angle at the enclosures' current precision; nullopt when the reduction to a
// turn is not bounded there.
std::optional<ExactPosition> position_from_angle(const Rational& angle) {
  using model_detail::Interval;
  ExactPosition position;
  position.angle = angle;
  if (sgn(angle) == 0) {
    position.angle_error = Rational(0);
    return position;
  }
  // Reduce to about [-pi, pi] and choose the chart (centre 0 or pi) from the middle of the
  // enclosures: choices, not decisions (the error bound below is certified whatever is chosen).
  Interval two_pi = Interval::pi() * Interval(Rational(2));
  Interval quotient = Interval(angle) / two_pi;
  mpfr_t middle;
  mpfr_init2(middle, model_detail::interval_bits);
  mpfi_mid(middle, quotient.get());
  mpz_class turns;
  mpfr_get_z(turns.get_mpz_t(), middle, MPFR_RNDN);
  mpfr_clear(middle);
  Interval reduced = Interval(angle) - two_pi * Interval(Rational(turns));
  if (!reduced.is_bounded()) return std::nullopt;
  Rational reduced_middle = reduced.middle(), quarter = (Interval::pi() / Interval(Rational(2))).middle();
  position.half_turn = abs(reduced_middle) > quarter;
  Interval shift = position.half_turn ? Interval::pi() * Interval(Rational(sgn(reduced_middle))) : Interval(Rational(0));
  Interval half = (reduced - shift) / Interval(Rational(2)), tangent;
  mpfi_tan(tangent.get(), half.get());
  if (!tangent.is_bounded()) return std::nullopt;
  // Round t to a multiple of 10^-18: the angle moves by at most 2 * 10^-18 rad.
  Rational grid(1, 1000000000000000000ul);
  Rational steps = tangent.middle() / grid;
  mpz_class whole;
  mpz_fdiv_q(whole.get_mpz_t(), steps.get_num_mpz_t(), steps.get_den_mpz_t());
  position.value = Rational(whole) * grid;
  Interval back;
  mpfi_atan(back.get(), Interval(position.value).get());
  Interval error = (back - half) * Interval(Rational(2)), size;
  mpfi_abs(size.get(), error.get());
  if (!size.is_bounded()) return std::nullopt;
  position.angle_error = round_down(size.upper(), 2) * 2 + Rational(1, 1000000000000000000ul);
  // An angle beyond about 10^60 rad reduces to a turn with an error above the verifier's limit
  // for a label (verify::max_angle_error): then the position carries no label and the statement
  // gives its exact angle 2 atan(t) (session 42).
  if (*position.angle_error > verify::max_angle_error()) {
    position.angle.reset();
    position.angle_error.reset();
  }
  return position;
}

}  // namespace

ExactPosition exact_position_from_angle(const Rational& angle) {
  if (auto position = position_from_angle(angle); position && position->angle) return *position;
  // Beyond about 10^60 rad the reduction to a turn at 256 bits is coarser than the label's limit,
  // beyond about 10^77 rad unbounded: retried with the enclosures' precision raised by the angle's
  // bit length (the reader's limit of 10^1000 needs about 3 600 bits). Until session 65 (hunt65)
  // the tangent was then any of the coarse enclosure's (1e77 rad: 0.026 turns, 9.5 degrees, from
  // the angle asked for, without a word) or, from 10^77 rad, `certify --at peg=20,0,1e400` stopped
  // with exit 3 "too large to reduce to a turn at 256 bits". The position carries no label (the
  // verifier's 256-bit check of a label could not hold it), as before beyond 10^60 rad.
  const mpfr_prec_t bits = model_detail::interval_bits + 64 +
                           std::max<mpfr_prec_t>(0, static_cast<mpfr_prec_t>(mpz_sizeinbase(angle.get_num_mpz_t(), 2)) -
                                                        static_cast<mpfr_prec_t>(mpz_sizeinbase(angle.get_den_mpz_t(), 2)));
  if (bits <= model_detail::most_interval_bits) {
    model_detail::PrecisionScope scope(bits);
    if (auto position = position_from_angle(angle)) {
      position->angle.reset();
      position->angle_error.reset();
      return *position;
    }
  }
  throw NumericError("the angle " + to_decimal_string(angle) + " rad is too large to reduce to a turn");
}

std::optional<Certificate> certify_interference(const Model& model, const std::string& first, const std::string& second,
                                                const std::map<std::string, ExactPosition>& positions,
                                                const CertifyContext& context) {
  Certificate c = start_certificate(model, context, ClaimKind::interference, first, second);
  const Part &a = part_of(model, first), &b = part_of(model, second);
  c.configuration = pair_positions(positions, a, b);
  verify::ExactMap map_a = exact_map(a, position_of(c.configuration, a)), map_b = exact_map(b, position_of(c.configuration, b));
  PartOverlap report = part_overlap(a, to_placement(map_a), b, to_placement(map_b), true);
  if (report.relation != PartRelation::overlapping) return std::nullopt;
  if (report.witness) {
    c.witness_point = report.witness;
  } else {   // a transversal crossing of two edges, found with the verifier's own predicate
    verify::PlacedPart placed_a = verify::place(a, map_a), placed_b = verify::place(b, map_b);
    for (std::size_t i = 0; i < a.loops.size() && !c.witness_crossing; ++i)
      for (std::size_t j = 0; j < a.loops[i].edges.size() && !c.witness_crossing; ++j)
        for (std::size_t k = 0; k < b.loops.size() && !c.witness_crossing; ++k)
          for (std::size_t l = 0; l < b.loops[k].edges.size() && !c.witness_crossing; ++l)
            if (verify::edges_cross(placed_a.loops[i][j], placed_b.loops[k][l]))
              c.witness_crossing = CrossingWitness{{first, i, j, a.loops[i].edges[j].label},
                                                   {second, k, l, b.loops[k].edges[l].label}, std::nullopt};
    if (!c.witness_crossing) return std::nullopt;
  }
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}

std::optional<Certificate> certify_clearance(const Model& model, const std::string& first, const std::string& second,
                                             const std::map<std::string, ExactPosition>& positions,
                                             std::optional<Rational> distance, const CertifyContext& context) {
  // a pair far from the origin for its size is certified moved to it (its enclosures there)
  if (std::optional<Model> moved = pair_moved_to_origin(model, first, second))
    return checked_as_given(certify_clearance(*moved, first, second, positions, distance, context), model);
  Certificate c = start_certificate(model, context, ClaimKind::clearance, first, second);
  const Part &a = part_of(model, first), &b = part_of(model, second);
  c.configuration = pair_positions(positions, a, b);
  verify::ExactMap map_a = exact_map(a, position_of(c.configuration, a)), map_b = exact_map(b, position_of(c.configuration, b));
  if (part_overlap(a, to_placement(map_a), b, to_placement(map_b)).relation != PartRelation::apart) return std::nullopt;
  // Capped at an upper bound of the distance (the L1 distance of two boundary points), so that
  // nothing is lost at any magnitude.
  Point p = map_a.apply(a.loops.at(0).edges.at(0).source), q = map_b.apply(b.loops.at(0).edges.at(0).source);
  Rational cap = abs(p.x - q.x) + abs(p.y - q.y);
  if (distance && *distance > cap) return std::nullopt;
  Rational bound = verify::boundary_distance_lower_bound(verify::shape_of(a), verify::to_interval_map(map_a), verify::shape_of(b), verify::to_interval_map(map_b), cap);
  std::optional<Rational> claimed = claimed_clearance(bound, distance, a, map_a, b, map_b, cap);
  if (!claimed) return std::nullopt;
  c.distance = *claimed;
  c.statement = certificate_statement(c, model);
  self_check(c, model);
  return c;
}

}  // namespace hipair
