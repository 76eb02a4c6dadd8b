#include "arrangement/clip_common.hpp"

#include "algebra/exact_real.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hipair::cspace::raw {

CurveGroups group_curves(const std::vector<IntegerPolynomial2>& curves) {
  CurveGroups out;
  std::vector<std::string> keys;   // exact text of the primitive polynomial, positive first term
  auto add_to_group = [&](IntegerPolynomial2 normal, std::size_t k) {
    mpz_class g = 0;
    int sign = 0;
    for (const auto& row : normal.coefficients)
      for (const auto& c : row) {
        mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
        if (sign == 0 && sgn(c) != 0) sign = sgn(c);
      }
    if (sgn(g) != 0)
      for (auto& row : normal.coefficients)
        for (auto& c : row) c = sign * c / g;
    std::string key = algebra::to_string(normal, "x", "y");
    auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) {
      keys.push_back(std::move(key));
      out.polynomials.push_back(std::move(normal));
      out.members.push_back({k});
    } else {
      auto& group = out.members[static_cast<std::size_t>(it - keys.begin())];
      if (std::find(group.begin(), group.end(), k) == group.end()) group.push_back(k);
    }
  };
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const auto& c = curves[k].coefficients;   // c[i][j]: coefficient of x^i y^j
    std::size_t min_i = c.size(), min_j = std::numeric_limits<std::size_t>::max();
    bool any = false;
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t j = 0; j < c[i].size(); ++j)
        if (sgn(c[i][j]) != 0) {
          any = true;
          min_i = std::min(min_i, i);
          min_j = std::min(min_j, j);
        }
    if (!any || (min_i == 0 && min_j == 0)) {
      add_to_group(curves[k], k);
      continue;
    }
    IntegerPolynomial2 rest;
    rest.coefficients.assign(c.size() - min_i, {});
    bool constant = true;
    for (std::size_t i = min_i; i < c.size(); ++i) {
      auto& row = rest.coefficients[i - min_i];
      if (c[i].size() > min_j) row.assign(c[i].begin() + static_cast<std::ptrdiff_t>(min_j), c[i].end());
      for (std::size_t j = 0; j < row.size(); ++j)
        if (sgn(row[j]) != 0 && (i > min_i || j > 0)) constant = false;
    }
    if (min_i > 0) add_to_group(IntegerPolynomial2{{{mpz_class(0)}, {mpz_class(1)}}}, k);   // x
    if (min_j > 0) add_to_group(IntegerPolynomial2{{{mpz_class(0), mpz_class(1)}}}, k);     // y
    if (!constant) add_to_group(std::move(rest), k);
  }
  return out;
}

bool clauses_hold(const std::vector<const std::vector<ValidityClause>*>& alternatives, const Rational& x,
                  const algebra::Real& y) {
  for (const auto* clauses : alternatives) {
    bool all = true;
    for (const auto& clause : *clauses) {
      bool holds = false;
      for (const auto& atom : clause.atoms)
        if (algebra::sign_at(atom, x, y) >= 0) {
          holds = true;
          break;
        }
      if (!holds) {
        all = false;
        break;
      }
    }
    if (all) return true;
  }
  return false;
}

int clauses_hold_filter(const std::vector<const std::vector<ValidityClause>*>& alternatives, algebra::Interval x_i,
                        algebra::Interval y_i) {
  if (!(x_i.lo <= x_i.hi) || !(y_i.lo <= y_i.hi)) return -1;   // NaN ends: undecided
  bool undecided = false;
  for (const auto* clauses : alternatives) {
    int alternative = 1;   // 1 holds, 0 fails, -1 undecided
    for (const auto& clause : *clauses) {
      int state = 0;   // 1 some atom certainly >= 0, 0 every atom certainly < 0, -1 else
      for (const auto& atom : clause.atoms) {
        const algebra::Interval v = algebra::IntervalPolynomial2(atom).evaluate(x_i, y_i);
        if (v.lo >= 0) {   // (false for a NaN end)
          state = 1;
          break;
        }
        if (!(v.hi < 0)) state = -1;
      }
      if (state == 0) {
        alternative = 0;
        break;
      }
      if (state == -1) alternative = -1;
    }
    if (alternative == 1) return 1;
    if (alternative == -1) undecided = true;
  }
  return undecided ? -1 : 0;
}

bool in_windows(const Rational& x, const std::vector<std::pair<Rational, Rational>>* windows) {
  if (!windows) return true;
  for (const auto& [lo, hi] : *windows)
    if (lo <= x && x <= hi) return true;
  return false;
}

bool group_cells(const std::vector<std::vector<std::array<double, 4>>>* cells, const std::vector<std::size_t>& members,
                 CellBoxes& out) {
  out.clear();
  if (!cells) return false;
  for (std::size_t member : members) {
    if (member >= cells->size() || (*cells)[member].empty()) return false;
    out.insert(out.end(), (*cells)[member].begin(), (*cells)[member].end());
  }
  std::sort(out.begin(), out.end());
  return true;
}

bool branch_meets_cells(const CellBoxes& cells, double x_lo, double x_hi,
                        const std::function<algebra::Interval(algebra::Interval)>& y_over) {
  if (!(x_lo <= x_hi)) return true;
  for (const auto& cell : cells) {
    if (cell[0] > x_hi) break;   // sorted by x_lo: no later box reaches back
    if (cell[1] < x_lo) continue;
    const algebra::Interval y = y_over({std::max(cell[0], x_lo), std::min(cell[1], x_hi)});
    if (!(y.lo == y.lo) || !(y.hi == y.hi)) return true;
    if (!(y.hi < cell[2] || y.lo > cell[3])) return true;
  }
  return false;
}

void fill_edge_box(const std::vector<Vertex>& vertices, Edge& out) {
  const Vertex& a = vertices[out.min_vertex];
  const Vertex& b = vertices[out.max_vertex];
  out.box[0] = std::min(a.x.lower_bound(), b.x.lower_bound());
  out.box[2] = std::max(a.x.upper_bound(), b.x.upper_bound());
  out.box[1] = std::min(a.y_lower_bound(), b.y_lower_bound());
  out.box[3] = std::max(a.y_upper_bound(), b.y_upper_bound());
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int k : {0, 1}) out.box[k] = std::nextafter(out.box[k], -inf);
  for (int k : {2, 3}) out.box[k] = std::nextafter(out.box[k], inf);
}

}  // namespace hipair::cspace::raw
