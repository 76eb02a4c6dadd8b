// Kernel slicer: exact 1-D slices of a pair's C-space from its contact polynomials and the
// exact overlap oracle, without building the arrangement.
//
// At a rational value v of the other part, every contact polynomial P(v, y) is a univariate
// integer polynomial; its real roots in the follower chart are the only places where the
// class of the slice can change. Each interval between consecutive roots gets a rational
// sample point classified by the overlap oracle (exact). Roots where the class does not change
// are kept (the engine ignores them); roots shared by several curves carry all their features.
#include "kinematics/slice.hpp"
#include "kinematics/slice_cells.hpp"
#include "curves/pose.hpp"
#include "curves/algebraic_overlap.hpp"
#include "algebra/interval_times.hpp"
#include "algebra/rational_order.hpp"
#include "algebra/rational_root.hpp"
#include "algebra/real_filters.hpp"
#include "algebra/square_free_memo.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <map>
#include <mutex>
#include <optional>
#include <cmath>

namespace hipair::kinematics_detail {

namespace algebra = cspace::algebra;
using cspace::ContactCurve;
using cspace::FeatureRef;

IntegerPolynomial2 transposed(const IntegerPolynomial2& polynomial) {
  IntegerPolynomial2 result;
  const auto& c = polynomial.coefficients;
  std::size_t rows = 0;
  for (const auto& row : c) rows = std::max(rows, row.size());
  result.coefficients.assign(rows, std::vector<mpz_class>(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) result.coefficients[j][i] = c[i][j];
  return result;
}

namespace {

constexpr int cull_cells = 64;       // sub-intervals of the other axis for curve culling
constexpr int follower_cells = 32;   // sub-intervals of the follower axis
// Fewest curve enclosures a carried class's proof may evaluate before the oracle decides
// instead (an enclosure costs ≈ 1/50 of an oracle query on the ratchet; KernelSlicerOptions::proof_curves).
constexpr std::size_t min_proof_curves = 32;

using cspace::public_kind;

// d/dy of c[i][j] x^i y^j (y: the second index, the follower in a CurveData's orientation).
IntegerPolynomial2 follower_derivative(const IntegerPolynomial2& polynomial) {
  IntegerPolynomial2 result;
  for (const auto& row : polynomial.coefficients) {
    std::vector<mpz_class> out;
    for (std::size_t j = 1; j < row.size(); ++j) out.push_back(row[j] * static_cast<unsigned long>(j));
    result.coefficients.push_back(std::move(out));
  }
  return result;
}

// Interval enclosure of an integer polynomial divided by a power of two, so that coefficients
// of any size stay finite in double (the zero set and the signs are those of the polynomial).
// (Horner's scheme by interval_detail::times: the bounds of operator*, so the same enclosures;
// the slicer's boxes mostly keep one sign — a driver value's enclosure, a run of follower cells,
// a double point.)
class ScaledIntervalPolynomial {
 public:
  ScaledIntervalPolynomial() = default;
  explicit ScaledIntervalPolynomial(const IntegerPolynomial2& polynomial) {
    std::size_t bits = 0;
    for (const auto& row : polynomial.coefficients)
      for (const mpz_class& c : row)
        if (c != 0) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
    std::size_t shift = bits > 800 ? bits - 800 : 0;
    mpz_class scale = mpz_class(1) << shift;
    for (const auto& row : polynomial.coefficients) {
      std::vector<algebra::Interval> out;
      for (const mpz_class& c : row) out.push_back(algebra::enclose(Rational(c, scale)));
      rows_.push_back(std::move(out));
    }
  }
  algebra::Interval evaluate(algebra::Interval x, algebra::Interval y) const {
    algebra::Interval result{0, 0};
    for (auto row = rows_.rbegin(); row != rows_.rend(); ++row) {
      algebra::Interval inner{0, 0};
      for (auto c = row->rbegin(); c != row->rend(); ++c) inner = algebra::interval_detail::times(inner, y) + *c;
      result = algebra::interval_detail::times(result, x) + inner;
    }
    // an overflow or an undefined product must not hide a zero
    if (!(result.lo <= result.hi)) return algebra::Interval{-HUGE_VAL, HUGE_VAL};
    return result;
  }
  /// The enclosure's coefficients in y at x (c[j] of y^j), for repeated evaluation at one x.
  std::vector<algebra::Interval> at_x(algebra::Interval x) const {
    std::vector<algebra::Interval> result;
    for (auto row = rows_.rbegin(); row != rows_.rend(); ++row) {
      if (result.size() < row->size()) result.resize(row->size(), algebra::Interval{0, 0});
      for (std::size_t j = 0; j < result.size(); ++j)
        result[j] = algebra::interval_detail::times(result[j], x) + (j < row->size() ? (*row)[j] : algebra::Interval{0, 0});
    }
    return result;
  }
  /// A polynomial of at_x at y: an enclosure of the polynomial at (x, y).
  static algebra::Interval evaluate_y(const std::vector<algebra::Interval>& coefficients, algebra::Interval y) {
    algebra::Interval result{0, 0};
    for (auto c = coefficients.rbegin(); c != coefficients.rend(); ++c) result = algebra::interval_detail::times(result, y) + *c;
    if (!(result.lo <= result.hi)) return algebra::Interval{-HUGE_VAL, HUGE_VAL};
    return result;
  }

 private:
  std::vector<std::vector<algebra::Interval>> rows_;
};

// One clause of a validity condition, oriented (other, follower): some atom >= 0.
struct OrientedClause {
  std::vector<ScaledIntervalPolynomial> atoms;
};

// The exact data of one feature pair's curve in a chart pair, oriented (other, follower). It
// depends on the chart pair only through its axes' half-turn flags (the generator's poses), so
// every strip of a chart pair shares one copy.
struct CurveData {
  IntegerPolynomial2 polynomial;
  ScaledIntervalPolynomial interval;
  /// The polynomial's partial derivative in the follower coordinate: where its enclosure
  /// excludes zero the curve is a graph over the follower axis there (KernelSlicerOptions::monotone_runs).
  ScaledIntervalPolynomial follower_slope;
  std::vector<OrientedClause> validity;
};

// One curve of a strip of a chart pair: its feature and, per cell of the other axis in the
// strip, the follower cells where it may vanish.
// Its feature pair (parts: the pair's first and second part as generated) and contact type
// give its label in any congruent pair that shares the strip.
struct StripCurve {
  std::size_t feature = 0;
  std::shared_ptr<const CurveData> data;
  std::vector<std::uint32_t> cells;   // cells[c - strip first cell]
  FeatureRef first, second;
  cspace::ContactType type = cspace::ContactType::vertex_segment;
};

}  // namespace

// The curves of a strip of the other axis, cells [first_cell, first_cell + width) (the whole
// chart when the other part is fixed or the slicer generates whole chart pairs), ascending by
// feature. Immutable once generated: congruent pairs share it (SelectionMemo).
struct KernelStrip {
  int first_cell = 0, width = 0;
  std::vector<StripCurve> curves;
  /// A feature pair's polynomial vanished identically (skipped: every configuration satisfies
  /// it, and its contacts are bounded by validity clauses, not by a curve): no class of the
  /// strip is carried over (KernelSlicerOptions::transfer_classes).
  bool zero_curve = false;
  /// The follower cells whose blocked-space cull is done (KernelSlicerOptions::lazy_cull): every
  /// curve of the whole strip's selection that survives in one of them is in `curves`. All
  /// cells unless the slicer culls lazily.
  std::uint32_t culled = ~std::uint32_t(0);
};

namespace {

using Strip = KernelStrip;

struct ChartPair {
  ChartAxis x_axis, y_axis;   // in the pair's own axis order (for the oracle)
  std::vector<std::shared_ptr<const Strip>> strips;              // in the order generated
  std::vector<int> strip_of_cell = std::vector<int>(cull_cells, -1);   // index into strips
  int next_width = 1;   // cells of the next strip generated (doubles: 1, 2, 4, ... 64)
  std::map<std::size_t, std::shared_ptr<const CurveData>> by_feature;   // of the strips generated
  // lazily culled strips (KernelSlicerOptions::lazy_cull), same index as `strips`: the cull
  // walked so far and the strip's chart box (x, y in the pair's axis order)
  std::vector<std::unique_ptr<cspace::CurveGenerator::Selection>> selections;
  std::vector<std::pair<ChartAxis, ChartAxis>> boxes;
};

class KernelSlicer final : public PairSlicer {
 public:
  KernelSlicer(const Model& model, std::size_t pair, std::size_t follower, const KernelSlicerOptions& options)
      : model_(model), options_(options) {
    options_.monotone_runs = options_.monotone_runs && monotone_runs_switch();
    options_.transfer_classes = options_.transfer_classes && transfer_classes_switch();
    if (pair >= model.pairs.size()) throw GeometryError("no pair " + std::to_string(pair));
    const PairSpec& spec = model.pairs[pair];
    if (follower != spec.first && follower != spec.second)
      throw GeometryError("part is not in the pair");
    axes_ = cspace::pair_axes(model, spec.first, spec.second);
    overlap_ = std::make_unique<cspace::PairOverlap>(model, axes_);
    name_ = model.parts[spec.first].name + ":" + model.parts[spec.second].name;
    follower_ = follower;
    other_ = follower == spec.first ? spec.second : spec.first;
    cspace::ChartLayout layout = cspace::chart_layout(model, axes_);
    std::size_t x_part = axes_.first_moves ? axes_.first : axes_.second;
    if (axes_.dimension() == 2) {
      follower_is_x_ = follower == x_part;
      other_moves_ = true;
      follower_charts_ = follower_is_x_ ? layout.x_charts : layout.y_charts;
      other_charts_ = follower_is_x_ ? layout.y_charts : layout.x_charts;
    } else {
      if (follower != x_part) throw GeometryError("the follower of a 1-D pair must be its moving part");
      follower_is_x_ = true;
      other_moves_ = false;
      follower_charts_ = layout.x_charts;
    }
    // canonical feature numbers: (feature of the first part, feature of the second part) in the
    // order of the parts' boundaries, (loop, edge, vertex before the edge's curve) — the order in
    // which the curve generator emits a chart's curves
    for (std::size_t side = 0; side < 2; ++side) {
      const Part& part = model.parts.at(side == 0 ? axes_.first : axes_.second);
      std::size_t edges = 0;
      for (const Loop& loop : part.loops) {
        edge_offsets_[side].push_back(edges);
        edges += loop.edges.size();
      }
      feature_count_[side] = 2 * edges;
    }
    // a carried class's proof may cost about what an oracle query does (see proof_curves)
    proof_curves_ = options_.proof_curves != 0 ? options_.proof_curves
                                               : std::max<std::size_t>(min_proof_curves, (feature_count_[0] + feature_count_[1]) / 2);
    std::size_t other_count = std::max<std::size_t>(1, other_charts_.size());
    pairs_.resize(other_count * follower_charts_.size());
    previous_.resize(pairs_.size());
    // the follower cells' edges, exact: every windowed slice compares them with its window
    for (const ChartAxis& axis : follower_charts_) {
      std::vector<Rational> edges;
      for (int cell = 0; cell <= follower_cells; ++cell) edges.push_back(axis.lo + (axis.hi - axis.lo) * cell / follower_cells);
      follower_edges_.push_back(std::move(edges));
    }
    // the curves of a chart pair are generated strip by strip of the other axis when first
    // sliced: a short driver range visits one or two strips of one chart pair
    lazy_ = other_moves_ && options_.strips && options_.lazy_cull;
    if (options_.selections) {
      // congruent pairs share whole strips instead (counted for every slicer of the analysis
      // when it is made, before any slice)
      generator_ = std::make_unique<cspace::CurveGenerator>(model_, axes_);
      congruence_key_ = generator_->congruence_key();
      if (!congruence_key_.empty()) options_.selections->count_congruence(congruence_key_ + (follower_is_x_ ? "|fx" : "|fy"));
    }
  }

  // Lazily culled strips only for a pair without a congruent partner (decided on first use,
  // when every slicer of the analysis has been counted).
  bool lazy() const {
    if (!lazy_ || !options_.selections || congruence_key_.empty()) return lazy_;
    return options_.selections->congruent(congruence_key_ + (follower_is_x_ ? "|fx" : "|fy")) <= 1;
  }

  // The canonical number of a curve's feature pair (see the constructor).
  std::size_t feature_number(const ContactCurve& curve) const {
    auto index = [&](const FeatureRef& ref, std::size_t side) {
      const std::vector<std::size_t>& offsets = edge_offsets_[side];
      if (ref.loop >= offsets.size()) throw GeometryError("internal: a contact curve names no loop of pair " + name_);
      return 2 * (offsets[ref.loop] + ref.edge) + (ref.kind == FeatureRef::Kind::vertex ? 0 : 1);
    };
    return index(curve.first, 0) * feature_count_[1] + index(curve.second, 1);
  }

  // Generates the strip of the chart pair (o, f) holding other-axis cell `cell` (under
  // build_mutex_). A chart pair's strips double in width as they are generated (1, 2, 4, ...
  // cells, centred on the cell asked for, clipped to the cells not yet generated), so a short
  // driver range pays for one 1/64 of the chart pair and a whole turn for at most about seven
  // generator runs per chart pair. Per strip, the generator's blocked-space cull works on the
  // strip's box; the follower cells each curve may vanish in are those of the whole chart's
  // cull (the same leaf tests).
  //
  // A value on the border of two cells needs both (`last` = cell + 1): when the strip laid out
  // for `cell` stops at that border and the next cell is not generated either, the strip takes
  // it too — one generator run instead of two (the second strip would be that one cell), and
  // the width doubles twice, so the strips laid out after it are those of two runs.
  void generate_strip(ChartPair& chart, std::size_t o, std::size_t f, int cell, int last) const {
    auto result = std::make_unique<Strip>();
    if (!other_moves_ || !options_.strips) {
      result->first_cell = 0;
      result->width = cull_cells;
    } else {
      int first = std::max(0, cell - chart.next_width / 2);
      int end = std::min(cull_cells, first + chart.next_width);
      for (int c = cell; c < end; ++c)
        if (chart.strip_of_cell[static_cast<std::size_t>(c)] >= 0) {
          end = c;
          break;
        }
      for (int c = cell; c > first; --c)
        if (chart.strip_of_cell[static_cast<std::size_t>(c - 1)] >= 0) {
          first = c;
          break;
        }
      chart.next_width = std::min(cull_cells, 2 * chart.next_width);
      if (last == end && last < cull_cells && chart.strip_of_cell[static_cast<std::size_t>(last)] < 0) {
        end = last + 1;
        chart.next_width = std::min(cull_cells, 2 * chart.next_width);
      }
      result->first_cell = first;
      result->width = end - first;
    }
    ChartAxis strip_axis = other_moves_ ? other_charts_[o] : chart.y_axis;
    if (other_moves_ && result->width < cull_cells) {
      const ChartAxis& other_axis = other_charts_[o];
      strip_axis.lo = other_axis.lo + (other_axis.hi - other_axis.lo) * result->first_cell / cull_cells;
      strip_axis.hi = other_axis.lo + (other_axis.hi - other_axis.lo) * (result->first_cell + result->width) / cull_cells;
    }
    const ChartAxis& x_axis = follower_is_x_ ? chart.x_axis : strip_axis;
    const ChartAxis& y_axis = follower_is_x_ ? strip_axis : chart.y_axis;
    // one generator per pair: the parts' features and disks are computed once, not per strip
    if (!generator_) generator_ = std::make_unique<cspace::CurveGenerator>(model_, axes_);
    if (lazy()) {
      // culled over no follower cell yet: extend_strip culls the cells the slice asks for
      result->culled = 0;
      chart.selections.resize(chart.strips.size());
      chart.boxes.resize(chart.strips.size(), {x_axis, y_axis});
      chart.selections.push_back(generator_->incremental_select(x_axis, y_axis));
      chart.boxes.emplace_back(x_axis, y_axis);
      push_strip(chart, std::move(result));
      return;
    }
    // a congruent pair's whole strip for the same chart pair, cells and follower
    std::string strip_key;
    if (options_.selections && !congruence_key_.empty()) {
      strip_key = congruence_key_ + (follower_is_x_ ? "|fx" : "|fy") + axis_key(other_moves_ ? other_charts_[o] : strip_axis) +
                  axis_key(follower_charts_[f]) + "|" + std::to_string(result->first_cell) + "+" + std::to_string(result->width);
      if (std::shared_ptr<const Strip> shared = options_.selections->find_strip(strip_key)) {
        for (const StripCurve& curve : shared->curves) {
          FeatureRef first = curve.first, second = curve.second;
          first.part = axes_.first;
          second.part = axes_.second;
          note_feature(curve.feature, first, second, curve.type);
          chart.by_feature.try_emplace(curve.feature, curve.data);
        }
        push_strip(chart, std::move(shared));
        return;
      }
    }
    std::vector<ContactCurve> curves;
    if (options_.selections && !congruence_key_.empty()) {
      // a congruent pair's selection for the same chart box, else this generator's own (then
      // select + generate_selected is generate)
      std::string key = congruence_key_ + axis_key(x_axis) + axis_key(y_axis);
      std::shared_ptr<const SelectionMemo::Selection> selection = options_.selections->find(key);
      if (!selection) selection = options_.selections->add(key, generator_->select(x_axis, y_axis));
      curves = generator_->generate_selected(x_axis, y_axis, *selection);
    } else {
      curves = generator_->generate(x_axis, y_axis);
    }
    add_curves(chart, *result, curves);
    cull(*result, other_moves_ ? other_charts_[o] : strip_axis, follower_charts_[f], other_moves_);
    strip_cells_culled_ += follower_cells;
    std::shared_ptr<const Strip> strip = std::move(result);
    if (!strip_key.empty()) strip = options_.selections->add_strip(strip_key, std::move(strip));
    push_strip(chart, std::move(strip));
  }

  // Culls lazily culled strip `s` of chart pair (o, f) over the follower cells of `mask` not
  // culled yet (under build_mutex_): the pairs the cull keeps there and not before are formed,
  // their follower cells marked, and merged into a new copy of the strip (a slice holds the old
  // one as long as it reads it).
  void extend_strip(ChartPair& chart, std::size_t s, std::size_t o, std::size_t f, std::uint32_t mask) const {
    const Strip& old = *chart.strips[s];
    const std::uint32_t cells = mask & ~old.culled;
    if (!cells || s >= chart.selections.size() || !chart.selections[s]) return;
    // the runs of new cells, from the lower double bound of their first edge to the upper of
    // their last: the quadtree's cells meeting a run include every cell holding a point of it
    const std::vector<Rational>& edges = follower_edges_[f];
    std::vector<std::pair<double, double>> ranges;
    for (int cell = 0, previous = -2; cell < follower_cells; ++cell) {
      if (!((cells >> cell) & 1u)) continue;
      const double upper = algebra::upper_double(edges[cell + 1]);
      if (previous == cell - 1) ranges.back().second = upper;   // the run goes on
      else ranges.emplace_back(algebra::lower_double(edges[cell]), upper);
      previous = cell;
    }
    std::vector<cspace::CurveGenerator::FeaturePair> pairs = chart.selections[s]->extend(follower_is_x_ ? 0 : 1, ranges);
    strip_cells_culled_ += static_cast<std::size_t>(std::popcount(cells));
    auto result = std::make_unique<Strip>();
    result->first_cell = old.first_cell;
    result->width = old.width;
    result->zero_curve = old.zero_curve;
    result->culled = old.culled | cells;
    if (pairs.empty()) {
      result->curves = old.curves;
    } else {
      const auto& [x_axis, y_axis] = chart.boxes[s];
      std::vector<ContactCurve> curves = generator_->generate_selected(x_axis, y_axis, pairs);
      Strip added;
      added.first_cell = old.first_cell;
      added.width = old.width;
      add_curves(chart, added, curves);
      cull(added, other_charts_[o], follower_charts_[f], other_moves_);
      result->zero_curve = result->zero_curve || added.zero_curve;
      // both ascending by feature, no feature in both (a feature pair is selected once)
      result->curves.reserve(old.curves.size() + added.curves.size());
      std::merge(old.curves.begin(), old.curves.end(), added.curves.begin(), added.curves.end(),
                 std::back_inserter(result->curves),
                 [](const StripCurve& a, const StripCurve& b) { return a.feature < b.feature; });
    }
    // culled over every follower cell: the strip is the whole strip's, its cull is done
    if (result->culled == ~std::uint32_t(0)) chart.selections[s].reset();
    chart.strips[s] = std::move(result);
  }

  // The strip curves of `curves` (the generator's, in feature order) added to `strip`, each
  // curve's data made once per chart pair; the follower cells are cull()'s.
  void add_curves(ChartPair& chart, Strip& strip, std::vector<ContactCurve>& curves) const {
    Strip* const result = &strip;
    for (ContactCurve& curve : curves) {
      if (curve.polynomial.is_zero()) {
        result->zero_curve = true;
        continue;
      }
      StripCurve entry;
      entry.feature = feature_number(curve);
      entry.first = curve.first;
      entry.second = curve.second;
      entry.type = curve.type;
      note_feature(entry.feature, curve.first, curve.second, curve.type, &curve.label);
      std::shared_ptr<const CurveData>& data = chart.by_feature[entry.feature];
      if (!data) {
        auto made = std::make_shared<CurveData>();
        made->polynomial = follower_is_x_ ? transposed(curve.polynomial) : std::move(curve.polynomial);
        made->interval = ScaledIntervalPolynomial(made->polynomial);
        made->follower_slope = ScaledIntervalPolynomial(follower_derivative(made->polynomial));
        for (const cspace::ValidityClause& clause : curve.validity) {
          OrientedClause oriented_clause;
          for (const IntegerPolynomial2& atom : clause.atoms)
            oriented_clause.atoms.emplace_back(follower_is_x_ ? transposed(atom) : atom);
          made->validity.push_back(std::move(oriented_clause));
        }
        data = std::move(made);
      }
      entry.data = data;
      result->curves.push_back(std::move(entry));
    }
    // the generator emits a chart's curves in feature order; the slices rely on it
    std::stable_sort(result->curves.begin(), result->curves.end(),
                     [](const StripCurve& a, const StripCurve& b) { return a.feature < b.feature; });
  }

  static void push_strip(ChartPair& chart, std::shared_ptr<const Strip> strip) {
    for (int c = strip->first_cell; c < strip->first_cell + strip->width; ++c)
      chart.strip_of_cell[static_cast<std::size_t>(c)] = static_cast<int>(chart.strips.size());
    chart.strips.push_back(std::move(strip));
  }

  // Names feature number `feature` (features_) on first meeting it: `label` when the curve
  // generator gave one, else written from the feature pair (the generator's own spelling).
  void note_feature(std::size_t feature, const FeatureRef& first, const FeatureRef& second, cspace::ContactType type,
                    const std::string* label = nullptr) const {
    if (features_.size() <= feature) features_.resize(feature + 1);
    if (!features_[feature].label.empty()) return;
    features_[feature] = ContactFeature{label ? *label : cspace::curve_label(model_, first, second, type), public_kind(type),
                                        FeatureIdentity{first.part, first.loop, first.edge, first.kind},
                                        FeatureIdentity{second.part, second.loop, second.edge, second.kind}};
  }

  // The chart pair (o, f) with its strips holding cells [cell_lo, cell_hi] generated and culled
  // over the follower cells of `mask` at least; `held`: those two strips (they stay alive while
  // the slice reads them).
  const ChartPair& chart_pair(std::size_t o, std::size_t f, std::size_t cell_lo, std::size_t cell_hi, std::uint32_t mask,
                              std::shared_ptr<const Strip> (&held)[2]) const {
    std::lock_guard<std::mutex> lock(build_mutex_);
    std::unique_ptr<ChartPair>& slot = pairs_.at(o * follower_charts_.size() + f);
    if (!slot) {
      auto chart = std::make_unique<ChartPair>();
      ChartAxis dummy{ChartAxis::Kind::translation, false, Rational(0), Rational(0)};
      const ChartAxis& other_axis = other_moves_ ? other_charts_[o] : dummy;
      chart->x_axis = follower_is_x_ ? follower_charts_[f] : other_axis;
      chart->y_axis = follower_is_x_ ? other_axis : follower_charts_[f];
      slot = std::move(chart);
    }
    for (std::size_t c = cell_lo; c <= cell_hi; ++c)
      if (slot->strip_of_cell[c] < 0) generate_strip(*slot, o, f, static_cast<int>(c), static_cast<int>(cell_hi));
    for (std::size_t c : {cell_lo, cell_hi}) extend_strip(*slot, static_cast<std::size_t>(slot->strip_of_cell[c]), o, f, mask);
    held[0] = slot->strips[static_cast<std::size_t>(slot->strip_of_cell[cell_lo])];
    held[1] = slot->strips[static_cast<std::size_t>(slot->strip_of_cell[cell_hi])];
    return *slot;
  }

  // The other-axis cells holding `value` of other chart o (two on a cell border; 0 when the
  // other part is fixed).
  std::pair<std::size_t, std::size_t> cells_holding(std::size_t o, const Rational& value) const {
    std::size_t cell_lo = 0, cell_hi = 0;
    if (other_moves_) {
      const ChartAxis& other_axis = other_charts_[o];
      Rational position = (value - other_axis.lo) * cull_cells / (other_axis.hi - other_axis.lo);
      long cell = std::clamp<long>(static_cast<long>(position.get_d()), 0, cull_cells - 1);
      cell_lo = cell_hi = static_cast<std::size_t>(cell);
      // a value on a cell border belongs to both cells
      if (cell + 1 < cull_cells && position >= cell + 1) cell_hi = static_cast<std::size_t>(cell + 1);
      if (cell > 0 && position <= cell) cell_lo = static_cast<std::size_t>(cell - 1);
    }
    return {cell_lo, cell_hi};
  }

  ChartSlice slice(std::size_t other_chart, const Rational& value, std::size_t follower_chart,
                   const ChartWindow* window) const override {
    if (window && follower_chart < follower_charts_.size() && window->lo <= follower_charts_[follower_chart].lo &&
        window->hi >= follower_charts_[follower_chart].hi)
      window = nullptr;
    if (!other_moves_ && !window) {
      std::lock_guard<std::mutex> lock(cache_mutex_);
      auto found = fixed_cache_.find(follower_chart);
      if (found != fixed_cache_.end()) return found->second;
    }
    std::size_t o = other_moves_ ? other_chart : 0;
    if (o >= std::max<std::size_t>(1, other_charts_.size()) || follower_chart >= follower_charts_.size())
      throw GeometryError("slice outside the charts of pair " + name_);
    auto [cell_lo, cell_hi] = cells_holding(o, value);   // other-axis cells holding the value
    const ChartAxis& axis = follower_charts_[follower_chart];
    Rational range_lo = window ? std::max(window->lo, axis.lo) : axis.lo;
    Rational range_hi = window ? std::min(window->hi, axis.hi) : axis.hi;
    if (range_hi < range_lo) range_hi = range_lo;
    const std::vector<Rational>& edges = follower_edges_[follower_chart];
    // the follower cells the range meets (binary searches over the ascending edges)
    const std::uint32_t window_mask = window ? slice_cells::cells_meeting(edges, range_lo, range_hi) : ~std::uint32_t(0);
    std::shared_ptr<const Strip> held[2];
    const ChartPair& chart = chart_pair(o, follower_chart, cell_lo, cell_hi, window_mask, held);
    // the curves of the strips holding the value, ascending by feature, with the follower cells
    // where each may vanish at the value
    std::vector<std::pair<const StripCurve*, std::uint32_t>> candidates;
    const bool two_strips = held[0] != held[1];
    for (const auto& held_strip : held) {
      const Strip& strip = *held_strip;
      const auto first = static_cast<std::size_t>(strip.first_cell), end = first + static_cast<std::size_t>(strip.width);
      for (const StripCurve& curve : strip.curves) {
        std::uint32_t mask = 0;
        for (std::size_t c = std::max(cell_lo, first); c <= std::min(cell_hi, end - 1); ++c) mask |= curve.cells[c - first];
        candidates.emplace_back(&curve, mask);
      }
      if (!two_strips) break;
    }
    if (two_strips) {
      // a value on a strip border: one candidate per feature, its cells those of both strips
      std::stable_sort(candidates.begin(), candidates.end(),
                       [](const auto& a, const auto& b) { return a.first->feature < b.first->feature; });
      std::vector<std::pair<const StripCurve*, std::uint32_t>> merged;
      for (const auto& candidate : candidates) {
        if (!merged.empty() && merged.back().first->feature == candidate.first->feature)
          merged.back().second |= candidate.second;
        else
          merged.push_back(candidate);
      }
      candidates = std::move(merged);
    }
    algebra::Interval value_box = algebra::enclose(value);
    std::vector<SlicePoint> points;
    for (const auto& [strip_curve, cells] : candidates) {
      const CurveData& curve = *strip_curve->data;
      const std::uint32_t mask = cells & window_mask;
      if (!mask) continue;
      algebra::Polynomial p;
      std::optional<algebra::Polynomial> square_free;   // of p, for monotone runs' roots
      bool substituted = false;
      // maximal runs of follower cells where the curve may vanish
      for (int first = 0; first < follower_cells;) {
        if (!(mask & (std::uint32_t(1) << first))) {
          ++first;
          continue;
        }
        int last = first;
        while (last + 1 < follower_cells && (mask & (std::uint32_t(1) << (last + 1)))) ++last;
        // [lo, hi] = [max(range_lo, edges[first]), min(range_hi, edges[last + 1])], read in place
        // (exact order, one-limb values in machine integers: compare_rationals)
        const Rational& lo = algebra::compare_rationals(range_lo, edges[first]) < 0 ? edges[first] : range_lo;
        const Rational& hi = algebra::compare_rationals(edges[last + 1], range_hi) < 0 ? edges[last + 1] : range_hi;
        first = last + 1;
        const int hi_vs_lo = algebra::compare_rationals(hi, lo);
        if (hi_vs_lo < 0) continue;
        const algebra::Interval run_box{algebra::lower_double(lo), algebra::upper_double(hi)};
        if (!curve.interval.evaluate(value_box, run_box).contains_zero()) continue;
        // The validity clauses over the whole run, before any root is sought: every root found
        // in [lo, hi] (its isolating interval, or an exact root's double enclosure, lies in
        // run_box) gets the same verdict from valid() when this one is decided (interval
        // evaluation is inclusion isotone): 0 drops them all, 1 keeps them all.
        int run_verdict = -1;
        if (options_.validity_prefilter && !curve.validity.empty()) {
          run_verdict = clauses_verdict(curve, value_box, run_box);
          if (run_verdict == 1) ++runs_kept_;
          if (run_verdict == 0) {
            ++runs_rejected_;
            continue;
          }
        }
        auto substitute = [&]() {
          if (substituted) return;
          p = algebra::substitute_x(curve.polynomial, value);
          algebra::trim(p);
          substituted = true;
        };
        if (options_.monotone_runs && hi_vs_lo > 0 &&
            !curve.follower_slope.evaluate(value_box, algebra::Interval{algebra::lower_double(lo), algebra::upper_double(hi)})
                 .contains_zero()) {
          // P(value, y) is strictly monotone on [lo, hi] (its y-derivative's enclosure over the
          // box excludes zero): one simple root there exactly when the signs at the ends differ,
          // isolated by (lo, hi) itself. The ends' signs from certified enclosures, exactly when
          // an enclosure holds zero (substitute_x scales by a positive factor: the same signs).
          auto end_sign = [&](const Rational& y) {
            algebra::Interval at = curve.interval.evaluate(value_box, algebra::enclose(y));
            if (at.lo > 0) return 1;
            if (at.hi < 0) return -1;
            substitute();
            return algebra::sign_at(p, y);
          };
          const int sign_lo = end_sign(lo), sign_hi = end_sign(hi);
          if (sign_lo == sign_hi) continue;   // both non-zero: monotone, no root
          Real root;
          // the validity prefilter's verdict where the root is isolated without its polynomial
          // (-1: undecided, or not asked when !prefiltered; valid() decides)
          int verdict = -1;
          bool prefiltered = false;
          if (sign_lo == 0 || sign_hi == 0) {
            root = Real::from_rational(sign_lo == 0 ? lo : hi);
          } else {
            // The root's interval narrowed first (narrow_in_doubles reads the curve's enclosure,
            // not the polynomial), and the validity clauses asked there before the square-free
            // test: a root they certainly reject needs no polynomial. The verdict on this
            // interval is valid()'s own (its prefilter reads the same interval), and it holds
            // for the rational root of a linear square-free part too, whose double enclosure
            // lies inside the interval (interval evaluation is inclusion isotone).
            root.lower = lo;
            root.upper = hi;
            narrow_in_doubles(curve, value_box, root, sign_lo);
            prefiltered = options_.validity_prefilter && !curve.validity.empty();
            if (run_verdict == 1)
              verdict = 1;
            else if (prefiltered)
              verdict = clauses_verdict(curve, value_box, algebra::Interval{root.lower_bound(), root.upper_bound()});
            if (verdict == 0) {
              ++monotone_roots_;
              continue;
            }
            substitute();
            // (remembered: the same curve and value come back for other follower charts,
            // windows and congruent pairs)
            if (!square_free) square_free = algebra::remembered_square_free_test(p);
            if (algebra::degree(*square_free) == 1) {
              // a linear factor's root is rational: exact, as Descartes' isolation gives it (the
              // zero-clearance test and the slices' consumers read `exact`)
              Rational r((*square_free)[0], (*square_free)[1]);
              r.canonicalize();
              root = Real::from_rational(Rational(-r));
            } else {
              root.polynomial = *square_free;
            }
          }
          ++monotone_roots_;
          // verdict 1: valid() would say so (its prefilter, or its refinements of an exact
          // root, read boxes inside this one); undecided: straight to its refinements
          if (verdict == 1 || run_verdict == 1 || valid(curve, value_box, root, options_.validity_prefilter && !prefiltered))
            points.push_back(SlicePoint{std::move(root), {strip_curve->feature}});
          continue;
        }
        substitute();
        if (algebra::degree(p) <= 0) break;   // no root, or the whole line (a degenerate slice)
        // real_roots takes the square-free part itself
        for (Real& root : algebra::descartes_real_roots(p, lo, hi)) {
          if (run_verdict != 1 && !valid(curve, value_box, root, options_.validity_prefilter)) continue;
          points.push_back(SlicePoint{std::move(root), {strip_curve->feature}});
        }
      }
    }
    // stable: the features of a point shared by several curves are listed ascending
    std::stable_sort(points.begin(), points.end(),
                     [](const SlicePoint& a, const SlicePoint& b) { return algebra::compare(a.value, b.value) < 0; });
    ChartSlice result;
    for (SlicePoint& point : points) {
      if (!result.points.empty() && algebra::compare(result.points.back().value, point.value) == 0) {
        auto& features = result.points.back().features;
        if (std::find(features.begin(), features.end(), point.features[0]) == features.end())
          features.push_back(point.features[0]);
        continue;
      }
      result.points.push_back(std::move(point));
    }
    // classes of the intervals between the points, within the chart box
    result.covered_lo = range_lo;
    result.covered_hi = range_hi;
    Real low = Real::from_rational(range_lo), high = Real::from_rational(range_hi);
    const std::size_t memo_index = o * follower_charts_.size() + follower_chart;
    std::optional<Transfer> transfer;
    if (options_.transfer_classes) transfer = transfer_from_previous(memo_index, o, value);
    for (std::size_t i = 0; i <= result.points.size(); ++i) {
      const Real& a = i == 0 ? low : result.points[i - 1].value;
      const Real& b = i == result.points.size() ? high : result.points[i].value;
      // consecutive points are distinct and ascending (sorted, equal ones merged above): only
      // the chart box's ends can meet a point
      if ((i == 0 || i == result.points.size()) && algebra::compare(a, b) >= 0) {
        result.kinds.push_back(SliceKind::empty);
        continue;
      }
      if (transfer) {
        std::optional<Rational> quick = separated_sample(a, b);
        SliceKind carried = SliceKind::empty;
        if (carried_kind(*transfer, follower_chart, quick ? *quick : sample_between(a, b, options_.shared_end_samples),
                         carried)) {
          ++transferred_;
          result.kinds.push_back(carried);
          continue;
        }
      }
      ++classified_;
      // the oracle's sample as without a transfer
      Rational sample = sample_between(a, b, options_.shared_end_samples);
      cspace::ChartPoint q;
      if (follower_is_x_) {
        q.x = sample;
        q.y = other_moves_ ? value : Rational(0);
      } else {
        q.x = value;
        q.y = sample;
      }
      cspace::Overlap relation = overlap_->classify(chart.x_axis, chart.y_axis, q);
      result.kinds.push_back(relation == cspace::Overlap::apart       ? SliceKind::free
                             : relation == cspace::Overlap::overlapping ? SliceKind::blocked
                                                                        : SliceKind::touching);
    }
    // zero-clearance fits: a point with blocked space on both sides may be a touching
    // configuration (a channel of zero width) or a curve through blocked space. When the root is
    // rational (decided completely: algebra::rational_root) it is held exactly and the oracle
    // decides at it; but first, a root (not exact, not linear) of one contact whose polynomial
    // changes sign there (odd multiplicity) is no touching configuration, rational or not (and
    // stays as it is): were the parts only touching, that contact would be their only one (every feature pair touching at the point has a valid
    // curve through it; culled curves vanish only in certainly blocked space), and moving to the
    // side where it opens would separate them, a free side. Any other irrational point (two or
    // more contacts, or a root of even multiplicity) is decided by the exact oracle at the
    // algebraic point (curves/algebraic_overlap.hpp, session 33; parts with arcs too since
    // session 34); where that cannot decide it stays blocked but undecided: counted
    // (SliceClassCounts::touching_undecided), and the analysis says so.
    for (std::size_t i = 0; i < result.points.size(); ++i) {
      if (result.kinds[i] != SliceKind::blocked || result.kinds[i + 1] != SliceKind::blocked) continue;
      SlicePoint& point = result.points[i];
      // the one-contact sign change first (most such points: curves through blocked space), but
      // an exact or linear root goes to the oracle as before
      if (!point.value.exact && algebra::degree(point.value.polynomial) >= 2 && point.features.size() == 1 &&
          changes_sign(candidates, point.features[0], value, point.value))
        continue;
      std::optional<Rational> exact = algebra::rational_root(point.value);
      if (exact) {
        if (!point.value.exact) point.value = Real::from_rational(*exact);
        cspace::ChartPoint q;
        if (follower_is_x_) {
          q.x = *exact;
          q.y = other_moves_ ? value : Rational(0);
        } else {
          q.x = value;
          q.y = *exact;
        }
        point.touching = overlap_->classify(chart.x_axis, chart.y_axis, q) == cspace::Overlap::touching;
        continue;
      }
      // irrational: the exact oracle at the algebraic point (segments and arcs)
      const Real at = follower_is_x_ ? point.value : Real::from_rational(value);
      const Real other = follower_is_x_ ? Real::from_rational(other_moves_ ? value : Rational(0)) : point.value;
      if (std::optional<cspace::Overlap> relation = cspace::algebraic_overlap(model_, axes_, chart.x_axis, chart.y_axis, at, other)) {
        point.touching = *relation == cspace::Overlap::touching;
        continue;
      }
      ++touching_undecided_;
      point.undecided = true;
    }
    if (!other_moves_ && !window) {
      std::lock_guard<std::mutex> lock(cache_mutex_);
      fixed_cache_[follower_chart] = result;
    }
    if (options_.transfer_classes) {
      auto stored = std::make_shared<const PreviousSlice>(PreviousSlice{value, result});
      std::lock_guard<std::mutex> lock(memo_mutex_);
      previous_[memo_index] = std::move(stored);
    }
    return result;
  }

  SliceClassCounts class_counts() const {
    return SliceClassCounts{classified_.load(), transferred_.load(), monotone_roots_.load(), touching_undecided_.load(),
                            strip_cells_culled_.load(), runs_rejected_.load(), runs_kept_.load()};
  }

  // unsigned wrap-around: a negative delta subtracts
  void add_touching_undecided(long delta) const { touching_undecided_ += static_cast<std::size_t>(delta); }

  const IntegerPolynomial2* polynomial(std::size_t other_chart, std::size_t follower_chart,
                                       std::size_t feature) const override {
    std::size_t o = other_moves_ ? other_chart : 0;
    if (o >= std::max<std::size_t>(1, other_charts_.size()) || follower_chart >= follower_charts_.size()) return nullptr;
    // the curves of a chart pair are shared by its strips: any generated strip's copy (a contact
    // the engine asks about was met in a slice, whose strips are generated)
    std::lock_guard<std::mutex> lock(build_mutex_);
    const std::unique_ptr<ChartPair>& chart = pairs_.at(o * follower_charts_.size() + follower_chart);
    if (!chart) return nullptr;
    auto found = chart->by_feature.find(feature);
    return found == chart->by_feature.end() ? nullptr : &found->second->polynomial;
  }

 private:
  // The last slice of a chart pair: the source of the classes carried over to the next one.
  struct PreviousSlice {
    Rational value;
    ChartSlice slice;
  };

  // What carries classes from the previous slice (at u0) to a slice at u1: that slice, the
  // driver interval's certified enclosure, and every curve of the strips covering it that may
  // vanish there, with the follower cells where it may (OR over the interval's cells).
  struct Transfer {
    std::shared_ptr<const PreviousSlice> previous;
    algebra::Interval drivers{0, 0};
    std::vector<std::pair<const CurveData*, std::uint32_t>> curves;
    /// Per curve (same index), its enclosure collapsed over the driver interval to a polynomial
    /// in the follower coordinate (ScaledIntervalPolynomial::at_x(drivers)), made on first use:
    /// each sample's proof then costs one univariate interval Horner per curve.
    std::vector<std::vector<algebra::Interval>> at_drivers;
    /// The follower cells culled in every strip of `curves` (KernelSlicerOptions::lazy_cull):
    /// a sample in another cell may meet a contact on a curve no strip holds.
    std::uint32_t culled = ~std::uint32_t(0);
  };

  // The transfer from the previous slice of chart pair (o, f) (memo index) to `value`, or
  // nothing when there is none, or when the driver interval leaves the generated strips or
  // spans more than a few cull cells (the proof would be weak: the oracle is cheaper).
  std::optional<Transfer> transfer_from_previous(std::size_t memo_index, std::size_t o, const Rational& value) const {
    Transfer transfer;
    {
      std::lock_guard<std::mutex> lock(memo_mutex_);
      transfer.previous = previous_[memo_index];
    }
    if (!transfer.previous) return std::nullopt;
    const Rational& u0 = transfer.previous->value;
    const Rational& u_min = u0 < value ? u0 : value;
    const Rational& u_max = u0 < value ? value : u0;
    std::size_t cell_lo = cells_holding(o, u_min).first, cell_hi = cells_holding(o, u_max).second;
    if (cell_hi > cell_lo + 3) return std::nullopt;
    if (other_moves_) transfer.drivers = algebra::Interval{algebra::lower_double(u_min), algebra::upper_double(u_max)};
    std::lock_guard<std::mutex> lock(build_mutex_);
    const std::unique_ptr<ChartPair>& chart = pairs_.at(memo_index);
    if (!chart) return std::nullopt;
    std::vector<int> strips;
    for (std::size_t c = cell_lo; c <= cell_hi; ++c) {
      int strip = chart->strip_of_cell[c];
      if (strip < 0) return std::nullopt;   // a curve of an ungenerated strip could cross
      if (std::find(strips.begin(), strips.end(), strip) == strips.end()) strips.push_back(strip);
    }
    for (int s : strips) {
      const Strip& strip = *chart->strips[static_cast<std::size_t>(s)];
      if (strip.zero_curve) return std::nullopt;
      transfer.culled &= strip.culled;
      const auto first = static_cast<std::size_t>(strip.first_cell), end = first + static_cast<std::size_t>(strip.width);
      for (const StripCurve& curve : strip.curves) {
        std::uint32_t mask = 0;
        for (std::size_t c = std::max(cell_lo, first); c <= std::min(cell_hi, end - 1); ++c) mask |= curve.cells[c - first];
        if (mask) transfer.curves.emplace_back(curve.data.get(), mask);
      }
    }
    if (strips.size() > 1) {
      // a curve in several strips: once, with the union of its cells
      std::sort(transfer.curves.begin(), transfer.curves.end());
      std::vector<std::pair<const CurveData*, std::uint32_t>> merged;
      for (const auto& entry : transfer.curves) {
        if (!merged.empty() && merged.back().first == entry.first) merged.back().second |= entry.second;
        else merged.push_back(entry);
      }
      transfer.curves = std::move(merged);
    }
    return transfer;
  }

  // True, with `kind`, when the class at (u1, s) is proven to be the previous slice's class at
  // (u0, s): s lies strictly between two consecutive points of the previous slice, inside its
  // covered range (exact comparisons), and no curve that may vanish in s's follower cells has
  // a zero on the segment [u0, u1] x {s} (interval enclosure). Every contact configuration lies
  // on a curve of the strips (the cull drops curves only inside certified blocked space), so
  // the segment holds none: free and blocked are then open in it and its class is constant.
  bool carried_kind(Transfer& transfer, std::size_t follower_chart, const Rational& s, SliceKind& kind) const {
    const ChartSlice& old = transfer.previous->slice;
    if (!(old.covered_lo < s && s < old.covered_hi)) return false;
    const std::optional<std::size_t> above = slice_cells::first_point_not_below(old.points, s);   // the first point above s
    if (!above) return false;   // s is a point of the previous slice
    const std::size_t lo = *above;
    if (old.kinds[lo] == SliceKind::empty) return false;
    // the follower cells holding s (two on a cell border: the cull's boxes are closed)
    const std::uint32_t bits = slice_cells::cells_holding(follower_edges_[follower_chart], s);
    if (bits & ~transfer.culled) return false;
    algebra::Interval at = algebra::enclose(s);
    if (transfer.at_drivers.size() != transfer.curves.size()) transfer.at_drivers.assign(transfer.curves.size(), {});
    std::size_t evaluations = 0;
    for (std::size_t c = 0; c < transfer.curves.size(); ++c) {
      const auto& [curve, cells] = transfer.curves[c];
      if (!(cells & bits)) continue;
      // past proof_curves_ enclosures the proof costs about what the oracle does: the oracle
      // decides
      if (++evaluations > proof_curves_) return false;
      // the curve's enclosure over the driver interval as a polynomial in the follower
      // coordinate, evaluated at s: an enclosure of the curve on the segment (Horner in the
      // driver first, inclusion isotone; a zero-free enclosure proves no zero there)
      std::vector<algebra::Interval>& collapsed = transfer.at_drivers[c];
      if (collapsed.empty()) collapsed = curve->interval.at_x(transfer.drivers);
      if (ScaledIntervalPolynomial::evaluate_y(collapsed, at).contains_zero()) return false;
    }
    kind = old.kinds[lo];
    return true;
  }

  // Narrows the isolating interval (lower, upper) of a root of `curve` at the driver value (in
  // value_box) by halvings at double points whose sign the curve's certified enclosure decides
  // (the sign at lower is `lower_sign`): at most 24, stopping at the first undecided point. The
  // polynomial's square-free part has the curve's sign pattern on the run (the rest of the
  // polynomial has no root there), so the ends keep non-zero opposite signs.
  static void narrow_in_doubles(const CurveData& curve, const algebra::Interval& value_box, Real& root, int lower_sign) {
    double lo = algebra::upper_double(root.lower), hi = algebra::lower_double(root.upper);
    if (!(lo < hi)) return;
    // the curve's enclosure at the driver value, once: each halving evaluates a polynomial in y
    const std::vector<algebra::Interval> at_value = curve.interval.at_x(value_box);
    bool moved_lo = false, moved_hi = false;
    for (int step = 0; step < 24; ++step) {
      const double middle = lo + (hi - lo) / 2;
      if (!(middle > lo && middle < hi)) break;
      const algebra::Interval at = ScaledIntervalPolynomial::evaluate_y(at_value, algebra::Interval{middle, middle});
      const int sign = at.lo > 0 ? 1 : at.hi < 0 ? -1 : 0;
      if (sign == 0) break;
      if (sign == lower_sign) {
        lo = middle;
        moved_lo = true;
      } else {
        hi = middle;
        moved_hi = true;
      }
    }
    if (moved_lo) root.lower = Rational(lo);
    if (moved_hi) root.upper = Rational(hi);
  }

  // A rational strictly between a < b read off their isolating intervals when they are
  // separated, else off certified double enclosures (no exact refinement), else nothing.
  // Separated intervals give the middle of the gap between them when a double lies strictly
  // inside it: a sample far from both points, so that the carried class's proof (no curve
  // vanishes at the sample) holds for narrow isolating intervals too; else a gap end.
  static std::optional<Rational> separated_sample(const Real& a, const Real& b) {
    std::optional<Rational> end;
    if (!a.exact && (b.exact ? a.upper < b.lower : a.upper <= b.lower)) end = a.upper;
    else if (!b.exact && a.exact && a.lower < b.lower) end = b.lower;
    else return algebra::double_between(a, b);
    // a < a_end < s < b_end <= b (a_end: a's upper end, or a itself when exact)
    const Rational& a_end = a.exact ? a.lower : a.upper;
    const double middle = 0.5 * a_end.get_d() + 0.5 * b.lower.get_d();
    if (std::isfinite(middle)) {
      Rational s(middle);
      if (a_end < s && s < b.lower) return s;
    }
    return end;
  }

  // A chart axis exactly, for the selection keys.
  static std::string axis_key(const ChartAxis& axis) {
    return "|axis:" + std::to_string(static_cast<int>(axis.kind)) + (axis.half_turn ? "h" : "-") + axis.lo.get_str() +
           "," + axis.hi.get_str();
  }

  // Marks, for every cell of the other axis in the strip, the follower cells where each curve
  // may vanish. Boxes of cells are tested coarse to fine: a box whose interval value excludes
  // zero excludes it in every sub-box (interval evaluation is inclusion isotone), so a cell is
  // marked exactly when its own box test contains zero, whatever the strip's width.
  static void cull(Strip& strip, const ChartAxis& other_axis, const ChartAxis& follower_axis, bool other_moves) {
    const int width = strip.width;
    // certified double bounds of the cell edges: a box from the lower bound of its first edge to
    // the upper bound of its last encloses its cells
    std::vector<double> follower_lows(follower_cells + 1), follower_highs(follower_cells + 1);
    std::vector<double> other_lows(cull_cells + 1, 0.0), other_highs(cull_cells + 1, 0.0);
    for (int cell = 0; cell <= follower_cells; ++cell) {
      Rational at = follower_axis.lo + (follower_axis.hi - follower_axis.lo) * cell / follower_cells;
      follower_lows[cell] = algebra::lower_double(at);
      follower_highs[cell] = algebra::upper_double(at);
    }
    const int first = strip.first_cell;
    if (other_moves)
      for (int cell = first; cell <= first + width; ++cell) {
        Rational at = other_axis.lo + (other_axis.hi - other_axis.lo) * cell / cull_cells;
        other_lows[cell] = algebra::lower_double(at);
        other_highs[cell] = algebra::upper_double(at);
      }
    int other_end = other_moves ? first + width : first + 1;
    for (StripCurve& curve : strip.curves) {
      curve.cells.assign(static_cast<std::size_t>(width), 0);
      // (other cells [o0, o1), follower cells [f0, f1))
      struct Box { int o0, o1, f0, f1; };
      std::vector<Box> stack{{first, other_end, 0, follower_cells}};
      while (!stack.empty()) {
        Box box = stack.back();
        stack.pop_back();
        algebra::Interval x{0, 0};
        if (other_moves) x = algebra::Interval{other_lows[box.o0], other_highs[box.o1]};
        algebra::Interval y{follower_lows[box.f0], follower_highs[box.f1]};
        if (!curve.data->interval.evaluate(x, y).contains_zero()) continue;
        if (box.o1 - box.o0 == 1 && box.f1 - box.f0 == 1) {
          curve.cells[box.o0 - first] |= std::uint32_t(1) << box.f0;
          continue;
        }
        if (box.o1 - box.o0 >= box.f1 - box.f0) {
          int middle = (box.o0 + box.o1) / 2;
          stack.push_back({box.o0, middle, box.f0, box.f1});
          stack.push_back({middle, box.o1, box.f0, box.f1});
        } else {
          int middle = (box.f0 + box.f1) / 2;
          stack.push_back({box.o0, box.o1, box.f0, middle});
          stack.push_back({box.o0, box.o1, middle, box.f1});
        }
      }
      if (!other_moves)
        for (int cell = 1; cell < width; ++cell) curve.cells[cell] = curve.cells[0];
    }
  }

  // Does the contact polynomial of `feature` (one of `candidates`) at the other part's `value`
  // change sign at the irrational `root`, a root of odd multiplicity? Decided when the root is
  // isolated among the roots of that polynomial: its polynomial is the square-free part of it
  // (the point's only feature gave it), which is non-zero at the interval's ends; false else.
  static bool changes_sign(const std::vector<std::pair<const StripCurve*, std::uint32_t>>& candidates,
                           std::size_t feature, const Rational& value, const Real& root) {
    for (const auto& candidate : candidates) {
      if (candidate.first->feature != feature) continue;
      algebra::Polynomial p = algebra::substitute_x(candidate.first->data->polynomial, value);
      algebra::trim(p);
      if (algebra::degree(p) < 1) return false;
      // square_free_test's answer is primitive with a positive leading coefficient, so it equals
      // primitive_part(root.polynomial) when it equals root.polynomial itself (the usual case:
      // the root was isolated from it); only otherwise is root.polynomial's content computed
      const algebra::Polynomial square_free = algebra::remembered_square_free_test(p);
      if (square_free != root.polynomial && square_free != algebra::primitive_part(root.polynomial)) return false;
      return algebra::sign_at(p, root.lower) * algebra::sign_at(p, root.upper) < 0;
    }
    return false;
  }

  // False when the contact point of `curve` at (value, root) certainly lies outside one of its
  // features (a root of the supporting polynomial that is no contact of these features).
  static bool valid(const CurveData& curve, const algebra::Interval& value_box, const Real& root, bool prefilter) {
    if (curve.validity.empty()) return true;
    // First at the root's own isolating interval: the refined intervals below lie inside it, and
    // outward-rounded interval evaluation is inclusion isotone, so a clause decided here (some
    // atom certainly >= 0, or every atom certainly < 0) is decided the same way at 2^-24 and
    // 2^-48; the verdict is then the one the refinements would give, without refining.
    if (prefilter && !root.exact) {
      int verdict = clauses_verdict(curve, value_box, algebra::Interval{root.lower_bound(), root.upper_bound()});
      if (verdict >= 0) return verdict == 1;
    }
    Real refined = root;
    for (int bits : {24, 48}) {
      refined.refine_to(Rational(1, mpz_class(1) << bits));
      int verdict = clauses_verdict(curve, value_box, algebra::Interval{refined.lower_bound(), refined.upper_bound()});
      if (verdict >= 0) return verdict == 1;   // 0: every atom of a clause certainly negative
    }
    return true;   // undecided at the finest precision: keep it (classification decides)
  }

  // A rational strictly between a < b, where the interval's class is read. The class is the same
  // anywhere strictly between two consecutive points (no kept curve vanishes there: the premise
  // of every slice), so the sample is free to choose: when the isolating intervals of two
  // irrational neighbours meet end to end (roots isolated on one bisection grid), their shared
  // end c satisfies a < c < b, and no refinement is needed; else rational_between.
  static Rational sample_between(const Real& a, const Real& b, bool shared_ends) {
    if (shared_ends && !a.exact && !b.exact && a.upper == b.lower) return a.upper;
    return algebra::rational_between(a, b);
  }

  // The verdict of the validity clauses on a box of the follower coordinate: 1 every clause
  // holds (an atom certainly >= 0), 0 some clause certainly fails (every atom certainly < 0),
  // -1 undecided.
  static int clauses_verdict(const CurveData& curve, const algebra::Interval& value_box,
                             const algebra::Interval& root_box) {
    bool undecided = false;
    for (const OrientedClause& clause : curve.validity) {
      bool holds = false, unknown = false;
      for (const auto& atom : clause.atoms) {
        algebra::Interval sign = atom.evaluate(value_box, root_box);
        if (sign.lo >= 0) holds = true;
        else if (!(sign.hi < 0)) unknown = true;   // (a NaN enclosure decides nothing)
      }
      if (holds) continue;
      if (!unknown) return 0;
      undecided = true;
    }
    return undecided ? -1 : 1;
  }

  const Model& model_;
  KernelSlicerOptions options_;
  cspace::PairAxes axes_;
  bool follower_is_x_ = true;
  bool lazy_ = false;   // KernelSlicerOptions::lazy_cull for a pair whose other part moves (see lazy())
  mutable std::vector<std::unique_ptr<ChartPair>> pairs_;
  mutable std::unique_ptr<cspace::CurveGenerator> generator_;   // created with the first chart pair
  mutable std::string congruence_key_;   // the generator's, with options_.selections
  std::unique_ptr<cspace::PairOverlap> overlap_;   // the exact oracle, both parts prepared once
  std::vector<std::size_t> edge_offsets_[2];   // per part of the pair: first edge of each loop
  std::size_t feature_count_[2] = {0, 0};      // per part: 2 x its edges (a vertex and a curve each)
  std::size_t proof_curves_ = min_proof_curves;   // most curve enclosures a carried class's proof evaluates
  mutable std::mutex build_mutex_;
  mutable std::mutex cache_mutex_;
  mutable std::map<std::size_t, ChartSlice> fixed_cache_;
  mutable std::mutex memo_mutex_;
  mutable std::vector<std::shared_ptr<const PreviousSlice>> previous_;   // per chart pair (o, f)
  mutable std::atomic<std::size_t> classified_{0}, transferred_{0};
  mutable std::atomic<std::size_t> monotone_roots_{0};   // roots isolated by a monotone run
  mutable std::atomic<std::size_t> touching_undecided_{0};   // SliceClassCounts::touching_undecided
  mutable std::atomic<std::size_t> strip_cells_culled_{0};   // SliceClassCounts::strip_cells_culled
  mutable std::atomic<std::size_t> runs_rejected_{0}, runs_kept_{0};   // SliceClassCounts::runs_*
  std::vector<std::vector<Rational>> follower_edges_;   // per follower chart: its cells' edges
};

}  // namespace

std::shared_ptr<const SelectionMemo::Selection> SelectionMemo::find(const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = selections_.find(key);
  if (found == selections_.end()) return nullptr;
  ++hits_;
  return found->second;
}

std::shared_ptr<const SelectionMemo::Selection> SelectionMemo::add(const std::string& key, Selection selection) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto [it, inserted] = selections_.try_emplace(key, nullptr);
  if (inserted) it->second = std::make_shared<const Selection>(std::move(selection));
  return it->second;
}

std::size_t SelectionMemo::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

std::shared_ptr<const KernelStrip> SelectionMemo::find_strip(const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = strips_.find(key);
  if (found == strips_.end()) return nullptr;
  ++strip_hits_;
  return found->second;
}

std::shared_ptr<const KernelStrip> SelectionMemo::add_strip(const std::string& key, std::shared_ptr<const KernelStrip> strip) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto [it, inserted] = strips_.try_emplace(key, std::move(strip));
  return it->second;
}

std::size_t SelectionMemo::strip_hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return strip_hits_;
}

void SelectionMemo::count_congruence(const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++congruence_counts_[key];
}

std::size_t SelectionMemo::congruent(const std::string& key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = congruence_counts_.find(key);
  return found == congruence_counts_.end() ? 0 : found->second;
}

SliceClassCounts kernel_slice_class_counts(const PairSlicer& slicer) {
  const auto* kernel = dynamic_cast<const KernelSlicer*>(&slicer);
  return kernel ? kernel->class_counts() : SliceClassCounts{};
}

void add_touching_undecided(const PairSlicer& slicer, long delta) {
  if (const auto* kernel = dynamic_cast<const KernelSlicer*>(&slicer)) kernel->add_touching_undecided(delta);
}

std::unique_ptr<PairSlicer> make_kernel_slicer(const Model& model, std::size_t pair, std::size_t follower,
                                               const KernelSlicerOptions& options) {
  return std::make_unique<KernelSlicer>(model, pair, follower, options);
}

}  // namespace hipair::kinematics_detail
