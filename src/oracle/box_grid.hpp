// A uniform grid over a fixed set of axis-parallel boxes (session 74, growth74): the broad phase
// of the overlap oracles asks "which of this part's edges may meet this box?" per edge of the
// other part; scanning every edge made each oracle call grow with the part's size (the face
// classification of an n x n gear pair grew n^1.7). The grid answers with a superset of the boxes
// that meet the query box, in ascending index order, from the cells the query covers.
//
// Exact in what it promises (no box meeting the query is left out), whatever the rounding: an
// item is filed in the cells [cell(lo), cell(hi)] of each axis and a query covers [cell(qlo),
// cell(qhi)], where cell(v) = floor((v - origin) / size) clamped to the grid is monotone in v
// (rounded subtraction and division by a positive constant are monotone); two boxes sharing a
// point v on an axis share cell(v) there. Items with a bound that is not finite (NaN never
// separates, an infinite box meets everything) and queries with one are answered with every item
// they may meet: such items are listed for every query, such a query lists every item.
// Callers still test each listed item's own box: the grid only removes items that cannot meet.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hipair::cspace {

class BoxGrid {
 public:
  /// A box as {xlo, xhi, ylo, yhi}.
  using Bounds = std::array<double, 4>;

  BoxGrid() = default;
  explicit BoxGrid(const std::vector<Bounds>& boxes) { build(boxes); }

  /// Files `boxes` (item i is boxes[i]); replaces what was filed before.
  void build(const std::vector<Bounds>& boxes) {
    items_ = boxes.size();
    everywhere_.clear();
    starts_.clear();
    filed_.clear();
    double xlo = HUGE_VAL, xhi = -HUGE_VAL, ylo = HUGE_VAL, yhi = -HUGE_VAL;
    std::vector<double> extents;
    extents.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const Bounds& b = boxes[i];
      if (!finite(b)) {
        everywhere_.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      xlo = std::min(xlo, b[0]);
      xhi = std::max(xhi, b[1]);
      ylo = std::min(ylo, b[2]);
      yhi = std::max(yhi, b[3]);
      extents.push_back(std::max(b[1] - b[0], b[3] - b[2]));
    }
    if (extents.empty()) {
      columns_ = rows_ = 0;
      return;
    }
    // cells about the median item's extent, at most 4 per item and 2^20 in all (a grid of
    // empty cells costs memory, not answers)
    std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
    double size = extents[extents.size() / 2];
    const double width = xhi - xlo, height = yhi - ylo;
    const double cap = std::min<double>(4.0 * static_cast<double>(extents.size()) + 16, 1 << 20);
    if (!(size > 0) || (width / size + 1) * (height / size + 1) > cap)
      size = std::max(std::sqrt(width * height / cap), std::max(width, height) / cap);
    if (!(size > 0) || !std::isfinite(size)) size = 1;
    x0_ = xlo;
    y0_ = ylo;
    size_ = size;
    columns_ = static_cast<std::size_t>(std::min(width / size, cap)) + 1;
    rows_ = static_cast<std::size_t>(std::min(height / size, cap)) + 1;
    // the sizing above keeps columns * rows <= 3 cap + 1; a width or height that overflows the
    // doubles (finite boxes 1e154 apart have an infinite area, 1e308 apart an infinite side)
    // leaves size 1 and would ask for up to (cap + 1)^2 cells: one cell then, every item in it
    // (a superset, as promised; integrator, review74 growth74 M2)
    if (!std::isfinite(width) || !std::isfinite(height) ||
        static_cast<double>(columns_) * static_cast<double>(rows_) > 3.0 * cap + 1.0) {
      size_ = 1;
      columns_ = rows_ = 1;
    }
    // counting sort of (cell, item) in item order: each cell's items ascending
    starts_.assign(columns_ * rows_ + 1, 0);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (!finite(boxes[i])) continue;
      const Span s = span(boxes[i]);
      for (std::size_t r = s.r0; r <= s.r1; ++r)
        for (std::size_t c = s.c0; c <= s.c1; ++c) ++starts_[r * columns_ + c + 1];
    }
    for (std::size_t k = 1; k < starts_.size(); ++k) starts_[k] += starts_[k - 1];
    filed_.resize(starts_.back());
    std::vector<std::uint32_t> next(starts_.begin(), starts_.end() - 1);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (!finite(boxes[i])) continue;
      const Span s = span(boxes[i]);
      for (std::size_t r = s.r0; r <= s.r1; ++r)
        for (std::size_t c = s.c0; c <= s.c1; ++c)
          filed_[next[r * columns_ + c]++] = static_cast<std::uint32_t>(i);
    }
  }

  /// The items whose boxes may meet q (a superset of those that do), ascending, no repeats.
  void query(const Bounds& q, std::vector<std::size_t>& out) const {
    out.clear();
    if (!finite(q)) {
      for (std::size_t i = 0; i < items_; ++i) out.push_back(i);
      return;
    }
    out.insert(out.end(), everywhere_.begin(), everywhere_.end());
    if (columns_ > 0 && !(q[1] < x0_ || q[3] < y0_)) {
      const Span s = span(q);
      const std::size_t before = out.size();
      for (std::size_t r = s.r0; r <= s.r1; ++r)
        for (std::size_t c = s.c0; c <= s.c1; ++c) {
          const std::size_t cell = r * columns_ + c;
          out.insert(out.end(), filed_.begin() + starts_[cell], filed_.begin() + starts_[cell + 1]);
        }
      // one cell's items are ascending already (and no other list was added)
      if (s.r0 != s.r1 || s.c0 != s.c1 || !everywhere_.empty() || before != 0) {
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
      }
    }
  }

  std::size_t size() const { return items_; }

 private:
  struct Span {
    std::size_t c0, c1, r0, r1;
  };
  static bool finite(const Bounds& b) {
    return std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]) && std::isfinite(b[3]);
  }
  static std::size_t cell(double v, double origin, double size, std::size_t count) {
    const double k = std::floor((v - origin) / size);
    if (!(k > 0)) return 0;  // (also NaN: not reached, queries and items are finite)
    if (k >= static_cast<double>(count - 1)) return count - 1;
    return static_cast<std::size_t>(k);
  }
  Span span(const Bounds& b) const {
    return Span{cell(b[0], x0_, size_, columns_), cell(b[1], x0_, size_, columns_),
                cell(b[2], y0_, size_, rows_), cell(b[3], y0_, size_, rows_)};
  }

  std::size_t items_ = 0;
  double x0_ = 0, y0_ = 0, size_ = 1;
  std::size_t columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> starts_;      // per cell, its first item in filed_ (CSR)
  std::vector<std::uint32_t> filed_;       // the cells' items, each cell's ascending
  std::vector<std::uint32_t> everywhere_;  // items with a bound not finite: listed for every query
};

}  // namespace hipair::cspace
