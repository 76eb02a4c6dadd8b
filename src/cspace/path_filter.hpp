// The crossing scanner's filtered path enclosure (cspace_queries.cpp, MotionScanner): a motion
// axis' polynomial over a stretch [A.lo, B.hi] of the path parameter, in outward-rounded double
// intervals (kernels::Interval), by a Taylor shift to a double m near the midpoint and Horner in
// h = u - m. `evaluate_path_filtered_d` is the form; `evaluate_path_filtered_pair` evaluates two
// polynomials of one length over the same stretch at once (a stretch asks its x and y axes, their
// rates and their accelerations in pairs), in two-lane vectors doing, lane by lane, the operations
// of the scalar form in its order — the same bits for each polynomial (kernels::Interval's
// products and sums: round to nearest, then one double outward; an end product 0 · inf is 0).
// Where an outward step meets a zero, an infinity or a NaN the lane takes kernels'
// interval_detail::up/down itself. Switch paired_paths() (on by default; CSpacePathFilter.* and
// the crossing tests compare it off).
#pragma once

#include "core/thread_switch.hpp"
#include "kernels/interval.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::cspace {

struct PairedPathsTag;
inline bool& paired_paths() { return thread_switch<PairedPathsTag>(); }
// How many pairs of enclosures were evaluated together on this thread (tests, profiling).
struct PairedPathsCountTag;
inline std::size_t& paired_path_count() { return thread_counter<PairedPathsCountTag>(); }

// Enclosure of p over [A.lo, B.hi] (p's coefficients enclosed, lowest degree first); nullopt on
// overflow.
inline std::optional<kernels::Interval> evaluate_path_filtered_d(const std::vector<kernels::Interval>& p,
                                                                 const kernels::Interval& A, const kernels::Interval& B) {
  using KInterval = kernels::Interval;
  double m = 0.5 * A.lo + 0.5 * B.hi;
  KInterval M = KInterval::point(m);
  // the shifted coefficients on the stack for the simulator's low degrees (no allocation per
  // call; the same operations in the same order)
  const std::size_t n = p.size();
  std::array<KInterval, 8> local;
  std::vector<KInterval> heap;
  KInterval* shifted = local.data();
  if (n > local.size()) {
    heap = p;
    shifted = heap.data();
  } else {
    std::copy(p.begin(), p.end(), local.begin());
  }
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j > i; --j) shifted[j - 1] = shifted[j - 1] + M * shifted[j];
  KInterval H(kernels::interval_detail::down(A.lo - m), kernels::interval_detail::up(B.hi - m));
  KInterval value(0);
  for (std::size_t i = n; i-- > 0;) value = value * H + shifted[i];
  if (!std::isfinite(value.lo) || !std::isfinite(value.hi)) return std::nullopt;
  return value;
}

namespace path_filter_detail {
using v2d = double __attribute__((vector_size(16)));
using v2u = std::uint64_t __attribute__((vector_size(16)));

// both lanes finite and non-zero: the outward step is the bit pattern's, by the sign
inline bool ordinary(v2d v) {
  const v2u magnitude = reinterpret_cast<v2u>(v) & v2u{0x7fffffffffffffffULL, 0x7fffffffffffffffULL};
  const v2d a = reinterpret_cast<v2d>(magnitude);
  const auto ok = (a < v2d{INFINITY, INFINITY}) & (a != v2d{0, 0});
  return ok[0] && ok[1];
}
// kernels::interval_detail::up / down, lane by lane
inline v2d up(v2d v) {
  if (ordinary(v)) {
    const v2u bits = reinterpret_cast<v2u>(v);
    return reinterpret_cast<v2d>(bits + v2u{1, 1} - ((bits >> 63) << 1));
  }
  return v2d{kernels::interval_detail::up(v[0]), kernels::interval_detail::up(v[1])};
}
inline v2d down(v2d v) {
  if (ordinary(v)) {
    const v2u bits = reinterpret_cast<v2u>(v);
    return reinterpret_cast<v2d>(bits - v2u{1, 1} + ((bits >> 63) << 1));
  }
  return v2d{kernels::interval_detail::down(v[0]), kernels::interval_detail::down(v[1])};
}
// kernels::Interval's end product (0 · inf = 0) and std::min / std::max, lane by lane
inline v2d end_product(v2d u, v2d v) {
  const v2d p = u * v;
  return p == p ? p : v2d{0, 0};
}
inline v2d min(v2d a, v2d b) { return b < a ? b : a; }
inline v2d max(v2d a, v2d b) { return a < b ? b : a; }
}  // namespace path_filter_detail

// evaluate_path_filtered_d(p, A, B) and evaluate_path_filtered_d(q, A, B) together (p and q of
// one length, at most 8 coefficients; otherwise false and nothing written).
inline bool evaluate_path_filtered_pair(const std::vector<kernels::Interval>& p, const std::vector<kernels::Interval>& q,
                                        const kernels::Interval& A, const kernels::Interval& B,
                                        std::optional<kernels::Interval>& p_value,
                                        std::optional<kernels::Interval>& q_value) {
  namespace d = path_filter_detail;
  using d::v2d;
  const std::size_t n = p.size();
  if (n != q.size() || n > 8) return false;
  const double m = 0.5 * A.lo + 0.5 * B.hi;
  const v2d M{m, m};
  std::array<v2d, 8> lo, hi;   // lane 0: p, lane 1: q
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = v2d{p[i].lo, q[i].lo};
    hi[i] = v2d{p[i].hi, q[i].hi};
  }
  // shifted[j - 1] + M * shifted[j]: M a point, so the four end products are two, each twice
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j > i; --j) {
      const v2d p1 = d::end_product(M, lo[j]), p2 = d::end_product(M, hi[j]);
      const v2d low = d::down(d::min(d::min(p1, p2), d::min(p1, p2)));
      const v2d high = d::up(d::max(d::max(p1, p2), d::max(p1, p2)));
      lo[j - 1] = d::down(lo[j - 1] + low);
      hi[j - 1] = d::up(hi[j - 1] + high);
    }
  const double h_lo = kernels::interval_detail::down(A.lo - m), h_hi = kernels::interval_detail::up(B.hi - m);
  const v2d Hl{h_lo, h_lo}, Hh{h_hi, h_hi};
  v2d vlo{0, 0}, vhi{0, 0};
  for (std::size_t i = n; i-- > 0;) {
    const v2d p1 = d::end_product(vlo, Hl), p2 = d::end_product(vlo, Hh), p3 = d::end_product(vhi, Hl),
              p4 = d::end_product(vhi, Hh);
    const v2d low = d::down(d::min(d::min(p1, p2), d::min(p3, p4)));
    const v2d high = d::up(d::max(d::max(p1, p2), d::max(p3, p4)));
    vlo = d::down(low + lo[i]);
    vhi = d::up(high + hi[i]);
  }
  auto value = [](double l, double h) -> std::optional<kernels::Interval> {
    if (!std::isfinite(l) || !std::isfinite(h)) return std::nullopt;
    return kernels::Interval(l, h);
  };
  p_value = value(vlo[0], vhi[0]);
  q_value = value(vlo[1], vhi[1]);
  return true;
}

}  // namespace hipair::cspace
