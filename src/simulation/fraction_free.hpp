// HIPAIR — fraction-free (Bareiss) elimination of rational matrices: the exact linear solves and
// echelon forms of the held-contact and impact decisions (held_force_sign.hpp's solve,
// exact_elimination.hpp's row_echelon) in integers, without the gcd that every rational product
// and sum takes (docs/performance.md, "Session 70 (speed70)": the escapement's exact impact
// decisions spent 29 M instructions of a 169 M loop in GMP's gcd).
//
// Each row is scaled to integers by its entries' common denominator (a nonzero factor per
// equation: the same solution set, the same zero pattern). Bareiss' step replaces an entry by
// (p a_ij - a_ik a_kj) / p_prev, an exact division (Sylvester's identity: every entry after t
// pivots is a (t+1)-minor of the integer matrix, whatever columns had no pivot), so a row is at
// every step a nonzero integer multiple of the same row in rational elimination with the same
// pivots: the same zero pattern, the same pivot rows and columns (the first nonzero entry, as the
// rational codes choose), and every quantity those codes read from the result the same exact
// rational — a regular system's one solution (Gauss–Jordan: the pivots end equal to the
// determinant d, the right-hand sides to d X), a singular one refused at the same column, and an
// echelon form's rank, pivot columns, zero rows and back-substitution (each row divided by its
// own pivot). Internal to src/simulation.
#pragma once

#include "core/thread_switch.hpp"

#include <hipair/rational.hpp>

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace hipair::simulation {

// The switch (on by default; a test turns it off on its thread to compare with the rational
// elimination it replaces) and how many solves and echelon forms it made on this thread.
struct FractionFreeTag;
inline bool& fraction_free() { return thread_switch<FractionFreeTag>(); }
struct FractionFreeCountTag;
inline std::size_t& fraction_free_eliminations() { return thread_counter<FractionFreeCountTag>(); }

namespace fraction_free_detail {

using IntegerMatrix = std::vector<std::vector<mpz_class>>;

// rows a (and b, when given, appended) times their common denominator, into `out`
inline void integer_row(const std::vector<Rational>& a, const std::vector<Rational>* b, std::vector<mpz_class>& out) {
  mpz_class l = 1, factor;
  auto widen = [&](const std::vector<Rational>& row) {
    for (const Rational& e : row)
      if (sgn(e) != 0 && mpz_cmp_ui(e.get_den_mpz_t(), 1) != 0) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), e.get_den_mpz_t());
  };
  widen(a);
  if (b) widen(*b);
  out.resize(a.size() + (b ? b->size() : 0));
  std::size_t j = 0;
  auto write = [&](const std::vector<Rational>& row) {
    for (const Rational& e : row) {
      mpz_class& o = out[j++];
      if (sgn(e) == 0) {
        o = 0;
      } else if (mpz_cmp_ui(e.get_den_mpz_t(), 1) == 0) {
        mpz_mul(o.get_mpz_t(), e.get_num_mpz_t(), l.get_mpz_t());
      } else {
        mpz_divexact(factor.get_mpz_t(), l.get_mpz_t(), e.get_den_mpz_t());
        mpz_mul(o.get_mpz_t(), e.get_num_mpz_t(), factor.get_mpz_t());
      }
    }
  };
  write(a);
  if (b) write(*b);
}

// M[i][j] = (p M[i][j] - f M[k][j]) / prev for j in [from, width)
inline void bareiss_row(std::vector<mpz_class>& row, const std::vector<mpz_class>& pivot_row, const mpz_class& p,
                        const mpz_class& f, const mpz_class& prev, std::size_t from, mpz_class& t) {
  const bool unit = mpz_cmp_ui(prev.get_mpz_t(), 1) == 0;
  for (std::size_t j = from; j < row.size(); ++j) {
    mpz_class& e = row[j];
    if (sgn(f) == 0 || sgn(pivot_row[j]) == 0) {
      if (sgn(e) == 0) continue;
      mpz_mul(t.get_mpz_t(), p.get_mpz_t(), e.get_mpz_t());
    } else {
      mpz_mul(t.get_mpz_t(), p.get_mpz_t(), e.get_mpz_t());
      mpz_submul(t.get_mpz_t(), f.get_mpz_t(), pivot_row[j].get_mpz_t());
    }
    if (unit) mpz_swap(e.get_mpz_t(), t.get_mpz_t());
    else mpz_divexact(e.get_mpz_t(), t.get_mpz_t(), prev.get_mpz_t());
  }
}

}  // namespace fraction_free_detail

/// X with A X = B (A n x n, B n rows of m entries), exactly; none when A is singular — the
/// answers of rational Gauss–Jordan elimination (held_force_sign.hpp's solve), by fraction-free
/// Gauss–Jordan elimination in integers (see above).
inline std::optional<std::vector<std::vector<Rational>>> fraction_free_solve(const std::vector<std::vector<Rational>>& A,
                                                                             const std::vector<std::vector<Rational>>& B) {
  using fraction_free_detail::IntegerMatrix;
  const std::size_t n = A.size();
  const std::size_t m = n > 0 ? B[0].size() : 0;
  ++fraction_free_eliminations();
  IntegerMatrix M(n);
  for (std::size_t i = 0; i < n; ++i) fraction_free_detail::integer_row(A[i], &B[i], M[i]);
  mpz_class prev = 1, f, t;
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t r = k;
    while (r < n && sgn(M[r][k]) == 0) ++r;
    if (r == n) return std::nullopt;
    std::swap(M[k], M[r]);
    const mpz_class& p = M[k][k];
    for (std::size_t i = 0; i < n; ++i) {
      if (i == k) continue;
      f = M[i][k];
      fraction_free_detail::bareiss_row(M[i], M[k], p, f, prev, k + 1, t);
      M[i][k] = 0;
      if (i < k) M[i][i] = p;   // (was prev: the earlier pivots all become the new minor)
    }
    prev = p;
  }
  // every pivot is now the determinant d of the row-scaled matrix, the right-hand sides d X
  std::vector<std::vector<Rational>> X(n, std::vector<Rational>(m));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      Rational& x = X[i][j];
      mpz_set(x.get_num_mpz_t(), M[i][n + j].get_mpz_t());
      mpz_set(x.get_den_mpz_t(), prev.get_mpz_t());
      x.canonicalize();
    }
  return X;
}

/// exact_elimination.hpp's row_echelon (forward elimination over the first `columns` columns,
/// later entries carried, the pivot the first nonzero entry from the current row down; the
/// pivot columns returned) in integers: E's rows become nonzero integer multiples of the rows
/// rational elimination leaves (see above). Every row of E must be at least as long as the one
/// above it is read (as row_echelon requires).
inline std::vector<std::size_t> fraction_free_echelon(std::vector<std::vector<Rational>>& E, std::size_t columns) {
  using fraction_free_detail::IntegerMatrix;
  const std::size_t k = E.size();
  ++fraction_free_eliminations();
  IntegerMatrix M(k);
  for (std::size_t i = 0; i < k; ++i) fraction_free_detail::integer_row(E[i], nullptr, M[i]);
  std::vector<std::size_t> pivot_column;
  mpz_class prev = 1, f, t;
  std::size_t row = 0;
  for (std::size_t c = 0; c < columns && row < k; ++c) {
    std::size_t r = row;
    while (r < k && sgn(M[r][c]) == 0) ++r;
    if (r == k) continue;
    std::swap(M[r], M[row]);
    const mpz_class& p = M[row][c];
    for (std::size_t i = row + 1; i < k; ++i) {
      f = M[i][c];
      fraction_free_detail::bareiss_row(M[i], M[row], p, f, prev, c + 1, t);
      M[i][c] = 0;
    }
    pivot_column.push_back(c);
    prev = p;
    ++row;
  }
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < M[i].size(); ++j) E[i][j] = Rational(M[i][j]);
  return pivot_column;
}

}  // namespace hipair::simulation
