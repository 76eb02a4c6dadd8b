// Interval sine and cosine through MPFI, remembered per thread (number_traits.hpp).
#include "model/parametric/number_traits.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>

namespace hipair::model_detail::number_detail {
namespace {

struct ArgumentKey {
  std::uint64_t lo, hi;
  bool operator==(const ArgumentKey&) const = default;
};

struct ArgumentHash {
  std::size_t operator()(const ArgumentKey& key) const {
    return std::hash<std::uint64_t>{}(key.lo * 0x9e3779b97f4a7c15ull ^ key.hi);
  }
};

// A bounded memo: cleared when full (an entry is a pure function of its key, so clearing changes
// no result, only what is recomputed).
class Memo {
 public:
  template <class Function>
  kernels::Interval get(const kernels::Interval& x, Function&& f) {
    // keyed by the bit patterns: -0.0 and 0.0 stay apart, as MPFI may treat them apart
    ArgumentKey key{std::bit_cast<std::uint64_t>(x.lo), std::bit_cast<std::uint64_t>(x.hi)};
    auto found = values_.find(key);
    if (found != values_.end()) return found->second;
    kernels::Interval value = through_mpfi(x, f);
    if (values_.size() >= capacity) values_.clear();
    values_.emplace(key, value);
    return value;
  }

 private:
  static constexpr std::size_t capacity = 1 << 14;
  std::unordered_map<ArgumentKey, kernels::Interval, ArgumentHash> values_;
};

}  // namespace

kernels::Interval interval_sin(const kernels::Interval& x) {
  thread_local Memo memo;
  return memo.get(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_sin(r, a); });
}

kernels::Interval interval_cos(const kernels::Interval& x) {
  thread_local Memo memo;
  return memo.get(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_cos(r, a); });
}

}  // namespace hipair::model_detail::number_detail
