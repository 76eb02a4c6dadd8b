// hipair::analyze_kinematics: drives the chain over the requested range on a grid, locates
// every contact change between grid points by bisection on exact slices, and collects the
// pieces, events, samples, play, contact usage, paths and reversal checks.
#include "core/angle_sign.hpp"
#include "core/length_display.hpp"
#include "core/model_scale.hpp"
#include "kinematics/engine.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>

#include <mpfr.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace hipair {

using namespace kinematics_detail;

std::map<std::string, FollowerLoad> model_loads(const Model& model) {
  std::map<std::string, FollowerLoad> loads;
  for (const Part& part : model.parts) {
    if (!part.dynamics) continue;
    const Dynamics& dynamics = *part.dynamics;
    FollowerLoad load;
    if (part.motion.kind == Motion::Kind::rotation) {
      if (dynamics.torsional_spring) {
        load.kind = FollowerLoad::Kind::spring;
        load.rest = dynamics.torsional_spring->rest;
        char text[64];
        std::snprintf(text, sizeof text, "%.4g", load.rest.get_d() * 180 / std::numbers::pi);
        load.source = std::string("torsional spring of the model (rest angle ") + text + " deg)";
      } else if (dynamics.torque && sgn(*dynamics.torque) != 0) {
        load.kind = sgn(*dynamics.torque) > 0 ? FollowerLoad::Kind::positive : FollowerLoad::Kind::negative;
        load.source = std::string("constant ") + (sgn(*dynamics.torque) > 0 ? "counter-clockwise" : "clockwise") +
                      " torque of the model";
      }
    } else if (part.motion.kind == Motion::Kind::translation) {
      if (dynamics.linear_spring) {
        load.kind = FollowerLoad::Kind::spring;
        load.rest = dynamics.linear_spring->rest;
        load.source = "linear spring of the model (rest offset " + length_in_mm(to_decimal_string(dynamics.linear_spring->rest, 6)) +
                      " mm)";   // in mm under a LengthDisplayScope (core/length_display.hpp)
      } else if (dynamics.force) {
        Rational along = dynamics.force->x * part.motion.direction.x + dynamics.force->y * part.motion.direction.y;
        if (sgn(along) != 0) {
          load.kind = sgn(along) > 0 ? FollowerLoad::Kind::positive : FollowerLoad::Kind::negative;
          load.source = "constant force of the model";
        }
      }
    }
    if (load.kind != FollowerLoad::Kind::none) loads[part.name] = load;
  }
  return loads;
}

namespace kinematics_detail {

// Is m pi + 2 (atan(to) - atan(from)) <= n pi? Exact: atan(to) - atan(from) lies in (-pi, pi),
// and against pi / 2 it is decided by the sign of cos of the difference, (1 + to from) over a
// positive number.
bool half_turns_at_most(const mpz_class& m, const Rational& from, const Rational& to, long n) {
  const mpz_class d = n - m;   // is atan(to) - atan(from) <= d pi / 2?
  if (d >= 2) return true;
  if (d <= -2) return false;
  const int cosine = sgn(Rational(1 + to * from));
  if (d == 1) return to <= from || cosine >= 0;
  if (d == 0) return to <= from;
  return to < from && cosine <= 0;
}

DriverPlan plan_driver(const AxisLine& line, const Rational& start, int direction, const DriverEnd& end,
                       std::vector<std::string>& warnings) {
  DriverPlan plan;
  LocatedCoordinate from = locate_coordinate(line, start);
  if (!from.position.value.exact) throw NumericError("driver start is not rational");
  plan.start = from.position;
  plan.start_half_turns = from.half_turns;
  LocatedCoordinate to;
  if (end.kind == DriverEnd::Kind::coordinate) {
    to = locate_coordinate(line, end.value);
    plan.beyond = to.beyond == direction;
  } else if (end.kind == DriverEnd::Kind::cycles) {
    if (end.value.get_den() == 1) {
      to = from;   // whole turns end where they start, 2 cycles half turns on
      to.half_turns += 2 * direction * end.value.get_num();
    } else {
      // start + 2 pi cycles: irrational; its rounding to well inside the chart value's 2^-60 grid
      const mpfr_prec_t bits = 200 + std::max(magnitude_bits(start), magnitude_bits(end.value));
      mpfr_t x, p;
      mpfr_inits2(bits, x, p, static_cast<mpfr_ptr>(nullptr));
      mpfr_const_pi(p, MPFR_RNDN);
      mpfr_mul_q(p, p, end.value.get_mpq_t(), MPFR_RNDN);
      mpfr_mul_si(p, p, 2 * direction, MPFR_RNDN);
      mpfr_set_q(x, start.get_mpq_t(), MPFR_RNDN);
      mpfr_add(x, x, p, MPFR_RNDN);
      mpq_t q;
      mpq_init(q);
      mpfr_get_q(q, x);
      to = locate_coordinate(line, Rational(q));
      mpq_clear(q);
      mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
    }
  } else if (line.rotation) {
    const std::size_t piece = direction > 0 ? line.pieces.size() - 1 : 0;
    to.position = AxisPosition{piece, Real::from_rational(direction > 0 ? line.pieces[piece].hi : line.pieces[piece].lo)};
    to.half_turns = line.half_turns[piece];
  } else {
    to = locate_coordinate(line, direction > 0 ? line.pieces.back().hi : line.pieces.front().lo);
  }
  plan.end = to.position;
  plan.end_half_turns = to.half_turns;
  // the frame: whole turns of the start taken out when it lies far out (0 keeps the doubles of
  // an ordinary start as they were)
  if (abs(from.half_turns) >= mpz_class(1) << 20) mpz_fdiv_q_2exp(plan.reference.get_mpz_t(), from.half_turns.get_mpz_t(), 1);
  plan.reference *= 2;
  auto relative = [&](const mpz_class& half_turns) {
    const mpz_class offset = half_turns - plan.reference;
    if (!offset.fits_slong_p()) throw NumericError("driver range too long");
    return offset.get_si();
  };
  const Rational& end_t = to.position.value.lower;
  std::size_t piece = from.position.piece;
  Rational t = from.position.value.lower;
  long base_pi = line.rotation ? relative(from.half_turns) : 0;
  const long end_base_pi = line.rotation ? relative(to.half_turns) : 0;
  // the end behind the start (a rounding of an end beside it): nothing to drive
  if ((end_base_pi - base_pi) * direction < 0 ||
      (end_base_pi == base_pi && to.position.piece == piece && (end_t - t) * direction < 0))
    return plan;
  for (int guard = 0; guard < 100000; ++guard) {
    const ChartAxis& chart = line.pieces[piece];
    DriverSegment segment{piece, t, direction > 0 ? chart.hi : chart.lo, base_pi, line.rotation ? base_pi * std::numbers::pi : 0.0};
    if (base_pi == end_base_pi && piece == to.position.piece) {
      segment.to = end_t;
      if (segment.to != segment.from) plan.segments.push_back(segment);
      if (plan.beyond) warnings.push_back("the driver reaches the end of its travel (motion limit) before the end of the range");
      return plan;
    }
    if (segment.to != segment.from) plan.segments.push_back(segment);
    const bool last = direction > 0 ? piece + 1 >= line.pieces.size() : piece == 0;
    if (!line.cyclic && (last || !line.seam_after(direction > 0 ? piece : piece - 1))) {
      warnings.push_back("the driver reaches the end of its travel (motion limit) before the end of the range");
      return plan;
    }
    if (direction > 0) {
      std::size_t next = line.next(piece);
      base_pi += line.rotation ? (line.cyclic ? 1 : line.half_turns[next] - line.half_turns[piece]) : 0;
      piece = next;
      t = line.pieces[piece].lo;
    } else {
      std::size_t previous = piece == 0 ? line.pieces.size() - 1 : piece - 1;
      base_pi -= line.rotation ? (line.cyclic ? 1 : line.half_turns[piece] - line.half_turns[previous]) : 0;
      piece = previous;
      t = line.pieces[piece].hi;
    }
  }
  throw NumericError("driver range too long");
}

}  // namespace kinematics_detail

namespace {

constexpr double pi = std::numbers::pi;
constexpr long max_driver_turns = 100;   // at most this many turns of a rotating driver (every turn's samples are kept)

using Segment = DriverSegment;

double segment_coordinate(const AxisLine& line, const Segment& segment, const Rational& t) {
  return line.rotation ? segment.base + 2 * std::atan(t.get_d()) : t.get_d();
}

// Certified enclosure of base_pi * pi + 2 atan(t) over t in [a, b] (rotation) or [a, b].
CertifiedRange certified_coordinate(const AxisLine& line, const Segment& segment, Rational a, Rational b) {
  if (b < a) std::swap(a, b);
  if (!line.rotation) return CertifiedRange{cspace::algebra::lower_double(a), cspace::algebra::upper_double(b)};
  mpfr_t x, p;
  mpfr_inits2(128, x, p, static_cast<mpfr_ptr>(nullptr));
  auto bound = [&](const Rational& t, mpfr_rnd_t rounding) {
    mpfr_set_q(x, t.get_mpq_t(), rounding);
    mpfr_atan(x, x, rounding);
    mpfr_mul_ui(x, x, 2, rounding);
    mpfr_const_pi(p, segment.base_pi >= 0 ? rounding : (rounding == MPFR_RNDD ? MPFR_RNDU : MPFR_RNDD));
    mpfr_mul_si(p, p, segment.base_pi, rounding);
    mpfr_add(x, x, p, rounding);
    return mpfr_get_d(x, rounding);
  };
  CertifiedRange range{bound(a, MPFR_RNDD), bound(b, MPFR_RNDU)};
  mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
  return range;
}


// Rational chart values of the grid inside a segment (excluding `from`, including `to`).
std::vector<Rational> grid_of(const AxisLine& line, const Segment& segment, double spacing) {
  double a = segment_coordinate(line, segment, segment.from), b = segment_coordinate(line, segment, segment.to);
  // a choice of samples: one step where the spacing is no positive double (a range whose length
  // underflows)
  const double ratio = std::abs(b - a) / spacing;
  long steps = std::isfinite(ratio) ? std::max<long>(1, std::lround(std::ceil(ratio - 1e-9))) : 1;
  std::vector<Rational> values;
  mpz_class scale = mpz_class(1) << 32;
  for (long i = 1; i < steps; ++i) {
    double c = a + (b - a) * double(i) / double(steps);
    double t = line.rotation ? std::tan((c - segment.base) / 2) : c;
    Rational value(mpz_class(static_cast<long>(std::llround(t * 4294967296.0))), scale);
    value.canonicalize();
    bool ascending = segment.to > segment.from;
    const Rational& last = values.empty() ? segment.from : values.back();
    if (ascending ? (value <= last || value >= segment.to) : (value >= last || value <= segment.to)) continue;
    values.push_back(value);
  }
  values.push_back(segment.to);
  return values;
}

struct OpenPiece {
  bool open = false;
  DriverLocation start;
  double start_position = 0;
  double lowest = 0, highest = 0;   // range of positions seen during the piece
  PartState state;
  /// A grid sample of the piece lies at another exact position than its start (its turns
  /// included): the piece is a drive (session 49; until then a span of the doubles > 1e-12).
  bool moved = false;
  /// The state left of the event that opened the piece (none at the start of the range).
  std::optional<PartState> before;
};

std::string chart_variable_note(const AxisLine& line) {
  return line.rotation ? "tan of half the angle from the chart centre" : "offset in mm";
}

// The contacts of the wall of blocked C-space that chain part k ran into between the driver's
// chart values ta and tb (exact): with the part held at its position in `before`, the
// driver's own slice of each pair of the part with the driver has its breakpoints there.
std::vector<ContactLabel> wall_contacts(const Chain& chain, const ChainState& before, std::size_t k,
                                        std::size_t driver_piece, const Rational& ta, const Rational& tb) {
  std::vector<ContactLabel> labels;
  const Model& model = *chain.model;
  const AxisLine& driver_line = chain.parts[0].line;
  const AxisLine& line = chain.parts[k].line;
  const PartState& part = before.parts[k];
  Rational lo = std::min(ta, tb), hi = std::max(ta, tb);
  for (std::size_t s : chain.parts[k].constraints) {
    const PairSlicer& constraint = *chain.slicers[s];
    if (!constraint.other_moves() || constraint.other() != chain.parts[0].part) continue;
    std::size_t pair = none;
    for (std::size_t p = 0; p < model.pairs.size(); ++p) {
      const PairSpec& spec = model.pairs[p];
      if ((spec.first == constraint.follower() && spec.second == constraint.other()) ||
          (spec.second == constraint.follower() && spec.first == constraint.other()))
        pair = p;
    }
    if (pair == none) continue;
    std::unique_ptr<PairSlicer> slicer;
    try {
      slicer = make_kernel_slicer(model, pair, chain.parts[0].part);
    } catch (const GeometryError&) {
      continue;
    }
    std::size_t part_chart = none, driver_chart = none;
    for (std::size_t c = 0; c < slicer->other_charts().size() && part_chart == none; ++c)
      if (line.piece_of(slicer->other_charts()[c]) == part.position.piece) part_chart = c;
    for (std::size_t c = 0; c < slicer->follower_charts().size() && driver_chart == none; ++c)
      if (driver_line.piece_of(slicer->follower_charts()[c]) == driver_piece) driver_chart = c;
    if (part_chart == none || driver_chart == none) continue;
    ChartSlice slice = slicer->slice(part_chart, rational_near(part.position.value), driver_chart);
    for (const SlicePoint& point : slice.points) {
      if (point.value.compare(lo) < 0 || point.value.compare(hi) > 0) continue;
      for (std::size_t f : point.features) {
        ContactLabel label{constraint.name(), slicer->features()[f].label, slicer->features()[f].kind, false, {}, {}};
        if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
      }
    }
  }
  return labels;
}

// A jump (a snap under the load, or a push through blocked space that stops the driver) is told
// from a contact change by a threshold, not exactly: the reports say so (session 49).
const std::string approximate_jump =
    "a jump by threshold, approximate: its position changes by more than 1e-7 across the located driver interval";

struct Sweep {
  const Chain& chain;
  const KinematicsOptions& options;
  KinematicsResult& result;
  std::vector<Segment> segments;
  Rational epsilon;
  // grid states for reversal checks
  struct GridPoint {
    std::size_t segment = 0;
    Rational t;
    ChainState state;
  };
  std::vector<GridPoint> grid;
  std::vector<OpenPiece> open;
  double total_travel = 1;
  /// The driver range is shorter than one grid step: the pictures' paths also pass through the
  /// states on both sides of every event (with only the range's ends, a path would run straight
  /// through a dwell).
  bool path_at_events = false;

  Sweep(const Chain& c, const KinematicsOptions& o, KinematicsResult& r) : chain(c), options(o), result(r) {}

  const AxisLine& driver_line() const { return chain.parts[0].line; }

  DriverLocation locate(std::size_t segment, const Rational& a, const Rational& b) const {
    DriverLocation location;
    location.chart = segments[segment].piece;
    location.chart_lower = std::min(a, b);
    location.chart_upper = std::max(a, b);
    location.coordinate = certified_coordinate(driver_line(), segments[segment], a, b);
    // the width rounded up: a bound the report states ("located to within")
    result.event_resolution = std::max(result.event_resolution, std::nextafter(location.coordinate.upper - location.coordinate.lower,
                                                                               std::numeric_limits<double>::infinity()));
    return location;
  }

  double unwrapped(std::size_t segment, const Rational& t) const {
    return segment_coordinate(driver_line(), segments[segment], t);
  }

  ChainState step_to(const ChainState& from, std::size_t segment, const Rational& t, bool strict = true) const {
    return step(chain, from, segments[segment].piece, t, unwrapped(segment, t), strict);
  }

  static bool jumped(const ChainState& a, const ChainState& b) {
    double driver = std::abs(b.driver_unwrapped - a.driver_unwrapped);
    for (std::size_t k = 1; k < a.parts.size() && k < b.parts.size(); ++k)
      if (std::abs(b.parts[k].unwrapped - a.parts[k].unwrapped) > 1e9 * driver + 1e-12) return true;
    return false;
  }

  // A contact change, a jump, or motion of a part that is free at both ends (it was pushed by
  // a contact that came and went between the two driver positions; a part on a zero-clearance
  // channel moves with it).
  bool differs(const ChainState& a, const ChainState& b) const {
    if (!same_contacts(a, b) || jumped(a, b)) return true;
    for (std::size_t k = 1; k < a.parts.size() && k < b.parts.size(); ++k)
      if (a.parts[k].side == 0 && b.parts[k].side == 0 && !a.parts[k].channel && !b.parts[k].channel &&
          compare(a.parts[k].position, b.parts[k].position) != 0 &&
          chain.parts[k].load.kind == FollowerLoad::Kind::none)
        return true;
    return false;
  }

  // Chain part k at the same exact unwrapped position in both states; a state at its spring's
  // rest is exactly at the rest (its AxisPosition may be a rounding of it).
  bool same_position(std::size_t k, const PartState& a, const PartState& b) const {
    const AxisLine& line = chain.parts[k].line;
    const Rational& rest = chain.parts[k].load.rest;
    if (a.at_rest && b.at_rest) return true;
    if (a.at_rest || b.at_rest) {
      const PartState& other = a.at_rest ? b : a;
      return compare_unwrapped(line, other.position, other.unwrapped, rest) == 0;
    }
    return compare_unwrapped(line, a.position, a.unwrapped, b.position, b.unwrapped) == 0;
  }

  std::vector<ContactLabel> labels(const PartState& state, std::size_t k) const {
    std::vector<ContactLabel> out;
    for (const SliceContact& contact : state.contacts) out.push_back(label_of(chain, contact, chain.parts[k].part));
    return out;
  }

  // Chain part k free at its spring's rest, held by nothing: every position of the state's
  // contact piece is the rest (a spring moves a free follower to its rest; held against an end
  // of its free range it would touch, a contact change).
  static bool free_at_rest(const PartState& state) { return state.at_rest && state.contacts.empty(); }

  // A piece whose start and end events' certified driver intervals overlap (shorter than the
  // events' resolution, 2^-46 of the driver's chart) has positive length when that is decided
  // exactly (session 51; until then every such piece was dropped as empty, and a real drive of
  // ~2^-49 rad, the spring test's R = e - 2^-k for k >= 92, was reported as nothing):
  // - the events' exact chart intervals are disjoint in one chart: its two samples differ;
  // - it is entered from, or left to, a spring's free rest (`free_at_rest`) and its sample lies
  //   at another exact position than the rest: the follower's position is continuous at the
  //   contact change (a jump is a `drop` event), so the change lies strictly before (after) the
  //   sample and the piece is a drive (it leaves the rest).
  // Returns whether its positive length is decided; `leaves_rest`: decided by the second rule.
  bool decided_short_piece(std::size_t k, const OpenPiece& piece, const DriverLocation& end, const PartState& last,
                           const PartState* after, bool& leaves_rest) const {
    leaves_rest = (piece.before && free_at_rest(*piece.before) && !same_position(k, *piece.before, piece.state)) ||
                  (after && free_at_rest(*after) && !same_position(k, last, *after));
    if (leaves_rest) return true;
    return piece.start.chart == end.chart &&
           (piece.start.chart_upper < end.chart_lower || end.chart_upper < piece.start.chart_lower);
  }

  void close_piece(std::size_t k, const DriverLocation& end, const PartState& last, const PartState* after = nullptr) {
    OpenPiece& piece = open[k];
    if (!piece.open) return;
    piece.open = false;
    bool unresolved = end.coordinate.lower <= piece.start.coordinate.upper && piece.start.coordinate.lower <= end.coordinate.upper;
    bool leaves_rest = false;
    if (unresolved && !decided_short_piece(k, piece, end, last, after, leaves_rest))
      return;   // empty: a contact change exactly at the start or the end of the range, or not decided
    KinematicPiece out;
    out.part = chain.model->parts[chain.parts[k].part].name;
    out.start = piece.start;
    out.end = end;
    out.side = piece.state.side;
    out.mode = piece.state.side != 0 ? KinematicPiece::Mode::contact
               : piece.state.kind == SliceKind::touching ? KinematicPiece::Mode::touching
                                                         : KinematicPiece::Mode::free;
    out.contacts = labels(piece.state, k);
    out.start_position = piece.start_position;
    out.end_position = last.unwrapped;
    double lowest = std::min({piece.lowest, last.unwrapped, out.start_position});
    double highest = std::max({piece.highest, last.unwrapped, out.start_position});
    // drive or dwell, exactly: a position of the piece (grid samples and ends) differs from its start
    out.moving = piece.moved || leaves_rest || !same_position(k, last, piece.state);
    out.unresolved_length = unresolved;
    if (leaves_rest) {
      // its ends' positions are the rest's, by continuity, where a neighbour is free at rest
      if (piece.before && free_at_rest(*piece.before)) out.start_position = piece.before->unwrapped;
      if (after && free_at_rest(*after)) out.end_position = after->unwrapped;
      lowest = std::min({lowest, out.start_position, out.end_position});
      highest = std::max({highest, out.start_position, out.end_position});
    }
    out.lowest_position = lowest;
    out.highest_position = highest;
    for (const SliceContact& contact : piece.state.contacts) {
      if (contact.limit) continue;
      const PairSlicer& slicer = *chain.slicers[contact.slicer];
      if (!slicer.other_moves()) continue;
      out.equation = "contact polynomial of '" + slicer.features()[contact.feature].label +
                     "' vanishes: variables are the " + chart_variable_note(chain.parts[chain.chain_index[slicer.other()]].line) +
                     " of " + chain.model->parts[slicer.other()].name + " and of " + out.part;
      break;
    }
    result.pieces.push_back(std::move(out));
  }

  void open_piece(std::size_t k, const DriverLocation& start, const PartState& state, const PartState* before = nullptr) {
    open[k] = OpenPiece{true, start, state.unwrapped, state.unwrapped, state.unwrapped, state};
    if (before) open[k].before = *before;
  }

  void record_event(std::size_t segment, const Rational& ta, const Rational& tb, const ChainState& a, const ChainState& b) {
    DriverLocation at = locate(segment, ta, tb);
    if (path_at_events) {
      add_path_points(a);
      add_path_points(b);
    }
    for (std::size_t k = 0; k < chain.parts.size(); ++k) {
      const PartState& before = a.parts[k];
      const PartState& after = b.parts[k];
      bool changed = before.side != after.side || before.contacts != after.contacts;
      bool jump = k > 0 && std::abs(after.unwrapped - before.unwrapped) > 1e-7;
      if (!changed && !jump) continue;
      KinematicEvent event;
      event.part = chain.model->parts[chain.parts[k].part].name;
      event.at = at;
      event.before = labels(before, k);
      event.after = labels(after, k);
      event.position = after.unwrapped;
      if (jump) {
        event.kind = KinematicEvent::Kind::drop;
        event.description = event.part + " snaps through free space under its load (" + approximate_jump + ")";
      } else if (before.contacts.empty()) {
        event.kind = KinematicEvent::Kind::contact_start;
        event.description = "contact starts";
      } else if (after.contacts.empty()) {
        event.kind = KinematicEvent::Kind::contact_end;
        event.description = "contact ends";
      } else {
        event.kind = KinematicEvent::Kind::contact_change;
        event.description = "contact changes";
      }
      result.events.push_back(event);
      if (k > 0) {
        close_piece(k, at, before, &after);
        open_piece(k, at, after, &before);
      }
    }
  }

  void record_jam(std::size_t segment, const Rational& ta, const Rational& tb, const ChainState& a, const ChainState& b,
                  std::size_t part, const std::string& reason, const std::vector<SliceContact>& contacts) {
    KinematicEvent event;
    event.kind = KinematicEvent::Kind::jam;
    event.at = locate(segment, ta, tb);
    std::size_t k = part == none ? 0 : part;
    event.part = chain.model->parts[chain.parts[k].part].name;
    for (const SliceContact& contact : contacts) {
      ContactLabel label = label_of(chain, contact, chain.parts[k].part);
      if (std::find(event.before.begin(), event.before.end(), label) == event.before.end()) event.before.push_back(label);
    }
    event.position = a.parts[k].unwrapped;
    if (path_at_events) add_path_points(a);
    event.description = (k == 0 ? "the driver cannot proceed: " : "the driver cannot proceed: " + event.part + ": ") + reason;
    result.events.push_back(event);
    result.jam = event;
    for (std::size_t j = 1; j < chain.parts.size(); ++j) close_piece(j, event.at, a.parts[j]);
  }

  // Advances from `left` (at t_left) to t_right, locating every contact change on the way.
  // Returns false when the driver is blocked.
  bool advance(ChainState& left, std::size_t segment, Rational t_left, const Rational& t_right) {
    ChainState right = step_to(left, segment, t_right);
    // A step longer than the follower's play may lose track of its free range, which then
    // looks closed: halve such steps before looking for a real blocking point.
    if (right.jammed || jumped(left, right)) {
      if (abs(t_right - t_left) > Rational(1, 1 << 20)) {
        Rational middle = (t_left + t_right) / 2;
        if (!advance(left, segment, t_left, middle)) return false;
        return advance(left, segment, middle, t_right);
      }
      if (right.coarse) right = step_to(left, segment, t_right, false);
    }
    for (int guard = 0; guard < 10000; ++guard) {
      if (!differs(left, right)) {
        left = std::move(right);
        return true;
      }
      ChainState a = left, b = right;
      Rational ta = t_left, tb = t_right;
      // b is step_to(a, segment, tb) for the current a (strict or not; no strip is generated
      // between that step and the state right of the event below, which then reuses it)
      bool b_from_a = true;
      while (abs(tb - ta) > epsilon) {
        Rational tm = (ta + tb) / 2;
        ChainState m = step_to(a, segment, tm);
        if (!differs(a, m)) {
          a = std::move(m);
          ta = tm;
          b_from_a = false;
        } else {
          b = std::move(m);
          tb = tm;
          b_from_a = true;
        }
      }
      // the state right of the event, reached from the left one by the smallest step (a state
      // reached by a longer step may show a change that a finer step does not)
      b = non_strict_step(chain, a, segments[segment].piece, tb, unwrapped(segment, tb), b_from_a ? &b : nullptr);
      if (!differs(a, b)) {
        left = std::move(b);
        t_left = tb;
        if (t_left == t_right) return true;
        right = step_to(left, segment, t_right);
        continue;
      }
      // a discontinuous push is a jam: the follower would have to jump through blocked space.
      // Parts are updated in chain order, so a part before the one that jammed in `b` may
      // already have been moved by such a jump; that jump, not what it did downstream (e.g. a
      // balance squeezed by a fork the jump moved), is what stops the driver.
      std::size_t upstream = b.jammed && b.jam_part != none ? b.jam_part : chain.parts.size();
      std::size_t jumping = none;
      for (std::size_t k = 1; k < upstream && k < b.parts.size() && jumping == none; ++k)
        if (b.parts[k].pushed && std::abs(b.parts[k].unwrapped - a.parts[k].unwrapped) > 1e-7) jumping = k;
      if (b.jammed || jumping != none) {
        bool jump = jumping != none;
        std::size_t part = jump ? jumping : b.jam_part;
        std::string reason = jump ? "would have to jump: the contact pushes it at right angles to its motion (dead point or locking face; " +
                                        approximate_jump + ")"
                                  : b.jam_reason;
        std::vector<SliceContact> contacts = jump ? a.parts[jumping].contacts : b.jam_contacts;
        if (jump) {
          contacts.insert(contacts.end(), b.parts[jumping].blocked_by.begin(), b.parts[jumping].blocked_by.end());
          contacts.insert(contacts.end(), b.parts[jumping].contacts.begin(), b.parts[jumping].contacts.end());
        }
        if (!jump && part != none && part > 0) {
          // just before the jam the part's free range is bounded by the contacts that close it
          const PartState& last = a.parts[part];
          if (last.lower.exists && last.upper.exists) {
            contacts.insert(contacts.end(), last.lower.contacts.begin(), last.lower.contacts.end());
            contacts.insert(contacts.end(), last.upper.contacts.begin(), last.upper.contacts.end());
          }
        }
        record_jam(segment, ta, tb, a, b, part, reason, contacts);
        if (jump) {
          // name the wall itself (e.g. a locking face), ahead of the ends of the blocked range
          std::vector<ContactLabel> wall = wall_contacts(chain, a, jumping, segments[segment].piece, ta, tb);
          for (KinematicEvent* event : {&result.events.back(), &*result.jam}) {
            std::vector<ContactLabel> named = wall;
            for (const ContactLabel& label : event->before)
              if (std::find(named.begin(), named.end(), label) == named.end()) named.push_back(label);
            event->before = std::move(named);
          }
        }
        left = std::move(a);
        return false;
      }
      record_event(segment, ta, tb, a, b);
      left = std::move(b);
      t_left = tb;
      if (t_left == t_right) return true;
      right = step_to(left, segment, t_right);
      if (right.coarse) return advance(left, segment, t_left, t_right);
    }
    throw NumericError("too many contact changes between two grid points");
  }

  void sample(const ChainState& state) {
    KinematicSample s;
    s.driver = state.driver_unwrapped;
    std::vector<Rates> r = rates(chain, state);
    for (std::size_t k = 1; k < chain.parts.size(); ++k) {
      const PartState& part = state.parts[k];
      const AxisLine& line = chain.parts[k].line;
      s.positions.push_back(part.unwrapped);
      if (open[k].open) {
        open[k].lowest = std::min(open[k].lowest, part.unwrapped);
        open[k].highest = std::max(open[k].highest, part.unwrapped);
        if (!open[k].moved) open[k].moved = !same_position(k, part, open[k].state);
      }
      s.velocity_ratios.push_back(r[k].ratio);
      if (options.accelerations) s.accelerations.push_back(r[k].acceleration);
      double width = std::numeric_limits<double>::infinity();
      if (part.lower.exists && part.upper.exists)
        width = distance_down(line, part.position, part.lower.at) + distance_up(line, part.position, part.upper.at);
      s.play.push_back(width);
      s.contacts.push_back(labels(part, k));
    }
    result.samples.push_back(std::move(s));
    add_path_points(state);
  }

  // The state's point on the path of every 2-D pair.
  void add_path_points(const ChainState& state) {
    for (std::size_t p = 0; p < chain.slicers.size(); ++p) {
      const PairSlicer& slicer = *chain.slicers[p];
      if (!slicer.other_moves()) continue;
      PairPath& path = result.paths[p];
      const Model& model = *chain.model;
      auto wrapped = [&](std::size_t part_index) {
        std::size_t k = chain.chain_index[part_index];
        double value = state.parts[k].unwrapped;
        if (chain.parts[k].line.rotation) value = std::remainder(value, 2 * pi);
        return value;
      };
      std::size_t x_part = *model.find_part(path.x_part), y_part = *model.find_part(path.y_part);
      PathPoint point{wrapped(x_part), wrapped(y_part), false};
      const PartState& follower = state.parts[chain.chain_index[slicer.follower()]];
      for (const SliceContact& contact : follower.contacts)
        if (!contact.limit && contact.slicer == p) point.contact = true;
      path.points.push_back(point);
    }
  }
};

// Shifts the driver's coordinates in `result` (those of the sweep's frame) by `half_turns` pi:
// certified ranges outwards, the other doubles to nearest; the events' resolution is then the
// widest shifted range (the doubles far out are coarse).
void shift_driver_coordinates(KinematicsResult& result, const mpz_class& half_turns) {
  mpfr_t x, p;
  mpfr_inits2(128 + static_cast<mpfr_prec_t>(mpz_sizeinbase(half_turns.get_mpz_t(), 2)), x, p, static_cast<mpfr_ptr>(nullptr));
  auto shifted = [&](double value, mpfr_rnd_t rounding) {
    const bool positive = sgn(half_turns) > 0;
    mpfr_const_pi(p, positive ? rounding : (rounding == MPFR_RNDD ? MPFR_RNDU : rounding == MPFR_RNDU ? MPFR_RNDD : rounding));
    mpfr_mul_z(p, p, half_turns.get_mpz_t(), rounding);
    mpfr_add_d(x, p, value, rounding);
    return mpfr_get_d(x, rounding);
  };
  auto near = [&](double& value) { value = shifted(value, MPFR_RNDN); };
  result.event_resolution = 0;
  auto range = [&](DriverLocation& at) {
    at.coordinate = CertifiedRange{shifted(at.coordinate.lower, MPFR_RNDD), shifted(at.coordinate.upper, MPFR_RNDU)};
    result.event_resolution = std::max(result.event_resolution, std::nextafter(at.coordinate.upper - at.coordinate.lower,
                                                                               std::numeric_limits<double>::infinity()));
  };
  near(result.reached);
  for (KinematicSample& sample : result.samples) near(sample.driver);
  for (KinematicEvent& event : result.events) {
    range(event.at);
    if (event.part == result.driver) near(event.position);
  }
  if (result.jam) {
    range(result.jam->at);
    if (result.jam->part == result.driver) near(result.jam->position);
  }
  for (KinematicPiece& piece : result.pieces) {
    range(piece.start);
    range(piece.end);
  }
  for (ReversalCheck& check : result.reversals) near(check.driver);
  mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
}

}  // namespace

KinematicsResult analyze_kinematics(const Model& model, const KinematicsOptions& options, const std::vector<CSpace>& spaces) {
  {
    // a mechanism far from the origin for its size is analysed moved to it by one exact
    // vector (the same angles and offsets: they are displacements), a rotation-only mechanism
    // far outside the doubles' range exactly rescaled (the same angles, and its C-spaces are
    // the same charts): core/model_scale.hpp
    if (std::optional<NormalisedMechanism> copy = normalised_mechanism(model))
      return analyze_kinematics(copy->model, options, spaces);
    std::vector<std::size_t> parts(model.parts.size());
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k] = k;
    require_kinematic_length_scale(model, parts);   // lengths as coordinates: absolute resolutions
  }
  auto clock_start = std::chrono::steady_clock::now();
  const std::size_t push_ties_before = undecided_push_ties();
  KinematicsResult result;
  result.model_name = model.name;
  // the driver
  std::size_t driver = none;
  if (!options.driver.empty()) {
    auto found = model.find_part(options.driver);
    if (!found) throw ModelError("/parts", "no part called '" + options.driver + "' to drive");
    driver = *found;
  } else {
    for (const PairSpec& pair : model.pairs) {
      for (std::size_t candidate : {pair.first, pair.second})
        if (model.parts[candidate].motion.kind == Motion::Kind::rotation ||
            model.parts[candidate].motion.kind == Motion::Kind::translation) {
          driver = candidate;
          break;
        }
      if (driver != none) break;
    }
    if (driver == none) throw ModelError("/pairs", "no pair with a rotating or translating part to drive");
  }
  const Part& driver_part = model.parts[driver];
  result.driver = driver_part.name;
  result.driver_rotates = driver_part.motion.kind == Motion::Kind::rotation;

  Chain chain = build_chain(model, driver, spaces, options.method, options.loads);
  chain.accelerations = options.accelerations;   // sampled only when asked for
  if (!options.model_loads)
    for (std::size_t k = 1; k < chain.parts.size(); ++k)
      if (!options.loads.count(model.parts[chain.parts[k].part].name)) chain.parts[k].load = FollowerLoad{};
  // A rotating follower's whole turns are followed in doubles (its unwrapped coordinate gives
  // compare_unwrapped the turns of its exact position): refused beyond 2^40 rad, where that
  // hint would lose them (session 56; the driver's are exact, plan_driver). Whole turns change
  // nothing for a part about a fixed axis: give its angle reduced.
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    if (!chain.parts[k].line.rotation) continue;
    const Part& part = model.parts[chain.parts[k].part];
    const Rational bound(mpz_class(1) << 40);
    const bool far_angle = abs(part.initial.angle) >= bound;
    const bool far_rest = chain.parts[k].load.kind == FollowerLoad::Kind::spring && abs(chain.parts[k].load.rest) >= bound;
    if (far_angle || far_rest)
      throw ModelError(part.pointer, "part '" + part.name + "': its " + (far_angle ? "initial angle" : "spring's rest angle") +
                                         " lies beyond 2^40 rad (about 1.1e12 rad); the kinematic analysis follows a driven "
                                         "part's whole turns in doubles: give the angle less whole turns (they change nothing "
                                         "for a part about a fixed axis)");
  }
  result.unconnected = chain.unconnected;
  result.warnings = chain.warnings;
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    result.followers.push_back(model.parts[chain.parts[k].part].name);
    result.follower_rotates.push_back(chain.parts[k].line.rotation);
    result.loads.push_back(chain.parts[k].load);
  }
  for (std::size_t p = 0; p < chain.slicers.size(); ++p) {
    const PairSlicer& slicer = *chain.slicers[p];
    result.slice_methods.push_back(slicer.name() + ": " + chain.slicer_methods[p]);
    PairPath path;
    path.pair = slicer.name();
    if (slicer.other_moves()) {
      std::size_t colon = slicer.name().find(':');
      path.x_part = slicer.name().substr(0, colon);
      path.y_part = slicer.name().substr(colon + 1);
    } else {
      path.x_part = model.parts[slicer.follower()].name;
    }
    result.paths.push_back(path);
  }
  if (chain.parts.size() < 2) throw ModelError("/pairs", "part '" + driver_part.name +
                                                        "' drives no other part (its pairs are with fixed parts only; where a fixed "
                                                        "part stops it is shown by 'hipair cspace' and 'hipair certify')");

  // the driver's travel: its end, and its length `travel` in doubles (approximate: the grid's
  // spacing, progress and the report's range; every decision on the travel is exact, plan_driver)
  const AxisLine& line = chain.parts[0].line;
  Rational start = result.driver_rotates ? driver_part.initial.angle : driver_part.initial.offset;
  double travel = 0;
  DriverEnd end;
  int direction = options.direction >= 0 ? 1 : -1;
  if (options.range) {
    start = options.range->first;
    const int sign = sgn(Rational(options.range->second - options.range->first));
    if (sign != 0) direction = sign;
    travel = std::abs(Rational(options.range->second - options.range->first).get_d()) * direction;
    end.value = options.range->second;
  } else if (result.driver_rotates && line.cyclic) {
    travel = direction * 2 * pi * options.cycles.get_d();
    end = DriverEnd{DriverEnd::Kind::cycles, options.cycles};
  } else {
    // to the end of the travel in the direction
    Rational limit = direction > 0 ? line.pieces.back().hi : line.pieces.front().lo;
    double coordinate = result.driver_rotates ? line.coordinate(direction > 0 ? line.pieces.size() - 1 : 0, limit.get_d()) : limit.get_d();
    travel = coordinate - start.get_d();
    end = result.driver_rotates ? DriverEnd{DriverEnd::Kind::limit, Rational(0)} : DriverEnd{DriverEnd::Kind::coordinate, limit};
  }
  // A range whose ends differ: say why it is still empty (session 32: "the driver range is
  // empty" for --range 1e-300:2e-300 told nothing).
  auto range_text = [&] {
    return "the driver range [" + to_decimal_string(options.range->first) + ", " + to_decimal_string(options.range->second) +
           "]" + (result.driver_rotates ? " rad" : " mm");
  };
  const bool ends_differ = options.range && options.range->first != options.range->second;
  // Every turn's samples are kept (about 3.5 MB and 0.3 s a turn on the cam follower): a range of
  // 100 000 rad grew past 1 GB in 20 s before "driver range too long" (≈ 30 000 turns) stopped it
  // (hunt41; tolerance's nominal path and library callers come here too, not only analyze's CLI).
  // Decided exactly (session 56): a range's length against 200 pi, the cycles against 100, a
  // limited rotation's travel to its limit from the located ends.
  auto too_long = [&] {
    throw ModelError("", (options.range ? range_text() : "the driver's " + to_decimal_string(options.cycles) + " cycles") +
                             " spans more than " + std::to_string(max_driver_turns) +
                             " turns of the driver: analyse a shorter range");
  };
  if (result.driver_rotates) {
    if (options.range) {
      if (angle_sign(Rational(0), mpz_class(2 * max_driver_turns), abs(Rational(options.range->second - options.range->first))) < 0)
        too_long();
    } else if (line.cyclic && options.cycles > max_driver_turns) {
      too_long();
    }
  }
  result.direction = direction;
  result.start = start.get_d();
  result.end = start.get_d() + travel;
  // the plan and the sweep hold at any angle; the report's angles are doubles
  if (result.driver_rotates && !std::isfinite(result.start))
    throw NumericError("the driver's angle " + to_decimal_string(start, 6) +
                       " rad lies beyond the range of doubles (about 1.8e308 rad), in which the driver's angles are "
                       "reported: give it less whole turns (they change nothing for a part about a fixed axis)");

  Sweep sweep(chain, options, result);
  DriverPlan plan = plan_driver(line, start, direction, end, result.warnings);
  if (result.driver_rotates && !options.range && !line.cyclic) {
    const bool up = direction > 0;
    const mpz_class half_turns = up ? mpz_class(plan.end_half_turns - plan.start_half_turns)
                                    : mpz_class(plan.start_half_turns - plan.end_half_turns);
    const Rational& a = up ? plan.start.value.lower : plan.end.value.lower;
    const Rational& b = up ? plan.end.value.lower : plan.start.value.lower;
    if (!half_turns_at_most(half_turns, a, b, 2 * max_driver_turns)) too_long();
  }
  // the travel in the frame's doubles where the frame is not the model's (far out; approximate)
  if (sgn(plan.reference) != 0 && result.driver_rotates && !plan.segments.empty()) {
    const Segment& first = plan.segments.front();
    const Segment& last = plan.segments.back();
    travel = segment_coordinate(line, last, last.to) - segment_coordinate(line, first, first.from);
    result.end = result.start + travel;
  }
  sweep.segments = std::move(plan.segments);
  if (sweep.segments.empty())
    throw NumericError(!ends_differ ? std::string("the driver range is empty")
                       : result.driver_rotates
                           ? range_text() + " is one driver position: a rotating driver is placed at half-angle tangents "
                                            "rounded to 2^-60 (about 1.7e-18 rad apart), and at its motion limit where the "
                                            "range lies beyond it; give a wider range within the limits"
                           : range_text() + " is one driver position: the range lies beyond the driver's motion limits");
  sweep.epsilon = Rational(1, mpz_class(1) << std::clamp(options.event_bits, 8, 200));
  sweep.open.resize(chain.parts.size());
  sweep.total_travel = std::abs(travel);
  double spacing = result.driver_rotates ? 2 * pi / std::max(8u, options.steps_per_cycle)
                                         : std::abs(travel) / std::max(8u, options.steps_per_cycle);
  sweep.path_at_events = sweep.total_travel < spacing;

  const double origin_unwrapped = sgn(plan.reference) == 0 ? result.start : sweep.unwrapped(0, sweep.segments[0].from);
  ChainState state = initial_state(chain, sweep.segments[0].piece, sweep.segments[0].from,
                                   sweep.unwrapped(0, sweep.segments[0].from), result.initial_interference);
  DriverLocation origin = sweep.locate(0, sweep.segments[0].from, sweep.segments[0].from);
  result.event_resolution = 0;
  if (state.jammed) {
    sweep.record_jam(0, sweep.segments[0].from, sweep.segments[0].from, state, state, state.jam_part, state.jam_reason,
                     state.jam_contacts);
  } else {
    for (std::size_t k = 1; k < chain.parts.size(); ++k) sweep.open_piece(k, origin, state.parts[k]);
    sweep.sample(state);
    sweep.grid.push_back({0, sweep.segments[0].from, state});
  }
  bool blocked = state.jammed;
  for (std::size_t s = 0; s < sweep.segments.size() && !blocked; ++s) {
    const Segment& segment = sweep.segments[s];
    if (s > 0) state = sweep.step_to(state, s, segment.from);   // same configuration in the next chart
    Rational t = segment.from;
    for (const Rational& next : grid_of(line, segment, spacing)) {
      if (!sweep.advance(state, s, t, next)) {
        blocked = true;
        break;
      }
      t = next;
      sweep.sample(state);
      sweep.grid.push_back({s, t, state});
      if (options.progress)
        options.progress(std::min(1.0, std::abs(state.driver_unwrapped - origin_unwrapped) / sweep.total_travel));
    }
  }
  result.reached = state.driver_unwrapped;
  if (options.progress) options.progress(1.0);
  if (!blocked) {
    const Segment& last = sweep.segments.back();
    DriverLocation end = sweep.locate(sweep.segments.size() - 1, last.to, last.to);
    for (std::size_t k = 1; k < chain.parts.size(); ++k) sweep.close_piece(k, end, state.parts[k]);
  }

  // reversal: lost motion before each follower moves when the driver turns back
  if (options.reversal && !sweep.grid.empty()) {
    std::vector<std::pair<std::size_t, std::size_t>> checks;   // (follower chain index, grid index)
    for (const KinematicPiece& piece : result.pieces) {
      if (!piece.moving || piece.mode != KinematicPiece::Mode::contact) continue;
      if (checks.size() >= options.reversal_points) break;
      std::size_t k = chain.chain_index[*model.find_part(piece.part)];
      double middle = 0.5 * (piece.start.value() + piece.end.value());
      std::size_t best = 0;
      for (std::size_t g = 0; g < sweep.grid.size(); ++g)
        if (std::abs(sweep.grid[g].state.driver_unwrapped - middle) <
            std::abs(sweep.grid[best].state.driver_unwrapped - middle))
          best = g;
      if (best == 0) continue;
      if (std::find(checks.begin(), checks.end(), std::make_pair(k, best)) != checks.end()) continue;
      checks.emplace_back(k, best);
    }
    for (auto [k, g] : checks) {
      ReversalCheck check;
      check.part = model.parts[chain.parts[k].part].name;
      check.driver = sweep.grid[g].state.driver_unwrapped;
      const ChainState& origin_state = sweep.grid[g].state;
      ChainState current = origin_state;
      // walk the grid backwards
      for (std::size_t j = g; j-- > 0;) {
        const auto& point = sweep.grid[j];
        const auto& later = sweep.grid[j + 1];
        ChainState next = sweep.step_to(current, point.segment, point.t);
        bool moved = next.jammed || compare(next.parts[k].position, origin_state.parts[k].position) != 0;
        if (moved) {
          // bisect inside the chart of `later` (a grid point at the end of a chart is the same
          // configuration as the start of the next chart)
          std::size_t chart_segment = later.segment;
          Rational ta = later.t;
          Rational tb = later.segment == point.segment ? point.t : sweep.segments[later.segment].from;
          ChainState a = current;
          while (abs(tb - ta) > sweep.epsilon) {
            Rational tm = (ta + tb) / 2;
            ChainState m = sweep.step_to(a, chart_segment, tm, false);
            if (!m.jammed && compare(m.parts[k].position, origin_state.parts[k].position) == 0) {
              a = std::move(m);
              ta = tm;
            } else {
              tb = tm;
            }
          }
          check.lost_motion = std::abs(sweep.unwrapped(chart_segment, ta) - check.driver);
          check.follower_moved = true;
          break;
        }
        current = std::move(next);
        if (std::abs(current.driver_unwrapped - check.driver) > (result.driver_rotates ? 2 * pi : sweep.total_travel)) break;
      }
      if (!check.follower_moved) check.lost_motion = std::abs(current.driver_unwrapped - check.driver);
      result.reversals.push_back(check);
    }
  }

  // back from the sweep's frame to the model's: the driver's coordinates shifted by the frame's
  // whole turns (certified enclosures outwards; the rest approximate, as they were)
  if (sgn(plan.reference) != 0) shift_driver_coordinates(result, plan.reference);

  // contact usage and play
  for (const KinematicPiece& piece : result.pieces) {
    for (const ContactLabel& contact : piece.contacts) {
      auto found = std::find_if(result.contacts.begin(), result.contacts.end(), [&](const ContactUse& use) {
        return use.part == piece.part && use.contact == contact;
      });
      if (found == result.contacts.end()) {
        ContactUse use;
        use.part = piece.part;
        use.contact = contact;
        result.contacts.push_back(use);
        found = result.contacts.end() - 1;
      }
      found->intervals.emplace_back(piece.start.value(), piece.end.value());
    }
  }
  for (ContactUse& use : result.contacts) {
    if (use.contact.limit) continue;
    std::string lower = use.contact.label;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    if (!options.expected_contacts.empty()) {
      bool expected = std::any_of(options.expected_contacts.begin(), options.expected_contacts.end(),
                                  [&](const std::string& pattern) { return use.contact.label.find(pattern) != std::string::npos; });
      if (!expected) {
        use.unintended = true;
        use.reason = "not among the expected contacts";
      }
      continue;
    }
    bool corner = use.contact.kind == ContactKind::vertex_segment || use.contact.kind == ContactKind::segment_vertex ||
                  use.contact.kind == ContactKind::vertex_arc || use.contact.kind == ContactKind::arc_vertex;
    if (lower.find("tip") != std::string::npos && lower.find("root") != std::string::npos) {
      use.unintended = true;
      use.reason = "a tooth tip touches a root: interference";
    } else if (corner) {
      use.unintended = true;
      use.reason = "a corner carries the contact: check for edge loading, under-cutting or interference";
    }
  }
  for (std::size_t f = 0; f < result.followers.size(); ++f) {
    PlaySummary play;
    play.part = result.followers[f];
    bool first = true;
    for (const KinematicSample& sample : result.samples) {
      double width = sample.play[f];
      if (!std::isfinite(width)) {
        play.unbounded = true;
        continue;
      }
      if (first || width < play.minimum) {
        play.minimum = width;
        play.at_minimum = sample.driver;
      }
      if (first || width > play.maximum) {
        play.maximum = width;
        play.at_maximum = sample.driver;
      }
      first = false;
    }
    // a follower with no sample on the path (no position of it is free at the start) has no play
    // to report: a summary of zeros read "Play ... 0.000° all along" (session 48, hunt48)
    if (!first || play.unbounded) {
      // held on both sides at no sample: no width (until session 50 the zeros of an empty summary
      // were read as "never held", also when every width measured was 0, a zero-clearance fit)
      if (first)
        play.minimum = play.maximum = play.at_minimum = play.at_maximum = std::numeric_limits<double>::quiet_NaN();
      result.play.push_back(play);
    }
  }
  // zero-clearance fits the kernel slicers could not decide (SliceClassCounts::touching_undecided)
  for (const auto& slicer : chain.slicers) {
    const std::size_t undecided = kernel_slice_class_counts(*slicer).touching_undecided;
    if (undecided > 0)
      result.warnings.push_back("pair " + slicer->name() + ": " + std::to_string(undecided) +
                                " slice point(s) with blocked space on both sides at an irrational root of two or more"
                                " contacts (or of one contact of even multiplicity) were not decided: reported as"
                                " blocked, though they may be zero-clearance fits (touching)");
  }
  // pushes out of blocked space whose nearer end certified enclosures did not decide (engine.cpp)
  if (const std::size_t ties = undecided_push_ties() - push_ties_before; ties > 0)
    result.warnings.push_back(std::to_string(ties) + " decision(s) of the direction a follower is pushed out of blocked"
                              " space found both ends of the blocked interval at distances equal to 2^-1024 (not decided"
                              " exactly): taken downwards");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace hipair
