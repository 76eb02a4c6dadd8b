#include "algebra/polynomial.hpp"
#include "algebra/content.hpp"

#include "kernels/weights.hpp"

#include <algorithm>

namespace hipair::cspace {

// ---------------------------------------------------------------- IntegerPolynomial2

int IntegerPolynomial2::degree_x() const noexcept {
  for (int i = static_cast<int>(coefficients.size()) - 1; i >= 0; --i)
    for (const mpz_class& c : coefficients[static_cast<std::size_t>(i)])
      if (sgn(c) != 0) return i;
  return -1;
}

int IntegerPolynomial2::degree_y() const noexcept {
  int degree = -1;
  for (const auto& row : coefficients)
    for (int j = static_cast<int>(row.size()) - 1; j > degree; --j)
      if (sgn(row[static_cast<std::size_t>(j)]) != 0) {
        degree = j;
        break;
      }
  return degree;
}

bool IntegerPolynomial2::is_zero() const { return degree_x() < 0; }

Rational evaluate(const IntegerPolynomial2& polynomial, const Rational& x, const Rational& y) {
  Rational total = 0;
  for (std::size_t i = polynomial.coefficients.size(); i-- > 0;) {
    const auto& row = polynomial.coefficients[i];
    Rational row_value = 0;
    for (std::size_t j = row.size(); j-- > 0;) row_value = row_value * y + Rational(row[j]);
    total = total * x + row_value;
  }
  return total;
}

bool depends_only_on_x(const IntegerPolynomial2& polynomial) { return polynomial.degree_y() <= 0; }
bool depends_only_on_y(const IntegerPolynomial2& polynomial) { return polynomial.degree_x() <= 0; }

namespace {

// The (1 + t^2) normalisation is the kernels' (kernels/weights.hpp).
bool divide_by_one_plus_x_squared(std::vector<std::vector<mpz_class>>& c) { return kernels::divide_by_half_angle_weight(c); }

std::vector<std::vector<mpz_class>> transposed(const std::vector<std::vector<mpz_class>>& c) {
  std::size_t columns = 0;
  for (const auto& row : c) columns = std::max(columns, row.size());
  std::vector<std::vector<mpz_class>> t(columns, std::vector<mpz_class>(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) t[j][i] = c[i][j];
  return t;
}

void trim(std::vector<std::vector<mpz_class>>& c) {
  for (auto& row : c)
    while (!row.empty() && sgn(row.back()) == 0) row.pop_back();
  while (!c.empty() && c.back().empty()) c.pop_back();
}

}  // namespace

void normalize(IntegerPolynomial2& polynomial) {
  auto& c = polynomial.coefficients;
  trim(c);
  if (c.empty()) return;
  const mpz_class content = algebra::smallest_first_content([&](auto visit) {
    for (const auto& row : c)
      for (const mpz_class& v : row) visit(v.get_mpz_t());
  });
  if (content > 1)
    for (auto& row : c)
      for (mpz_class& v : row) mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), content.get_mpz_t());
  // Pad rows to a rectangle for the divisions, then trim again.
  while (divide_by_one_plus_x_squared(c)) trim(c);
  // (the transpose only when (1 + y^2) divides: the same division, no copies otherwise)
  if (kernels::half_angle_weight_divides_y(c)) {
    auto t = transposed(c);
    bool divided = false;
    while (divide_by_one_plus_x_squared(t)) {
      trim(t);
      divided = true;
    }
    if (divided) c = transposed(t);
  }
  trim(c);
}

// ---------------------------------------------------------------- RationalPolynomial2

RationalPolynomial2::RationalPolynomial2(int constant) : RationalPolynomial2(Rational(constant)) {}

RationalPolynomial2::RationalPolynomial2(const Rational& constant) {
  if (sgn(constant) != 0) {
    resize(1, 1);
    numerators_[0] = constant.get_num();
    denominator_ = constant.get_den();
  }
}

RationalPolynomial2 RationalPolynomial2::variable(int which) {
  RationalPolynomial2 p;
  if (which == 0) {
    p.resize(2, 1);
  } else {
    p.resize(1, 2);
  }
  p.numerators_[1] = 1;
  return p;
}

const mpz_class& RationalPolynomial2::numerator(int i, int j) const {
  static const mpz_class zero = 0;
  if (i < 0 || j < 0 || i >= rows_ || j >= columns_) return zero;
  return numerators_[static_cast<std::size_t>(i * columns_ + j)];
}

Rational RationalPolynomial2::coefficient(int i, int j) const {
  Rational value(numerator(i, j), denominator_);
  value.canonicalize();
  return value;
}

void RationalPolynomial2::set_coefficient(int i, int j, const Rational& value) {
  if (i >= rows_ || j >= columns_) resize(std::max(rows_, i + 1), std::max(columns_, j + 1));
  // bring everything over lcm(denominator, value's denominator)
  mpz_class common;
  mpz_lcm(common.get_mpz_t(), denominator_.get_mpz_t(), value.get_den_mpz_t());
  if (common != denominator_) {
    mpz_class factor = common / denominator_;
    for (mpz_class& n : numerators_) n *= factor;
    denominator_ = common;
  }
  numerators_[static_cast<std::size_t>(i * columns_ + j)] = value.get_num() * (common / value.get_den());
  trim();
}

void RationalPolynomial2::resize(int rows, int columns) {
  if (rows == rows_ && columns == columns_) return;
  std::vector<mpz_class> next(static_cast<std::size_t>(rows * columns));
  for (int i = 0; i < std::min(rows, rows_); ++i)
    for (int j = 0; j < std::min(columns, columns_); ++j)
      next[static_cast<std::size_t>(i * columns + j)] =
          std::move(numerators_[static_cast<std::size_t>(i * columns_ + j)]);
  numerators_ = std::move(next);
  rows_ = rows;
  columns_ = columns;
}

void RationalPolynomial2::trim() {
  int rows = 0;
  int columns = 0;
  for (int i = 0; i < rows_; ++i)
    for (int j = 0; j < columns_; ++j)
      if (sgn(numerators_[static_cast<std::size_t>(i * columns_ + j)]) != 0) {
        rows = std::max(rows, i + 1);
        columns = std::max(columns, j + 1);
      }
  resize(rows, columns);
  if (rows == 0) denominator_ = 1;
}

Rational RationalPolynomial2::evaluate(const Rational& x, const Rational& y) const {
  Rational total = 0;
  for (int i = rows_; i-- > 0;) {
    Rational row_value = 0;
    for (int j = columns_; j-- > 0;) row_value = row_value * y + Rational(numerator(i, j));
    total = total * x + row_value;
  }
  total /= Rational(denominator_);
  return total;
}

// a + sign b (sign +1 or -1): the numerators over the lcm of the denominators. Equal
// denominators (the common case: the kernels' sums of products of the same poses) are summed
// as they stand, without the products by a scale of 1; the values, hence the polynomial and
// its representation, are those of a + b and a + (-b).
RationalPolynomial2 RationalPolynomial2::combine(const RationalPolynomial2& a, const RationalPolynomial2& b, int sign) {
  RationalPolynomial2 r;
  r.resize(std::max(a.rows_, b.rows_), std::max(a.columns_, b.columns_));
  auto at = [&r](int i, int j) -> mpz_ptr {
    return r.numerators_[static_cast<std::size_t>(i * r.columns_ + j)].get_mpz_t();
  };
  if (a.denominator_ == b.denominator_) {
    r.denominator_ = a.denominator_;
    for (int i = 0; i < a.rows_; ++i)
      for (int j = 0; j < a.columns_; ++j)
        mpz_set(at(i, j), a.numerators_[static_cast<std::size_t>(i * a.columns_ + j)].get_mpz_t());
    for (int i = 0; i < b.rows_; ++i)
      for (int j = 0; j < b.columns_; ++j) {
        mpz_srcptr term = b.numerators_[static_cast<std::size_t>(i * b.columns_ + j)].get_mpz_t();
        if (sign > 0)
          mpz_add(at(i, j), at(i, j), term);
        else
          mpz_sub(at(i, j), at(i, j), term);
      }
  } else {
    mpz_class scale_a, scale_b;
    mpz_lcm(r.denominator_.get_mpz_t(), a.denominator_.get_mpz_t(), b.denominator_.get_mpz_t());
    mpz_divexact(scale_a.get_mpz_t(), r.denominator_.get_mpz_t(), a.denominator_.get_mpz_t());
    mpz_divexact(scale_b.get_mpz_t(), r.denominator_.get_mpz_t(), b.denominator_.get_mpz_t());
    for (int i = 0; i < a.rows_; ++i)
      for (int j = 0; j < a.columns_; ++j)
        mpz_mul(at(i, j), a.numerators_[static_cast<std::size_t>(i * a.columns_ + j)].get_mpz_t(),
                scale_a.get_mpz_t());
    for (int i = 0; i < b.rows_; ++i)
      for (int j = 0; j < b.columns_; ++j) {
        mpz_srcptr term = b.numerators_[static_cast<std::size_t>(i * b.columns_ + j)].get_mpz_t();
        if (sign > 0)
          mpz_addmul(at(i, j), term, scale_b.get_mpz_t());
        else
          mpz_submul(at(i, j), term, scale_b.get_mpz_t());
      }
  }
  r.trim();
  return r;
}

RationalPolynomial2 operator+(const RationalPolynomial2& a, const RationalPolynomial2& b) {
  if (a.is_zero()) return b;
  if (b.is_zero()) return a;
  return RationalPolynomial2::combine(a, b, 1);
}

RationalPolynomial2 operator-(const RationalPolynomial2& a) {
  RationalPolynomial2 r = a;
  for (mpz_class& c : r.numerators_) mpz_neg(c.get_mpz_t(), c.get_mpz_t());
  return r;
}

RationalPolynomial2 operator-(const RationalPolynomial2& a, const RationalPolynomial2& b) {
  if (b.is_zero()) return a;
  if (a.is_zero()) return -b;
  return RationalPolynomial2::combine(a, b, -1);
}

RationalPolynomial2 operator*(const RationalPolynomial2& a, const RationalPolynomial2& b) {
  RationalPolynomial2 r;
  if (a.is_zero() || b.is_zero()) return r;
  r.resize(a.rows_ + b.rows_ - 1, a.columns_ + b.columns_ - 1);
  mpz_mul(r.denominator_.get_mpz_t(), a.denominator_.get_mpz_t(), b.denominator_.get_mpz_t());
  for (int i = 0; i < a.rows_; ++i)
    for (int j = 0; j < a.columns_; ++j) {
      const mpz_class& ac = a.numerators_[static_cast<std::size_t>(i * a.columns_ + j)];
      if (sgn(ac) == 0) continue;
      for (int k = 0; k < b.rows_; ++k)
        for (int l = 0; l < b.columns_; ++l) {
          const mpz_class& bc = b.numerators_[static_cast<std::size_t>(k * b.columns_ + l)];
          if (sgn(bc) == 0) continue;
          mpz_class& target = r.numerators_[static_cast<std::size_t>((i + k) * r.columns_ + j + l)];
          mpz_addmul(target.get_mpz_t(), ac.get_mpz_t(), bc.get_mpz_t());
        }
    }
  // (no trim: a and b are trimmed — every value of this type is — so their last rows A(y),
  // B(y) are non-zero polynomials and the product's last row A(y) B(y) is non-zero; the same
  // for the last columns)
  return r;
}

bool operator==(const RationalPolynomial2& a, const RationalPolynomial2& b) {
  if (a.rows_ != b.rows_ || a.columns_ != b.columns_) return false;
  for (int i = 0; i < a.rows_; ++i)
    for (int j = 0; j < a.columns_; ++j)
      if (a.coefficient(i, j) != b.coefficient(i, j)) return false;
  return true;
}

IntegerPolynomial2 normalized_integer_polynomial(const RationalPolynomial2& polynomial) {
  // The denominator is positive: the numerators alone have the same zero set and sign.
  IntegerPolynomial2 result;
  if (polynomial.is_zero()) return result;
  result.coefficients.assign(static_cast<std::size_t>(polynomial.rows()),
                             std::vector<mpz_class>(static_cast<std::size_t>(polynomial.columns())));
  for (int i = 0; i < polynomial.rows(); ++i)
    for (int j = 0; j < polynomial.columns(); ++j)
      result.coefficients[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
          polynomial.numerator(i, j);
  normalize(result);
  return result;
}

}  // namespace hipair::cspace
