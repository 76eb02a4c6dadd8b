// HIPAIR — parameter distributions and Monte Carlo draws (sampling.hpp).
#include "tolerance/sampling.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hipair::tolerance_detail {

double round_to_double(const Rational& x, bool up) {
  constexpr double most = std::numeric_limits<double>::max();
  if (abs(x) > Rational(most)) {   // beyond the doubles: get_d's infinity would make Rational(d) raise SIGFPE
    bool positive = sgn(x) > 0;
    if (up == positive) return positive ? INFINITY : -INFINITY;
    return positive ? most : -most;
  }
  double d = x.get_d();
  if (up && Rational(d) < x) d = std::nextafter(d, INFINITY);
  if (!up && Rational(d) > x) d = std::nextafter(d, -INFINITY);
  return d;
}

namespace {

// splitmix64: one independent, reproducible stream per Monte Carlo sample.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

struct Stream {
  std::uint64_t state;
  double uniform() {  // (0, 1)
    state = mix(state);
    return (static_cast<double>(state >> 11) + 0.5) * 0x1.0p-53;
  }
};

double lower_tail(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }   // Phi(z)
double upper_tail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }    // 1 - Phi(z)

// A normal(mean, sigma) truncated to [lo, hi], by inverting its CDF with u in (0, 1): bisection
// on [lo, hi], so the result never leaves it. In the upper half the survival function is used
// (accurate in the far tail); where both tails underflow the truncated normal is uniform to
// double precision and is drawn so.
double truncated_normal(double mean, double sigma, double lo, double hi, double u) {
  double a = (lo - mean) / sigma, b = (hi - mean) / sigma;
  bool upper = a > 0;
  double fa = upper ? upper_tail(a) : lower_tail(a), fb = upper ? upper_tail(b) : lower_tail(b);
  double target = fa + u * (fb - fa);
  if (!(std::fabs(fb - fa) > 0)) return std::clamp(lo + u * (hi - lo), lo, hi);
  double x0 = lo, x1 = hi;
  for (int i = 0; i < 200 && x0 < x1; ++i) {
    double m = x0 + 0.5 * (x1 - x0);
    if (m <= x0 || m >= x1) break;
    double z = (m - mean) / sigma;
    double f = upper ? upper_tail(z) : lower_tail(z);
    bool before = upper ? f > target : f < target;   // m is below the quantile
    if (before) x0 = m;
    else x1 = m;
  }
  return std::clamp(x0 + 0.5 * (x1 - x0), lo, hi);
}

}  // namespace

std::vector<Distribution> distributions(const Model& model) {
  std::vector<Distribution> result;
  for (const Parameter& p : model.parameters) {
    Distribution d;
    Rational lo = p.range.lo - p.nominal, hi = p.range.hi - p.nominal;
    d.lo = lo.get_d();
    d.hi = hi.get_d();
    // Sampling, sensitivities and bands work in doubles about the nominal: a range whose ends or
    // width overflow them (a tolerance of 1e400) would come out as infinities and NaNs.
    if (!std::isfinite(d.hi - d.lo) || (p.sigma && !std::isfinite(p.sigma->get_d())))
      throw ModelError("/parameters/" + p.name, std::string("its tolerance range") + (p.sigma ? " or sigma" : "") +
                                                    " is beyond the doubles the tolerance analysis samples in (a width or "
                                                    "deviation above about 1.8e308)");
    d.sample_lo = round_to_double(lo, true);
    d.sample_hi = round_to_double(hi, false);
    d.box_lo = round_to_double(lo, false);
    d.box_hi = round_to_double(hi, true);
    double width = d.hi - d.lo;
    if (width <= 0 || d.sample_lo > d.sample_hi) {
      d.sample_lo = d.sample_hi = 0;
      result.push_back(d);
      continue;
    }
    switch (p.distribution) {
      case Parameter::Distribution::uniform:
        d.kind = Distribution::Kind::uniform;
        d.mean = 0.5 * (d.lo + d.hi);
        d.sigma = width / std::sqrt(12.0);
        break;
      case Parameter::Distribution::normal:
        d.kind = Distribution::Kind::normal;
        d.mean = 0;
        d.sigma = p.sigma->get_d();
        break;
      case Parameter::Distribution::none:
        d.kind = Distribution::Kind::normal;
        d.mean = 0.5 * (d.lo + d.hi);
        d.sigma = width / 6;
        break;
    }
    result.push_back(d);
  }
  return result;
}

std::vector<double> draw(const std::vector<Distribution>& ds, std::uint64_t seed, std::size_t index) {
  Stream stream{mix(seed ^ mix(index + 1))};
  std::vector<double> x(ds.size(), 0.0);
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const Distribution& d = ds[i];
    switch (d.kind) {
      case Distribution::Kind::fixed: break;
      case Distribution::Kind::uniform:
        x[i] = std::clamp(d.sample_lo + (d.sample_hi - d.sample_lo) * stream.uniform(), d.sample_lo, d.sample_hi);
        break;
      case Distribution::Kind::normal:
        x[i] = truncated_normal(d.mean, d.sigma, d.sample_lo, d.sample_hi, stream.uniform());
        break;
    }
  }
  return x;
}

}  // namespace hipair::tolerance_detail
