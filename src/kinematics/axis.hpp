// The axis of one moving part as a sequence of C-space charts, exact positions on it, and
// slices along it (free / blocked intervals bounded by labelled contact points). Internal.
#pragma once

#include "kinematics/slice.hpp"

#include <hipair/model.hpp>

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace hipair::kinematics_detail {

/// A part's axis: its charts in ascending coordinate order. A full rotation is cyclic (two
/// charts, t in [-1, 1] around 0 and around pi); a limited rotation or a translation is a line.
struct AxisLine {
  bool rotation = true;
  bool cyclic = false;
  bool limited = false;              ///< line ends are motion limits (else: beyond every contact)
  std::vector<ChartAxis> pieces;
  /// Rotation: piece p is the chart about half_turns[p] pi, exactly (0 and 1 for a cyclic axis;
  /// a limited rotation's charts in the order of these, session 55: before, in the order of
  /// double angles, garbage for limits beyond 2^53 rad); 0 for a translation.
  std::vector<long> half_turns;
  std::vector<double> offsets;       ///< half_turns[p] pi in double: coordinate = offsets[p] + 2 atan(t) (rotation) or t

  /// Part coordinate (rad or mm) of chart value `t` of piece `piece`, in double.
  double coordinate(std::size_t piece, double t) const;
  /// Index of the piece equal to `chart`, or nullopt. For a translation, the single piece
  /// whenever the chart lies inside it.
  std::optional<std::size_t> piece_of(const ChartAxis& chart) const;
  /// Piece `piece`'s upper end is glued to the next piece's lower end (the next is the first
  /// piece for the last one of a cyclic axis).
  bool seam_after(std::size_t piece) const;
  std::size_t next(std::size_t piece) const { return piece + 1 < pieces.size() ? piece + 1 : 0; }
  /// Period of the coordinate (2 pi) for a cyclic axis, 0 otherwise.
  double period() const;
};

/// The axis of part `part` from the charts the slicers use for it.
AxisLine make_axis(const Model& model, std::size_t part, const std::vector<ChartAxis>& charts);

/// An exact position on an axis: a chart value of one piece. Canonical: a position on a seam
/// is the start of the next piece.
struct AxisPosition {
  std::size_t piece = 0;
  Real value;
  /// truncated_double(value), computed on first use by coordinate() (NaN until then). Copies
  /// carry it with the value; nothing changes `value` in place after construction.
  mutable double approximate = std::numeric_limits<double>::quiet_NaN();
};

AxisPosition canonical(const AxisLine& line, AxisPosition position);
/// Exact order along the axis (for a cyclic axis: from the start of piece 0).
int compare(const AxisPosition& a, const AxisPosition& b);
/// Double part coordinate.
double coordinate(const AxisLine& line, const AxisPosition& position);
/// The value itself when it is exact (Real::exact) or lies on a cell edge k 2^-bits, else the
/// midpoint of the cell [k, k + 1) 2^-bits that holds it (within 2^-(bits + 1)). Not a function
/// of the isolating interval: slices and rates read at it do not depend on how a root was
/// isolated (unless a rational root off the grid is exact in one isolation and not in another).
Rational rational_near(const Real& value, int bits = 64);
/// The double nearest the value towards zero (mpq_get_d's truncation of the exact number; the
/// value itself when it is a rational double). A function of the number, not of its isolating
/// interval; Real::approximate truncates a point of a narrow interval instead, and may differ by
/// one unit in the last place.
double truncated_double(const Real& value);

/// A contact (slicer, feature) or a motion limit on an axis slice.
struct SliceContact {
  std::size_t slicer = 0;
  std::size_t feature = 0;
  bool limit = false;
  bool window = false;   ///< the edge of a sliced window: beyond it the slice is unknown
  friend bool operator==(const SliceContact&, const SliceContact&) = default;
};

/// A point of an axis slice where the class changes.
struct Breakpoint {
  AxisPosition at;
  std::vector<SliceContact> contacts;
  SliceKind after = SliceKind::free;
  /// Blocked on both sides, but a touching configuration: a zero-clearance channel (a free range
  /// of zero width). The class does not change across it.
  bool channel = false;
};

/// The 1-D C-space of a part along its whole axis: classes change at the breakpoints.
/// Intervals are numbered 0..n (n breakpoints): interval i lies between breakpoint i-1 and i
/// (interval 0 starts at the axis start; interval n ends at the axis end). On a cyclic axis
/// interval n continues into interval 0 across the start.
struct AxisSlice {
  SliceKind start_kind = SliceKind::free;   ///< class just after the axis start
  std::vector<Breakpoint> points;
  SliceKind kind(std::size_t interval) const { return interval == 0 ? start_kind : points[interval - 1].after; }
};

/// A part of an axis to slice: coordinates within `half_width` of `center` (rad or mm).
struct AxisWindow {
  AxisPosition center;
  double half_width = 0;
};

/// The slice a slicer returns for follower chart `chart` with `window` (nullptr: the whole
/// chart), read off `wide`: a slice of the same slicer, chart and other-part value whose covered
/// range holds the window's range. Its points inside that range, and the classes of the
/// intervals around them (a class is the same anywhere between two consecutive points of a
/// slice). nullopt when `wide` does not cover the range, when the range is a single value, or
/// when a point of `wide` lies on an end of the range (the slicer gives an empty interval there).
std::optional<ChartSlice> restrict_chart_slice(const ChartSlice& wide, const ChartAxis& chart,
                                               const ChartWindow* window);

/// The chart slices slice_on_axis took for one follower at one chain state, kept so that a
/// narrower window at the same other-part values is read off them (restrict_chart_slice)
/// instead of being sliced again: the engine slices first the window its part's old free range
/// needs, then asks the narrower windows it asks anyway, in the same order, on the same slices.
/// A kernel slicer's count of undecided zero-clearance points (SliceClassCounts) is kept as if
/// every window asked had been sliced: apply() settles it.
struct ChartSliceMemo {
  struct Entry {
    std::size_t slicer = 0, other_chart = 0, follower_chart = 0;
    Rational value;
    ChartSlice slice;
  };
  std::vector<Entry> entries;
  /// Slices taken only to be read off (the wider window's): their undecided points are not
  /// counted until a window asked reads them.
  bool reading_ahead = false;
  std::vector<std::pair<std::size_t, long>> undecided;   ///< (slicer index, count to add)
  std::size_t restricted = 0;                             ///< chart slices read off an entry (tests)
  /// Adds the undecided counts to the slicers (`slicers[slicer index]`).
  template <class Slicers>
  void apply(const Slicers& slicers) {
    for (const auto& [index, delta] : undecided)
      if (delta != 0) add_touching_undecided(*slicers[index], delta);
    undecided.clear();
  }
};

/// Per-thread switch of the engine's reading ahead (the window a part's old free range needs
/// sliced first, the narrower windows asked before it read off that slice: ChartSliceMemo); on
/// by default, tests turn it off to compare whole analyses with and without it.
struct WindowReadingTag;
inline bool& window_reading_switch() { return thread_switch<WindowReadingTag>(); }
/// Chart slices read off a wider one (ChartSliceMemo) on this thread: tests.
inline std::size_t& window_reads() { return thread_counter<WindowReadingTag>(); }

/// One pair's contribution: the follower chart slices of `slicer` (index `slicer_index`) with
/// the other part at (other_chart, value), placed on the follower's axis. With a window, only
/// the window is sliced: the rest is marked blocked, bounded by contacts flagged `window`.
/// With `memo`, a chart slice is read off an entry when one covers its range; a chart slice
/// taken while the memo is reading ahead is added to it.
AxisSlice slice_on_axis(const AxisLine& line, const PairSlicer& slicer, std::size_t slicer_index,
                        std::size_t other_chart, const Rational& value, const AxisWindow* window = nullptr,
                        ChartSliceMemo* memo = nullptr);
/// True when one of the contacts is a window edge.
bool has_window_edge(const std::vector<SliceContact>& contacts);
/// Intersection of free space: blocked where any is blocked, free where all are free.
AxisSlice intersect(const AxisLine& line, const AxisSlice& a, const AxisSlice& b);

/// An end of a free range.
struct Bound {
  bool exists = false;       ///< false: no contact on that side (axis end without limit, or the whole circle)
  bool limit = false;        ///< the axis end at a motion limit
  AxisPosition at;
  std::vector<SliceContact> contacts;
};

/// Where a position lies in an axis slice.
struct Placement {
  bool on_point = false;     ///< exactly on breakpoint `point`
  std::size_t point = 0;
  std::size_t interval = 0;  ///< otherwise inside interval `interval`
};

Placement place(const AxisLine& line, const AxisSlice& slice, const AxisPosition& position);
/// Lower and upper ends of interval `interval` (normalised for cyclic axes).
Bound lower_end(const AxisLine& line, const AxisSlice& slice, std::size_t interval);
Bound upper_end(const AxisLine& line, const AxisSlice& slice, std::size_t interval);
/// The interval just after breakpoint `point`, and just before it.
std::size_t interval_after(const AxisSlice& slice, std::size_t point);
std::size_t interval_before(const AxisLine& line, const AxisSlice& slice, std::size_t point);

/// Distance in coordinate (rad or mm) from `from` going down to `to` (cyclic: modulo period).
double distance_down(const AxisLine& line, const AxisPosition& from, const AxisPosition& to);
double distance_up(const AxisLine& line, const AxisPosition& from, const AxisPosition& to);

/// Exact decisions on unwrapped coordinates (session 49). A position's unwrapped coordinate (a
/// part state's `unwrapped`: whole turns included) is known exactly from its AxisPosition and
/// the number of whole turns, which `unwrapped` (its double, within a quarter turn of it) gives:
/// it is turns_pi(line, position, unwrapped) pi + 2 atan(t) for a rotation, t for a translation.

/// Exact sign of (the unwrapped coordinate of `position`, `unwrapped` its double) - `value`.
/// Translation: the exact comparison of t with the rational. Rotation: the only rational of
/// the form m pi + 2 atan(t) with t algebraic is 0 (m = 0, t = 0: compared exactly); any other
/// is transcendental (Lindemann), so certified MPFR enclosures of m pi + 2 atan(t), refined
/// until they separate from `value`, decide it. \throws NumericError if 2^16 bits do not.
int compare_unwrapped(const AxisLine& line, const AxisPosition& position, double unwrapped, const Rational& value);
/// Exact order of two unwrapped positions (each with its double, for its whole turns).
int compare_unwrapped(const AxisLine& line, const AxisPosition& a, double a_unwrapped, const AxisPosition& b,
                      double b_unwrapped);
/// Exact sign of (b - a) - (c - b) for unwrapped positions a <= b <= c (the push out of blocked
/// space: the distance down from b to a against the distance up to c): an exact rational
/// comparison when all three are rational (translation), else certified enclosures refined until
/// they separate the sign from 0 or, past 2^10 bits, until they lie inside Liouville's bound for
/// a nonzero value (a tie, 0: 2 t_b - t_a - t_c on a translation, the imaginary or real part of
/// (1 + i t_b)^2 (1 - i t_a)(1 - i t_c) on a rotation, vanish). `decided` is false (and 0 is
/// returned) only when that bound lies past 2^-(2^20) (charts' polynomials of huge degree or
/// coefficients: the bisections would take hours).
int compare_push_distances(const AxisLine& line, const AxisPosition& a, double a_unwrapped, const AxisPosition& b,
                           double b_unwrapped, const AxisPosition& c, double c_unwrapped, bool& decided);

}  // namespace hipair::kinematics_detail
