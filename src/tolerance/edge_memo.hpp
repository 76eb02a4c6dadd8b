// The Taylor-model geometry of the certified band's sub-boxes, edge by edge (session 41,
// docs/performance.md "Session 41 (tol41)"). certified_range splits a contact curve's box along
// one parameter at a time, and each sub-box that needs the Taylor-model partials evaluates both
// edges of the feature pair as Taylor-model jets over it (CurveSolver::taylor_geometry; a spur
// gear's flank with its square roots and trigonometry, ~2 M instructions an edge on the
// 100-parameter gear train). An edge reads only the parameters of its own formulas (a tooth of
// gear C not those of gear D): a split along a parameter the edge does not read leaves its jets
// the same, bit for bit. The memo keys an edge by the inputs it reads — for every parameter its
// formulas depend on (found once per edge by evaluating them with ParameterReads, below,
// derived parameters included) the box's two ends by bit pattern and the parameter's variable
// index — so a hit is the value the evaluation would give, bit for bit.
#pragma once

#include "model/parametric/parametric.hpp"
#include "tolerance/jet.hpp"

#include <hipair/cspace.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace hipair::tolerance_detail {

struct Box;

/// A number type for the parametric model that records which parameter deviations a value
/// depends on: every operation's result reads what its operands read (a constant reads none).
struct ParameterReads {
  std::vector<std::uint32_t> indices;   ///< sorted, without repeats

  ParameterReads() = default;
  ParameterReads(int) {}   // NOLINT(google-explicit-constructor): a constant
  static ParameterReads of(std::size_t i) {
    ParameterReads r;
    r.indices.push_back(static_cast<std::uint32_t>(i));
    return r;
  }
};
ParameterReads operator+(const ParameterReads& a, const ParameterReads& b);
inline ParameterReads operator-(const ParameterReads& a, const ParameterReads& b) { return a + b; }
inline ParameterReads operator*(const ParameterReads& a, const ParameterReads& b) { return a + b; }
inline ParameterReads operator/(const ParameterReads& a, const ParameterReads& b) { return a + b; }
inline ParameterReads operator-(const ParameterReads& a) { return a; }

/// The Taylor-model jets of the deviations over `box` (n parameters): a parameter in `active`
/// (the a-th) is the jet variable a of k + 1 (k = active.size(): the free coordinate is k) as
/// the Taylor model of variable a over its range; any other is its range (a point when it does
/// not vary) as a constant. CurveSolver::taylor_geometry's jets.
std::vector<Jet<TaylorModel1>> taylor_deviations(const Box& box, const std::vector<std::size_t>& active);

/// The memo of one model's edges (and parts' axes) as Taylor-model jets over boxes. Shared by
/// the threads of the band (a mutex); bounded (cleared at `max_entries`).
class TaylorEdgeMemo {
 public:
  using TaylorJet = Jet<TaylorModel1>;
  static constexpr std::size_t max_entries = 20000;

  explicit TaylorEdgeMemo(std::shared_ptr<const model_detail::ParametricModel> model) : model_(std::move(model)) {}

  /// model.edge_value(f.part, f.loop, f.edge, model.parameter_values(taylor_deviations(box,
  /// active))) bit for bit; `parameters` gives those parameter values (called on a miss only).
  /// \throws NumericError as edge_value.
  model_detail::EdgeValue<TaylorJet> edge(const FeatureIdentity& f, const Box& box, const std::vector<std::size_t>& active,
                                          const std::function<const std::vector<TaylorJet>&()>& parameters);
  /// model.motion_value(part, ...) likewise.
  void motion(std::size_t part, const Box& box, const std::vector<std::size_t>& active,
              const std::function<const std::vector<TaylorJet>&()>& parameters, kernels::Vector<TaylorJet>& pivot,
              kernels::Vector<TaylorJet>& direction);

  /// The deviations an edge's formulas read (ParameterReads; sorted).
  std::vector<std::uint32_t> edge_reads(const FeatureIdentity& f);
  std::vector<std::uint32_t> motion_reads(std::size_t part);

  /// Clear when holding `entries` (default max_entries).
  void set_limit(std::size_t entries);

  std::size_t hits() const { return hits_; }
  std::size_t misses() const { return misses_; }

 private:
  struct Entry {
    model_detail::EdgeValue<TaylorJet> edge;
    kernels::Vector<TaylorJet> pivot, direction;
  };
  // (part, loop, edge): loop = -1 for a part's axes
  using Item = std::vector<std::uint64_t>;
  const std::vector<std::uint32_t>& reads(const Item& item);
  Item key(const Item& item, const Box& box, const std::vector<std::size_t>& active);
  std::shared_ptr<const Entry> find(const Item& key);
  void store(Item key, std::shared_ptr<const Entry> entry);

  std::shared_ptr<const model_detail::ParametricModel> model_;
  std::mutex mutex_;
  std::vector<ParameterReads> parameter_reads_;   ///< parameter_values of ParameterReads::of(i)
  std::map<Item, std::vector<std::uint32_t>> reads_;
  std::map<Item, std::shared_ptr<const Entry>> entries_;
  std::size_t hits_ = 0, misses_ = 0;
  std::size_t limit_ = max_entries;
};

}  // namespace hipair::tolerance_detail

namespace hipair::model_detail {

template <>
struct Arithmetic<tolerance_detail::ParameterReads> {
  using R = tolerance_detail::ParameterReads;
  static R constant(const Rational&) { return R(); }
  static R pi() { return R(); }
  static R sqrt(const R& x) { return x; }
  static R sin(const R& x) { return x; }
  static R cos(const R& x) { return x; }
  static R tan(const R& x) { return x; }
  static R atan2(const R& y, const R& x) { return y + x; }
  static R abs(const R& x) { return x; }
  static R min(const R& a, const R& b) { return a + b; }
  static R max(const R& a, const R& b) { return a + b; }
};

}  // namespace hipair::model_detail
