// Axes of moving parts, exact positions on them, and slices along them.
#include "kinematics/axis.hpp"
#include "kinematics/slice_cells.hpp"

#include "algebra/liouville.hpp"
#include "algebra/rational_order.hpp"
#include "algebra/real_filters.hpp"
#include "core/angle_limits.hpp"

#include <hipair/error.hpp>

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>

namespace hipair::kinematics_detail {

namespace algebra = cspace::algebra;

namespace {
constexpr double pi = std::numbers::pi;

bool same_chart(const ChartAxis& a, const ChartAxis& b) {
  return a.kind == b.kind && a.half_turn == b.half_turn && a.lo == b.lo && a.hi == b.hi;
}

// The fewest whole turns k with 2 atan(t) + (m0 + 2 k) pi >= L, exactly (the signs of
// core/angle_sign.hpp, never 0 here but at t = m = L = 0, where >= holds); the estimate is a
// choice (the whole turns nearest L / 2 pi).
mpz_class fewest_turns(const Rational& t, long m0, const Rational& L) {
  mpz_class k = nearest_whole_turns(L);
  while (angle_sign(t, m0 + 2 * k, L) < 0) ++k;
  while (angle_sign(t, m0 + 2 * (k - 1), L) >= 0) --k;
  return k;
}
}  // namespace

double AxisLine::coordinate(std::size_t piece, double t) const {
  return rotation ? offsets[piece] + 2 * std::atan(t) : t;
}

std::optional<std::size_t> AxisLine::piece_of(const ChartAxis& chart) const {
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (!rotation) {
      if (chart.lo >= pieces[p].lo && chart.hi <= pieces[p].hi) return p;
    } else if (same_chart(pieces[p], chart)) {
      return p;
    }
  }
  return std::nullopt;
}

bool AxisLine::seam_after(std::size_t piece) const {
  if (!rotation) return false;
  if (piece + 1 >= pieces.size() && !cyclic) return false;
  const ChartAxis& a = pieces[piece];
  const ChartAxis& b = pieces[next(piece)];
  return a.hi == 1 && b.lo == -1 && a.half_turn != b.half_turn;
}

double AxisLine::period() const { return cyclic ? 2 * pi : 0.0; }

AxisLine make_axis(const Model& model, std::size_t part, const std::vector<ChartAxis>& charts) {
  const Motion& motion = model.parts.at(part).motion;
  AxisLine line;
  if (charts.empty()) throw GeometryError("part '" + model.parts[part].name + "' has no chart");
  if (motion.kind == Motion::Kind::translation) {
    line.rotation = false;
    ChartAxis piece = charts[0];
    for (const ChartAxis& chart : charts) {
      piece.lo = std::min(piece.lo, chart.lo);
      piece.hi = std::max(piece.hi, chart.hi);
    }
    line.pieces = {piece};
    line.half_turns = {0};
    line.offsets = {0.0};
    line.limited = motion.translation_limits.has_value();
    return line;
  }
  line.rotation = true;
  std::vector<ChartAxis> unique;
  for (const ChartAxis& chart : charts)
    if (std::none_of(unique.begin(), unique.end(), [&](const ChartAxis& u) { return same_chart(u, chart); }))
      unique.push_back(chart);
  bool full = unique.size() == 2 && unique[0].lo == -1 && unique[0].hi == 1 && unique[1].lo == -1 &&
              unique[1].hi == 1 && unique[0].half_turn != unique[1].half_turn;
  // limits of a whole turn or more are the whole turn (exact: core/angle_limits.hpp; limits
  // short of it by less than the charts' outward rounding give two full charts too)
  if (full && !(motion.angle_limits && !at_least_whole_turn(Rational(motion.angle_limits->hi - motion.angle_limits->lo)))) {
    line.cyclic = true;
    line.pieces = unique;
    if (line.pieces[0].half_turn) std::swap(line.pieces[0], line.pieces[1]);
    line.half_turns = {0, 1};
    line.offsets = {0.0, pi};
    return line;
  }
  line.limited = true;
  // Each chart about m pi, m = centre + 2 k, k the fewest whole turns with the chart's start
  // at or above the lower limit less 10^-6 rad (the first chart starts below the limit by its
  // outward rounding; without limits, the lower end -pi); the pieces in the order of m. Exact
  // (session 55; before, doubles: limits beyond 2^53 rad gave infinite or coarse offsets and
  // the charts in any order).
  const Rational slack(1, 1000000);
  std::vector<std::pair<mpz_class, ChartAxis>> placed;
  for (const ChartAxis& chart : unique) {
    const long centre = chart.half_turn ? 1 : 0;
    mpz_class m = motion.angle_limits ? centre + 2 * fewest_turns(chart.lo, centre, Rational(motion.angle_limits->lo - slack))
                                      : centre + 2 * fewest_turns(chart.lo, centre + 1, Rational(-slack));
    placed.emplace_back(std::move(m), chart);
  }
  std::sort(placed.begin(), placed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [m, chart] : placed) {
    if (!m.fits_slong_p())
      throw GeometryError("part '" + model.parts[part].name + "' (" + motion.pointer +
                          "): rotation angle limits beyond about 10^19 rad (2^63 half turns) are out of the kinematic analysis' range");
    line.half_turns.push_back(m.get_si());
    line.offsets.push_back(m.get_d() * pi);
    line.pieces.push_back(chart);
  }
  return line;
}

AxisPosition canonical(const AxisLine& line, AxisPosition position) {
  const ChartAxis& piece = line.pieces[position.piece];
  if (line.seam_after(position.piece) && position.value.compare(piece.hi) == 0) {
    std::size_t next = line.next(position.piece);
    return AxisPosition{next, Real::from_rational(line.pieces[next].lo)};
  }
  return position;
}

int compare(const AxisPosition& a, const AxisPosition& b) {
  if (a.piece != b.piece) return a.piece < b.piece ? -1 : 1;
  // both truncated doubles known (coordinate() keeps them): truncation towards zero is
  // non-decreasing, so trunc(a) < trunc(b) implies a < b, exactly (equal ones decide nothing)
  if (!std::isnan(a.approximate) && !std::isnan(b.approximate) && a.approximate != b.approximate)
    return a.approximate < b.approximate ? -1 : 1;
  return algebra::compare(a.value, b.value);
}

double coordinate(const AxisLine& line, const AxisPosition& position) {
  // canonical (a function of the number, not of its isolating interval): computed once per
  // position and its copies
  if (std::isnan(position.approximate)) position.approximate = truncated_double(position.value);
  return line.coordinate(position.piece, position.approximate);
}

namespace {

// Doubles in their order as 64-bit integers (finite doubles; -0 and +0 both 0).
std::int64_t ordered_key(double d) {
  std::int64_t bits = 0;
  std::memcpy(&bits, &d, sizeof bits);
  return bits >= 0 ? bits : -(bits & std::numeric_limits<std::int64_t>::max());
}

double from_ordered_key(std::int64_t key) {
  std::int64_t bits = key >= 0 ? key : (-key) | std::numeric_limits<std::int64_t>::min();
  double d = 0;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

}  // namespace

double truncated_double(const Real& value) {
  if (value.exact) return value.lower.get_d();   // mpq_get_d: truncated towards zero
  // Certified double bounds lo < value < hi by the double bisection (no exact arithmetic; a few
  // units in the last place apart for a well-conditioned root), then trunc(lo) = lo <=
  // trunc(value) <= hi (trunc is non-decreasing), and a binary search over the doubles between
  // with exact signs finds trunc(value). The result does not depend on the interval.
  Real copy = value;
  auto [lo, hi] = algebra::double_bounds(copy);
  if (!(std::isfinite(lo) && std::isfinite(hi))) {
    // beyond the filter's range: exact dyadic bisection to a relative 2^-60 first
    Rational width = abs(copy.upper) + abs(copy.lower);
    width /= Rational(mpz_class(1) << 60);
    algebra::refine_dyadically(copy, width);
    if (copy.exact) return copy.lower.get_d();
    lo = copy.lower.get_d();
    hi = copy.upper.get_d();
  }
  const int lower_sign = algebra::sign_at(copy.polynomial, copy.lower);
  // -1, 0, +1: value against the double d (exact)
  auto against = [&](double d) {
    Rational at(d);
    if (algebra::compare_rationals(at, copy.lower) <= 0) return 1;
    if (algebra::compare_rationals(at, copy.upper) >= 0) return -1;
    int sign = algebra::sign_at(copy.polynomial, at);
    if (sign == 0) return 0;
    // value in (lower, upper): narrow the copy to the side holding it (the same number)
    if (sign == lower_sign) {
      copy.lower = at;
      return 1;
    }
    copy.upper = at;
    return -1;
  };
  // trunc(value) >= d: positive cells start at their double ([d, next d) truncates to d),
  // non-positive ones end at theirs ((previous d, d] truncates to d)
  auto at_least = [&](double d) {
    if (d > 0) return against(d) >= 0;
    return against(std::nextafter(d, -std::numeric_limits<double>::infinity())) > 0;
  };
  std::int64_t low = ordered_key(lo), high = ordered_key(hi);
  while (low < high) {
    const std::int64_t middle = low + (high - low + 1) / 2;
    if (at_least(from_ordered_key(middle))) low = middle;
    else high = middle - 1;
  }
  return from_ordered_key(low);
}

Rational rational_near(const Real& value, int bits) {
  if (value.exact) return value.lower;
  // the midpoint of the cell [k, k + 1) 2^-bits holding the value (a function of the number,
  // not of its isolating interval), or the value itself on a cell edge
  Real copy = value;
  const mpz_class scale = mpz_class(1) << bits;
  algebra::refine_dyadically(copy, Rational(1, scale));   // any interval serves (see above)
  mpz_class cell, upper_cell;
  for (;;) {
    if (copy.exact) return copy.lower;
    Rational scaled = copy.lower * scale;
    mpz_fdiv_q(cell.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());
    scaled = copy.upper * scale;
    mpz_cdiv_q(upper_cell.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());
    // the value lies in (lower, upper), inside [cell, upper_cell] 2^-bits
    if (upper_cell == cell + 1) break;
    if (upper_cell == cell + 2) {
      Rational edge(mpz_class(cell + 1), scale);
      edge.canonicalize();
      int side = value.compare(edge);
      if (side == 0) return edge;
      if (side > 0) cell += 1;
      break;
    }
    copy.refine();
  }
  Rational middle(mpz_class(2 * cell + 1), mpz_class(2 * scale));
  middle.canonicalize();
  return middle;
}

namespace {

struct Item {
  AxisPosition at;
  std::vector<SliceContact> contacts;
  SliceKind after = SliceKind::empty;
  bool channel = false;   ///< a touching point between blocked intervals (SlicePoint::touching)
};

void add_contacts(std::vector<SliceContact>& into, const std::vector<SliceContact>& from) {
  for (const SliceContact& contact : from)
    if (std::find(into.begin(), into.end(), contact) == into.end()) into.push_back(contact);
}

// Merges items at equal positions (the last non-empty class wins).
std::vector<Item> merge_equal(std::vector<Item> items) {
  std::vector<Item> merged;
  for (Item& item : items) {
    if (!merged.empty() && compare(merged.back().at, item.at) == 0) {
      add_contacts(merged.back().contacts, item.contacts);
      if (item.after != SliceKind::empty) merged.back().after = item.after;
      merged.back().channel = merged.back().channel || item.channel;
      continue;
    }
    merged.push_back(std::move(item));
  }
  return merged;
}

// Builds an axis slice from items in axis order. The first item is at the axis start; on a
// cyclic axis the items at the end of the last piece canonicalise to the start and come last.
AxisSlice compress(const AxisLine& line, std::vector<Item> items) {
  AxisSlice slice;
  if (items.empty()) return slice;
  auto at_origin = [&](const Item& item) {
    return item.at.piece == 0 && item.at.value.compare(line.pieces[0].lo) == 0;
  };
  std::vector<SliceContact> tail_contacts;
  while (items.size() > 1 && at_origin(items.back())) {
    add_contacts(tail_contacts, items.back().contacts);
    items.pop_back();
  }
  items = merge_equal(std::move(items));
  add_contacts(items.front().contacts, tail_contacts);
  std::size_t first = 0;
  while (first < items.size() && items[first].after == SliceKind::empty) ++first;
  SliceKind start = first < items.size() ? items[first].after : SliceKind::free;
  slice.start_kind = start;
  SliceKind current = start;
  slice.points.reserve(items.size());   // (see restrict_chart_slice: no copies on growth)
  // items[i], i >= 1, is read once here: its position and contacts move into the breakpoint
  for (std::size_t i = 1; i < items.size(); ++i) {
    Item& item = items[i];
    // a zero-clearance channel is kept although blocked space continues across it
    bool channel = item.channel && current == SliceKind::blocked && item.after == SliceKind::blocked;
    if (item.after == SliceKind::empty || (item.after == current && !channel)) continue;
    slice.points.push_back(Breakpoint{std::move(item.at), std::move(item.contacts), item.after, channel});
    current = item.after;
  }
  if (line.cyclic && current != start)   // the class changes at the start itself
    slice.points.insert(slice.points.begin(), Breakpoint{std::move(items.front().at), std::move(items.front().contacts), start});
  return slice;
}

}  // namespace

bool has_window_edge(const std::vector<SliceContact>& contacts) {
  return std::any_of(contacts.begin(), contacts.end(), [](const SliceContact& c) { return c.window; });
}

namespace {

// The chart range of piece `p` inside the window, or nullopt when the window misses the piece;
// `full` is set when the window covers it.
std::optional<ChartWindow> window_on_piece(const AxisLine& line, std::size_t p, const AxisWindow& window, bool& full) {
  const ChartAxis& piece = line.pieces[p];
  double c0 = line.coordinate(p, piece.lo.get_d()), c1 = line.coordinate(p, piece.hi.get_d());
  double centre = coordinate(line, window.center);
  full = false;
  std::vector<std::pair<double, double>> hits;
  for (int shift = -1; shift <= 1; ++shift) {
    if (!line.cyclic && shift != 0) continue;
    double lo = centre - window.half_width + shift * line.period();
    double hi = centre + window.half_width + shift * line.period();
    double a = std::max(lo, c0), b = std::min(hi, c1);
    if (a <= b) hits.emplace_back(a, b);
  }
  if (hits.empty()) return std::nullopt;
  if (hits.size() > 1 || (hits[0].first <= c0 && hits[0].second >= c1)) {
    full = true;
    return std::nullopt;
  }
  auto chart_value = [&](double c, bool up) {
    double t = line.rotation ? std::tan((c - line.offsets[p]) / 2) : c;
    double scaled = (up ? std::ceil(t * 1099511627776.0) : std::floor(t * 1099511627776.0));
    // beyond 2^984 the product overflows (no mpz from an infinity): such a t is an integer
    // double itself, an infinite or NaN one leaves that side of the piece open
    if (!std::isfinite(scaled)) {
      if (!std::isfinite(t)) return (t == t && t < 0) || (t != t && !up) ? piece.lo : piece.hi;
      return std::clamp(Rational(t), piece.lo, piece.hi);
    }
    Rational value(mpz_class(scaled), mpz_class(1) << 40);
    value.canonicalize();
    return std::clamp(value, piece.lo, piece.hi);
  };
  return ChartWindow{chart_value(hits[0].first, false), chart_value(hits[0].second, true)};
}

}  // namespace

std::optional<ChartSlice> restrict_chart_slice(const ChartSlice& wide, const ChartAxis& chart,
                                               const ChartWindow* window) {
  // the range as the slicers compute it
  Rational lo = window ? std::max(window->lo, chart.lo) : chart.lo;
  Rational hi = window ? std::min(window->hi, chart.hi) : chart.hi;
  if (!(lo < hi) || lo < wide.covered_lo || hi > wide.covered_hi) return std::nullopt;
  // the first points at or above lo and hi; nullopt when one equals them
  std::optional<std::size_t> first = slice_cells::first_point_not_below(wide.points, lo),
                             end = slice_cells::first_point_not_below(wide.points, hi);
  if (!first || !end) return std::nullopt;
  // (lo, points[first]) lies in wide's interval before points[first], (points[end - 1], hi) in
  // the one after points[end - 1]: non-empty intervals of wide (lo and hi are strictly between
  // its points), whose classes hold anywhere inside them
  ChartSlice out;
  out.covered_lo = std::move(lo);
  out.covered_hi = std::move(hi);
  // (reserved: a vector of points grown by push_back copies every point it moves, Rational's
  // move not being noexcept)
  out.points.reserve(*end - *first);
  out.kinds.reserve(*end - *first + 1);
  out.kinds.push_back(wide.kinds[*first]);
  for (std::size_t i = *first; i < *end; ++i) {
    out.points.push_back(wide.points[i]);
    out.kinds.push_back(wide.kinds[i + 1]);
  }
  return out;
}

namespace {

long undecided_points(const ChartSlice& slice) {
  return static_cast<long>(std::count_if(slice.points.begin(), slice.points.end(),
                                         [](const SlicePoint& point) { return point.undecided; }));
}

void add_undecided(ChartSliceMemo& memo, std::size_t slicer_index, long delta) {
  for (auto& [index, count] : memo.undecided)
    if (index == slicer_index) {
      count += delta;
      return;
    }
  memo.undecided.emplace_back(slicer_index, delta);
}

// A chart slice read off an entry of the memo covering its range, else taken (and added).
ChartSlice memo_slice(ChartSliceMemo& memo, const PairSlicer& slicer, std::size_t slicer_index, std::size_t other_chart,
                      const Rational& value, std::size_t follower_chart, const ChartWindow* window) {
  const ChartAxis& chart = slicer.follower_charts()[follower_chart];
  for (const ChartSliceMemo::Entry& entry : memo.entries) {
    if (entry.slicer != slicer_index || entry.other_chart != other_chart || entry.follower_chart != follower_chart ||
        entry.value != value)
      continue;
    std::optional<ChartSlice> read = restrict_chart_slice(entry.slice, chart, window);
    if (!read) continue;
    ++memo.restricted;
    ++window_reads();
    if (!memo.reading_ahead) add_undecided(memo, slicer_index, undecided_points(*read));
    return std::move(*read);
  }
  ChartSlice taken = slicer.slice(other_chart, value, follower_chart, window);
  // A slice read ahead is kept, and its undecided points (which the slicer counted) count when
  // a window asked reads them. A window asked and not read off (wider than the slice read
  // ahead) is asked once and is the widest yet: nothing narrower is read off it.
  if (memo.reading_ahead) {
    add_undecided(memo, slicer_index, -undecided_points(taken));
    memo.entries.push_back(ChartSliceMemo::Entry{slicer_index, other_chart, follower_chart, value, taken});
  }
  return taken;
}

}  // namespace

AxisSlice slice_on_axis(const AxisLine& line, const PairSlicer& slicer, std::size_t slicer_index,
                        std::size_t other_chart, const Rational& value, const AxisWindow* window,
                        ChartSliceMemo* memo) {
  std::vector<Item> items;
  auto emit = [&](std::size_t piece, Real at, std::vector<SliceContact> contacts, SliceKind after, bool channel = false) {
    items.push_back(Item{canonical(line, AxisPosition{piece, std::move(at)}), std::move(contacts), after, channel});
  };
  const SliceContact edge{slicer_index, 0, false, true};
  for (std::size_t p = 0; p < line.pieces.size(); ++p) {
    const ChartAxis& piece = line.pieces[p];
    std::optional<std::size_t> chart_index;
    for (std::size_t c = 0; c < slicer.follower_charts().size(); ++c) {
      const ChartAxis& chart = slicer.follower_charts()[c];
      if (line.rotation ? same_chart(chart, piece) : (chart.lo >= piece.lo && chart.hi <= piece.hi)) {
        chart_index = c;
        break;
      }
    }
    std::optional<ChartWindow> part;
    if (window) {
      bool full = false;
      part = window_on_piece(line, p, *window, full);
      if (!part && !full) {   // the window misses this piece: unknown
        emit(p, Real::from_rational(piece.lo), {edge}, SliceKind::blocked);
        continue;
      }
    }
    if (!chart_index) {
      if (part) {
        if (part->lo > piece.lo) emit(p, Real::from_rational(piece.lo), {edge}, SliceKind::blocked);
        emit(p, Real::from_rational(part->lo), {edge}, SliceKind::free);
        if (part->hi < piece.hi) emit(p, Real::from_rational(part->hi), {edge}, SliceKind::blocked);
      } else {
        emit(p, Real::from_rational(piece.lo), {}, SliceKind::free);
      }
      continue;
    }
    const ChartAxis& chart = slicer.follower_charts()[*chart_index];
    ChartSlice chart_slice = memo ? memo_slice(*memo, slicer, slicer_index, other_chart, value, *chart_index,
                                               part ? &*part : nullptr)
                                  : slicer.slice(other_chart, value, *chart_index, part ? &*part : nullptr);
    const Rational& covered_lo = chart_slice.covered_lo;
    const Rational& covered_hi = chart_slice.covered_hi;
    bool cut_lo = part && covered_lo > chart.lo, cut_hi = part && covered_hi < chart.hi;
    if (cut_lo && covered_lo > piece.lo) emit(p, Real::from_rational(piece.lo), {edge}, SliceKind::blocked);
    if (!cut_lo && chart.lo > piece.lo) emit(p, Real::from_rational(piece.lo), {}, SliceKind::free);
    emit(p, Real::from_rational(covered_lo), cut_lo ? std::vector<SliceContact>{edge} : std::vector<SliceContact>{},
         chart_slice.kinds.front());
    for (std::size_t i = 0; i < chart_slice.points.size(); ++i) {
      std::vector<SliceContact> contacts;
      for (std::size_t feature : chart_slice.points[i].features) contacts.push_back(SliceContact{slicer_index, feature, false});
      // the slice is this call's own copy: its points' values move onto the axis
      emit(p, std::move(chart_slice.points[i].value), std::move(contacts), chart_slice.kinds[i + 1],
           chart_slice.points[i].touching);
    }
    if (cut_hi) emit(p, Real::from_rational(covered_hi), {edge}, SliceKind::blocked);
    else if (chart.hi < piece.hi) emit(p, Real::from_rational(chart.hi), {}, SliceKind::free);
  }
  return compress(line, std::move(items));
}

namespace {
SliceKind combine(SliceKind a, SliceKind b) {
  if (a == SliceKind::blocked || b == SliceKind::blocked) return SliceKind::blocked;
  if (a == SliceKind::touching || b == SliceKind::touching) return SliceKind::touching;
  return SliceKind::free;
}
SliceKind last_kind(const AxisSlice& slice) { return slice.points.empty() ? slice.start_kind : slice.points.back().after; }
}  // namespace

AxisSlice intersect(const AxisLine& line, const AxisSlice& a, const AxisSlice& b) {
  AxisSlice result;
  SliceKind ka = line.cyclic ? last_kind(a) : a.start_kind;
  SliceKind kb = line.cyclic ? last_kind(b) : b.start_kind;
  SliceKind current = combine(ka, kb);
  result.start_kind = combine(a.start_kind, b.start_kind);
  std::size_t i = 0, j = 0;
  bool first = true;
  while (i < a.points.size() || j < b.points.size()) {
    int order = i == a.points.size() ? 1 : j == b.points.size() ? -1 : compare(a.points[i].at, b.points[j].at);
    Breakpoint point;
    // the point itself is a touching configuration of both constraints: each has a breakpoint
    // there (a class change or a channel: a contact) or is not blocked there
    bool touching_here = (order <= 0 || ka != SliceKind::blocked) && (order >= 0 || kb != SliceKind::blocked);
    if (order <= 0) {
      point.at = a.points[i].at;
      add_contacts(point.contacts, a.points[i].contacts);
      ka = a.points[i].after;
      ++i;
    }
    if (order >= 0) {
      if (order > 0) point.at = b.points[j].at;
      add_contacts(point.contacts, b.points[j].contacts);
      kb = b.points[j].after;
      ++j;
    }
    SliceKind kind = combine(ka, kb);
    bool channel = touching_here && current == SliceKind::blocked && kind == SliceKind::blocked &&
                   !has_window_edge(point.contacts) &&
                   std::any_of(point.contacts.begin(), point.contacts.end(), [](const SliceContact& c) { return !c.limit; });
    bool at_origin = point.at.piece == 0 && point.at.value.compare(line.pieces[0].lo) == 0;
    if (!line.cyclic && first && at_origin) {
      result.start_kind = kind;
      current = kind;
      first = false;
      continue;
    }
    first = false;
    if (kind == current && !channel) continue;
    point.after = kind;
    point.channel = channel;
    current = kind;
    result.points.push_back(std::move(point));
  }
  return result;
}

Placement place(const AxisLine& line, const AxisSlice& slice, const AxisPosition& position) {
  const auto& points = slice.points;
  std::size_t lo = 0, hi = points.size();   // first point with at > position
  while (lo < hi) {
    std::size_t mid = (lo + hi) / 2;
    if (compare(points[mid].at, position) <= 0) lo = mid + 1;
    else hi = mid;
  }
  Placement placement;
  if (lo > 0 && compare(points[lo - 1].at, position) == 0) {
    placement.on_point = true;
    placement.point = lo - 1;
    return placement;
  }
  placement.interval = lo;
  if (line.cyclic && placement.interval == 0 && !points.empty()) placement.interval = points.size();
  return placement;
}

Bound lower_end(const AxisLine& line, const AxisSlice& slice, std::size_t interval) {
  Bound bound;
  const auto& points = slice.points;
  if (interval >= 1) {
    bound.exists = true;
    bound.at = points[interval - 1].at;
    bound.contacts = points[interval - 1].contacts;
    return bound;
  }
  if (line.cyclic) return bound;   // whole circle
  if (!line.limited) return bound;
  bound.exists = true;
  bound.limit = true;
  bound.at = AxisPosition{0, Real::from_rational(line.pieces.front().lo)};
  bound.contacts = {SliceContact{0, 0, true}};
  return bound;
}

Bound upper_end(const AxisLine& line, const AxisSlice& slice, std::size_t interval) {
  Bound bound;
  const auto& points = slice.points;
  if (interval < points.size()) {
    bound.exists = true;
    bound.at = points[interval].at;
    bound.contacts = points[interval].contacts;
    return bound;
  }
  if (line.cyclic) {
    if (points.empty()) return bound;
    bound.exists = true;
    bound.at = points.front().at;
    bound.contacts = points.front().contacts;
    return bound;
  }
  if (!line.limited) return bound;
  bound.exists = true;
  bound.limit = true;
  bound.at = AxisPosition{line.pieces.size() - 1, Real::from_rational(line.pieces.back().hi)};
  bound.contacts = {SliceContact{0, 0, true}};
  return bound;
}

std::size_t interval_after(const AxisSlice& slice, std::size_t point) { return point + 1; }

std::size_t interval_before(const AxisLine& line, const AxisSlice& slice, std::size_t point) {
  if (line.cyclic && point == 0) return slice.points.size();
  return point;
}

double distance_down(const AxisLine& line, const AxisPosition& from, const AxisPosition& to) {
  double d = coordinate(line, from) - coordinate(line, to);
  if (line.cyclic) {
    if (compare(from, to) == 0) return 0;
    d = std::fmod(d, 2 * pi);
    if (d < 0) d += 2 * pi;
  }
  return d;
}

double distance_up(const AxisLine& line, const AxisPosition& from, const AxisPosition& to) {
  double d = coordinate(line, to) - coordinate(line, from);
  if (line.cyclic) {
    if (compare(from, to) == 0) return 0;
    d = std::fmod(d, 2 * pi);
    if (d < 0) d += 2 * pi;
  }
  return d;
}

namespace {

// A certified enclosure [lo, hi] of a real number in MPFR.
struct Enclosure {
  mpfr_t lo, hi;
  explicit Enclosure(mpfr_prec_t precision) { mpfr_inits2(precision, lo, hi, static_cast<mpfr_ptr>(nullptr)); }
  ~Enclosure() { mpfr_clears(lo, hi, static_cast<mpfr_ptr>(nullptr)); }
  Enclosure(const Enclosure&) = delete;
  Enclosure& operator=(const Enclosure&) = delete;
};

// The position's unwrapped coordinate is half_turns pi + 2 atan(t) (rotation).
long half_turns(const AxisLine& line, const AxisPosition& position, double unwrapped) {
  long m = line.half_turns[position.piece];
  if (line.cyclic) m += 2 * std::lround((unwrapped - coordinate(line, position)) / (2 * pi));
  return m;
}

// The unwrapped coordinate in doubles for the filters of compare_unwrapped and
// compare_push_distances: a rotation's m pi + 2 atan(t_d), t_d the truncated double of t (|t| <= 1:
// within 2^-52 of it), is within (|m| + 8) 2^-50 of the exact value (atan 1-Lipschitz, libm's
// atan within an ulp, three roundings); NaN when |m| >= 2^20 (no filter). A translation's t_d is
// within 2^-52 |t| of t.
double filtered_unwrapped(const AxisLine& line, const AxisPosition& position, double unwrapped) {
  if (std::isnan(position.approximate)) position.approximate = truncated_double(position.value);
  if (!line.rotation) return position.approximate;
  const long m = half_turns(line, position, unwrapped);
  if (std::abs(m) >= (1L << 20)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(m) * pi + 2 * std::atan(position.approximate);
}

// Encloses the unwrapped coordinate of `position` with its chart value refined to 2^-bits, in
// MPFR of `bits` + 32 bits, directed roundings (atan and the integer multiple of pi monotone).
void enclose_unwrapped(const AxisLine& line, const AxisPosition& position, double unwrapped, int bits, Enclosure& out) {
  Real t = position.value;
  if (!t.exact) t.refine_to(Rational(mpz_class(1), mpz_class(1) << bits));
  // an exact value has lower == upper == the value
  mpfr_set_q(out.lo, t.lower.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(out.hi, t.upper.get_mpq_t(), MPFR_RNDU);
  if (!line.rotation) return;
  mpfr_atan(out.lo, out.lo, MPFR_RNDD);
  mpfr_atan(out.hi, out.hi, MPFR_RNDU);
  mpfr_mul_2ui(out.lo, out.lo, 1, MPFR_RNDD);
  mpfr_mul_2ui(out.hi, out.hi, 1, MPFR_RNDU);
  long m = half_turns(line, position, unwrapped);
  if (m == 0) return;
  mpfr_t turn;
  mpfr_init2(turn, mpfr_get_prec(out.lo));
  // m pi >= m pi_lo for m > 0, >= m pi_hi for m < 0; the product rounded down (up for hi)
  mpfr_const_pi(turn, m > 0 ? MPFR_RNDD : MPFR_RNDU);
  mpfr_mul_si(turn, turn, m, MPFR_RNDD);
  mpfr_add(out.lo, out.lo, turn, MPFR_RNDD);
  mpfr_const_pi(turn, m > 0 ? MPFR_RNDU : MPFR_RNDD);
  mpfr_mul_si(turn, turn, m, MPFR_RNDU);
  mpfr_add(out.hi, out.hi, turn, MPFR_RNDU);
  mpfr_clear(turn);
}

}  // namespace

int compare_unwrapped(const AxisLine& line, const AxisPosition& position, double unwrapped, const Rational& value) {
  if (!line.rotation) return position.value.compare(value);
  if (sgn(value) == 0 && half_turns(line, position, unwrapped) == 0) return position.value.compare(value);
  // Filter: the angle in doubles, m pi + 2 atan(t_d) with t_d the truncated double of t (|t| <= 1:
  // within 2^-52 of it), is within (|m| + 8) 2^-50 of the exact one (atan 1-Lipschitz, libm's atan
  // within an ulp, three roundings); with |m| < 2^20 and |value| < 2^20 a difference beyond 1e-9
  // (over 2^20 times that bound) is a certain sign.
  const double value_d = value.get_d();
  if (std::abs(value_d) < 1048576.0) {
    const double angle = filtered_unwrapped(line, position, unwrapped);
    if (angle - value_d > 1e-9) return 1;
    if (value_d - angle > 1e-9) return -1;
  }
  // value != m pi + 2 atan(t): enclosures separate it at some precision
  for (int bits = 64; bits <= (1 << 16); bits *= 2) {
    Enclosure box(bits + 32);
    enclose_unwrapped(line, position, unwrapped, bits, box);
    if (mpfr_cmp_q(box.lo, value.get_mpq_t()) > 0) return 1;
    if (mpfr_cmp_q(box.hi, value.get_mpq_t()) < 0) return -1;
  }
  throw NumericError("a follower's angle and its spring's rest angle " + value.get_str() +
                     " rad could not be separated at 65536 bits");
}

int compare_unwrapped(const AxisLine& line, const AxisPosition& a, double a_unwrapped, const AxisPosition& b,
                      double b_unwrapped) {
  if (line.cyclic) {
    long turns_a = std::lround((a_unwrapped - coordinate(line, a)) / (2 * pi));
    long turns_b = std::lround((b_unwrapped - coordinate(line, b)) / (2 * pi));
    if (turns_a != turns_b) return turns_a < turns_b ? -1 : 1;
  }
  return compare(a, b);
}

namespace {

// Encloses 2 b - a - c from enclosures of the three at 2^-bits into d (precision bits + 40);
// its sign when the enclosure excludes 0, else 0.
int separated_push(const AxisLine& line, const AxisPosition& a, double a_unwrapped, const AxisPosition& b,
                   double b_unwrapped, const AxisPosition& c, double c_unwrapped, int bits, Enclosure& d) {
  Enclosure ea(bits + 32), eb(bits + 32), ec(bits + 32);
  enclose_unwrapped(line, a, a_unwrapped, bits, ea);
  enclose_unwrapped(line, b, b_unwrapped, bits, eb);
  enclose_unwrapped(line, c, c_unwrapped, bits, ec);
  mpfr_mul_2ui(d.lo, eb.lo, 1, MPFR_RNDD);
  mpfr_sub(d.lo, d.lo, ea.hi, MPFR_RNDD);
  mpfr_sub(d.lo, d.lo, ec.hi, MPFR_RNDD);
  mpfr_mul_2ui(d.hi, eb.hi, 1, MPFR_RNDU);
  mpfr_sub(d.hi, d.hi, ea.lo, MPFR_RNDU);
  mpfr_sub(d.hi, d.hi, ec.lo, MPFR_RNDU);
  return mpfr_sgn(d.lo) > 0 ? 1 : mpfr_sgn(d.hi) < 0 ? -1 : 0;
}

// An upper bound on log2 (1 + t^2) for every t in x's isolating interval.
long log2_one_plus_square(const Real& x) {
  Rational top = abs(x.lower) > abs(x.upper) ? Rational(abs(x.lower)) : Rational(abs(x.upper));
  mpz_class ceiling;
  mpz_cdiv_q(ceiling.get_mpz_t(), top.get_num_mpz_t(), top.get_den_mpz_t());
  ceiling += 1;   // 1 + t^2 <= (ceil |t| + 1)^2
  return 2 * static_cast<long>(mpz_sizeinbase(ceiling.get_mpz_t(), 2));
}

}  // namespace

int compare_push_distances(const AxisLine& line, const AxisPosition& a, double a_unwrapped, const AxisPosition& b,
                           double b_unwrapped, const AxisPosition& c, double c_unwrapped, bool& decided) {
  decided = true;
  if (!line.rotation && a.value.exact && b.value.exact && c.value.exact) {
    return sgn(Rational(2 * b.value.lower - a.value.lower - c.value.lower));
  }
  // (b - a) - (c - b) = 2 b - a - c; the filter: each double within 2^-30 (1 + |its value|) of
  // the exact one (filtered_unwrapped's bounds, |m| < 2^20), so beyond 1e-8 (1 + the sum) the
  // doubles' sign is certain
  const double da = filtered_unwrapped(line, a, a_unwrapped), db = filtered_unwrapped(line, b, b_unwrapped),
               dc = filtered_unwrapped(line, c, c_unwrapped);
  const double difference = 2 * db - da - dc, margin = 1e-8 * (1 + std::abs(da) + 2 * std::abs(db) + std::abs(dc));
  if (difference > margin) return 1;
  if (difference < -margin) return -1;
  for (int bits = 64; bits <= (1 << 10); bits *= 2) {
    Enclosure d(bits + 40);
    if (int sign = separated_push(line, a, a_unwrapped, b, b_unwrapped, c, c_unwrapped, bits, d)) return sign;
  }
  // A tie, or a near one: D = 2 b - a - c is 0 exactly iff an integer polynomial F of the chart
  // values t_a, t_b, t_c vanishes, with |F| <= K |D|; a nonzero F is at least 2^-B (Liouville's
  // inequality, algebra::liouville_bits), so D != 0 is at least 2^-(B + log2 K), and an enclosure
  // of D inside (-2^-(B + log2 K), 2^-(B + log2 K)) is a tie.
  // - a translation: F = D = 2 t_b - t_a - t_c (length 4, degrees 1, 1, 1; K = 1);
  // - a rotation: unwrapped positions m pi + 2 atan(t), so D = N pi + 2 phi (N = 2 m_b - m_a - m_c)
  //   with phi = 2 atan t_b - atan t_a - atan t_c the argument of Z = (1 + i t_b)^2 (1 - i t_a)
  //   (1 - i t_c); near D = 0, phi is near -N pi / 2 and F = Im Z (N even) or Re Z (N odd) has
  //   |F| = |Z| |sin(D / 2)| <= |Z| |D| / 2 (so F = 0 and |D| < 2 pi give D = 0). Both
  //   Im Z = 2 t_b (1 - t_a t_c) - (1 - t_b^2)(t_a + t_c) and Re Z = (1 - t_b^2)(1 - t_a t_c) +
  //   2 t_b (t_a + t_c) have length 8 and degrees 1, 2, 1; |Z| / 2 <= (1 + t_a^2)(1 + t_b^2)
  //   (1 + t_c^2) / 2.
  const std::vector<const Real*> values{&a.value, &b.value, &c.value};
  long threshold = line.rotation ? algebra::liouville_bits(values, {1, 2, 1}, 3) + log2_one_plus_square(a.value) +
                                       log2_one_plus_square(b.value) + log2_one_plus_square(c.value)
                                 : algebra::liouville_bits(values, {1, 1, 1}, 2);
  // a bound past 2^20 bits would take the bisections of the chart values hours: undecided
  if (threshold > (1L << 20)) {
    decided = false;
    return 0;
  }
  mpfr_t bound;
  mpfr_init2(bound, 8);
  mpfr_set_ui_2exp(bound, 1, -threshold, MPFR_RNDN);   // exact: a power of two
  int sign = 0;
  for (int bits = 1 << 11;; bits *= 2) {
    Enclosure d(bits + 40);
    sign = separated_push(line, a, a_unwrapped, b, b_unwrapped, c, c_unwrapped, bits, d);
    if (sign != 0 || (mpfr_cmpabs(d.lo, bound) < 0 && mpfr_cmpabs(d.hi, bound) < 0)) break;
  }
  mpfr_clear(bound);
  return sign;
}

}  // namespace hipair::kinematics_detail
