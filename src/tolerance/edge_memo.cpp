// The Taylor-model geometry memo (edge_memo.hpp).
#include "tolerance/edge_memo.hpp"

#include "tolerance/solver.hpp"

#include <algorithm>
#include <bit>
#include <iterator>

namespace hipair::tolerance_detail {

ParameterReads operator+(const ParameterReads& a, const ParameterReads& b) {
  if (a.indices.empty()) return b;
  if (b.indices.empty()) return a;
  ParameterReads r;
  r.indices.reserve(a.indices.size() + b.indices.size());
  std::set_union(a.indices.begin(), a.indices.end(), b.indices.begin(), b.indices.end(), std::back_inserter(r.indices));
  return r;
}

std::vector<Jet<TaylorModel1>> taylor_deviations(const Box& box, const std::vector<std::size_t>& active) {
  using TaylorJet = Jet<TaylorModel1>;
  std::size_t n = box.lo.size();
  std::size_t k = active.size();
  std::vector<TaylorJet> jets(n);
  for (std::size_t i = 0; i < n; ++i) {
    // a parameter varying in the box that the curve does not depend on enters as its range
    bool varies = box.hi[i] > box.lo[i];
    jets[i] = TaylorJet(TaylorModel1(varies ? Interval(box.lo[i], box.hi[i]) : Interval::point(box.lo[i])));
  }
  for (std::size_t a = 0; a < k; ++a) {
    std::size_t i = active[a];
    jets[i] = TaylorJet::variable(TaylorModel1::over(box.lo[i], box.hi[i], a), a, k + 1);
  }
  return jets;
}

namespace {
void read_into(ParameterReads& all, const ParameterReads& x) { all = all + x; }
void read_into(ParameterReads& all, const kernels::Vector<ParameterReads>& v) {
  read_into(all, v.x);
  read_into(all, v.y);
}
}  // namespace

const std::vector<std::uint32_t>& TaylorEdgeMemo::reads(const Item& item) {
  // (the caller holds mutex_)
  auto found = reads_.find(item);
  if (found != reads_.end()) return found->second;
  if (parameter_reads_.empty()) {
    std::vector<ParameterReads> deviations(model_->parameter_count());
    for (std::size_t i = 0; i < deviations.size(); ++i) deviations[i] = ParameterReads::of(i);
    parameter_reads_ = model_->parameter_values(deviations);
  }
  ParameterReads all;
  std::size_t part = static_cast<std::size_t>(item[0]);
  if (item[1] == ~std::uint64_t{0}) {
    kernels::Vector<ParameterReads> pivot, direction;
    model_->motion_value(part, parameter_reads_, pivot, direction);
    read_into(all, pivot);
    read_into(all, direction);
  } else {
    model_detail::EdgeValue<ParameterReads> e = model_->edge_value(part, static_cast<std::size_t>(item[1]),
                                                                   static_cast<std::size_t>(item[2]), parameter_reads_);
    read_into(all, e.source);
    read_into(all, e.target);
    read_into(all, e.center);
    read_into(all, e.radius_squared);
  }
  return reads_.emplace(item, std::move(all.indices)).first->second;
}

TaylorEdgeMemo::Item TaylorEdgeMemo::key(const Item& item, const Box& box, const std::vector<std::size_t>& active) {
  // every input of the item's jets: the jets' length, and per parameter read its box ends (bit
  // patterns) and its variable index (or none)
  Item key = item;
  key.push_back(active.size());
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::uint32_t i : reads(item)) {
    auto position = std::find(active.begin(), active.end(), std::size_t{i});
    key.push_back(i);
    key.push_back(std::bit_cast<std::uint64_t>(box.lo[i]));
    key.push_back(std::bit_cast<std::uint64_t>(box.hi[i]));
    key.push_back(position == active.end() ? ~std::uint64_t{0} : static_cast<std::uint64_t>(position - active.begin()));
  }
  return key;
}

std::shared_ptr<const TaylorEdgeMemo::Entry> TaylorEdgeMemo::find(const Item& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = entries_.find(key);
  if (found == entries_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  return found->second;
}

void TaylorEdgeMemo::set_limit(std::size_t entries) {
  std::lock_guard<std::mutex> lock(mutex_);
  limit_ = entries;
  if (entries_.size() >= limit_) entries_.clear();
}

void TaylorEdgeMemo::store(Item key, std::shared_ptr<const Entry> entry) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (entries_.size() >= limit_) entries_.clear();
  entries_.emplace(std::move(key), std::move(entry));
}

model_detail::EdgeValue<TaylorEdgeMemo::TaylorJet> TaylorEdgeMemo::edge(
    const FeatureIdentity& f, const Box& box, const std::vector<std::size_t>& active,
    const std::function<const std::vector<TaylorJet>&()>& parameters) {
  Item k = key(Item{f.part, f.loop, f.edge}, box, active);
  if (std::shared_ptr<const Entry> hit = find(k)) return hit->edge;
  auto entry = std::make_shared<Entry>();
  entry->edge = model_->edge_value(f.part, f.loop, f.edge, parameters());
  store(std::move(k), entry);
  return entry->edge;
}

void TaylorEdgeMemo::motion(std::size_t part, const Box& box, const std::vector<std::size_t>& active,
                            const std::function<const std::vector<TaylorJet>&()>& parameters,
                            kernels::Vector<TaylorJet>& pivot, kernels::Vector<TaylorJet>& direction) {
  Item k = key(Item{part, ~std::uint64_t{0}, 0}, box, active);
  if (std::shared_ptr<const Entry> hit = find(k)) {
    pivot = hit->pivot;
    direction = hit->direction;
    return;
  }
  auto entry = std::make_shared<Entry>();
  model_->motion_value(part, parameters(), entry->pivot, entry->direction);
  store(std::move(k), entry);
  pivot = entry->pivot;
  direction = entry->direction;
}

std::vector<std::uint32_t> TaylorEdgeMemo::edge_reads(const FeatureIdentity& f) {
  std::lock_guard<std::mutex> lock(mutex_);
  return reads(Item{f.part, f.loop, f.edge});
}

std::vector<std::uint32_t> TaylorEdgeMemo::motion_reads(std::size_t part) {
  std::lock_guard<std::mutex> lock(mutex_);
  return reads(Item{part, ~std::uint64_t{0}, 0});
}

}  // namespace hipair::tolerance_detail
