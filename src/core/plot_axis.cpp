// Value axes of line plots: nice ticks and labels that differ (see plot_axis.hpp).
#include "core/plot_axis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

namespace hipair {
namespace {

using Wide = long double;

// Labels with more significant digits than this are written as offsets from a base.
constexpr std::int64_t direct_limit = 1000000;

// n x 10^e written exactly. Fixed notation with `decimals` digits after the point when
// decimals >= 0 (and e >= -decimals); otherwise scientific with trailing zeros dropped.
std::string decimal(std::int64_t n, int e, int decimals) {
  if (n == 0) return decimals > 0 ? "0." + std::string(decimals, '0') : "0";
  std::string sign = n < 0 ? "-" : "";
  std::uint64_t magnitude = n < 0 ? static_cast<std::uint64_t>(-(n + 1)) + 1 : static_cast<std::uint64_t>(n);
  std::string digits = std::to_string(magnitude);
  if (decimals >= 0) {
    if (e >= 0) return sign + digits + std::string(e, '0') + (decimals > 0 ? "." + std::string(decimals, '0') : "");
    // e < 0: the point -e digits from the right, then padded to `decimals`
    int point = -e;
    if (static_cast<int>(digits.size()) <= point) digits = std::string(point - digits.size() + 1, '0') + digits;
    std::string whole = digits.substr(0, digits.size() - point), fraction = digits.substr(digits.size() - point);
    fraction += std::string(std::max(0, decimals - point), '0');
    return sign + whole + (fraction.empty() ? "" : "." + fraction);
  }
  while (digits.size() > 1 && digits.back() == '0') {
    digits.pop_back();
    ++e;
  }
  int exponent = e + static_cast<int>(digits.size()) - 1;
  std::string mantissa = digits.substr(0, 1) + (digits.size() > 1 ? "." + digits.substr(1) : "");
  return sign + mantissa + "e" + (exponent < 0 ? "-" : "+") + std::to_string(std::abs(exponent));
}

// Number of decimal digits of |n| (1 for 0).
int digit_count(std::int64_t n) {
  std::uint64_t m = n < 0 ? static_cast<std::uint64_t>(-(n + 1)) + 1 : static_cast<std::uint64_t>(n);
  int count = 1;
  while (m >= 10) {
    m /= 10;
    ++count;
  }
  return count;
}

// Labels for the values n_i x 10^e of one axis: fixed notation with a common number of
// decimals when the values are of ordinary size, else scientific.
std::vector<std::string> labels_of(const std::vector<std::int64_t>& n, int e, bool signed_offsets) {
  int widest = 1;
  for (std::int64_t v : n) widest = std::max(widest, digit_count(v));
  bool fixed = e >= -6 && e + widest <= 7;
  std::vector<std::string> out;
  for (std::int64_t v : n) {
    std::string text = decimal(v, e, fixed ? std::max(0, -e) : -1);
    if (signed_offsets && v == 0) text = "0";   // the base itself
    if (signed_offsets && v > 0) text = "+" + text;
    out.push_back(text);
  }
  return out;
}

// A single value n x 10^e, fixed when of ordinary size, without trailing zeros.
std::string base_text(std::int64_t n, int e) {
  while (n != 0 && n % 10 == 0) {
    n /= 10;
    ++e;
  }
  int exponent = e + digit_count(n) - 1;
  bool fixed = n == 0 || (exponent >= -5 && exponent < 7);
  return decimal(n, e, fixed ? std::max(0, -e) : -1);
}

int trailing_zeros(std::int64_t n) {
  if (n == 0) return 99;
  int count = 0;
  while (n % 10 == 0) {
    n /= 10;
    ++count;
  }
  return count;
}

}  // namespace

std::pair<double, double> finite_bounds(const std::vector<double>& values) {
  double nan = std::numeric_limits<double>::quiet_NaN();
  double lo = nan, hi = nan;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::isnan(lo) ? v : std::min(lo, v);
    hi = std::isnan(hi) ? v : std::max(hi, v);
  }
  return {lo, hi};
}

PlotAxis plot_axis(double data_lo, double data_hi, const PlotAxisOptions& options) {
  bool lo_ok = std::isfinite(data_lo), hi_ok = std::isfinite(data_hi);
  Wide lo = lo_ok ? data_lo : hi_ok ? data_hi : 0.0;
  Wide hi = hi_ok ? data_hi : lo_ok ? data_lo : 0.0;
  if (hi < lo) std::swap(lo, hi);
  Wide size = std::max(std::fabs(lo), std::fabs(hi));
  Wide least = size * std::ldexp(Wide(1), -50);   // a few units in the last place of a double
  if (hi == lo) {
    Wide half = lo == 0 ? Wide(1) : std::pow(Wide(10), std::floor(std::log10(std::fabs(lo))) - 1);
    lo -= half;
    hi += half;
  } else if (hi - lo < least) {
    Wide middle = lo / 2 + hi / 2;
    lo = middle - least / 2;
    hi = middle + least / 2;
  }
  Wide pad = std::max(0.0, options.pad) * (hi - lo);
  lo -= pad;
  hi += pad;
  int max_ticks = std::clamp(options.max_ticks, 4, 50);

  // The smallest nice step giving at most max_ticks ticks (a few candidates suffice; the loop
  // also absorbs rounding of log10).
  Wide target = (hi - lo) / (max_ticks - 1);
  int e = static_cast<int>(std::floor(std::log10(target))) - 1;
  const int mantissas[] = {1, 2, 5};
  int choice = 0;
  Wide step = 0, k_lo = 0, k_hi = 0;
  for (int attempt = 0; attempt < 12; ++attempt, choice = (choice + 1) % 3, e += choice == 0) {
    step = mantissas[choice] * std::pow(Wide(10), e);
    k_lo = options.snap ? std::floor(lo / step) : std::ceil(lo / step);
    k_hi = options.snap ? std::ceil(hi / step) : std::floor(hi / step);
    if (k_hi - k_lo + 1 <= max_ticks) break;
  }
  int m = mantissas[choice];
  PlotAxis axis;
  axis.step = step;
  if (options.snap) {
    lo = std::min(lo, k_lo * step);
    hi = std::max(hi, k_hi * step);
  }
  // k x step must lie within [lo, hi] although lo / step was rounded
  while (k_lo * step < lo) k_lo += 1;
  while (k_hi * step > hi) k_hi -= 1;
  axis.lo = lo;
  axis.hi = hi;
  std::vector<std::int64_t> n;
  for (Wide k = k_lo; k <= k_hi; k += 1) {
    axis.ticks.push_back(k * step);
    n.push_back(static_cast<std::int64_t>(k) * m);
  }
  std::int64_t widest = 0;
  for (std::int64_t v : n) widest = std::max<std::int64_t>(widest, v < 0 ? -v : v);
  if (widest < direct_limit) {
    axis.labels = labels_of(n, e, false);
    return axis;
  }
  // Offsets from the roundest tick (most trailing zeros; the middle one on a tie).
  std::size_t base = 0;
  for (std::size_t i = 0; i < n.size(); ++i) {
    int zi = trailing_zeros(n[i]), zb = trailing_zeros(n[base]);
    double mid = (n.size() - 1) / 2.0;
    if (zi > zb || (zi == zb && std::fabs(i - mid) < std::fabs(base - mid))) base = i;
  }
  std::vector<std::int64_t> offsets;
  for (std::int64_t v : n) offsets.push_back(v - n[base]);
  axis.labels = labels_of(offsets, e, true);
  axis.base_label = base_text(n[base], e) + " +";
  return axis;
}

}  // namespace hipair
