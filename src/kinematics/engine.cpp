// Quasi-static motion of a chain of fixed-axis parts on exact C-space slices.
//
// Rule for a follower when the driver moves from u to u' (both exact rational chart values):
// its free range at u' is the intersection of the slices of all its pairs with parts placed
// before it. If its old position is still free it stays there (no load), or moves to the end
// of the free range its load pushes it to (or to the spring's rest, if that comes first). If
// its old position became blocked, a contact has pushed it: it moves to the end of the
// neighbouring free range that overlaps its old range (the free range moved continuously). If
// no such range exists the follower is squeezed and the driver is blocked.
#include "kinematics/engine.hpp"

#include "core/angle_limits.hpp"
#include "core/angle_sign.hpp"
#include "kernels/implicit_curve.hpp"

#include <hipair/error.hpp>
#include <hipair/motion_words.hpp>

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <optional>

namespace hipair::kinematics_detail {

namespace algebra = cspace::algebra;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double infinity = std::numeric_limits<double>::infinity();

bool same_chart(const ChartAxis& a, const ChartAxis& b) {
  return a.kind == b.kind && a.half_turn == b.half_turn && a.lo == b.lo && a.hi == b.hi;
}

int motion_dof(const Motion& motion) { return motion.degrees_of_freedom(); }

bool fixed_axis(const Motion& motion) {
  return motion.kind == Motion::Kind::fixed || motion.kind == Motion::Kind::rotation ||
         motion.kind == Motion::Kind::translation;
}

// Why a pair of the model is not one the kinematic analysis takes (its parts both fixed-axis
// and not both fixed), named with its JSON pointer, as `hipair cspace` names a pair it does
// not build; empty for a pair it takes.
std::string pair_refusal(const Model& model, const PairSpec& spec) {
  const Part& a = model.parts[spec.first];
  const Part& b = model.parts[spec.second];
  const std::string pair = "pair '" + a.name + "':'" + b.name + "' (" + spec.pointer + ")";
  if (motion_dof(a.motion) == 0 && motion_dof(b.motion) == 0) return pair + ": both parts are fixed";
  if (fixed_axis(a.motion) && fixed_axis(b.motion)) return {};
  const Part& odd = fixed_axis(a.motion) ? b : a;
  const Part& other = &odd == &a ? b : a;
  return pair + ": the " + described_part(odd) + " against the " + described_part(other) + " has a C-space of " +
         std::to_string(a.motion.degrees_of_freedom() + b.motion.degrees_of_freedom()) +
         " dimensions, which the kinematic analysis does not take (analyze takes pairs of fixed, rotating and translating "
         "parts, and a pin-slot part's work cycle; `hipair cspace` builds a planar part's C-space against a fixed part)";
}

// Rounds a rational to the grid 2^-bits (nearest).
Rational round_to_bits(const Rational& value, int bits) {
  mpz_class scale = mpz_class(1) << bits;
  Rational scaled = value * scale + Rational(1, 2);
  mpz_class floor_value;
  mpz_fdiv_q(floor_value.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());
  Rational result(floor_value, scale);
  result.canonicalize();
  return result;
}

// tan((theta - multiple_of_pi * pi) / 2), rounded to the grid 2^-bits. The precision covers the
// magnitudes of theta and of the multiple of pi (session 56: 200 bits left nothing of theta - m pi
// beyond about 10^40 rad), so the difference keeps bits + 140 bits.
Rational half_tangent(const Rational& theta, const mpz_class& multiple_of_pi, int bits) {
  if (sgn(multiple_of_pi) == 0 && theta == 0) return Rational(0);
  const mpfr_prec_t precision =
      std::max<long>(200, bits + 140 + std::max(magnitude_bits(theta), magnitude_bits(multiple_of_pi)) + 2);
  mpfr_t x, p;
  mpfr_inits2(precision, x, p, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_q(x, theta.get_mpq_t(), MPFR_RNDN);
  mpfr_const_pi(p, MPFR_RNDN);
  mpfr_mul_z(p, p, multiple_of_pi.get_mpz_t(), MPFR_RNDN);
  mpfr_sub(x, x, p, MPFR_RNDN);
  mpfr_div_ui(x, x, 2, MPFR_RNDN);
  mpfr_tan(x, x, MPFR_RNDN);
  mpq_t exact;
  mpq_init(exact);
  mpfr_get_q(exact, x);
  Rational value(exact);
  mpq_clear(exact);
  mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
  return round_to_bits(value, bits);
}

void sort_contacts(std::vector<SliceContact>& contacts) {
  std::sort(contacts.begin(), contacts.end(), [](const SliceContact& a, const SliceContact& b) {
    return std::tie(a.limit, a.slicer, a.feature) < std::tie(b.limit, b.slicer, b.feature);
  });
  contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
}

}  // namespace

LocatedCoordinate locate_coordinate(const AxisLine& line, const Rational& coordinate_value, int bits) {
  LocatedCoordinate out;
  if (!line.rotation) {
    const ChartAxis& piece = line.pieces.front();
    out.beyond = coordinate_value < piece.lo ? -1 : coordinate_value > piece.hi ? 1 : 0;
    out.position = AxisPosition{0, Real::from_rational(std::clamp(coordinate_value, piece.lo, piece.hi))};
    return out;
  }
  // 2 theta against (2 m -+ 1) pi, exactly (core/angle_sign.hpp: never equal but at 0)
  const Rational twice = 2 * coordinate_value;
  auto below_half_turn = [&](const mpz_class& odd) { return angle_sign(Rational(0), odd, twice) > 0; };   // 2 theta < odd pi
  std::size_t piece = 0;
  mpz_class m;
  if (line.cyclic) {
    // the chart about m pi with theta in [m pi - pi / 2, m pi + pi / 2): piece 0 about the even m,
    // piece 1 about the odd (session 56: a double floor before, garbage beyond 2^53 rad); the
    // nearest whole turns are an estimate, made exact by the signs
    m = 2 * nearest_whole_turns(coordinate_value);
    while (below_half_turn(2 * m - 1)) --m;
    while (!below_half_turn(2 * m + 1)) ++m;
    piece = mpz_odd_p(m.get_mpz_t()) ? 1 : 0;
  } else {
    // the first piece whose end is not below theta (pieces in the order of their half turns,
    // glued at seams), exactly; below the first or above the last: that end (session 56: the
    // nearest piece by double distances before)
    piece = line.pieces.size();
    for (std::size_t p = 0; p < line.pieces.size() && piece == line.pieces.size(); ++p) {
      const mpz_class half_turns(line.half_turns[p]);
      // theta <= half_turns pi + 2 atan(hi): inside piece p, or in a gap before it (its start)
      if (angle_sign(line.pieces[p].hi, half_turns, coordinate_value) >= 0) piece = p;
    }
    // beyond the piece's start or end: that end (the half-angle tangent about the piece's centre
    // of an angle more than a half turn away is no clamp to the right side)
    std::optional<Rational> end;
    if (piece == line.pieces.size()) {
      piece = line.pieces.size() - 1;
      out.beyond = 1;
      end = line.pieces[piece].hi;
    } else if (angle_sign(line.pieces[piece].lo, mpz_class(line.half_turns[piece]), coordinate_value) > 0) {
      if (piece == 0) out.beyond = -1;
      end = line.pieces[piece].lo;
    }
    m = line.half_turns[piece];
    if (end) {
      out.position = canonical(line, AxisPosition{piece, Real::from_rational(*end)});
      out.half_turns = out.position.piece != piece ? mpz_class(line.half_turns[out.position.piece]) : m;
      return out;
    }
  }
  Rational t = half_tangent(coordinate_value, m, bits);
  t = std::clamp(t, line.pieces[piece].lo, line.pieces[piece].hi);
  AxisPosition position{piece, Real::from_rational(t)};
  out.position = canonical(line, position);
  if (out.position.piece != piece) m = line.cyclic ? mpz_class(m + 1) : mpz_class(line.half_turns[out.position.piece]);
  out.half_turns = m;
  return out;
}

AxisPosition position_of_coordinate(const AxisLine& line, const Rational& coordinate_value, int bits) {
  return locate_coordinate(line, coordinate_value, bits).position;
}

AxisPosition rest_position(const AxisLine& line, const Rational& rest, const Bound& low, double low_unwrapped,
                           const Bound& high, double high_unwrapped) {
  // the rest's double: only the hint of its whole turns for compare_unwrapped (within a quarter
  // turn of the rest while |rest| < 2^40 rad, which analyze_kinematics requires of a rotating
  // follower's spring rest and initial angle, session 56)
  const double rest_unwrapped = rest.get_d();
  for (int bits = 60; bits <= 4096; bits *= 2) {
    AxisPosition at = position_of_coordinate(line, rest, bits);
    if (!line.rotation) return at;   // the rest itself (clamped to the axis, whose ends bound it)
    bool above_low = !low.exists || compare_unwrapped(line, low.at, low_unwrapped, at, rest_unwrapped) < 0;
    bool below_high = !high.exists || compare_unwrapped(line, at, rest_unwrapped, high.at, high_unwrapped) < 0;
    if (above_low && below_high) return at;
  }
  throw NumericError("a spring's rest angle " + rest.get_str() + " rad lies within 2^-4096 of a contact");
}

// ------------------------------------------------------------------------------ chain

namespace {

// The chain's parts in breadth-first order from the driver through its usable pairs (both parts
// fixed-axis, not both fixed), the parts' chain indices, and the pairs left out with the reason.
void order_chain(const Model& model, std::size_t driver, std::vector<bool>& usable,
                 std::vector<std::size_t>& chain_index, std::vector<std::size_t>& order, std::vector<std::string>* warnings) {
  usable.assign(model.pairs.size(), true);
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairSpec& spec = model.pairs[p];
    const Part& a = model.parts[spec.first];
    const Part& b = model.parts[spec.second];
    if (!fixed_axis(a.motion) || !fixed_axis(b.motion)) {
      usable[p] = false;
      if (warnings)
        warnings->push_back("pair " + a.name + ":" + b.name +
                            " is skipped: kinematic analysis handles parts that rotate or translate about fixed axes");
    }
    if (motion_dof(a.motion) == 0 && motion_dof(b.motion) == 0) usable[p] = false;
  }
  chain_index.assign(model.parts.size(), none);
  order.assign(1, driver);
  chain_index[driver] = 0;
  for (std::size_t head = 0; head < order.size(); ++head) {
    std::size_t current = order[head];
    for (std::size_t p = 0; p < model.pairs.size(); ++p) {
      if (!usable[p]) continue;
      const PairSpec& spec = model.pairs[p];
      std::size_t other = spec.first == current ? spec.second : spec.second == current ? spec.first : none;
      if (other == none || motion_dof(model.parts[other].motion) == 0 || chain_index[other] != none) continue;
      chain_index[other] = order.size();
      order.push_back(other);
    }
  }
}

// The follower a usable pair's slicer constrains (a moving part of the chain), or none when the
// pair is not the chain's (no part of it reached from the driver).
std::size_t chain_follower(const Model& model, const PairSpec& spec, const std::vector<std::size_t>& chain_index) {
  std::size_t ia = chain_index[spec.first], ib = chain_index[spec.second];
  bool fixed_a = motion_dof(model.parts[spec.first].motion) == 0;
  bool fixed_b = motion_dof(model.parts[spec.second].motion) == 0;
  if (fixed_a) return ib == none ? none : spec.second;
  if (fixed_b) return ia == none ? none : spec.first;
  if (ia != none && ib != none) return ia > ib ? spec.first : spec.second;
  return none;
}

}  // namespace

std::vector<std::size_t> chain_pairs(const Model& model, std::size_t driver) {
  std::vector<bool> usable;
  std::vector<std::size_t> chain_index, order, pairs;
  order_chain(model, driver, usable, chain_index, order, nullptr);
  for (std::size_t p = 0; p < model.pairs.size(); ++p)
    if (usable[p] && chain_follower(model, model.pairs[p], chain_index) != none) pairs.push_back(p);
  return pairs;
}

Chain build_chain(const Model& model, std::size_t driver, const std::vector<CSpace>& spaces,
                  SliceMethod method, const std::map<std::string, FollowerLoad>& loads) {
  Chain chain;
  chain.model = &model;
  const Part& driver_part = model.parts.at(driver);
  if (driver_part.motion.kind != Motion::Kind::rotation && driver_part.motion.kind != Motion::Kind::translation)
    throw GeometryError("the driver '" + driver_part.name + "' must rotate or translate about a fixed axis");
  std::vector<bool> usable;
  std::vector<std::size_t> order;
  order_chain(model, driver, usable, chain.chain_index, order, &chain.warnings);
  for (std::size_t i = 0; i < model.parts.size(); ++i)
    if (chain.chain_index[i] == none && motion_dof(model.parts[i].motion) > 0) chain.unconnected.push_back(model.parts[i].name);
  chain.parts.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) chain.parts[k].part = order[k];

  KernelSlicerOptions kernel_options;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    if (!usable[p]) continue;
    const PairSpec& spec = model.pairs[p];
    std::size_t follower = chain_follower(model, spec, chain.chain_index);
    if (follower == none) continue;
    std::unique_ptr<PairSlicer> slicer;
    std::string used = "kernels";
    if (method != SliceMethod::kernels) {
      const CSpace* space = nullptr;
      for (const CSpace& candidate : spaces)
        if (candidate.first_part() == model.parts[spec.first].name && candidate.second_part() == model.parts[spec.second].name)
          space = &candidate;
      if (space) {
        try {
          slicer = make_cspace_slicer(model, *space, p, follower);
          used = "cspace";
        } catch (const GeometryError& error) {
          if (method == SliceMethod::cspace) throw;
          chain.warnings.push_back("pair " + model.parts[spec.first].name + ":" + model.parts[spec.second].name +
                                   ": C-space slices unavailable (" + error.what() + "), using the contact kernels");
        }
      } else if (method == SliceMethod::cspace) {
        throw GeometryError("no C-space was built for pair " + model.parts[spec.first].name + ":" +
                            model.parts[spec.second].name);
      }
    }
    if (!slicer) {
      // the kernel slicers of the chain share the selections of congruent pairs
      if (!kernel_options.selections) kernel_options.selections = std::make_shared<SelectionMemo>();
      slicer = make_kernel_slicer(model, p, follower, kernel_options);
    }
    chain.parts[chain.chain_index[follower]].constraints.push_back(chain.slicers.size());
    chain.slicers.push_back(std::move(slicer));
    chain.slicer_methods.push_back(used);
  }
  // axes
  for (std::size_t k = 0; k < chain.parts.size(); ++k) {
    std::vector<ChartAxis> charts;
    for (const auto& slicer : chain.slicers) {
      if (slicer->follower() == chain.parts[k].part)
        charts.insert(charts.end(), slicer->follower_charts().begin(), slicer->follower_charts().end());
      if (slicer->other_moves() && slicer->other() == chain.parts[k].part)
        charts.insert(charts.end(), slicer->other_charts().begin(), slicer->other_charts().end());
    }
    if (charts.empty()) {
      // (the driver: any other chain part is reached through a pair the analysis takes)
      std::string reasons;
      for (const PairSpec& spec : model.pairs)
        if (spec.first == chain.parts[k].part || spec.second == chain.parts[k].part)
          if (std::string why = pair_refusal(model, spec); !why.empty()) reasons += "; " + why;
      throw GeometryError("part '" + model.parts[chain.parts[k].part].name + "' is in no pair that can be analysed" +
                          (reasons.empty() ? std::string() : ":" + reasons.substr(1)));
    }
    chain.parts[k].line = make_axis(model, chain.parts[k].part, charts);
  }
  chain.other_chart_of_piece.resize(chain.slicers.size());
  for (std::size_t s = 0; s < chain.slicers.size(); ++s) {
    const PairSlicer& slicer = *chain.slicers[s];
    if (!slicer.other_moves()) continue;
    const AxisLine& line = chain.parts[chain.chain_index[slicer.other()]].line;
    for (const ChartAxis& piece : line.pieces) {
      std::size_t found = none;
      for (std::size_t c = 0; c < slicer.other_charts().size(); ++c)
        if (!line.rotation || same_chart(slicer.other_charts()[c], piece)) {
          found = c;
          break;
        }
      chain.other_chart_of_piece[s].push_back(found);
    }
  }
  // loads
  std::map<std::string, FollowerLoad> from_model = hipair::model_loads(model);
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    const std::string& name = model.parts[chain.parts[k].part].name;
    if (auto found = loads.find(name); found != loads.end()) chain.parts[k].load = found->second;
    else if (auto modelled = from_model.find(name); modelled != from_model.end()) chain.parts[k].load = modelled->second;
  }
  return chain;
}

// ------------------------------------------------------------------------------ step

namespace {

// The other part's chart and value for slicer s at `state` (false: the pair is skipped — the
// other part's piece has no chart of the pair, or its value lies beyond any contact of the pair).
bool other_of(const Chain& chain, const ChainState& state, std::size_t s, std::size_t& other_chart, Rational& value) {
  const PairSlicer& slicer = *chain.slicers[s];
  if (!slicer.other_moves()) return true;
  const PartState& other = state.parts[chain.chain_index[slicer.other()]];
  other_chart = chain.other_chart_of_piece[s][other.position.piece];
  if (other_chart == none) return false;
  value = rational_near(other.position.value);
  const ChartAxis& chart = slicer.other_charts()[other_chart];
  return !(value < chart.lo || value > chart.hi);
}

AxisSlice constraint_slice(const Chain& chain, const ChainState& state, std::size_t k,
                           const AxisWindow* window = nullptr, ChartSliceMemo* memo = nullptr) {
  const AxisLine& line = chain.parts[k].line;
  AxisSlice result;
  bool first = true;
  for (std::size_t s : chain.parts[k].constraints) {
    const PairSlicer& slicer = *chain.slicers[s];
    std::size_t other_chart = 0;
    Rational value;
    if (!other_of(chain, state, s, other_chart, value)) continue;
    // a pair with a fixed part is sliced whole (and kept by its slicer): no memo
    AxisSlice slice = slicer.other_moves() ? slice_on_axis(line, slicer, s, other_chart, value, window, memo)
                                           : slice_on_axis(line, slicer, s, other_chart, value);
    result = first ? std::move(slice) : intersect(line, result, slice);
    first = false;
  }
  return result;
}

void jam(ChainState& state, std::size_t part, std::string reason, std::vector<SliceContact> contacts) {
  state.jammed = true;
  state.jam_part = part;
  state.jam_reason = std::move(reason);
  sort_contacts(contacts);
  state.jam_contacts = std::move(contacts);
}

bool non_blocked(const AxisSlice& slice, std::size_t interval) { return slice.kind(interval) != SliceKind::blocked; }

enum class Outcome { moved, jammed, widen, coarse };


// Moves part k of `next` given its old state and its free space `slice`. `widen`: the decision
// needs the slice beyond its window.
Outcome update_part(const Chain& chain, std::size_t k, const PartState& old, const AxisSlice& slice, ChainState& next,
                    bool initial, double max_push) {
  const AxisLine& line = chain.parts[k].line;
  const AxisPosition& y = old.position;
  PartState& out = next.parts[k];
  out.blocked_by.clear();
  out.at_rest = false;
  Placement placement = place(line, slice, y);
  std::size_t n = slice.points.size();
  std::size_t interval = 0;
  AxisPosition start = y;   // where the follower is after being pushed
  double moved = 0;         // signed coordinate change so far
  bool pushed = false;
  auto old_down = [&]() { return old.lower.exists && !initial ? distance_down(line, y, old.lower.at) : infinity; };
  auto old_up = [&]() { return old.upper.exists && !initial ? distance_up(line, y, old.upper.at) : infinity; };
  // A follower in contact follows the contact curve it was on (compliant motion), however
  // narrow its free channel: find the same contact with the same orientation nearby.
  // A zero-clearance channel (a touching point with blocked space on both sides) is a free
  // range of zero width: the follower sits on it and moves with it.
  auto settle = [&](std::size_t i, double offset) {
    const Breakpoint& point = slice.points[i];
    Bound bound;
    bound.exists = true;
    bound.at = point.at;
    bound.contacts = point.contacts;
    out.position = point.at;
    out.unwrapped = old.unwrapped + offset;
    out.lower = bound;
    out.upper = bound;
    out.kind = SliceKind::touching;
    out.pushed = offset != 0;
    out.push_distance = std::abs(offset);
    out.side = 0;
    out.channel = true;
    out.contacts = point.contacts;
    sort_contacts(out.contacts);
    return Outcome::moved;
  };
  auto offset_to = [&](const AxisPosition& at) {
    if (compare(at, y) == 0) return 0.0;
    double offset = coordinate(line, at) - coordinate(line, y);
    return line.cyclic ? std::remainder(offset, 2 * pi) : offset;
  };
  if (!initial && old.channel) {
    // the same channel nearby: a channel point sharing a contact with the old one
    std::size_t nearest = none;
    double best = infinity, best_offset = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Breakpoint& point = slice.points[i];
      if (!point.channel) continue;
      bool shares = std::any_of(point.contacts.begin(), point.contacts.end(), [&](const SliceContact& c) {
        return !c.limit && std::find(old.contacts.begin(), old.contacts.end(), c) != old.contacts.end();
      });
      if (!shares) continue;
      double offset = offset_to(point.at);
      if (std::abs(offset) < best) {
        best = std::abs(offset);
        nearest = i;
        best_offset = offset;
      }
    }
    if (nearest != none && best <= pi / 8) {
      if (best > max_push) return Outcome::coarse;
      return settle(nearest, best_offset);
    }
  }
  if (placement.on_point && slice.points[placement.point].channel) return settle(placement.point, 0);
  out.channel = false;
  std::size_t followed = none;
  double followed_offset = 0;   // signed coordinate offset of the contact point from y
  if (!initial && old.side != 0 && !old.contacts.empty()) {
    double best = infinity;
    for (std::size_t i = 0; i < n; ++i) {
      const Breakpoint& point = slice.points[i];
      bool shares = std::any_of(point.contacts.begin(), point.contacts.end(), [&](const SliceContact& c) {
        return !c.limit && std::find(old.contacts.begin(), old.contacts.end(), c) != old.contacts.end();
      });
      if (!shares) continue;
      bool blocked_below = !non_blocked(slice, interval_before(line, slice, i));
      bool blocked_above = !non_blocked(slice, interval_after(slice, i));
      if (old.side < 0 ? !(blocked_below && !blocked_above) : !(blocked_above && !blocked_below)) continue;
      double offset = 0;
      if (compare(point.at, y) != 0) {
        offset = coordinate(line, point.at) - coordinate(line, y);
        if (line.cyclic) offset = std::remainder(offset, 2 * pi);
      }
      if (std::abs(offset) < best) {
        best = std::abs(offset);
        followed = i;
        followed_offset = offset;
      }
    }
    if (followed != none && best > pi / 8) followed = none;   // too far to be the same contact
  }
  if (followed != none) {
    // the contact point moved to `offset` from y: it pushes when it moved into the free side
    std::size_t free_side = old.side < 0 ? interval_after(slice, followed) : interval_before(line, slice, followed);
    bool pushing = old.side < 0 ? followed_offset >= 0 : followed_offset <= 0;
    interval = free_side;
    if (pushing && std::abs(followed_offset) > max_push) return Outcome::coarse;
    if (pushing) {
      // The contact may not carry the follower past the far end of its old free range unless
      // that end is still bounded by the same contact: otherwise the step may have passed
      // through a point where the free range closes (the driver is blocked there).
      Bound far = old.side < 0 ? upper_end(line, slice, free_side) : lower_end(line, slice, free_side);
      const Bound& old_far = old.side < 0 ? old.upper : old.lower;
      if (has_window_edge(far.contacts)) return Outcome::widen;
      bool same_far = far.exists && old_far.exists && std::any_of(far.contacts.begin(), far.contacts.end(), [&](const SliceContact& c) {
        return std::find(old_far.contacts.begin(), old_far.contacts.end(), c) != old_far.contacts.end();
      });
      if (!same_far && old_far.exists) {
        // the contact point reached the old far end or passed it: decided exactly
        double reach = old.side < 0 ? distance_up(line, y, old_far.at) : distance_down(line, y, old_far.at);
        int past = compare_unwrapped(line, slice.points[followed].at, old.unwrapped + followed_offset, old_far.at,
                                     old.unwrapped - old.side * reach);
        if (old.side > 0 ? past <= 0 : past >= 0) {
          if (std::isfinite(max_push)) return Outcome::coarse;
          std::vector<SliceContact> contacts = old.contacts;
          contacts.insert(contacts.end(), old_far.contacts.begin(), old_far.contacts.end());
          jam(next, k, "its free range closed: it cannot move out of the way", std::move(contacts));
          return Outcome::jammed;
        }
      }
    }
    if (pushing) {
      start = slice.points[followed].at;
      moved = followed_offset;
      pushed = followed_offset != 0;
      out.push_distance = std::abs(moved);
    } else if (placement.on_point || !non_blocked(slice, placement.interval) || placement.interval != free_side) {
      followed = none;   // y is not in the free range next to the contact: decide as usual
    }
  }
  if (followed != none) {
    // decided above
  } else if (placement.on_point) {
    std::size_t before = interval_before(line, slice, placement.point);
    std::size_t after = interval_after(slice, placement.point);
    bool free_before = non_blocked(slice, before), free_after = after <= n && non_blocked(slice, after);
    if (!free_before && !free_after) {
      if (has_window_edge(slice.points[placement.point].contacts)) return Outcome::widen;
      jam(next, k, "squeezed between two contacts", slice.points[placement.point].contacts);
      return Outcome::jammed;
    }
    if (free_before && free_after) interval = old_up() >= old_down() ? after : before;
    else interval = free_before ? before : after;
  } else if (non_blocked(slice, placement.interval)) {
    interval = placement.interval;
  } else {
    std::size_t i = placement.interval;
    Bound blocked_low = lower_end(line, slice, i), blocked_high = upper_end(line, slice, i);
    if (has_window_edge(blocked_low.contacts) || has_window_edge(blocked_high.contacts)) return Outcome::widen;
    bool can_below = blocked_low.exists && !blocked_low.limit;
    bool can_above = blocked_high.exists && !blocked_high.limit;
    std::size_t below = 0, above = 0;
    if (can_below) {
      below = i - 1;
      if (line.cyclic && below == 0) below = n;
      can_below = non_blocked(slice, below);
    }
    if (can_above) {
      above = (line.cyclic && i == n) ? 1 : i + 1;
      can_above = above <= n && non_blocked(slice, above);
    }
    // an end of the blocked interval may be a zero-clearance channel: a place to stay
    std::size_t low_point = i >= 1 ? i - 1 : (line.cyclic && n > 0 ? n - 1 : none);
    std::size_t high_point = i < n ? i : (line.cyclic && n > 0 ? 0 : none);
    bool channel_below = !can_below && blocked_low.exists && !blocked_low.limit && low_point != none &&
                         slice.points[low_point].channel && compare(slice.points[low_point].at, blocked_low.at) == 0;
    bool channel_above = !can_above && blocked_high.exists && !blocked_high.limit && high_point != none &&
                         slice.points[high_point].channel && compare(slice.points[high_point].at, blocked_high.at) == 0;
    can_below = can_below || channel_below;
    can_above = can_above || channel_above;
    double down = can_below ? distance_down(line, y, blocked_low.at) : infinity;
    double up = can_above ? distance_up(line, y, blocked_high.at) : infinity;
    // the free range moved continuously: the new one overlaps the old one
    // (exactly: the blocked interval's end lies strictly inside the old free range)
    if (can_below && old.lower.exists && !initial &&
        compare_unwrapped(line, blocked_low.at, old.unwrapped - down, old.lower.at, old.unwrapped - old_down()) <= 0)
      can_below = false;
    if (can_above && old.upper.exists && !initial &&
        compare_unwrapped(line, blocked_high.at, old.unwrapped + up, old.upper.at, old.unwrapped + old_up()) >= 0)
      can_above = false;
    if (!can_below && !can_above) {
      std::vector<SliceContact> contacts = old.contacts;
      contacts.insert(contacts.end(), blocked_low.contacts.begin(), blocked_low.contacts.end());
      contacts.insert(contacts.end(), blocked_high.contacts.begin(), blocked_high.contacts.end());
      jam(next, k, "its free range closed: it cannot move out of the way", std::move(contacts));
      return Outcome::jammed;
    }
    // nearer end, down on a tie: decided exactly (certified enclosures of the distances; a tie
    // they cannot separate is counted, analyze warns)
    bool go_down = can_below;
    if (can_below && can_above) {
      bool decided = true;
      double here = old.unwrapped;
      go_down = compare_push_distances(line, blocked_low.at, here - down, y, here, blocked_high.at, here + up, decided) <= 0;
      if (!decided) ++undecided_push_ties();
    }
    if ((go_down ? down : up) > max_push) return Outcome::coarse;
    if (go_down ? channel_below : channel_above) {
      Outcome settled = settle(go_down ? low_point : high_point, go_down ? -down : up);
      out.blocked_by = blocked_low.contacts;
      out.blocked_by.insert(out.blocked_by.end(), blocked_high.contacts.begin(), blocked_high.contacts.end());
      sort_contacts(out.blocked_by);
      return settled;
    }
    if (go_down) {
      interval = below;
      start = blocked_low.at;
      moved = -down;
    } else {
      interval = above;
      start = blocked_high.at;
      moved = up;
    }
    pushed = true;
    out.push_distance = std::abs(moved);
    out.blocked_by = blocked_low.contacts;
    out.blocked_by.insert(out.blocked_by.end(), blocked_high.contacts.begin(), blocked_high.contacts.end());
    sort_contacts(out.blocked_by);
  }
  Bound low = lower_end(line, slice, interval), high = upper_end(line, slice, interval);
  if (has_window_edge(low.contacts) || has_window_edge(high.contacts)) return Outcome::widen;
  AxisPosition target = start;
  const FollowerLoad& load = chain.parts[k].load;
  switch (load.kind) {
    case FollowerLoad::Kind::none: break;
    case FollowerLoad::Kind::negative:
      if (low.exists) {
        moved -= distance_down(line, start, low.at);
        target = low.at;
      }
      break;
    case FollowerLoad::Kind::positive:
      if (high.exists) {
        moved += distance_up(line, start, high.at);
        target = high.at;
      }
      break;
    case FollowerLoad::Kind::spring: {
      // Exact (session 49): the follower at `start` (unwrapped `here`) moves towards the
      // spring's rest until the end of its free range if that end is reached first (or at the
      // rest itself: the contact holds it), else to the rest; at the rest it stays.
      double here = old.unwrapped + moved;
      int towards = -compare_unwrapped(line, start, here, load.rest);
      if (towards == 0) {
        out.at_rest = true;
        break;
      }
      const Bound& end = towards < 0 ? low : high;
      double reach = !end.exists ? infinity : towards < 0 ? distance_down(line, start, end.at) : distance_up(line, start, end.at);
      double end_unwrapped = here + towards * reach;
      if (end.exists && towards * compare_unwrapped(line, end.at, end_unwrapped, load.rest) <= 0) {
        moved += towards * reach;
        target = end.at;
      } else {
        target = rest_position(line, load.rest, low, here - (low.exists ? distance_down(line, start, low.at) : 0),
                               high, here + (high.exists ? distance_up(line, start, high.at) : 0));
        moved += load.rest.get_d() - here;   // the unwrapped double (approximate): the state is at_rest, exactly
        out.at_rest = true;
      }
      break;
    }
  }
  out.position = target;
  out.unwrapped = old.unwrapped + moved;
  out.lower = low;
  out.upper = high;
  out.kind = slice.kind(interval);
  out.pushed = pushed;
  out.side = 0;
  out.contacts.clear();
  if (low.exists && compare(target, low.at) == 0) {
    out.side = -1;
    out.contacts = low.contacts;
  } else if (high.exists && compare(target, high.at) == 0) {
    out.side = 1;
    out.contacts = high.contacts;
  } else if (placement.on_point && compare(target, y) == 0) {
    out.contacts = slice.points[placement.point].contacts;   // grazing touch
  }
  sort_contacts(out.contacts);
  return Outcome::moved;
}

// The half widths of the windows a part's slices are asked in: the first, and `full`, from which
// on a window covers the whole axis (the whole axis is sliced).
struct WindowWidths {
  double first = 0, full = 0;
};
// The widths are a choice, not a decision: windows are widened until the decision is local, so
// every answer is the whole axis' (a double range here only costs slicing).
WindowWidths window_widths(const AxisLine& line) {
  const double full = line.rotation ? 4.0 : Rational(line.pieces.front().hi - line.pieces.front().lo).get_d();
  return WindowWidths{line.rotation ? 0.06 : 0.1 * full, full};
}

// In a slice windowed around y (half width `width`), the blocked interval holding y is the whole
// slice's only when both its ends are points well inside the window: a blocked interval reaching
// a window edge merges with the unknown space beyond it (marked blocked, the edge's flagged
// contact dropped with the class unchanged), so the end found there is a point on the window's
// far side (cyclic axes), an axis end or none, not the whole slice's end. True as well when y is
// on a point or in space that is not blocked (an end of free space at a window edge is flagged:
// has_window_edge).
bool blocked_ends_inside(const AxisLine& line, const AxisSlice& slice, const AxisPosition& y, double width) {
  const Placement placement = place(line, slice, y);
  if (placement.on_point || slice.kind(placement.interval) != SliceKind::blocked) return true;
  const Bound low = lower_end(line, slice, placement.interval), high = upper_end(line, slice, placement.interval);
  // the window's edges lie at `width` from y up to rounding: three quarters of it is inside, and
  // a point beyond the far edge of a cyclic axis' window lies at least 2 pi - width away
  const double inside = 0.75 * width;
  return low.exists && high.exists && !has_window_edge(low.contacts) && !has_window_edge(high.contacts) &&
         distance_down(line, y, low.at) <= inside && distance_up(line, y, high.at) <= inside;
}

// Slices part k around its old position, widening the window until the decision is local.
Outcome update_windowed(const Chain& chain, std::size_t k, const PartState& old, ChainState& next, bool initial,
                        double max_push = std::numeric_limits<double>::infinity()) {
  const AxisLine& line = chain.parts[k].line;
  const auto [first_width, full] = window_widths(line);
  double width = initial ? full : first_width;
  // The windows asked are width, 4 width, 16 width, ... until a decision does not need the
  // slice beyond the window. A decision needs both ends of the free range it ends in (and the
  // followed contact), which lie near the old free range's ends. So the first of those windows
  // that holds the old free range is sliced first, and the narrower ones asked before it are
  // read off that slice (ChartSliceMemo): the same windows asked in the same order, each the
  // slice its slicer would give (restrict_chart_slice), the same decisions, without slicing
  // each. (A window between two widths, just holding the old free range, was tried: on the
  // ratchet it cost as much as the wider width, and its undecided points would not be the
  // wider width's.)
  ChartSliceMemo memo;
  if (!initial && window_reading_switch()) {
    double needed = 0;
    for (const Bound* bound : {&old.lower, &old.upper}) {
      if (!bound->exists) {
        needed = full;   // an end beyond every window but the whole axis
        break;
      }
      needed = std::max(needed, bound == &old.lower ? distance_down(line, old.position, bound->at)
                                                    : distance_up(line, old.position, bound->at));
    }
    double ahead = width;
    while (ahead < full && ahead < needed) ahead *= 4;
    if (ahead > width) {
      AxisWindow window{old.position, ahead};
      memo.reading_ahead = true;
      constraint_slice(chain, next, k, ahead < full ? &window : nullptr, &memo);
      memo.reading_ahead = false;
    }
  }
  for (;;) {
    AxisWindow window{old.position, width};
    bool windowed = width < full;
    AxisSlice slice = constraint_slice(chain, next, k, windowed ? &window : nullptr, &memo);
    Outcome outcome = update_part(chain, k, old, slice, next, initial, max_push);
    if (outcome != Outcome::widen || !windowed) {
      memo.apply(chain.slicers);
      return outcome == Outcome::widen ? Outcome::jammed : outcome;
    }
    next.jammed = false;
    width *= 4;
  }
}

}  // namespace

ChainState step(const Chain& chain, const ChainState& state, std::size_t piece, const Rational& value,
                double unwrapped, bool strict) {
  ChainState next;
  next.driver_piece = piece;
  next.driver_value = value;
  next.driver_unwrapped = unwrapped;
  next.parts.resize(chain.parts.size());
  PartState& driver = next.parts[0];
  driver.position = canonical(chain.parts[0].line, AxisPosition{piece, Real::from_rational(value)});
  driver.unwrapped = unwrapped;
  if (!chain.parts[0].constraints.empty()) {
    AxisSlice slice = constraint_slice(chain, next, 0);
    Placement placement = place(chain.parts[0].line, slice, driver.position);
    if (placement.on_point) {
      driver.contacts = slice.points[placement.point].contacts;
      sort_contacts(driver.contacts);
    } else if (!non_blocked(slice, placement.interval)) {
      std::vector<SliceContact> contacts = state.parts[0].contacts;
      Bound low = lower_end(chain.parts[0].line, slice, placement.interval);
      Bound high = upper_end(chain.parts[0].line, slice, placement.interval);
      contacts.insert(contacts.end(), low.contacts.begin(), low.contacts.end());
      contacts.insert(contacts.end(), high.contacts.begin(), high.contacts.end());
      jam(next, 0, "the driver runs into a fixed part", contacts);
      return next;
    }
  }
  // The driver's motion in doubles: in the sweep's frame (analyze.cpp, DriverPlan::reference) the
  // unwrapped coordinates stay below 2^20 half turns, so it is within a few units in the last
  // place of the exact motion (session 56: at 10^17 deg it was 0 or 0.25 rad). It sets max_push,
  // a choice of step (a coarse step is subdivided; the events are then located exactly), and
  // with the velocity ratio whether a contact still pushes (an approximate rate, as reported).
  double driver_motion = unwrapped - state.driver_unwrapped;
  std::vector<Rates> known{rate_of(chain, next, 0, {})};
  std::vector<Rates> old_rates;
  if (strict && !state.parts.empty()) old_rates = rates(chain, state);
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    double max_push = std::numeric_limits<double>::infinity();
    if (strict) {
      // a push may follow the old velocity ratio (four times over) or any ratio up to 20
      double ratio = k < old_rates.size() && std::isfinite(old_rates[k].ratio) ? std::abs(old_rates[k].ratio) : 0.0;
      max_push = std::max(20.0, 4 * ratio) * std::abs(driver_motion) + 1e-12;
    }
    Outcome outcome = update_windowed(chain, k, state.parts[k], next, false, max_push);
    if (outcome == Outcome::coarse) {
      jam(next, k, "step too long to follow the contact", {});
      next.coarse = true;
      return next;
    }
    if (outcome == Outcome::jammed) return next;
    known.push_back(rate_of(chain, next, k, known));
    // Without a load, a contact holds only while it pushes: a boundary moving away from the
    // follower (past a turning point) leaves it behind.
    PartState& part = next.parts[k];
    if (chain.parts[k].load.kind == FollowerLoad::Kind::none && part.side != 0 && driver_motion != 0 &&
        std::isfinite(known[k].ratio)) {
      double velocity = known[k].ratio * driver_motion;
      std::size_t curves = std::count_if(part.contacts.begin(), part.contacts.end(), [](const SliceContact& c) { return !c.limit; });
      // the slope of a single contact curve is reliable; at a corner (several curves) trust the push
      if (velocity * -part.side <= 0 && (curves == 1 || !part.pushed)) {
        part.side = 0;
        part.contacts.clear();
        known[k] = Rates{};
      }
    }
  }
  // known[k] was computed as rates() would (parts in chain order, part k final from then on)
  next.known_rates = std::move(known);
  return next;
}

ChainState non_strict_step(const Chain& chain, const ChainState& state, std::size_t piece, const Rational& value,
                           double unwrapped, ChainState* strict) {
  if (strict && !strict->coarse) return std::move(*strict);
  return step(chain, state, piece, value, unwrapped, false);
}

ChainState initial_state(const Chain& chain, std::size_t piece, const Rational& value, double unwrapped,
                         std::vector<Interference>& interference) {
  const Model& model = *chain.model;
  ChainState start;
  start.parts.resize(chain.parts.size());
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    const Part& part = model.parts[chain.parts[k].part];
    Rational coordinate_value = part.motion.kind == Motion::Kind::rotation ? part.initial.angle : part.initial.offset;
    start.parts[k].position = position_of_coordinate(chain.parts[k].line, coordinate_value);
    start.parts[k].unwrapped = coordinate_value.get_d();   // whole-turn hint: |angle| < 2^40 rad (analyze_kinematics)
  }
  ChainState next;
  next.driver_piece = piece;
  next.driver_value = value;
  next.driver_unwrapped = unwrapped;
  next.parts.resize(chain.parts.size());
  next.parts[0].position = canonical(chain.parts[0].line, AxisPosition{piece, Real::from_rational(value)});
  next.parts[0].unwrapped = unwrapped;
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    const AxisLine& line = chain.parts[k].line;
    // The slices of part k's pairs around its initial position, in the windows update_windowed
    // asks (width, 4 width, ... then the whole axis), widened until neither the interference
    // found nor the decision needs the slice beyond the window: a window's slice is the whole
    // slice's restriction (its edges bounded by contacts flagged `window`), so every class,
    // bound and contact read inside it is the whole slice's. Their intersection is the free
    // space update_windowed(initial) would slice again (the same slices, skipped by the same
    // rules as constraint_slice: a pair with a fixed part is sliced whole).
    const auto [first_width, full] = window_widths(line);
    for (double width = initial_windows_switch() ? first_width : full;; width *= 4) {
      const bool windowed = width < full;
      const AxisWindow window{start.parts[k].position, width};
      std::vector<Interference> found;
      AxisSlice free_space;
      bool first = true, widen = false;
      // interference of each pair at the initial configuration
      for (std::size_t s : chain.parts[k].constraints) {
        const PairSlicer& slicer = *chain.slicers[s];
        std::size_t other_chart = 0;
        Rational other_value;
        if (!other_of(chain, next, s, other_chart, other_value)) continue;
        AxisSlice slice = slice_on_axis(line, slicer, s, other_chart, other_value,
                                        windowed && slicer.other_moves() ? &window : nullptr);
        if (windowed && !blocked_ends_inside(line, slice, start.parts[k].position, width)) {
          widen = true;   // the overlap may reach beyond the window
          break;
        }
        Placement placement = place(line, slice, start.parts[k].position);
        if (!placement.on_point && slice.kind(placement.interval) == SliceKind::blocked) {
          Bound low = lower_end(line, slice, placement.interval), high = upper_end(line, slice, placement.interval);
          std::string description = "the parts overlap at the initial configuration";
          std::vector<std::string> labels;
          for (const Bound* bound : {&low, &high})
            for (const SliceContact& contact : bound->contacts)
              if (!contact.limit) labels.push_back(slicer.features()[contact.feature].label);
          if (!labels.empty()) {
            description += " (the overlap is bounded by: ";
            for (std::size_t i = 0; i < labels.size(); ++i) description += (i ? "; " : "") + labels[i];
            description += ")";
          }
          found.push_back(Interference{slicer.name(), description});
        }
        free_space = first ? std::move(slice) : intersect(line, free_space, slice);
        first = false;
      }
      // the decision reads the ends of the blocked interval holding the part, if any
      if (!widen && windowed && !first) widen = !blocked_ends_inside(line, free_space, start.parts[k].position, width);
      Outcome outcome = Outcome::widen;
      if (!widen) {
        const PartState before = next.parts[k];
        outcome = update_part(chain, k, start.parts[k], free_space, next, true, std::numeric_limits<double>::infinity());
        if (outcome == Outcome::widen && windowed) {
          next.parts[k] = before;   // decided again in the wider window, as from the start
          next.jammed = false;
          widen = true;
        }
      }
      if (widen) {
        ++initial_widenings();
        continue;
      }
      interference.insert(interference.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
      if (outcome == Outcome::widen || outcome == Outcome::jammed) return next;
      break;
    }
  }
  return next;
}

bool same_contacts(const ChainState& a, const ChainState& b) {
  if (a.jammed != b.jammed) return false;
  if (a.parts.size() != b.parts.size()) return false;
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    if (a.parts[k].side != b.parts[k].side) return false;
    if (a.parts[k].contacts != b.parts[k].contacts) return false;
  }
  return true;
}

Rates rate_of(const Chain& chain, const ChainState& state, std::size_t k, const std::vector<Rates>& known) {
  Rates result;
  if (k == 0) {
    result.ratio = 1;
    return result;
  }
  const PartState& part = state.parts[k];
  if (part.side == 0 && !part.channel) return result;
  const SliceContact* contact = nullptr;
  for (const SliceContact& c : part.contacts)
    if (!c.limit) {
      contact = &c;
      break;
    }
  if (!contact) return result;
  const PairSlicer& slicer = *chain.slicers[contact->slicer];
  if (!slicer.other_moves()) return result;
  std::size_t q = chain.chain_index[slicer.other()];
  if (q >= known.size()) return result;
  const PartState& other = state.parts[q];
  std::size_t other_chart = chain.other_chart_of_piece[contact->slicer][other.position.piece];
  const AxisLine& line = chain.parts[k].line;
  std::size_t follower_chart = none;
  for (std::size_t c = 0; c < slicer.follower_charts().size(); ++c)
    if (!line.rotation || same_chart(slicer.follower_charts()[c], line.pieces[part.position.piece])) {
      follower_chart = c;
      break;
    }
  if (other_chart == none || follower_chart == none) return result;
  const IntegerPolynomial2* polynomial = slicer.polynomial(other_chart, follower_chart, contact->feature);
  if (!polynomial) return result;
  Rational u = rational_near(other.position.value, 60), v = rational_near(part.position.value, 60);
  // implicit differentiation of the contact curve P(u, v) = 0, exact at the rational point:
  // dv/du, d2v/du2, then in part coordinates (rad or mm)
  CurveSlopes slopes =
      contact_slopes(*polynomial, u, v, chain.parts[q].line.rotation, line.rotation, chain.accelerations);
  if (slopes.singular) {
    result.ratio = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  double derivative = slopes.first;    // d(follower coordinate) / d(other coordinate)
  double curvature = slopes.second;
  result.ratio = derivative * known[q].ratio;
  if (chain.accelerations)
    result.acceleration = curvature * known[q].ratio * known[q].ratio + derivative * known[q].acceleration;
  return result;
}

namespace {

// An unreduced fraction of integers (denominator nonzero, of either sign): products and sums
// without gcds; the value is canonicalised once, where a double is taken.
struct Fraction {
  mpz_class num, den;
};

Fraction operator*(const Fraction& a, const Fraction& b) { return {a.num * b.num, a.den * b.den}; }

Fraction operator+(const Fraction& a, const Fraction& b) {
  if (a.den == b.den) return {a.num + b.num, a.den};
  return {a.num * b.den + b.num * a.den, a.den * b.den};
}

Fraction operator/(const Fraction& a, const Fraction& b) { return {a.num * b.den, a.den * b.num}; }

// Rates are reported approximate; a decision reads only their sign (a pushing contact), which
// mpq_get_d keeps but for a ratio below 2^-1074 in magnitude (then 0).
double to_double(const Fraction& f) {
  Rational value(f.num, f.den);
  value.canonicalize();
  return value.get_d();   // mpq_get_d: a function of the value, truncated towards zero
}

// X' and X'' of a part coordinate X in its chart coordinate t = n / d (d > 0): the half-angle
// chart's 2 / (1 + t^2) = 2 d^2 / w and -4 t / (1 + t^2)^2 = -4 n d^3 / w^2 (w = n^2 + d^2),
// a translation's 1 and 0.
std::pair<Fraction, Fraction> axis_slopes(bool rotates, const mpz_class& n, const mpz_class& d) {
  if (!rotates) return {Fraction{1, 1}, Fraction{0, 1}};
  mpz_class d2 = d * d, w = n * n + d2;
  return {Fraction{2 * d2, w}, Fraction{-4 * n * d * d2, w * w}};
}

}  // namespace

CurveSlopes contact_slopes(const IntegerPolynomial2& polynomial, const Rational& u, const Rational& v,
                           bool other_rotates, bool part_rotates, bool second_derivative) {
  // u = a / b, v = c / d (canonical: b, d > 0). With M >= deg_u P, N >= deg_v P (both >= 2),
  // the partials scaled to integers: FX = b^(M-1) d^N P_u, FY = b^M d^(N-1) P_v,
  // FXX = b^(M-2) d^N P_uu, FXY = b^(M-1) d^(N-1) P_uv, FYY = b^M d^(N-2) P_vv; the term of
  // c_ij carries g = c_ij b^(M-i) d^(N-j) times powers of a and c.
  const auto& c = polynomial.coefficients;
  std::size_t degree_u = c.empty() ? 0 : c.size() - 1, degree_v = 0;
  for (const auto& row : c)
    if (!row.empty()) degree_v = std::max(degree_v, row.size() - 1);
  std::size_t M = std::max<std::size_t>(degree_u, 2), N = std::max<std::size_t>(degree_v, 2);
  const mpz_class &a = u.get_num(), &b = u.get_den(), &cv = v.get_num(), &d = v.get_den();
  std::vector<mpz_class> ap(M + 1, 1), bp(M + 1, 1), cp(N + 1, 1), dp(N + 1, 1);
  for (std::size_t k = 1; k <= M; ++k) {
    ap[k] = ap[k - 1] * a;
    bp[k] = bp[k - 1] * b;
  }
  for (std::size_t k = 1; k <= N; ++k) {
    cp[k] = cp[k - 1] * cv;
    dp[k] = dp[k - 1] * d;
  }
  mpz_class FX, FY, FXX, FXY, FYY, g;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) {
      if (sgn(c[i][j]) == 0) continue;
      g = c[i][j] * bp[M - i] * dp[N - j];
      long ii = static_cast<long>(i), jj = static_cast<long>(j);
      if (i >= 1) FX += ii * g * ap[i - 1] * cp[j];
      if (j >= 1) FY += jj * g * ap[i] * cp[j - 1];
      if (!second_derivative) continue;
      if (i >= 2) FXX += ii * (ii - 1) * g * ap[i - 2] * cp[j];
      if (i >= 1 && j >= 1) FXY += ii * jj * g * ap[i - 1] * cp[j - 1];
      if (j >= 2) FYY += jj * (jj - 1) * g * ap[i] * cp[j - 2];
    }
  CurveSlopes out;
  if (sgn(FY) == 0) {
    out.singular = true;
    return out;
  }
  // chart slopes: v' = -P_u / P_v = p / q with p = -FX b, q = FY d;
  // v'' = -(P_uu + 2 P_uv v' + P_vv v'^2) / P_v = -(FXX b^2 q^2 + 2 FXY b d p q + FYY d^2 p^2) / (FY^3 d^3)
  mpz_class p = -FX * b, q = FY * d;
  Fraction first{p, q};
  // part coordinates: dY/dX = Y' v' / X', d^2Y/dX^2 = (Y'' v'^2 + Y' v'' - (dY/dX) X'') / X'^2
  auto [x1, x2] = axis_slopes(other_rotates, a, b);
  auto [y1, y2] = axis_slopes(part_rotates, cv, d);
  Fraction ratio = y1 * first / x1;
  out.first = to_double(ratio);
  if (!second_derivative) return out;
  Fraction second{-(FXX * b * b * q * q + 2 * FXY * b * d * p * q + FYY * d * d * p * p), FY * FY * FY * d * d * d};
  Fraction minus_one{-1, 1};
  Fraction acceleration = (y2 * first * first + y1 * second + minus_one * ratio * x2) / (x1 * x1);
  out.second = to_double(acceleration);
  return out;
}

CurveSlopes contact_slopes_rational(const IntegerPolynomial2& polynomial, const Rational& u, const Rational& v,
                                    bool other_rotates, bool part_rotates) {
  kernels::Partials<Rational> d =
      kernels::polynomial_partials(polynomial.coefficients, u, v, [](const mpz_class& c) { return Rational(c); });
  CurveSlopes out;
  if (d.fy == 0) {
    out.singular = true;
    return out;
  }
  kernels::Slopes<Rational> chart = kernels::implicit_slopes(d.fx, d.fy, d.fxx, d.fxy, d.fyy);
  kernels::Slopes<Rational> part_axis = part_rotates ? kernels::half_angle_slopes(v) : kernels::offset_slopes<Rational>();
  kernels::Slopes<Rational> other_axis =
      other_rotates ? kernels::half_angle_slopes(u) : kernels::offset_slopes<Rational>();
  kernels::Slopes<Rational> slopes = kernels::part_slopes(chart, other_axis, part_axis);
  out.first = slopes.first.get_d();
  out.second = slopes.second.get_d();
  return out;
}

std::vector<Rates> rates(const Chain& chain, const ChainState& state) {
  if (state.known_rates.size() == chain.parts.size()) return state.known_rates;
  std::vector<Rates> result;
  for (std::size_t k = 0; k < chain.parts.size(); ++k) result.push_back(rate_of(chain, state, k, result));
  return result;
}

ContactLabel label_of(const Chain& chain, const SliceContact& contact, std::size_t part) {
  ContactLabel label;
  const Model& model = *chain.model;
  if (contact.limit) {
    label.pair = model.parts[part].name;
    label.label = "motion limit of " + model.parts[part].name;
    label.limit = true;
    return label;
  }
  const PairSlicer& slicer = *chain.slicers[contact.slicer];
  label.pair = slicer.name();
  label.label = slicer.features()[contact.feature].label;
  label.kind = slicer.features()[contact.feature].kind;
  label.first = slicer.features()[contact.feature].first;
  label.second = slicer.features()[contact.feature].second;
  return label;
}

}  // namespace hipair::kinematics_detail
