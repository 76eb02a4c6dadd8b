#include "algebra/exact_real.hpp"
#include "algebra/content.hpp"
#include "algebra/interval_shift.hpp"
#include "algebra/interval_times.hpp"
#include "algebra/modular_gcd.hpp"
#include "algebra/multiprecision_sign.hpp"
#include "algebra/ordinate.hpp"
#include "algebra/real_approximation.hpp"
#include "algebra/near_quotient.hpp"
#include "algebra/rational_root.hpp"
#include "algebra/rational_order.hpp"
#include "algebra/real_filters.hpp"
#include "algebra/simplest_small.hpp"
#include "algebra/square_free_memo.hpp"

#include <hipair/error.hpp>

#include <mpfr.h>

#include <algorithm>
#include <charconv>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <unordered_map>

namespace hipair::cspace::algebra {

// ---------------------------------------------------------------- univariate basics

int degree(const Polynomial& p) { return static_cast<int>(p.size()) - 1; }

void trim(Polynomial& p) {
  while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

Polynomial derivative(const Polynomial& p) {
  Polynomial d;
  for (std::size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * static_cast<unsigned long>(i));
  trim(d);
  return d;
}

namespace {

// Memos of pure functions of polynomials, per thread (below: gcd, square_free_part,
// square_free_test), keyed by the coefficients.
struct PolynomialHash {
  std::size_t operator()(const Polynomial& p) const noexcept {
    std::size_t h = p.size();
    for (const mpz_class& c : p) {
      const mpz_srcptr z = c.get_mpz_t();
      h = h * 1000003u ^ static_cast<std::size_t>(z->_mp_size);
      const std::size_t limbs = mpz_size(z);
      for (std::size_t i = 0; i < limbs; ++i) h = h * 1000003u ^ static_cast<std::size_t>(mpz_getlimbn(z, static_cast<mp_size_t>(i)));
    }
    return h;
  }
};

// Two polynomials in order (gcd's arguments), compared coefficient by coefficient.
struct PolynomialPairHash {
  std::size_t operator()(const std::pair<Polynomial, Polynomial>& key) const noexcept {
    const PolynomialHash hash;
    return hash(key.first) * 0x9E3779B97F4A7C15ULL ^ hash(key.second);
  }
};

// The words a polynomial holds (its coefficients' limbs, and one for each coefficient).
std::size_t words_of(const Polynomial& p) {
  std::size_t words = p.size();
  for (const mpz_class& c : p) words += mpz_size(c.get_mpz_t());
  return words;
}
std::size_t words_of(const std::pair<Polynomial, Polynomial>& p) { return words_of(p.first) + words_of(p.second); }

// A per-thread memo: keys and values, and the words they hold.
template <class Key, class Hash>
struct BoundedMemo {
  using key_type = Key;
  std::unordered_map<Key, Polynomial, Hash> map;
  std::size_t words = 0;
};
using PolynomialMemo = BoundedMemo<Polynomial, PolynomialHash>;
using PolynomialPairMemo = BoundedMemo<std::pair<Polynomial, Polynomial>, PolynomialPairHash>;

// compute()'s value for `key`, looked up in `memo` first and remembered there (emptied when it
// holds 4,096 entries or 2^21 words, 16 MB: a few polynomials of huge coefficients do not fill
// a thread's memory). compute must be a pure function of key.
template <class Memo, class Compute>
Polynomial remembered(Memo& memo, const typename Memo::key_type& key, Compute compute) {
  constexpr std::size_t capacity = 4096, word_budget = std::size_t{1} << 21;
  auto found = memo.map.find(key);
  if (found != memo.map.end()) return found->second;
  Polynomial value = compute();
  const std::size_t words = words_of(key) + words_of(value);
  if (memo.map.size() >= capacity || memo.words + words > word_budget) {
    memo.map.clear();
    memo.words = 0;
  }
  if (words <= word_budget) {
    memo.map.emplace(key, value);
    memo.words += words;
  }
  return value;
}

// The sign of Sum a_i n^i d^(deg-i), the value times d^deg (d > 0): the sign of p(n/d).
// Horner on integers held in per-thread scratch integers that keep their storage from call to
// call (GMP grows them as needed; no allocation once they are large enough), products written
// to a second integer (an aliased mpz_mul copies). When d is a power of two 2^e (the
// bisections' midpoints, every dyadic end) the powers of d are shifts: a_i d^(deg-i) =
// a_i << e (deg-i), no multiplication. The same integer either way, hence the same sign.
struct HornerScratch {
  mpz_t result, product, term, d_power;
  HornerScratch() {
    mpz_init(result);
    mpz_init(product);
    mpz_init(term);
    mpz_init(d_power);
  }
  ~HornerScratch() {
    mpz_clear(result);
    mpz_clear(product);
    mpz_clear(term);
    mpz_clear(d_power);
  }
  HornerScratch(const HornerScratch&) = delete;
  HornerScratch& operator=(const HornerScratch&) = delete;
};

int homogeneous_sign(const Polynomial& p, const mpz_class& n, const mpz_class& d) {
  if (p.empty()) return 0;
  const int deg = degree(p);
  if (deg == 0) return sgn(p.back());
  thread_local HornerScratch scratch;
  mpz_ptr result = scratch.result, product = scratch.product, term = scratch.term;
  mpz_set(result, p.back().get_mpz_t());
  const std::size_t d_bits = mpz_sizeinbase(d.get_mpz_t(), 2);
  const bool dyadic = sgn(d) > 0 && mpz_scan1(d.get_mpz_t(), 0) == d_bits - 1;
  if (dyadic) {
    const mp_bitcnt_t e = d_bits - 1;
    for (int i = deg - 1; i >= 0; --i) {
      mpz_mul(product, result, n.get_mpz_t());
      const mpz_class& a = p[static_cast<std::size_t>(i)];
      if (sgn(a) == 0) {
        mpz_swap(result, product);
        continue;
      }
      mpz_mul_2exp(term, a.get_mpz_t(), e * static_cast<mp_bitcnt_t>(deg - i));
      mpz_add(result, product, term);
    }
    return mpz_sgn(result);
  }
  mpz_ptr d_power = scratch.d_power;
  mpz_set_ui(d_power, 1);
  for (int i = deg - 1; i >= 0; --i) {
    mpz_mul(term, d_power, d.get_mpz_t());
    mpz_swap(d_power, term);
    mpz_mul(product, result, n.get_mpz_t());
    mpz_addmul(product, p[static_cast<std::size_t>(i)].get_mpz_t(), d_power);
    mpz_swap(result, product);
  }
  return mpz_sgn(result);
}

mpz_class content(const Polynomial& p) {
  return smallest_first_content([&](auto visit) {
    for (const mpz_class& c : p) visit(c.get_mpz_t());
  });
}

// Pseudo-remainder a = q b + r scaled so that the scale factor is positive:
// returns r' = s * rem(a, b) with s > 0.
Polynomial positive_pseudo_remainder(Polynomial a, const Polynomial& b) {
  const int db = degree(b);
  const mpz_class& lb = b.back();
  int steps = 0;
  while (degree(a) >= db && !a.empty()) {
    const int shift = degree(a) - db;
    mpz_class la = a.back();
    for (auto& c : a) c *= lb;
    for (int i = 0; i <= db; ++i) a[static_cast<std::size_t>(i + shift)] -= la * b[static_cast<std::size_t>(i)];
    trim(a);
    ++steps;
  }
  if (sgn(lb) < 0 && steps % 2 == 1)
    for (auto& c : a) c = -c;
  return a;
}

}  // namespace

int sign_at(const Polynomial& p, const Rational& x) {
  return homogeneous_sign(p, x.get_num(), x.get_den());
}

Rational value_at(const Polynomial& p, const Rational& x) {
  Rational result = 0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) result = result * x + Rational(*it);
  return result;
}

Polynomial primitive_part(const Polynomial& p) {
  Polynomial q = p;
  trim(q);
  if (q.empty()) return q;
  mpz_class g = content(q);
  if (sgn(q.back()) < 0) g = -g;
  if (g == 1) return q;   // already primitive, leading coefficient positive (a division by 1 changes nothing)
  for (auto& c : q) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
  return q;
}

namespace {

// Arithmetic modulo a prime below 2^31: products fit in 64 bits.
using Residues = std::vector<std::uint64_t>;

std::uint64_t power_mod(std::uint64_t base, std::uint64_t exponent, std::uint64_t prime) {
  std::uint64_t result = 1;
  base %= prime;
  while (exponent > 0) {
    if (exponent & 1) result = result * base % prime;
    base = base * base % prime;
    exponent >>= 1;
  }
  return result;
}

void trim_residues(Residues& a) {
  while (!a.empty() && a.back() == 0) a.pop_back();
}

// A gcd of a and b modulo the prime (Euclid's last non-zero remainder, not made monic); empty
// when both are zero.
Residues modular_euclid(Residues a, Residues b, std::uint64_t prime) {
  trim_residues(a);
  trim_residues(b);
  if (a.size() < b.size()) std::swap(a, b);
  while (!b.empty()) {
    // a <- a mod b
    const std::uint64_t inverse = power_mod(b.back(), prime - 2, prime);
    while (a.size() >= b.size()) {
      const std::uint64_t factor = a.back() * inverse % prime;
      const std::size_t shift = a.size() - b.size();
      for (std::size_t i = 0; i < b.size(); ++i)
        a[shift + i] = (a[shift + i] + (prime - factor) * b[i]) % prime;
      trim_residues(a);   // the leading residue is now 0
      if (a.empty()) break;
    }
    std::swap(a, b);
  }
  return a;
}

// Degree of gcd(a, b) modulo the prime (Euclid); -1 when both are zero.
int modular_gcd_degree(Residues a, Residues b, std::uint64_t prime) {
  return static_cast<int>(modular_euclid(std::move(a), std::move(b), prime).size()) - 1;
}

// The residues of p's coefficients modulo the prime.
Residues residues(const Polynomial& p, std::uint64_t prime) {
  Residues r;
  r.reserve(p.size());
  for (const mpz_class& c : p) r.push_back(mpz_fdiv_ui(c.get_mpz_t(), static_cast<unsigned long>(prime)));
  return r;
}

// Primes below 2^31, descending from 2^31 - 1 (deterministic Miller-Rabin: the bases 2, 7
// and 61 decide every n < 4 759 123 141), made once: the moduli of the modular gcd.
bool prime_below_2_31(std::uint64_t n) {
  if (n < 2) return false;
  for (std::uint64_t p : {2u, 3u, 5u, 7u, 11u, 13u, 61u})
    if (n % p == 0) return n == p;
  std::uint64_t d = n - 1;
  int s = 0;
  while (d % 2 == 0) {
    d /= 2;
    ++s;
  }
  for (std::uint64_t a : {2u, 7u, 61u}) {
    std::uint64_t x = power_mod(a, d, n);
    if (x == 1 || x == n - 1) continue;
    bool composite = true;
    for (int r = 1; r < s && composite; ++r) {
      x = x * x % n;
      composite = x != n - 1;
    }
    if (composite) return false;
  }
  return true;
}

constexpr std::size_t modular_gcd_primes = 96;

const std::vector<std::uint64_t>& gcd_primes() {
  static const std::vector<std::uint64_t> primes = [] {
    std::vector<std::uint64_t> out;
    for (std::uint64_t n = 2147483647ULL; out.size() < modular_gcd_primes; n -= 2)
      if (prime_below_2_31(n)) out.push_back(n);
    return out;
  }();
  return primes;
}

// Does the primitive g (positive leading coefficient, degree >= 1) divide p in Z[x]? Exact
// division: by Gauss's lemma a quotient of p by a primitive divisor is integral, so a step
// whose leading coefficient lc(g) does not divide has no integral quotient, and g divides p
// exactly when every step divides and the remainder is zero.
bool divides_exactly(const Polynomial& g, Polynomial r) {
  const int dg = degree(g);
  const mpz_srcptr lg = g.back().get_mpz_t();
  mpz_class c;
  for (int k = degree(r) - dg; k >= 0; --k) {
    const mpz_ptr top = r[static_cast<std::size_t>(k + dg)].get_mpz_t();
    if (!mpz_divisible_p(top, lg)) return false;
    mpz_divexact(c.get_mpz_t(), top, lg);
    for (int i = 0; i <= dg; ++i)
      mpz_submul(r[static_cast<std::size_t>(k + i)].get_mpz_t(), c.get_mpz_t(), g[static_cast<std::size_t>(i)].get_mpz_t());
  }
  return std::all_of(r.begin(), r.end(), [](const mpz_class& v) { return sgn(v) == 0; });
}

// The primitive gcd of the primitive x and y (degrees >= 1, positive leading coefficients) by
// Brown's modular algorithm, or nullopt (then the remainder sequence decides): the monic gcds
// modulo primes that divide neither leading coefficient, times h = gcd(lc x, lc y), combined by
// the Chinese remainder theorem over the primes of the least degree seen, in the symmetric
// range. The answer is checked, not trusted: a candidate G (the primitive part of the combined
// images, tried once the images stop changing) that divides x and y exactly divides their gcd
// D, while deg G, the least modular degree, is >= deg D (D's reduction divides each modular
// gcd and keeps its degree: the primes divide no leading coefficient, and lc D divides lc x).
// So G = D up to sign, and both are primitive with a positive leading coefficient: G is the
// remainder sequence's answer, bit for bit. A modular degree 0 proves deg D = 0 (D = 1).
std::optional<Polynomial> modular_gcd(const Polynomial& x, const Polynomial& y) {
  mpz_class h;
  mpz_gcd(h.get_mpz_t(), x.back().get_mpz_t(), y.back().get_mpz_t());
  int least = std::min(degree(x), degree(y)) + 1;   // no prime used yet
  std::vector<mpz_class> combined;                  // the images combined, in [0, modulus)
  mpz_class modulus = 1, half, step;
  bool unchanged = false, tried = false;
  for (std::uint64_t prime : gcd_primes()) {
    const auto p = static_cast<unsigned long>(prime);
    if (mpz_fdiv_ui(x.back().get_mpz_t(), p) == 0 || mpz_fdiv_ui(y.back().get_mpz_t(), p) == 0) continue;
    Residues g = modular_euclid(residues(x, prime), residues(y, prime), prime);
    const int d = static_cast<int>(g.size()) - 1;
    if (d == 0) return Polynomial{mpz_class(1)};
    if (d > least) continue;   // an unlucky prime: the gcd's reduction is a proper divisor
    // h times the monic gcd modulo the prime
    const std::uint64_t scale = mpz_fdiv_ui(h.get_mpz_t(), p) * power_mod(g.back(), prime - 2, prime) % prime;
    for (auto& c : g) c = c * scale % prime;
    if (d < least) {   // the first prime, or every earlier one was unlucky: start again
      least = d;
      combined.assign(g.size(), mpz_class(0));
      for (std::size_t k = 0; k < g.size(); ++k) combined[k] = static_cast<unsigned long>(g[k]);
      modulus = p;
      mpz_fdiv_q_2exp(half.get_mpz_t(), modulus.get_mpz_t(), 1);
      unchanged = tried = false;
      continue;
    }
    // combine: v + modulus * ((r - v) / modulus mod prime), and whether the symmetric
    // representative already had this image
    const std::uint64_t modulus_residue = mpz_fdiv_ui(modulus.get_mpz_t(), p);
    const std::uint64_t inverse = power_mod(modulus_residue, prime - 2, prime);
    unchanged = true;
    for (std::size_t k = 0; k < g.size(); ++k) {
      mpz_class& v = combined[k];
      const std::uint64_t v_residue = mpz_fdiv_ui(v.get_mpz_t(), p);
      const std::uint64_t symmetric =
          mpz_cmp(v.get_mpz_t(), half.get_mpz_t()) <= 0 ? v_residue : (v_residue + prime - modulus_residue) % prime;
      if (symmetric != g[k]) unchanged = false;
      const std::uint64_t t = (g[k] + prime - v_residue) % prime * inverse % prime;
      mpz_mul_ui(step.get_mpz_t(), modulus.get_mpz_t(), static_cast<unsigned long>(t));
      v += step;
    }
    mpz_mul_ui(modulus.get_mpz_t(), modulus.get_mpz_t(), p);
    mpz_fdiv_q_2exp(half.get_mpz_t(), modulus.get_mpz_t(), 1);
    if (!unchanged) tried = false;
    if (!unchanged || tried) continue;
    tried = true;   // the same candidate again only after an image changes it
    Polynomial candidate(combined.size());
    for (std::size_t k = 0; k < combined.size(); ++k) {
      candidate[k] = combined[k];
      if (combined[k] > half) candidate[k] -= modulus;
    }
    candidate = primitive_part(candidate);
    if (degree(candidate) == least && divides_exactly(candidate, x) && divides_exactly(candidate, y)) return candidate;
  }
  return std::nullopt;
}

// The primitive gcd: by the modular algorithm where it answers, else by the primitive
// polynomial remainder sequence. a_primitive: the caller knows a is primitive with a positive
// leading coefficient (primitive_part(a) = a: its content is not computed again).
Polynomial exact_gcd(const Polynomial& a, const Polynomial& b, bool a_primitive = false) {
  Polynomial x = a_primitive ? a : primitive_part(a), y = primitive_part(b);
  if (x.empty()) return y;
  if (y.empty()) return x;
  if (degree(x) < degree(y)) std::swap(x, y);
  // (a linear or constant argument: a step or two of the sequence, cheaper than the primes;
  // coefficients beyond 1 400 bits, the x 10^400 models': the gcd's images, h times the gcd with
  // up to about twice their bits, would not fit the product of the 96 moduli, 2 976 bits, and
  // the primes would be spent for nothing)
  auto widest = [](const Polynomial& p) {
    std::size_t bits = 0;
    for (const mpz_class& c : p) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
    return bits;
  };
  if (degree(y) >= 2 && modular_gcd_enabled().load(std::memory_order_relaxed) && widest(x) <= 1400 &&
      widest(y) <= 1400)
    if (std::optional<Polynomial> g = modular_gcd(x, y)) {
      modular_gcd_answers().fetch_add(1, std::memory_order_relaxed);
      return std::move(*g);
    }
  while (!y.empty()) {
    Polynomial r = primitive_part(positive_pseudo_remainder(x, y));
    x = std::move(y);
    y = std::move(r);
  }
  return primitive_part(x);
}

}  // namespace

std::atomic<bool>& modular_gcd_enabled() {
  static std::atomic<bool> on{true};
  return on;
}

std::atomic<std::size_t>& modular_gcd_answers() {
  static std::atomic<std::size_t> answers{0};
  return answers;
}

// The same gcds come back again and again: the overlapping cut abscissae of the quadratic
// traits (common_root_in_overlap) and the square-free parts of the same resultants in every
// tile of a chart (on a 6 x 9 gears' operating region 3,916 gcds of 1,851 distinct pairs). The
// value is a pure function of the pair (compared coefficient by coefficient), so a hit returns
// exactly what exact_gcd would. Bounded (remembered's capacity).
namespace {

PolynomialPairMemo& gcd_memo() {
  thread_local PolynomialPairMemo memo;
  return memo;
}

// square_free_part(q) of a primitive q with a positive leading coefficient (q's content not
// computed again, here or in the gcd).
Polynomial square_free_part_of_primitive(const Polynomial& q) {
  if (degree(q) <= 1) return q;
  const Polynomial d = derivative(q);
  // gcd(q, d): the same memo and value as gcd()'s
  Polynomial g = remembered(gcd_memo(), std::pair<Polynomial, Polynomial>(q, d), [&] { return exact_gcd(q, d, true); });
  if (degree(g) == 0) return q;
  // exact division q / g
  Polynomial quotient(static_cast<std::size_t>(degree(q) - degree(g) + 1));
  Polynomial remainder = q;
  const mpz_class& lg = g.back();
  for (int k = degree(q) - degree(g); k >= 0; --k) {
    mpz_class coefficient = remainder[static_cast<std::size_t>(k + degree(g))];
    // g is primitive and divides q over Q; by Gauss's lemma the quotient is integral.
    mpz_divexact(coefficient.get_mpz_t(), coefficient.get_mpz_t(), lg.get_mpz_t());
    quotient[static_cast<std::size_t>(k)] = coefficient;
    for (int i = 0; i <= degree(g); ++i)
      remainder[static_cast<std::size_t>(k + i)] -= coefficient * g[static_cast<std::size_t>(i)];
  }
  // primitive with a positive leading coefficient already: q = g quotient with q and g
  // primitive, so the quotient is primitive (Gauss's lemma: content(q) = content(g)
  // content(quotient)), and lc(quotient) = lc(q) / lc(g) > 0
  return quotient;
}

}  // namespace

Polynomial gcd(const Polynomial& a, const Polynomial& b) {
  return remembered(gcd_memo(), std::pair<Polynomial, Polynomial>(a, b), [&] { return exact_gcd(a, b); });
}

Polynomial square_free_part(const Polynomial& p) { return square_free_part_of_primitive(primitive_part(p)); }

Polynomial from_rationals(const std::vector<Rational>& coefficients) {
  mpz_class common = 1;
  for (const auto& c : coefficients) mpz_lcm(common.get_mpz_t(), common.get_mpz_t(), c.get_den_mpz_t());
  Polynomial p;
  for (const auto& c : coefficients) {
    mpz_class v = c.get_num() * (common / c.get_den());
    p.push_back(v);
  }
  return primitive_part(p);
}

std::string to_string(const Polynomial& p, const std::string& variable) {
  if (p.empty()) return "0";
  // written into one string (the JSON writer describes every vertex number by its polynomial):
  // the digits by mpz_get_str into the string's own storage, the magnitudes without a copy of
  // each coefficient
  std::string out;
  bool first = true;
  char exponent[16];
  for (int i = degree(p); i >= 0; --i) {
    const mpz_srcptr c = p[static_cast<std::size_t>(i)].get_mpz_t();
    const int sign = mpz_sgn(c);
    if (sign == 0) continue;
    if (first)
      out += sign < 0 ? "-" : "";
    else
      out += sign < 0 ? " - " : " + ";
    first = false;
    if (i == 0 || mpz_cmpabs_ui(c, 1) != 0) {
      // mpz_get_str writes c's digits after a '-' when c < 0 (sizeinbase may exceed the digits
      // by one; the terminating zero needs one more): the sign is dropped after
      const std::size_t start = out.size();
      out.resize(start + mpz_sizeinbase(c, 10) + 2);
      mpz_get_str(out.data() + start, 10, c);
      const std::size_t written = std::strlen(out.data() + start);
      if (sign < 0) out.erase(start, 1);
      out.resize(start + written - (sign < 0 ? 1 : 0));
      if (i > 0) out += '*';
    }
    if (i > 0) out += variable;
    if (i > 1) {
      out += '^';
      out.append(exponent, std::to_chars(exponent, exponent + sizeof exponent, i).ptr);
    }
  }
  return out;
}

namespace {

// sign(r - d) for a finite double d, exact, without forming a rational from d (mpq_set_d
// allocated and copied on every enclosure): d = m 2^e with an integer |m| < 2^53, and
// r - d has the sign of num - m 2^e den (den > 0), compared after multiplying both sides by
// 2^-e when e < 0. Per-thread scratch integers keep their storage.
int compare_with_double(const Rational& r, double d) {
  if (d == 0) return sgn(r);
  int exponent = 0;
  const double fraction = std::frexp(d, &exponent);   // d = fraction 2^exponent, 1/2 <= |fraction| < 1
  const auto m = static_cast<long>(std::ldexp(fraction, 53));   // exact: 53 significant bits at most
  const long e = static_cast<long>(exponent) - 53;
  struct Scratch {
    mpz_t left, right;
    Scratch() {
      mpz_init(left);
      mpz_init(right);
    }
    ~Scratch() {
      mpz_clear(left);
      mpz_clear(right);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
  };
  thread_local Scratch scratch;
  static_assert(sizeof(long) >= 8, "m needs 53 bits");
  mpz_mul_si(scratch.right, r.get_den_mpz_t(), m);   // m den
  int c = 0;
  if (e >= 0) {
    mpz_mul_2exp(scratch.right, scratch.right, static_cast<mp_bitcnt_t>(e));   // m 2^e den
    c = mpz_cmp(r.get_num_mpz_t(), scratch.right);
  } else {
    mpz_mul_2exp(scratch.left, r.get_num_mpz_t(), static_cast<mp_bitcnt_t>(-e));   // num 2^-e
    c = mpz_cmp(scratch.left, scratch.right);
  }
  return c < 0 ? -1 : c > 0 ? 1 : 0;
}

}  // namespace

double lower_double(const Rational& r) {
  double lower, upper;
  if (enclose_rational(r, lower, upper)) return lower;   // both parts within 53 bits
  double d = r.get_d();
  if (std::isinf(d)) return d > 0 ? std::numeric_limits<double>::max() : d;
  if (compare_with_double(r, d) < 0) d = std::nextafter(d, -std::numeric_limits<double>::infinity());   // d > r
  return d;
}

double upper_double(const Rational& r) {
  double lower, upper;
  if (enclose_rational(r, lower, upper)) return upper;
  double d = r.get_d();
  if (std::isinf(d)) return d < 0 ? std::numeric_limits<double>::lowest() : d;
  if (compare_with_double(r, d) > 0) d = std::nextafter(d, std::numeric_limits<double>::infinity());   // d < r
  return d;
}

// ---------------------------------------------------------------- Sturm sequences

SturmSequence::SturmSequence(const Polynomial& square_free) {
  Polynomial p = primitive_part(square_free);
  if (p.empty()) return;
  sequence_.push_back(p);
  Polynomial d = primitive_part(derivative(p));
  if (d.empty()) return;
  sequence_.push_back(d);
  while (degree(sequence_.back()) > 0) {
    Polynomial r = positive_pseudo_remainder(sequence_[sequence_.size() - 2], sequence_.back());
    if (r.empty()) break;
    for (auto& c : r) c = -c;
    mpz_class g = content(r);  // positive
    for (auto& c : r) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
    sequence_.push_back(std::move(r));
  }
}

int SturmSequence::variations(const Rational& x) const {
  int count = 0, previous = 0;
  for (const auto& p : sequence_) {
    int s = sign_at(p, x);
    if (s == 0) continue;
    if (previous != 0 && s != previous) ++count;
    previous = s;
  }
  return count;
}

int SturmSequence::variations_at_infinity(bool positive) const {
  int count = 0, previous = 0;
  for (const auto& p : sequence_) {
    int s = sgn(p.back());
    if (!positive && degree(p) % 2 == 1) s = -s;
    if (previous != 0 && s != previous) ++count;
    previous = s;
  }
  return count;
}

int SturmSequence::count(const Rational& a, const Rational& b) const {
  if (sequence_.empty() || !(a < b)) return 0;
  return variations(a) - variations(b);
}

int SturmSequence::count_up_to(const Rational& b) const {
  if (sequence_.empty()) return 0;
  return variations_at_infinity(false) - variations(b);
}

int SturmSequence::total() const {
  if (sequence_.empty()) return 0;
  return variations_at_infinity(false) - variations_at_infinity(true);
}

// ---------------------------------------------------------------- real algebraic numbers

Real Real::from_rational(const Rational& value) {
  Real r;
  // primitive_part of {-num, den}, written in place: divided by their gcd (content), whose sign
  // makes the leading coefficient positive (den != 0, so nothing is trimmed)
  r.polynomial.resize(2);
  mpz_class& c0 = r.polynomial[0];
  mpz_class& c1 = r.polynomial[1];
  mpz_neg(c0.get_mpz_t(), value.get_num_mpz_t());
  mpz_set(c1.get_mpz_t(), value.get_den_mpz_t());
  thread_local mpz_class g;
  mpz_gcd(g.get_mpz_t(), c0.get_mpz_t(), c1.get_mpz_t());
  if (sgn(c1) < 0) mpz_neg(g.get_mpz_t(), g.get_mpz_t());
  if (mpz_cmp_ui(g.get_mpz_t(), 1) != 0) {
    mpz_divexact(c0.get_mpz_t(), c0.get_mpz_t(), g.get_mpz_t());
    mpz_divexact(c1.get_mpz_t(), c1.get_mpz_t(), g.get_mpz_t());
  }
  r.lower = value;
  r.upper = value;
  r.exact = true;
  return r;
}

void Real::refine() {
  if (exact) return;
  Rational middle = (lower + upper) / 2;
  int s = sign_at(polynomial, middle);
  if (s == 0) {
    lower = upper = middle;
    exact = true;
    return;
  }
  if (s == sign_at(polynomial, lower))
    lower = middle;
  else
    upper = middle;
}

namespace {

// True when the denominator of r (positive) is a power of two, 1 included.
bool power_of_two_denominator(const Rational& r) {
  const mpz_srcptr den = r.get_den_mpz_t();
  return mpz_scan1(den, 0) + 1 == mpz_sizeinbase(den, 2);
}

// r.canonicalize(), without a gcd when the denominator is a power of two (then the common
// factor is the largest power of two dividing the numerator, up to the denominator).
void canonicalize(Rational& r) {
  if (!power_of_two_denominator(r)) {
    r.canonicalize();
    return;
  }
  mpz_ptr num = r.get_num_mpz_t();
  mpz_ptr den = r.get_den_mpz_t();
  if (mpz_sgn(num) == 0) {
    mpz_set_ui(den, 1);
    return;
  }
  mp_bitcnt_t shift = std::min(mpz_scan1(num, 0), mpz_sizeinbase(den, 2) - 1);
  mpz_tdiv_q_2exp(num, num, shift);   // exact: 2^shift divides the numerator
  mpz_tdiv_q_2exp(den, den, shift);
}

// A certified double filter for the sign of an integer polynomial at a point given by an
// interval enclosure: the coefficients scaled by one power of two (so that large ones stay
// finite; the sign does not change) and enclosed outwards, evaluated by interval Horner.
// Returns 0 when the enclosure of the value contains zero or is not finite: the caller then
// decides exactly.
class SignFilter {
 public:
  explicit SignFilter(const Polynomial& p) {
    std::size_t bits = 0;
    for (const mpz_class& c : p)
      if (sgn(c) != 0) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
    std::size_t shift = bits > 900 ? bits - 900 : 0;
    coefficients_.reserve(p.size());
    if (shift == 0) {
      // the bounds below for shift 0 (f = c), from one conversion and without a copy of c
      for (const mpz_class& c : p) {
        const double d = mpz_get_d(c.get_mpz_t());   // towards zero
        if (mpz_sizeinbase(c.get_mpz_t(), 2) <= 53)
          coefficients_.push_back({d, d});
        else if (sgn(c) > 0)
          coefficients_.push_back({d, std::nextafter(d, HUGE_VAL)});
        else
          coefficients_.push_back({std::nextafter(d, -HUGE_VAL), d});
      }
      return;
    }
    mpz_class floor_value;
    for (const mpz_class& c : p) {
      // c / 2^shift lies in [f, f + 1] for f = floor(c / 2^shift); mpz_get_d truncates
      // towards zero, so the double next to it away from zero bounds the other side
      mpz_fdiv_q_2exp(floor_value.get_mpz_t(), c.get_mpz_t(), shift);
      double lo = truncated_bound(floor_value, false);
      if (shift == 0) {
        coefficients_.push_back({lo, truncated_bound(floor_value, true)});
      } else {
        floor_value += 1;
        coefficients_.push_back({lo, truncated_bound(floor_value, true)});
      }
    }
  }
  // A double below (upper = false) or above z.
  static double truncated_bound(const mpz_class& z, bool upper) {
    double d = mpz_get_d(z.get_mpz_t());   // |d| <= |z|, towards zero
    if (mpz_sizeinbase(z.get_mpz_t(), 2) <= 53) return d;   // exact
    bool away = upper ? sgn(z) > 0 : sgn(z) < 0;
    return away ? std::nextafter(d, upper ? HUGE_VAL : -HUGE_VAL) : d;
  }
  /// p(x) and p'(x) in plain doubles from the coefficients' lower bounds (an approximation only,
  /// for a Newton iterate whose cell the certified sign() then checks); false when not finite.
  bool approximate_value(double x, double& value, double& slope) const {
    value = 0;
    slope = 0;
    for (auto c = coefficients_.rbegin(); c != coefficients_.rend(); ++c) {
      slope = slope * x + value;
      value = value * x + c->lo;
    }
    return std::isfinite(value) && std::isfinite(slope);
  }
  int sign(Interval x) const {
    if (coefficients_.empty()) return 0;
    const Interval value = horner_from_leading(coefficients_, x);
    if (!std::isfinite(value.lo) || !std::isfinite(value.hi)) return 0;
    if (value.lo > 0) return 1;
    if (value.hi < 0) return -1;
    return 0;
  }

 private:
  std::vector<Interval> coefficients_;
};

// A certified double enclosure [lo, hi] of a non-exact Real, narrowed by bisection in double
// arithmetic: a midpoint m certainly inside (lower, upper) (outside the enclosures of the
// ends) where the sign filter decides p(m) != 0 lies below the root when p(m) has the sign of
// p(lower) (the root is simple and the only one in the interval; the filter must certify
// opposite signs at the ends, else the exact path decides), else above. Bisection stops
// for good where the filter cannot decide, near an end, or when lo and hi are adjacent
// doubles. No exact arithmetic unless the filter cannot decide the sign at `lower` itself.
class DoubleBisection {
 public:
  explicit DoubleBisection(const Real& r)
      : filter_(r.polynomial), lower_box_(enclose(r.lower)), upper_box_(enclose(r.upper)) {
    lo_ = lower_box_.lo;
    hi_ = upper_box_.hi;
    stuck_ = !std::isfinite(lower_box_.hi) || !std::isfinite(upper_box_.lo);
    if (stuck_) return;
    lower_sign_ = filter_.sign(lower_box_);
    if (lower_sign_ == 0) lower_sign_ = sign_at(r.polynomial, r.lower);
    // the signs at the ends must be certainly opposite (an isolating interval as documented,
    // e.g. not a double root): otherwise the exact path decides
    stuck_ = lower_sign_ == 0 || filter_.sign(upper_box_) != -lower_sign_;
  }
  /// At most `steps` more halvings; false when no further halving is possible.
  bool advance(int steps) {
    for (int i = 0; i < steps && !stuck_; ++i) {
      double m = lo_ + (hi_ - lo_) / 2;
      if (!(m > lo_ && m < hi_) || !(m > lower_box_.hi && m < upper_box_.lo)) {
        stuck_ = true;
        break;
      }
      int s = filter_.sign(Interval{m, m});
      if (s == 0) {
        stuck_ = true;
        break;
      }
      if (s == lower_sign_)
        lo_ = m;
      else
        hi_ = m;
    }
    return !stuck_;
  }
  double lo() const { return lo_; }
  double hi() const { return hi_; }

 private:
  SignFilter filter_;
  Interval lower_box_, upper_box_;
  double lo_ = 0, hi_ = 0;
  int lower_sign_ = 0;
  bool stuck_ = false;
};

}  // namespace

namespace {

// 2^-n exactly, 0 <= n <= 1022 (a normal double): its exponent field written directly (what
// std::ldexp(1.0, -n) returns, without the library call).
double negative_power_of_two(unsigned long n) {
  const std::uint64_t bits = static_cast<std::uint64_t>(1023 - n) << 52;
  double d = 0;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

}  // namespace

std::atomic<bool>& refine_jump_enabled() {
  static std::atomic<bool> enabled{true};
  return enabled;
}

std::size_t& refine_jumps() {
  thread_local std::size_t jumps = 0;   // per thread: no shared cache line in parallel builds
  return jumps;
}

namespace {

// The root's place t in (0, 1) along the interval (start, start + span), approximately: Newton
// steps in plain doubles from the middle (approximate_value), nothing when an iterate leaves the
// interval or a value is not finite. (The filtered cells below check what it suggests.)
std::optional<double> newton_place(const SignFilter& filter, double start, double span) {
  if (!std::isfinite(start) || !std::isfinite(span) || !(span > 0)) return std::nullopt;
  double x = start + span / 2;
  for (int i = 0; i < 8; ++i) {
    double value = 0, slope = 0;
    if (!filter.approximate_value(x, value, slope) || slope == 0) return std::nullopt;
    const double step = value / slope;
    if (!std::isfinite(step)) return std::nullopt;
    x -= step;
    if (!(x > start && x < start + span)) return std::nullopt;
    if (std::fabs(step) <= span * 0x1p-56) break;
  }
  return (x - start) / span;
}

// refine_to's filtered halvings taken at once: the cell (m, m + 1) / 2^level of the halvings'
// grid over (lower, lower + span) that holds the root, with level <= deepest (<= 52), found from
// a Newton iterate in plain doubles and accepted only where the certified filter gives the sign
// of p(lower) at its start and the other sign at its end (both ends strictly inside the
// interval). The root is then strictly inside that cell, so it is no grid point of that level or
// a coarser one: no halving meets it exactly, each keeps the half holding it, and the halvings
// reach this cell, m at that level — the same j and k as taking the steps one by one (the
// signs are certified either way). Nothing when the iterate leaves the interval or the filter
// cannot decide at a level's ends down to level 8: the caller halves as before.
std::optional<std::pair<std::uint64_t, unsigned long>> filtered_cell(const SignFilter& filter, const Interval& lower_box,
                                                                       const Interval& span_box, int lower_sign,
                                                                       unsigned long deepest) {
  const std::optional<double> t = newton_place(filter, lower_box.lo + (lower_box.hi - lower_box.lo) / 2,
                                               span_box.lo + (span_box.hi - span_box.lo) / 2);
  if (!t) return std::nullopt;
  for (unsigned long level = deepest; level >= 8; level = level >= 16 ? level - 8 : 0) {
    const double cells = std::ldexp(1.0, static_cast<int>(level));
    double m = std::floor(*t * cells);
    for (int attempt = 0; attempt < 3; ++attempt) {
      if (!(m >= 1 && m + 1 < cells)) break;   // an end of the interval: halve as before
      const int at_start = filter.sign(lower_box + span_box * Interval{m / cells, m / cells});   // exact: m < 2^52
      const int at_end = filter.sign(lower_box + span_box * Interval{(m + 1) / cells, (m + 1) / cells});
      if (at_start == 0 || at_end == 0) break;   // undecided: a coarser level
      if (at_start != lower_sign) {
        m -= 1;   // the root is below the cell
        continue;
      }
      if (at_end == lower_sign) {
        m += 1;   // above
        continue;
      }
      return std::pair<std::uint64_t, unsigned long>{static_cast<std::uint64_t>(m), level};
    }
  }
  return std::nullopt;
}

}  // namespace

void Real::refine_to(const Rational& width) {
  if (exact) return;
  Rational span = upper - lower;   // once: the width test here and the bisection below
  if (span <= width) return;
  // The bisection of refine(), on integers: after k halvings the interval is
  // [lower + j w / 2^k, lower + (j + 1) w / 2^k] with w = upper - lower, so every midpoint is
  // (a q 2^k + p b m) / (b q 2^k) for lower = a / b, w = p / q and an odd m. Signs are taken
  // at these unreduced fractions (the sign of p(N / D) with D > 0 does not depend on common
  // factors), and the ends are reduced once at the end: the same intervals, and the same exact
  // roots, as halving canonical rationals, without a gcd per step. The sign at the lower end
  // is evaluated once: it never changes (lower only moves to midpoints of the same sign).
  // the sign at the lower end: by the certified filter where it decides, else exactly
  const SignFilter filter(polynomial);
  const Interval lower_box = enclose(lower);
  int lower_sign = std::isfinite(lower_box.lo) && std::isfinite(lower_box.hi) ? filter.sign(lower_box) : 0;
  if (lower_sign == 0) lower_sign = sign_at(polynomial, lower);
  auto reduced = [](const Rational& r) {
    // a power-of-two denominator (bisection ends) is coprime to the numerator iff that is odd
    if (power_of_two_denominator(r)) return mpz_cmp_ui(r.get_den_mpz_t(), 1) == 0 || mpz_odd_p(r.get_num_mpz_t());
    mpz_class g;
    mpz_gcd(g.get_mpz_t(), r.get_num_mpz_t(), r.get_den_mpz_t());
    return g == 1;
  };
  if (!reduced(lower) || !reduced(upper)) {
    // GMP's arithmetic keeps an unreduced end's factors in the midpoints: halve as before, so
    // that the ends are written the same way
    while (upper - lower > width) {
      Rational middle = (lower + upper) / 2;
      int s = sign_at(polynomial, middle);
      if (s == 0) {
        lower = upper = middle;
        exact = true;
        return;
      }
      if (s == lower_sign)
        lower = std::move(middle);
      else
        upper = std::move(middle);
    }
    return;
  }
  const mpz_class& p = span.get_num();
  const mpz_class& q = span.get_den();
  const mpz_class base = lower.get_num() * q;   // a q
  const mpz_class step = p * lower.get_den();    // p b
  const mpz_class denominator = lower.get_den() * q;   // b q
  const mpz_class limit_left = p * width.get_den();    // the interval is wider than width while
  const mpz_class& limit_right = width.get_num();      // p w_den > w_num q 2^k
  mpz_class j = 0, m, numerator, scaled_denominator, right = limit_right * q;
  unsigned long k = 0;
  // The certified double filter decides the sign at a midpoint lower + span m / 2^k while
  // m / 2^k is a double (k <= 52) and the value's enclosure excludes zero; else exactly.
  const Interval span_box = enclose(span);
  bool filtering = std::isfinite(lower_box.lo) && std::isfinite(lower_box.hi) && std::isfinite(span_box.hi);
  if (filtering && limit_left > right) {
    // The loop's first steps with j and m = 2 j + 1 as machine integers (k < 52): the number of
    // halvings is counted once (the smallest n with limit_left <= right 2^n), and the steps the
    // filter decides take no mpz arithmetic; the first it cannot decide, and every step from
    // k = 52 on, is the loop below's (the same steps, the same j).
    std::size_t left_bits = mpz_sizeinbase(limit_left.get_mpz_t(), 2), right_bits = mpz_sizeinbase(right.get_mpz_t(), 2);
    unsigned long halvings = left_bits > right_bits + 1 ? static_cast<unsigned long>(left_bits - right_bits - 1) : 0;
    mpz_class shifted = right << halvings;   // right 2^halvings < 2^(left_bits - 1) <= limit_left
    while (limit_left > shifted) {
      mpz_mul_2exp(shifted.get_mpz_t(), shifted.get_mpz_t(), 1);
      ++halvings;
    }
    std::uint64_t small_j = 0;
    if (refine_jump_enabled().load(std::memory_order_relaxed) && halvings >= 12)
      if (auto cell = filtered_cell(filter, lower_box, span_box, lower_sign, std::min<unsigned long>(halvings, 52))) {
        small_j = cell->first;
        k = cell->second;
        ++refine_jumps();
      }
    while (k < 52 && k < halvings) {
      std::uint64_t small_m = 2 * small_j + 1;
      double t = static_cast<double>(small_m) * negative_power_of_two(k + 1);   // exact: m < 2^52
      int s = filter.sign(lower_box + span_box * Interval{t, t});
      if (s == 0) break;   // undecided: the loop below takes this step exactly
      ++k;
      small_j = s == lower_sign ? small_m : 2 * small_j;
    }
    static_assert(sizeof(unsigned long) >= sizeof(std::uint64_t), "mpz_set_ui takes the 64-bit j");
    mpz_set_ui(j.get_mpz_t(), static_cast<unsigned long>(small_j));
    mpz_mul_2exp(right.get_mpz_t(), right.get_mpz_t(), k);
  }
  while (limit_left > right) {
    // m = 2 j + 1 in place (no temporaries per step; the same numbers)
    mpz_mul_2exp(m.get_mpz_t(), j.get_mpz_t(), 1);
    mpz_add_ui(m.get_mpz_t(), m.get_mpz_t(), 1);
    ++k;
    int s = 0;
    if (filtering && k <= 52) {
      double t = m.get_d() * negative_power_of_two(k);   // exact: m < 2^k <= 2^52
      s = filter.sign(lower_box + span_box * Interval{t, t});
    }
    if (s == 0) {
      mpz_mul_2exp(numerator.get_mpz_t(), base.get_mpz_t(), k);   // (base << k) + step m
      mpz_addmul(numerator.get_mpz_t(), step.get_mpz_t(), m.get_mpz_t());
      mpz_mul_2exp(scaled_denominator.get_mpz_t(), denominator.get_mpz_t(), k);
      s = homogeneous_sign(polynomial, numerator, scaled_denominator);
    }
    if (s == 0) {   // decided exactly (the filter never returns 0 as a sign)
      lower = Rational(numerator, scaled_denominator);
      canonicalize(lower);
      upper = lower;
      exact = true;
      return;
    }
    if (s == lower_sign)
      mpz_swap(j.get_mpz_t(), m.get_mpz_t());
    else
      mpz_mul_2exp(j.get_mpz_t(), j.get_mpz_t(), 1);
    mpz_mul_2exp(right.get_mpz_t(), right.get_mpz_t(), 1);
  }
  // an end that never moved keeps its representation (as halving did), a moved one is reduced
  scaled_denominator = denominator << k;
  if (j != 0) {
    lower = Rational(mpz_class((base << k) + step * j), scaled_denominator);
    canonicalize(lower);
  }
  if (j + 1 != mpz_class(1) << k) {
    upper = Rational(mpz_class((base << k) + step * (j + 1)), scaled_denominator);
    canonicalize(upper);
  }
}

namespace {

// mpz <-> __int128 for numbers of at most 126 bits (sign and magnitude, two 64-bit limbs).
using Wide = __int128;
static_assert(sizeof(mp_limb_t) == 8, "two limbs hold 128 bits");
Wide to_wide(const mpz_class& z) {
  const mp_size_t n = std::abs(z.get_mpz_t()->_mp_size);
  const mp_limb_t* d = z.get_mpz_t()->_mp_d;
  const unsigned __int128 magnitude =
      (n > 1 ? static_cast<unsigned __int128>(d[1]) << 64 : 0) | (n > 0 ? d[0] : 0);
  return sgn(z) < 0 ? -static_cast<Wide>(magnitude) : static_cast<Wide>(magnitude);
}
void from_wide(Wide w, mpz_class& z) {
  const unsigned __int128 magnitude = w < 0 ? -static_cast<unsigned __int128>(w) : static_cast<unsigned __int128>(w);
  const mp_limb_t limbs[2] = {static_cast<mp_limb_t>(magnitude), static_cast<mp_limb_t>(magnitude >> 64)};
  mpz_import(z.get_mpz_t(), 2, -1, sizeof(mp_limb_t), 0, 0, limbs);
  if (w < 0) mpz_neg(z.get_mpz_t(), z.get_mpz_t());
}

// The least n >= 0 with needed <= reached 2^n (both positive): the number of steps of
// refine_dyadically's loop, whose width test doubles `reached` per step.
unsigned long halvings(const mpz_class& needed, const mpz_class& reached) {
  const std::size_t left_bits = mpz_sizeinbase(needed.get_mpz_t(), 2), right_bits = mpz_sizeinbase(reached.get_mpz_t(), 2);
  unsigned long steps = left_bits > right_bits + 1 ? static_cast<unsigned long>(left_bits - right_bits - 1) : 0;
  mpz_class shifted = reached << steps;   // reached 2^steps < 2^(left_bits - 1) <= needed
  while (needed > shifted) {
    mpz_mul_2exp(shifted.get_mpz_t(), shifted.get_mpz_t(), 1);
    ++steps;
  }
  return steps;
}

// The certified filter's sign of p(m / 2^k), m below 2^126 in magnitude, k <= 900: m enclosed
// by the nearest double and its neighbour on the far side, scaled by 2^-k exactly while normal
// (checked); 0 when undecided.
int wide_filter_sign(const SignFilter& filter, Wide m, unsigned long k) {
  const double d = static_cast<double>(m);   // nearest; the far side's neighbour bounds m
  const Wide back = static_cast<Wide>(d);    // exact: |d| <= 2^126
  double lo = d, hi = d;
  if (back < m) hi = std::nextafter(d, HUGE_VAL);
  if (back > m) lo = std::nextafter(d, -HUGE_VAL);
  const double unit = negative_power_of_two(k);   // 2^-k, k <= 900: exact products
  lo *= unit;
  hi *= unit;
  const bool normal = (lo == 0 || std::fabs(lo) >= 0x1p-1000) && (hi == 0 || std::fabs(hi) >= 0x1p-1000);
  return normal ? filter.sign(Interval{lo, hi}) : 0;
}

// dyadic_steps_in_machine_integers' first halvings at once, as filtered_cell for refine_to: the
// cell (low 2^L + m step, low 2^L + (m + 1) step) / 2^(scale_bits + L) at a level L <= deepest
// (<= 50, so that m is a double's integer and every numerator stays below 2^126: the caller's
// bits + steps <= 124) whose ends the filter certifies to have the sign of p at the interval's
// start and the other sign; the root is then strictly inside it and the halvings reach it (see
// filtered_cell). Returns (its start's numerator, L); nothing down to level 8: the caller steps.
std::optional<std::pair<Wide, unsigned long>> filtered_dyadic_cell(const SignFilter& filter, int lower_sign, Wide low,
                                                                   Wide step, unsigned long scale_bits,
                                                                   unsigned long deepest) {
  if (scale_bits > 800) return std::nullopt;
  const double unit = negative_power_of_two(scale_bits);
  const std::optional<double> t = newton_place(filter, static_cast<double>(low) * unit, static_cast<double>(step) * unit);
  if (!t) return std::nullopt;
  for (unsigned long level = deepest; level >= 8; level = level >= 16 ? level - 8 : 0) {
    const double cells = std::ldexp(1.0, static_cast<int>(level));
    double m = std::floor(*t * cells);
    for (int attempt = 0; attempt < 3; ++attempt) {
      if (!(m >= 1 && m + 1 < cells)) break;
      const Wide start = low * (static_cast<Wide>(1) << level) + static_cast<Wide>(m) * step;
      const int at_start = wide_filter_sign(filter, start, scale_bits + level);
      const int at_end = wide_filter_sign(filter, start + step, scale_bits + level);
      if (at_start == 0 || at_end == 0) break;
      if (at_start != lower_sign) {
        m -= 1;
        continue;
      }
      if (at_end == lower_sign) {
        m += 1;
        continue;
      }
      return std::pair<Wide, unsigned long>{start, level};
    }
  }
  return std::nullopt;
}

// refine_dyadically's bisection steps with its numerators as machine integers: the loop
//   while (needed > reached) { a = 2 a; middle = a + difference; scale, reached doubled;
//                              a = middle when p(middle / scale) has lower_sign }
// runs a fixed number of steps n (the least with needed <= reached 2^n), and every middle is
// below 2^126 in magnitude when a and difference have at most 124 - n bits: then each step
// is two additions of __int128; the sign at a middle is the certified double filter's on the
// middle's enclosure (the __int128 rounded to the nearest double and the double next to it on
// the far side, scaled by 2^-k exactly while normal), else homogeneous_sign exactly on the
// same numerator and denominator — the same signs, hence the same steps, as the mpz loop.
// Returns false when it took no step (the caller's loop runs) or after the n steps (a, scale,
// scale_bits and reached updated as the loop leaves them: needed <= reached); true when a
// middle is a root (`middle` and `scale` its numerator and denominator).
bool dyadic_steps_in_machine_integers(const Polynomial& polynomial, const SignFilter& filter, int lower_sign,
                                      const mpz_class& needed, const mpz_class& difference, mpz_class& a,
                                      mpz_class& scale, unsigned long& scale_bits, mpz_class& reached,
                                      mpz_class& middle) {
  const unsigned long steps = halvings(needed, reached);
  const std::size_t bits = std::max(mpz_sizeinbase(a.get_mpz_t(), 2), mpz_sizeinbase(difference.get_mpz_t(), 2));
  if (bits + steps > 124 || scale_bits + steps > 900) return false;
  const Wide step = to_wide(difference);
  Wide low = to_wide(a);
  unsigned long first = 1;
  if (refine_jump_enabled().load(std::memory_order_relaxed) && steps >= 12)
    if (auto cell = filtered_dyadic_cell(filter, lower_sign, low, step, scale_bits, std::min<unsigned long>(steps, 50))) {
      low = cell->first;
      first = cell->second + 1;
      ++refine_jumps();
    }
  for (unsigned long i = first; i <= steps; ++i) {
    low *= 2;
    const Wide m = low + step;
    int s = wide_filter_sign(filter, m, scale_bits + i);
    if (s == 0) {
      from_wide(m, middle);
      mpz_mul_2exp(scale.get_mpz_t(), scale.get_mpz_t(), i);   // 2^(scale_bits + i)
      s = homogeneous_sign(polynomial, middle, scale);
      if (s == 0) return true;
      mpz_fdiv_q_2exp(scale.get_mpz_t(), scale.get_mpz_t(), i);
    }
    if (s == lower_sign) low = m;
  }
  from_wide(low, a);
  mpz_mul_2exp(scale.get_mpz_t(), scale.get_mpz_t(), steps);
  mpz_mul_2exp(reached.get_mpz_t(), reached.get_mpz_t(), steps);
  scale_bits += steps;
  return false;
}

// refine_dyadically's remaining `steps` halvings of (a, a + difference) / 2^scale_bits at once,
// when they are many (the quadratic traits' multiple-precision levels, 2^-128 ... 2^-2000):
// the root is the only one in the interval and simple (Real), so a cell
// (A, A + difference) / 2^(scale_bits + steps) of the halvings' grid whose ends have non-zero
// signs, lower_sign at A and the other at A + difference, holds it strictly inside; no grid
// point of that level or a coarser one is the root, so no halving meets it exactly, and every
// halving keeps the half that holds it: the loop ends at that cell. The cell's index comes
// from an approximation of the root (Newton steps in MPFR from the interval's middle, stopped
// when an iterate leaves the interval), and only the two exact signs at its ends decide; the
// neighbouring cell on the side those signs point to is tried once; otherwise false and the
// caller's loop halves as before. True: a, scale, scale_bits and reached as the loop leaves them.
bool dyadic_cell_from_approximation(const Polynomial& polynomial, int lower_sign, unsigned long steps,
                                    const mpz_class& difference, mpz_class& a, mpz_class& scale,
                                    unsigned long& scale_bits, mpz_class& reached) {
  std::size_t coefficient_bits = 0;
  for (const mpz_class& c : polynomial) coefficient_bits = std::max(coefficient_bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  const mpfr_prec_t precision = static_cast<mpfr_prec_t>(mpz_sizeinbase(a.get_mpz_t(), 2) + steps + coefficient_bits + 64);
  const Polynomial slope = derivative(polynomial);
  mpfr_t x, lo, hi, value, derivative_value, t;
  for (mpfr_ptr v : {x, lo, hi, value, derivative_value, t}) mpfr_init2(v, precision);
  struct Clear {
    mpfr_ptr values[6];
    ~Clear() {
      for (mpfr_ptr v : values) mpfr_clear(v);
    }
  } clear{{x, lo, hi, value, derivative_value, t}};
  auto horner = [&](const Polynomial& p, mpfr_ptr out) {
    mpfr_set_ui(out, 0, MPFR_RNDN);
    for (auto c = p.rbegin(); c != p.rend(); ++c) {
      mpfr_mul(out, out, x, MPFR_RNDN);
      mpfr_add_z(out, out, c->get_mpz_t(), MPFR_RNDN);
    }
  };
  // the interval and its middle, in units of 2^-scale_bits
  mpfr_set_z(lo, a.get_mpz_t(), MPFR_RNDN);
  mpfr_add_z(hi, lo, difference.get_mpz_t(), MPFR_RNDN);
  mpfr_add(x, lo, hi, MPFR_RNDN);
  mpfr_div_2ui(x, x, 1, MPFR_RNDN);
  for (mpfr_ptr v : {x, lo, hi}) mpfr_div_2ui(v, v, scale_bits, MPFR_RNDN);
  // Newton steps at a working precision doubled per step from 64 bits (the iterate's correct
  // bits double too), then three at the full precision
  mpfr_prec_t working = std::min<mpfr_prec_t>(64, precision);
  for (int at_full = 0; at_full < 3;) {
    mpfr_prec_round(x, working, MPFR_RNDN);
    for (mpfr_ptr v : {value, derivative_value, t}) mpfr_set_prec(v, working);
    horner(polynomial, value);
    horner(slope, derivative_value);
    if (mpfr_zero_p(derivative_value) || !mpfr_number_p(value) || !mpfr_number_p(derivative_value)) return false;
    mpfr_div(t, value, derivative_value, MPFR_RNDN);
    mpfr_sub(x, x, t, MPFR_RNDN);
    if (mpfr_less_p(x, lo) || mpfr_greater_p(x, hi)) return false;
    if (working == precision) ++at_full;
    working = std::min(2 * working, precision);
  }
  mpfr_set_prec(t, precision);
  // the cell's index: floor((x 2^scale_bits - a) 2^steps / difference), within [0, 2^steps - 1]
  mpfr_mul_2ui(t, x, scale_bits, MPFR_RNDN);
  mpfr_sub_z(t, t, a.get_mpz_t(), MPFR_RNDN);
  mpfr_mul_2ui(t, t, steps, MPFR_RNDN);
  mpfr_div_z(t, t, difference.get_mpz_t(), MPFR_RNDN);
  mpz_class index;
  mpfr_get_z(index.get_mpz_t(), t, MPFR_RNDD);
  const mpz_class last = (mpz_class(1) << steps) - 1;
  if (index < 0) index = 0;
  if (index > last) index = last;
  mpz_class fine_scale = scale << steps, start = a << steps, end;
  for (int attempt = 0; attempt < 2; ++attempt) {
    mpz_class cell = start + index * difference;
    end = cell + difference;
    const int at_start = homogeneous_sign(polynomial, cell, fine_scale);
    if (at_start == 0) return false;
    if (at_start != lower_sign) {   // the root is below the cell
      if (index == 0) return false;
      index -= 1;
      continue;
    }
    const int at_end = homogeneous_sign(polynomial, end, fine_scale);
    if (at_end == 0) return false;
    if (at_end == lower_sign) {   // the root is above the cell
      if (index == last) return false;
      index += 1;
      continue;
    }
    a = std::move(cell);
    scale = std::move(fine_scale);
    scale_bits += steps;
    mpz_mul_2exp(reached.get_mpz_t(), reached.get_mpz_t(), steps);
    return true;
  }
  return false;
}

}  // namespace

void refine_dyadically(Real& r, const Rational& width) {
  if (r.exact || r.upper - r.lower <= width) return;
  // Every sign below is decided first by the certified double filter (the polynomial's
  // coefficients and the point enclosed outwards, interval Horner); exactly only when the
  // enclosure of the value contains zero. The filter never returns a wrong sign and never 0,
  // so the bisection takes the same steps, and ends at the same interval, as the exact one.
  const SignFilter filter(r.polynomial);
  const Interval lower_box = enclose(r.lower);
  int lower_sign = std::isfinite(lower_box.lo) && std::isfinite(lower_box.hi) ? filter.sign(lower_box) : 0;
  if (lower_sign == 0) lower_sign = sign_at(r.polynomial, r.lower);
  // inward dyadic ends a / 2^k >= lower and b / 2^k <= upper, 2^-k <= (upper - lower) / 4
  Rational gap = (r.upper - r.lower) / 4;
  // the least k >= 0 with 2^-k <= gap = p / q (canonical, p > 0), i.e. q <= p 2^k: with
  // 2^(bits(q) - 1) <= q < 2^bits(q) and likewise p, it is c = bits(q) - bits(p) or c + 1
  // (p 2^(c - 1) < 2^(bits(q) - 1) <= q, p 2^(c + 1) >= 2^bits(q) > q), 0 when c < 0
  unsigned long k = 0;
  {
    const long c = static_cast<long>(mpz_sizeinbase(gap.get_den_mpz_t(), 2)) -
                   static_cast<long>(mpz_sizeinbase(gap.get_num_mpz_t(), 2));
    if (c >= 0) {
      mpz_class shifted;
      mpz_mul_2exp(shifted.get_mpz_t(), gap.get_num_mpz_t(), static_cast<mp_bitcnt_t>(c));
      k = static_cast<unsigned long>(c) + (cmp(gap.get_den(), shifted) <= 0 ? 0 : 1);
    }
  }
  mpz_class scale = mpz_class(1) << k;
  mpz_class a, b;
  mpz_class scaled_lower = r.lower.get_num() * scale, scaled_upper = r.upper.get_num() * scale;
  mpz_cdiv_q(a.get_mpz_t(), scaled_lower.get_mpz_t(), r.lower.get_den_mpz_t());
  mpz_fdiv_q(b.get_mpz_t(), scaled_upper.get_mpz_t(), r.upper.get_den_mpz_t());
  // the scale is 2^k throughout (doubled per step)
  unsigned long scale_bits = k;
  auto sign = [&](const mpz_class& numerator, const mpz_class& denominator) {
    // numerator / 2^scale_bits enclosed in doubles: mpz_get_d truncates towards zero, exact
    // up to 53 bits, else the next double away from zero bounds the other side; the scaling
    // by 2^-scale_bits is exact while the result stays normal (checked)
    if (scale_bits <= 900) {
      double d = mpz_get_d(numerator.get_mpz_t());
      double lo = d, hi = d;
      if (mpz_sizeinbase(numerator.get_mpz_t(), 2) > 53) {
        if (sgn(numerator) > 0)
          hi = std::nextafter(d, HUGE_VAL);
        else
          lo = std::nextafter(d, -HUGE_VAL);
      }
      // times 2^-scale_bits (a normal double: scale_bits <= 900), exact while the result is
      // normal, which is checked (std::ldexp's values, without the library call)
      const double unit = negative_power_of_two(scale_bits);
      lo *= unit;
      hi *= unit;
      const bool normal = (lo == 0 || std::fabs(lo) >= 0x1p-1000) && (hi == 0 || std::fabs(hi) >= 0x1p-1000);
      if (normal && std::isfinite(lo) && std::isfinite(hi)) {
        int s = filter.sign(Interval{lo, hi});
        if (s != 0) return s;
      }
    }
    return homogeneous_sign(r.polynomial, numerator, denominator);
  };
  auto settle_exact = [&](const mpz_class& numerator, const mpz_class& denominator) {
    Rational root(numerator, denominator);
    root.canonicalize();
    r.lower = r.upper = root;
    r.exact = true;
  };
  int sign_a = sign(a, scale), sign_b = sign(b, scale);
  if (sign_a == 0) return settle_exact(a, scale);
  if (sign_b == 0) return settle_exact(b, scale);
  if (sign_a != lower_sign || sign_b == lower_sign) {   // the root is outside [a, b] / 2^k
    r.refine_to(width);
    return;
  }
  // invariant: the root is in (a / 2^k, b / 2^k), p(a / 2^k) has the sign lower_sign.
  // A step doubles a, b and the scale and makes a or b the old a + b, so b - a is the same at
  // every step: b = a + difference throughout, and the width test (b - a) w_den <= w_num 2^k
  // compares a constant with a number doubled per step (no product, no temporary per step;
  // the same steps and ends as halving [a, b] with both ends kept).
  const mpz_class& width_num = width.get_num();
  const mpz_class& width_den = width.get_den();
  const mpz_class difference = b - a;
  const mpz_class needed = difference * width_den;
  mpz_class reached = width_num * scale;
  mpz_class middle;
  if (needed > reached && dyadic_steps_in_machine_integers(r.polynomial, filter, lower_sign, needed, difference, a,
                                                           scale, scale_bits, reached, middle))
    return settle_exact(middle, scale);
  if (needed > reached) {
    const unsigned long steps = halvings(needed, reached);
    if (steps >= 24) dyadic_cell_from_approximation(r.polynomial, lower_sign, steps, difference, a, scale, scale_bits, reached);
  }
  while (needed > reached) {
    mpz_mul_2exp(a.get_mpz_t(), a.get_mpz_t(), 1);
    mpz_add(middle.get_mpz_t(), a.get_mpz_t(), difference.get_mpz_t());   // old a + old b
    mpz_mul_2exp(scale.get_mpz_t(), scale.get_mpz_t(), 1);
    mpz_mul_2exp(reached.get_mpz_t(), reached.get_mpz_t(), 1);
    ++scale_bits;
    int s = sign(middle, scale);
    if (s == 0) return settle_exact(middle, scale);
    if (s == lower_sign) mpz_swap(a.get_mpz_t(), middle.get_mpz_t());   // else b = middle = a + difference
  }
  b = a + difference;
  r.lower = Rational(a, scale);
  r.upper = Rational(b, scale);
  r.lower.canonicalize();
  r.upper.canonicalize();
}

bool detect_small_rational(Real& r) {
  if (r.exact) return true;
  // a root p/q with q^2 < 1/(2 width) is the only rational of denominator <= q in the interval
  Rational scale = 1 + abs(r.lower) + abs(r.upper);
  for (int bits : {8, 24, 64}) {
    Rational width = scale / Rational(mpz_class(1) << bits);
    r.refine_to(width);
    if (r.exact) return true;
    Rational candidate = simplest_between(r.lower, r.upper);
    if (sign_at(r.polynomial, candidate) == 0) {
      r.lower = r.upper = candidate;
      r.exact = true;
      return true;
    }
  }
  return false;
}

void Real::detect_rational() {
  if (detect_small_rational(*this)) return;
  // complete: a rational root of larger denominator (the refinement above is a fast path for
  // the small ones), decided by rational_roots of the polynomial (primes and Hensel lifting)
  if (std::optional<Rational> value = rational_root(*this)) {
    lower = upper = *value;
    exact = true;
  }
}

double Real::approximate() const {
  if (exact) return lower.get_d();
  Real copy = *this;
  return approximate_refining(copy);
}

double approximate_refining(Real& copy) {
  if (copy.exact) return copy.lower.get_d();
  if (sgn(copy.lower) <= 0 && sgn(copy.upper) >= 0) {
    // an enclosure reaching 0 does not measure the number (a root of 2.5e-401 in (0, 4e-133)
    // gave 2e-134, session 62): first its sign, exactly, then an enclosure apart from 0 (the
    // polynomial does not vanish at 0 unless the number is 0: it has one root in the interval)
    const int sign = copy.compare(Rational(0));
    if (sign == 0) return 0.0;
    (sign > 0 ? copy.lower : copy.upper) = 0;
    while (!copy.exact && sgn(copy.lower) * sgn(copy.upper) <= 0) {
      Rational narrower = copy.upper - copy.lower;
      mpq_div_2exp(narrower.get_mpq_t(), narrower.get_mpq_t(), 32);
      copy.refine_to(narrower);
    }
    if (copy.exact) return copy.lower.get_d();
  }
  Rational width = abs(copy.upper) + abs(copy.lower);
  mpq_div_2exp(width.get_mpq_t(), width.get_mpq_t(), 60);   // / 2^60
  if (width == 0) width = Rational(1, mpz_class(1) << 60);
  copy.refine_to(width);
  // the middle: the sum halved by a shift of the denominator (the same rational as dividing by 2)
  Rational middle;
  mpq_add(middle.get_mpq_t(), copy.lower.get_mpq_t(), copy.upper.get_mpq_t());
  mpq_div_2exp(middle.get_mpq_t(), middle.get_mpq_t(), 1);
  return middle.get_d();
}

int Real::compare(const Rational& r) const {
  if (exact) {
    const int c = compare_rationals(lower, r);
    return c < 0 ? -1 : (c > 0 ? 1 : 0);
  }
  if (compare_rationals(r, lower) <= 0) return 1;
  if (compare_rationals(r, upper) >= 0) return -1;
  int s = sign_at(polynomial, r);
  if (s == 0) return 0;
  return s == sign_at(polynomial, lower) ? 1 : -1;
}

std::string Real::description(const std::string& variable) const {
  return root_description(polynomial, lower, upper, exact, variable);
}

std::string root_description(const Polynomial& polynomial, const Rational& lower, const Rational& upper, bool exact,
                             const std::string& variable) {
  if (exact) return to_exact_string(lower);
  // appended into one string (no temporary per part)
  std::string text = to_string(polynomial, variable);
  text += " = 0, ";
  text += variable;
  text += " in (";
  text += to_exact_string(lower);
  text += ", ";
  text += to_exact_string(upper);
  text += ')';
  return text;
}

namespace {

// The certified double filter of compare() and equal(): bisect both enclosures in doubles,
// eight halvings at a time, until they separate (-1: a < b, 1: a > b) or neither can be
// narrowed further (0: undecided).
int separated_in_doubles(const Real& a, const Real& b) {
  DoubleBisection x(a), y(b);
  for (;;) {
    if (x.hi() < y.lo()) return -1;
    if (y.hi() < x.lo()) return 1;
    bool x_moves = x.advance(8);
    bool y_moves = y.advance(8);
    if (!x_moves && !y_moves) return 0;
  }
}

// Overlapping isolating intervals of one square-free polynomial (one simple root in each open
// interval, non-zero opposite signs at the ends): the order of the two roots, read off the signs
// at the ends of the common part (lo, hi) — the signs by the certified double filter, exactly
// where it cannot decide. A sign change there: the common part holds one root, which is both
// (equal). None: it holds none (at most one root of either lies in it), so the root of the interval
// starting lower lies below lo and the other above hi: when a.lower < b.lower, b's root lies
// above hi, which must then be a.upper (it is below b.upper), so a < b; symmetrically a > b.
// nullopt when the polynomials differ, or when the premise does not hold (an end's sign is 0,
// or no sign change with equal lower ends): compare() and equal() decide as without this test.
std::optional<int> one_polynomial_order(const Real& a, const Real& b) {
  if (!(a.polynomial == b.polynomial)) return std::nullopt;
  const Rational& lo = std::max(a.lower, b.lower);
  const Rational& hi = std::min(a.upper, b.upper);
  const SignFilter filter(a.polynomial);
  auto sign = [&](const Rational& x) {
    const Interval box = enclose(x);
    int s = std::isfinite(box.lo) && std::isfinite(box.hi) ? filter.sign(box) : 0;
    return s != 0 ? s : sign_at(a.polynomial, x);
  };
  const int s_lo = sign(lo), s_hi = sign(hi);
  if (s_lo == 0 || s_hi == 0) return std::nullopt;
  if (s_lo != s_hi) return 0;
  const int lowers = cmp(a.lower, b.lower);
  if (lowers == 0) return std::nullopt;
  return lowers < 0 ? -1 : 1;
}

// Overlapping isolating intervals: the numbers are equal iff the gcd of their polynomials has a
// root in the common part.
bool common_root_in_overlap(const Real& a, const Real& b) {
  Polynomial g = gcd(a.polynomial, b.polynomial);
  if (degree(g) < 1) return false;
  Rational lo = std::max(a.lower, b.lower), hi = std::min(a.upper, b.upper);
  SturmSequence sturm(g);
  return sturm.count(lo, hi) - (sign_at(g, hi) == 0 ? 1 : 0) > 0;
}

}  // namespace

namespace {

// compare()'s exact tail, for overlapping intervals that the filters did not separate: equal iff
// the gcd has a root in the common part.
int compare_overlapping(const Real& a, const Real& b) {
  {
    // distinct numbers usually separate after a few halvings: try that before the gcd
    Real x = a, y = b;
    Rational width = std::max(Rational(x.upper - x.lower), Rational(y.upper - y.lower)) / 1048576;
    x.refine_to(width);
    y.refine_to(width);
    if (x.exact || y.exact) return compare(x, y);
    if (x.upper <= y.lower) return -1;
    if (y.upper <= x.lower) return 1;
  }
  if (common_root_in_overlap(a, b)) return 0;
  // distinct numbers: refine copies until their intervals separate (sixteen halvings a round)
  Real x = a, y = b;
  for (;;) {
    Rational width = std::max(Rational(x.upper - x.lower), Rational(y.upper - y.lower)) / 65536;
    x.refine_to(width);
    y.refine_to(width);
    if (x.exact || y.exact) return compare(x, y);
    if (x.upper <= y.lower) return -1;
    if (y.upper <= x.lower) return 1;
  }
}

}  // namespace

int compare(const Real& a, const Real& b) {
  if (a.exact) return -b.compare(a.lower);
  if (b.exact) return a.compare(b.lower);
  if (compare_rationals(a.upper, b.lower) <= 0) return -1;
  if (compare_rationals(b.upper, a.lower) <= 0) return 1;
  // one polynomial (the same root met in two slices, two roots of one slice): two signs decide,
  // before the double bisection of both numbers (which cannot separate equal ones)
  if (std::optional<int> order = one_polynomial_order(a, b)) return *order;
  if (int s = separated_in_doubles(a, b)) return s;
  // Coefficients of more than 192 bits (mixed scales, where the double filter cannot bisect):
  // both brackets bisected in MPFR (every sign certified) at the start precision; where they
  // still overlap, equality by the gcd, and distinct numbers by MPFR at rising precisions, the
  // exact bisection only past those. Narrower coefficients keep the exact path, as for sign_at.
  const MultiprecisionBits bits = multiprecision_order_bits(a, b);
  if (bits.width > 192) {
    const auto order = multiprecision_order(a, b, bits.start, bits.cap, [&] { return common_root_in_overlap(a, b); });
    if (order) return *order;
  }
  return compare_overlapping(a, b);
}

int exact_compare(const Real& a, const Real& b) {
  if (a.exact) return -b.compare(a.lower);
  if (b.exact) return a.compare(b.lower);
  if (compare_rationals(a.upper, b.lower) <= 0) return -1;
  if (compare_rationals(b.upper, a.lower) <= 0) return 1;
  return compare_overlapping(a, b);
}

std::optional<Rational> double_between(const Real& a, const Real& b) {
  if (a.exact && b.exact) return std::nullopt;
  // a's certified upper end and b's lower end; an exact number's double bounds stay as they are
  std::optional<DoubleBisection> x, y;
  if (!a.exact) x.emplace(a);
  if (!b.exact) y.emplace(b);
  const double a_hi_exact = a.exact ? upper_double(a.lower) : 0;
  const double b_lo_exact = b.exact ? lower_double(b.lower) : 0;
  for (int round = 0; round < 8; ++round) {
    // a < a_hi and b_lo < b strictly for a bisected number (its ends have certified non-zero
    // signs); an exact number's double bounds may equal it
    double a_hi = x ? x->hi() : a_hi_exact, b_lo = y ? y->lo() : b_lo_exact;
    if (a_hi < b_lo) {
      double middle = a_hi + (b_lo - a_hi) / 2;
      if (middle > a_hi && middle < b_lo) return Rational(middle);
      if (x) return Rational(a_hi);
      if (y) return Rational(b_lo);
      return std::nullopt;
    }
    bool moved = false;
    if (x) moved = x->advance(8) || moved;
    if (y) moved = y->advance(8) || moved;
    if (!moved) return std::nullopt;
  }
  return std::nullopt;
}

std::pair<double, double> double_bounds(const Real& x, int halvings) {
  DoubleBisection bisection(x);
  bisection.advance(halvings);
  return {bisection.lo(), bisection.hi()};
}

int compare_filtered(const Real& x, const Rational& r) {
  if (x.exact || compare_rationals(r, x.lower) <= 0 || compare_rationals(r, x.upper) >= 0) return x.compare(r);
  SignFilter filter(x.polynomial);
  int at = filter.sign(enclose(r));
  if (at == 0) return x.compare(r);
  int low = filter.sign(enclose(x.lower));
  if (low == 0) low = sign_at(x.polynomial, x.lower);
  return at == low ? 1 : -1;
}

bool equal(const Real& a, const Real& b) {
  if (a.exact) return b.compare(a.lower) == 0;
  if (b.exact) return a.compare(b.lower) == 0;
  if (compare_rationals(a.upper, b.lower) <= 0 || compare_rationals(b.upper, a.lower) <= 0) return false;
  // compare()'s tests without its refinement before the gcd (which only sorts distinct numbers)
  if (std::optional<int> order = one_polynomial_order(a, b)) return *order == 0;
  if (separated_in_doubles(a, b) != 0) return false;
  return common_root_in_overlap(a, b);
}

Rational simplest_between(const Rational& lo, const Rational& hi) {
  // an empty interval is a caller's bug: say so instead of dividing by zero below
  if (!(lo < hi))
    throw NumericError("internal: no rational strictly between " + to_exact_string(lo) + " and " +
                       to_exact_string(hi));
  Rational result;
  if (simplest_between_small(lo, hi, result)) return result;   // ends below 2^62: machine integers
  return simplest_between_gmp(lo, hi);
}

Rational simplest_between_gmp(const Rational& lo, const Rational& hi) {
  // Continued-fraction descent: smallest denominator in the open interval (lo, hi), on the
  // integers a / b = lo, c / d = hi (b, d > 0): at each level, with f = floor(a / b), the
  // answer is f + 1 when that is below c / d, else f + 1 / z with z the simplest rational in
  // (d / (c - f d), b / (a - f b)) (z = floor(d / (c - f d)) + 1 when a / b = f). The answer
  // f0 + 1 / (f1 + 1 / (... + 1 / z)) is composed bottom up, each step (f n + m, n) from
  // (n, m), coprime with a positive denominator: canonical without a gcd.
  mpz_class a = lo.get_num(), b = lo.get_den(), c = hi.get_num(), d = hi.get_den();
  mpz_class f, r, t;
  std::vector<mpz_class> quotients;
  mpz_class last;   // the integer ending the descent
  for (bool top = true;; top = false) {
    mpz_fdiv_qr(f.get_mpz_t(), r.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());   // a = f b + r, 0 <= r < b
    // f + 1 < c / d?
    t = f + 1;
    t *= d;
    if (t < c) {
      if (top) {
        // an integer lies inside; prefer the one of smallest magnitude
        if (sgn(a) < 0 && sgn(c) > 0) return Rational(0);
        if (sgn(c) <= 0) {
          mpz_class ceil_hi;
          mpz_cdiv_q(ceil_hi.get_mpz_t(), c.get_mpz_t(), d.get_mpz_t());
          ceil_hi -= 1;
          if (Rational(ceil_hi) > lo) return Rational(ceil_hi);
        }
        return Rational(f + 1);
      }
      last = f + 1;
      break;
    }
    quotients.push_back(f);
    mpz_submul(c.get_mpz_t(), f.get_mpz_t(), d.get_mpz_t());   // c - f d, in (0, d]
    if (sgn(r) == 0) {
      mpz_fdiv_q(last.get_mpz_t(), d.get_mpz_t(), c.get_mpz_t());
      last += 1;
      break;
    }
    // next interval: (d / (c - f d), b / r)
    mpz_class next_a = d, next_b = c, next_c = b, next_d = r;
    a = std::move(next_a);
    b = std::move(next_b);
    c = std::move(next_c);
    d = std::move(next_d);
  }
  mpz_class n = last, m = 1;   // the value n / m, n > 0
  for (auto q = quotients.rbegin(); q != quotients.rend(); ++q) {
    // q + m / n = (q n + m) / n
    mpz_class next = *q * n + m;
    m = std::move(n);
    n = std::move(next);
  }
  Rational result(n, m);
  return result;
}

Rational rational_between(const Real& a, const Real& b) {
  // the loop's first pass on the numbers themselves (no copies, which the refinement below
  // needs): separated enclosures, or two exact numbers (every sample of a polygon pair's edge
  // and face between rational vertices) — the same answers
  if (a.upper < b.lower) return simplest_between(a.upper, b.lower);
  if (a.exact && b.exact) return simplest_between(a.lower, b.lower);
  Real x = a, y = b;
  for (;;) {
    const Rational& hi_x = x.upper;  // x <= hi_x
    const Rational& lo_y = y.lower;  // lo_y <= y
    if (hi_x < lo_y) return simplest_between(hi_x, lo_y);
    if (x.exact && y.exact) return simplest_between(x.lower, y.lower);
    if (x.exact && hi_x == lo_y && !y.exact) {
      y.refine();
      continue;
    }
    x.refine();
    y.refine();
  }
}

std::optional<Rational> rational_root_by_refinement(const Real& r) {
  if (r.exact) return r.lower;
  const Polynomial& p = r.polynomial;
  if (degree(p) < 1) throw NumericError("internal: an isolated real root of a constant polynomial");
  // Q = |a_n| / content: the denominator of a rational root divides it
  const mpz_class q_bound = abs(p.back()) / content(p);
  const Rational final_width(1, q_bound * q_bound);
  Real copy = r;
  const Rational start_width = copy.upper - copy.lower;
  // stages: 2^-16, 2^-32, 2^-64, ... of the starting width, then 1/Q^2
  for (unsigned long bits = 16;; bits *= 2) {
    if (copy.exact) return copy.lower;   // the bisection met the root
    Rational candidate = simplest_between(copy.lower, copy.upper);
    if (candidate.get_den() > q_bound) return std::nullopt;   // no denominator <= Q inside
    if (mpz_divisible_p(q_bound.get_mpz_t(), candidate.get_den_mpz_t()) && sign_at(p, candidate) == 0)
      return candidate;
    if (copy.upper - copy.lower <= final_width) return std::nullopt;   // the only candidate failed
    Rational width = start_width / Rational(mpz_class(1) << bits);
    if (width < final_width) width = final_width;
    refine_dyadically(copy, width);
  }
}

std::optional<std::vector<Rational>> rational_roots(const Polynomial& polynomial) {
  Polynomial p = polynomial;
  trim(p);
  if (degree(p) < 1) return std::vector<Rational>{};
  std::vector<Rational> roots;
  // the root 0: divide out y
  std::size_t zeros = 0;
  while (zeros < p.size() && p[zeros] == 0) ++zeros;
  if (zeros > 0) {
    roots.push_back(Rational(0));
    p.erase(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(zeros));
  }
  const int n = degree(p);
  if (n < 1) return roots;
  // A root num/den (lowest terms) has |num| <= |a_0| and den <= |a_n| (num | a_0, den | a_n, for
  // any integer polynomial: no content needs dividing out, which would cost gcds of the coefficients):
  // it is the unique such fraction congruent to a modulo M > 2 |a_0| |a_n|, where a is its
  // image modulo a power of a prime l not dividing a_n (den is invertible), a root of p there.
  const mpz_class bound_num = abs(p.front()), bound_den = abs(p.back());
  const mpz_class needed = 2 * bound_num * bound_den;
  const Polynomial dp = derivative(p);
  auto value_mod = [](const Polynomial& q, const mpz_class& x, const mpz_class& m) {
    mpz_class v = 0;
    for (auto c = q.rbegin(); c != q.rend(); ++c) {
      v = v * x + *c;
      mpz_mod(v.get_mpz_t(), v.get_mpz_t(), m.get_mpz_t());
    }
    return v;
  };
  // Up to 6 usable primes (not dividing a_n, every root modulo it simple) among 40 from 257 on:
  // none of them with a root modulo it proves that p has no rational root (the common case,
  // without lifting); else the one with the fewest roots is lifted.
  mpz_class prime = 257, best_prime;
  std::vector<unsigned long> best_residues;
  int usable = 0;
  for (int attempt = 0; attempt < 40 && usable < 6; ++attempt, mpz_nextprime(prime.get_mpz_t(), prime.get_mpz_t())) {
    if (mpz_divisible_p(bound_den.get_mpz_t(), prime.get_mpz_t())) continue;
    const unsigned long l = prime.get_ui();
    std::vector<unsigned long> reduced, reduced_derivative;
    for (const mpz_class& c : p) reduced.push_back(mpz_fdiv_ui(c.get_mpz_t(), l));
    for (const mpz_class& c : dp) reduced_derivative.push_back(mpz_fdiv_ui(c.get_mpz_t(), l));
    auto small_value = [l](const std::vector<unsigned long>& q, unsigned long x) {
      unsigned long v = 0;
      for (auto c = q.rbegin(); c != q.rend(); ++c) v = (v * x + *c) % l;
      return v;
    };
    std::vector<unsigned long> residues;
    bool simple = true;
    for (unsigned long x = 0; x < l && simple; ++x) {
      if (small_value(reduced, x) != 0) continue;
      if (small_value(reduced_derivative, x) == 0) simple = false;
      residues.push_back(x);
    }
    if (!simple) continue;
    if (residues.empty()) return roots;   // no root modulo l: no rational root but 0
    if (usable++ == 0 || residues.size() < best_residues.size()) {
      best_prime = prime;
      best_residues = std::move(residues);
    }
  }
  if (usable == 0) return std::nullopt;   // every prime tried has a multiple root modulo it (or divides a_n)
  // each simple root modulo l lifts to exactly one l-adic root (Hensel): every rational root is met
  for (unsigned long residue : best_residues) {
    // quadratic Hensel lifting: a <- a - p(a) / p'(a) modulo l^(2^k), until l^(2^k) > needed
    mpz_class a = residue, modulus = best_prime;
    while (modulus <= needed) {
      modulus *= modulus;
      mpz_class inverse = value_mod(dp, a, modulus);
      if (!mpz_invert(inverse.get_mpz_t(), inverse.get_mpz_t(), modulus.get_mpz_t()))
        throw NumericError("internal: a simple root modulo a prime lost its derivative");
      a -= value_mod(p, a, modulus) * inverse;
      mpz_mod(a.get_mpz_t(), a.get_mpz_t(), modulus.get_mpz_t());
    }
    // rational reconstruction: the extended Euclidean remainders of (modulus, a) down to the
    // first one <= |a_0| give num = r1, den = t1 (up to sign)
    mpz_class r0 = modulus, r1 = a, t0 = 0, t1 = 1, quotient, next;
    while (r1 > bound_num) {
      mpz_fdiv_q(quotient.get_mpz_t(), r0.get_mpz_t(), r1.get_mpz_t());
      next = r0 - quotient * r1;
      r0 = std::move(r1);
      r1 = std::move(next);
      next = t0 - quotient * t1;
      t0 = std::move(t1);
      t1 = std::move(next);
    }
    if (t1 == 0 || abs(t1) > bound_den) continue;
    Rational candidate(r1, t1);
    candidate.canonicalize();
    if (sign_at(p, candidate) == 0) roots.push_back(candidate);
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

std::optional<Rational> rational_root(const Real& r) {
  if (r.exact) return r.lower;
  const Polynomial& p = r.polynomial;
  const int n = degree(p);
  if (n < 1) throw NumericError("internal: an isolated real root of a constant polynomial");
  if (n == 1) {
    Rational value(p[0], p[1]);
    value.canonicalize();
    return Rational(-value);
  }
  if (std::optional<std::vector<Rational>> roots = rational_roots(p)) {
    for (const Rational& root : *roots)
      if (r.compare(root) == 0) return root;
    return std::nullopt;
  }
  return rational_root_by_refinement(r);
}

Rational root_bound(const Polynomial& p) {
  // Cauchy: 1 + max |a_i / a_n|
  Rational best = 0;
  for (int i = 0; i < degree(p); ++i) {
    Rational q(abs(p[static_cast<std::size_t>(i)]), abs(p.back()));
    q.canonicalize();   // GMP's rational functions expect canonical operands (== compares num/den)
    if (q > best) best = q;
  }
  return best + 1;
}

namespace {

// The roots of a square-free p of degree >= 1 in [lo, hi] when lo = hi or p is linear (then
// true); false otherwise (nothing appended).
bool isolated_trivially(const Polynomial& p, const Rational& lo, const Rational& hi, std::vector<Real>& roots) {
  if (lo == hi) {
    if (sign_at(p, lo) == 0) roots.push_back(Real::from_rational(lo));
    return true;
  }
  if (degree(p) == 1) {   // linear: the root is rational
    Rational root(-p[0], p[1]);
    root.canonicalize();
    if (lo <= root && root <= hi) roots.push_back(Real::from_rational(root));
    return true;
  }
  return false;
}

void isolate(const Polynomial& p, const SturmSequence& sturm, Rational a, Rational b, int n,
             std::vector<Real>& out) {
  // roots in (a, b], n of them, appended ascending
  if (n <= 0) return;
  if (sign_at(p, b) == 0) {
    // b is the largest root in (a, b]; isolate the others in (a, c] with no root in (c, b)
    if (n > 1) {
      Rational c = (a + b) / 2;
      while (sturm.count(c, b) > 1) c = (c + b) / 2;
      isolate(p, sturm, a, c, n - 1, out);
    }
    out.push_back(Real::from_rational(b));
    return;
  }
  if (n == 1) {
    while (sign_at(p, a) == 0) {
      Rational m = (a + b) / 2;
      if (sign_at(p, m) == 0) {
        out.push_back(Real::from_rational(m));
        return;
      }
      if (sturm.count(a, m) == 1)
        b = m;
      else
        a = m;
    }
    Real r;
    r.polynomial = p;
    r.lower = a;
    r.upper = b;
    out.push_back(std::move(r));
    return;
  }
  Rational m = (a + b) / 2;
  int left = sturm.count(a, m);
  isolate(p, sturm, a, m, left, out);
  isolate(p, sturm, m, b, n - left, out);
}

// real_roots(p, lo, hi) of a p that is its own square_free_part (primitive, square-free,
// positive leading coefficient).
std::vector<Real> square_free_real_roots(const Polynomial& p, const Rational& lo, const Rational& hi) {
  std::vector<Real> roots;
  if (degree(p) < 1 || lo > hi) return roots;
  if (isolated_trivially(p, lo, hi, roots)) return roots;
  SturmSequence sturm(p);
  if (sign_at(p, lo) == 0) roots.push_back(Real::from_rational(lo));
  isolate(p, sturm, lo, hi, sturm.count(lo, hi), roots);
  return roots;
}

}  // namespace

std::vector<Real> real_roots(const Polynomial& input, const Rational& lo, const Rational& hi) {
  // the same polynomial as square_free_part(input), without the exact gcd when a modular one
  // certifies that there is no square factor
  return square_free_real_roots(square_free_test(input), lo, hi);
}

std::vector<Real> real_roots(const Polynomial& input) {
  // square_free_test(input) is square_free_part(input) (see real_roots above), which is its own
  // square-free part: its roots in the bound are isolated without testing it again
  Polynomial p = square_free_test(input);
  if (degree(p) < 1) return {};
  Rational bound = root_bound(p);
  return square_free_real_roots(p, -bound, bound);
}

// ---------------------------------------------------------------- Descartes' rule of signs

namespace {

// Sign variations of the coefficients, zeros skipped.
int sign_variations(const Polynomial& q) {
  int variations = 0, last = 0;
  for (const mpz_class& c : q) {
    const int s = sgn(c);
    if (s == 0) continue;
    if (last != 0 && s != last) ++variations;
    last = s;
  }
  return variations;
}

// q(t) -> q(t + 1), in place (Horner's scheme, additions only).
void taylor_shift_by_one(Polynomial& q) {
  const std::size_t n = q.size();
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = n - 1; j-- > i;) mpz_add(q[j].get_mpz_t(), q[j].get_mpz_t(), q[j + 1].get_mpz_t());
}

// Divides every coefficient by their common power of two (same roots, same signs).
void remove_common_power_of_two(Polynomial& q) {
  mp_bitcnt_t common = ~static_cast<mp_bitcnt_t>(0);
  for (const mpz_class& c : q)
    if (sgn(c) != 0) common = std::min(common, mpz_scan1(c.get_mpz_t(), 0));
  if (common == 0 || common == ~static_cast<mp_bitcnt_t>(0)) return;
  for (mpz_class& c : q) mpz_fdiv_q_2exp(c.get_mpz_t(), c.get_mpz_t(), common);
}

// Upper bound on the number of roots of q in the open interval (0, 1): the sign variations of
// (1 + t)^n q(1 / (1 + t)) (Descartes' rule; exact when 0 or 1).
int descartes_bound(const Polynomial& q) {
  Polynomial m(q.rbegin(), q.rend());
  taylor_shift_by_one(m);
  return sign_variations(m);
}

struct DescartesIsolator {
  const Polynomial& p;   // square-free, primitive
  const Rational& lo;
  Rational width;        // hi - lo
  std::vector<Real>& out;

  Rational at(const mpz_class& k, unsigned long level) const {
    Rational t(k, mpz_class(1) << level);
    t.canonicalize();
    return lo + width * t;
  }

  // q(t) is a positive multiple of p(lo + width (k + t) / 2^level), t in (0, 1); the ends are
  // roots of p when left_root / right_root. Appends the roots in the open part, ascending.
  void isolate(Polynomial q, const mpz_class& k, unsigned long level, bool left_root, bool right_root) {
    const int bound = descartes_bound(q);
    if (bound == 0) return;
    if (bound == 1 && !left_root && !right_root) {
      Real r;
      r.polynomial = p;
      r.lower = at(k, level);
      r.upper = at(k + 1, level);
      out.push_back(std::move(r));
      return;
    }
    // halves: 2^n q(t / 2) and 2^n q((t + 1) / 2)
    const std::size_t n = q.size() - 1;
    for (std::size_t i = 0; i < n; ++i) mpz_mul_2exp(q[i].get_mpz_t(), q[i].get_mpz_t(), n - i);
    Polynomial right = q;
    taylor_shift_by_one(right);
    const bool middle_root = sgn(right[0]) == 0;   // 2^n q(1/2)
    remove_common_power_of_two(q);
    remove_common_power_of_two(right);
    const mpz_class left_k = 2 * k;
    isolate(std::move(q), left_k, level + 1, left_root, middle_root);
    if (middle_root) out.push_back(Real::from_rational(at(left_k + 1, level + 1)));
    isolate(std::move(right), left_k + 1, level + 1, middle_root, right_root);
  }
};

}  // namespace

namespace {

// The exact square-free parts of square_free_test's primitive polynomials that are not
// square-free modulo the test primes, remembered per thread: the tiles of one chart share
// their curves, so the same resultants come back tile after tile (on the 18 x 27 gears'
// operating region, 8,000 exact square-free parts of 532 distinct polynomials). The value is a
// pure function of the key (compared coefficient by coefficient), so a hit returns exactly
// what square_free_part would. Bounded: emptied when it holds `capacity` polynomials.
Polynomial memoised_square_free_part(const Polynomial& p) {
  thread_local PolynomialMemo memo;
  return remembered(memo, p, [&] { return square_free_part_of_primitive(p); });
}

}  // namespace

bool coprime_modularly(const Polynomial& p, const Polynomial& q) {
  // the primitive gcd g of p and q divides p in Z[x], so its leading coefficient divides p's: a
  // prime not dividing p's keeps g's degree, and g mod the prime divides both reductions
  if (p.empty() || q.empty()) return false;
  for (std::uint64_t prime : {2147483647ULL, 2147483629ULL, 2147483587ULL}) {
    if (mpz_fdiv_ui(p.back().get_mpz_t(), static_cast<unsigned long>(prime)) == 0) continue;
    if (modular_gcd_degree(residues(p, prime), residues(q, prime), prime) == 0) return true;
  }
  return false;
}

Polynomial square_free_test(const Polynomial& input, bool* exact_needed) {
  if (exact_needed) *exact_needed = false;
  Polynomial p = primitive_part(input);
  if (degree(p) <= 1) return p;
  for (std::uint64_t prime : {2147483647ULL, 2147483629ULL, 2147483587ULL}) {
    if (mpz_fdiv_ui(p.back().get_mpz_t(), static_cast<unsigned long>(prime)) == 0) continue;
    // the derivative's residues from p's: (i p_i) mod prime = (i (p_i mod prime)) mod prime
    // (i < degree < prime; products below 2^62), the residues of derivative(p) without forming it
    Residues r = residues(p, prime), dr(r.size() - 1);
    for (std::size_t i = 1; i < r.size(); ++i) dr[i - 1] = i * r[i] % prime;
    if (modular_gcd_degree(std::move(r), std::move(dr), prime) == 0) return p;
  }
  if (exact_needed) *exact_needed = true;
  return memoised_square_free_part(p);
}

// square_free_test's answers, remembered per thread (descartes_real_roots' inputs and the
// kernel slicer's substituted curves). The quadratic traits isolates the same resultants,
// discriminants and leading coefficients in every tile a curve crosses (a chart's curves do not
// depend on the tile's box), the kernel slicer substitutes the same driver value into the same
// curve for several follower charts, windows and congruent pairs, and the test's primitive part
// (a gcd of every coefficient) and modular gcds cost more than the isolation of a tile's few
// roots. The answer is a pure function of the input polynomial (compared coefficient by
// coefficient), so a hit returns exactly what square_free_test would. Bounded: emptied when it
// holds `capacity` polynomials.
Polynomial remembered_square_free_test(const Polynomial& input) {
  thread_local PolynomialMemo memo;
  return remembered(memo, input, [&] { return square_free_test(input); });
}

std::vector<Real> descartes_real_roots(const Polynomial& input, const Rational& lo, const Rational& hi) {
  std::vector<Real> roots;
  if (degree(input) < 1 || lo > hi) return roots;
  Polynomial p = remembered_square_free_test(input);
  if (isolated_trivially(p, lo, hi, roots)) return roots;
  // q(t) = D^n p(lo + (hi - lo) t) with lo = a / b, hi - lo = c / e, D = b e:
  // sum p_i (a e + c b t)^i D^(n - i), by Horner's scheme on polynomials in t.
  DescartesIsolator isolator{p, lo, Rational(hi - lo), roots};
  const mpz_class shift = lo.get_num() * isolator.width.get_den();
  const mpz_class scale = isolator.width.get_num() * lo.get_den();
  const mpz_class denominator = lo.get_den() * isolator.width.get_den();
  const int n = degree(p);
  Polynomial q(static_cast<std::size_t>(n) + 1);
  q[0] = p.back();
  mpz_class denominator_power = 1;
  for (int i = n - 1, size = 1; i >= 0; --i, ++size) {
    // q <- q (shift + scale t) + p_i D^(n - i)
    for (int j = size; j >= 1; --j) {
      mpz_mul(q[static_cast<std::size_t>(j)].get_mpz_t(), q[static_cast<std::size_t>(j)].get_mpz_t(), shift.get_mpz_t());
      mpz_addmul(q[static_cast<std::size_t>(j)].get_mpz_t(), q[static_cast<std::size_t>(j - 1)].get_mpz_t(), scale.get_mpz_t());
    }
    mpz_mul(q[0].get_mpz_t(), q[0].get_mpz_t(), shift.get_mpz_t());
    mpz_mul(denominator_power.get_mpz_t(), denominator_power.get_mpz_t(), denominator.get_mpz_t());
    mpz_addmul(q[0].get_mpz_t(), p[static_cast<std::size_t>(i)].get_mpz_t(), denominator_power.get_mpz_t());
  }
  // q's common power of two removed (the isolation reads only signs: any positive multiple of
  // q isolates the same roots in the same intervals). The whole content was divided out before:
  // on the 18 x 27 gears' operating region it is a power of two times an odd part of ~5 bits
  // on average (15 810 calls), and the gcds that found it cost 1.6 % of the build.
  remove_common_power_of_two(q);
  const bool lo_root = sgn(q[0]) == 0;
  mpz_class total = 0;
  for (const auto& c : q) total += c;
  const bool hi_root = sgn(total) == 0;
  if (lo_root) roots.push_back(Real::from_rational(lo));
  isolator.isolate(std::move(q), mpz_class(0), 0, lo_root, hi_root);
  if (hi_root) roots.push_back(Real::from_rational(hi));
  return roots;
}

Real nth_real_root(const Polynomial& p, int index) {
  std::vector<Real> roots = real_roots(p);
  if (index < 0 || index >= static_cast<int>(roots.size()))
    throw NumericError("internal: contact curve has no real root number " + std::to_string(index));
  return roots[static_cast<std::size_t>(index)];
}

Real nth_real_root_in(const Polynomial& input, int index, const Rational& lo, const Rational& hi) {
  Polynomial p = square_free_test(input);   // = square_free_part(input)
  if (degree(p) < 1) throw NumericError("internal: evaluating a constant contact curve");
  if (degree(p) == 1) {
    Rational root(-p[0], p[1]);
    root.canonicalize();
    if (index != 0 || !(lo < root && root < hi))
      throw NumericError("internal: contact curve root " + std::to_string(index) + " is not in its certified box");
    return Real::from_rational(root);
  }
  SturmSequence sturm(p);
  Rational a = lo, b = hi;
  if (sturm.count_up_to(a) > index || sturm.count_up_to(b) <= index || sign_at(p, a) == 0)
    throw NumericError("internal: contact curve root " + std::to_string(index) + " is not in its certified box");
  // invariant: count_up_to(a) <= index < count_up_to(b), p(a) != 0
  while (sturm.count(a, b) > 1) {
    Rational m = (a + b) / 2;
    if (sturm.count_up_to(m) > index)
      b = m;
    else
      a = m;
  }
  // exactly one root in (a, b]; p(a) may be zero only if a is not lo (then a is a root below)
  for (;;) {
    if (sign_at(p, b) == 0) return Real::from_rational(b);
    if (sign_at(p, a) != 0) break;
    Rational m = (a + b) / 2;
    if (sturm.count(a, m) == 1)
      b = m;
    else
      a = m;
  }
  Real r;
  r.polynomial = std::move(p);
  r.lower = std::move(a);
  r.upper = std::move(b);
  return r;
}

// ---------------------------------------------------------------- bivariate

Polynomial substitute_x(const IntegerPolynomial2& f, const Rational& x) {
  const auto& c = f.coefficients;
  int dx = static_cast<int>(c.size()) - 1;
  std::size_t dy = 0;
  for (const auto& row : c) dy = std::max(dy, row.size());
  Polynomial result(dy);
  const mpz_class& n = x.get_num();
  const mpz_class& d = x.get_den();
  // coefficient of y^j: sum_i c[i][j] n^i d^(dx - i) (products accumulated in place: no
  // temporary integer per term; per-thread scratch for the weights)
  thread_local std::vector<mpz_class> weights;
  thread_local mpz_class dp;
  if (weights.size() < static_cast<std::size_t>(std::max(dx + 1, 0))) weights.resize(static_cast<std::size_t>(dx + 1));
  for (int i = 0; i <= dx; ++i) {
    mpz_class& w = weights[static_cast<std::size_t>(i)];
    mpz_pow_ui(w.get_mpz_t(), n.get_mpz_t(), static_cast<unsigned long>(i));
    mpz_pow_ui(dp.get_mpz_t(), d.get_mpz_t(), static_cast<unsigned long>(dx - i));
    mpz_mul(w.get_mpz_t(), w.get_mpz_t(), dp.get_mpz_t());
  }
  for (int i = 0; i <= dx; ++i)
    for (std::size_t j = 0; j < c[static_cast<std::size_t>(i)].size(); ++j)
      mpz_addmul(result[j].get_mpz_t(), c[static_cast<std::size_t>(i)][j].get_mpz_t(),
                 weights[static_cast<std::size_t>(i)].get_mpz_t());
  trim(result);
  return result;
}

Polynomial substitute_y(const IntegerPolynomial2& f, const Rational& y) {
  const auto& c = f.coefficients;
  std::size_t dy = 0;
  for (const auto& row : c) dy = std::max(dy, row.size());
  int degree_y = static_cast<int>(dy) - 1;
  if (degree_y < 0) return {};
  const mpz_class& n = y.get_num();
  const mpz_class& d = y.get_den();
  std::vector<mpz_class> weights(dy);
  for (int j = 0; j <= degree_y; ++j) {
    mpz_class w, dp;
    mpz_pow_ui(w.get_mpz_t(), n.get_mpz_t(), static_cast<unsigned long>(j));
    mpz_pow_ui(dp.get_mpz_t(), d.get_mpz_t(), static_cast<unsigned long>(degree_y - j));
    weights[static_cast<std::size_t>(j)] = w * dp;
  }
  Polynomial result(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) result[i] += c[i][j] * weights[j];
  trim(result);
  return result;
}

Polynomial y_coefficient(const IntegerPolynomial2& f, int j) {
  Polynomial result(f.coefficients.size());
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    if (static_cast<std::size_t>(j) < f.coefficients[i].size()) result[i] = f.coefficients[i][static_cast<std::size_t>(j)];
  trim(result);
  return result;
}

Polynomial product(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial result(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) mpz_addmul(result[i + j].get_mpz_t(), a[i].get_mpz_t(), b[j].get_mpz_t());
  trim(result);
  return result;
}

Polynomial substitute_ordinate(const IntegerPolynomial2& f, const Polynomial& P, const Polynomial& Q) {
  // Horner in y: H = f_d, then H = H P + f_j Q^(d - j) for j = d - 1 ... 0
  const int d = f.degree_y();
  if (d < 0) return {};
  Polynomial result = y_coefficient(f, d), power{mpz_class(1)};
  for (int j = d - 1; j >= 0; --j) {
    power = product(power, Q);
    Polynomial term = product(y_coefficient(f, j), power);
    result = product(result, P);
    if (result.size() < term.size()) result.resize(term.size());
    for (std::size_t i = 0; i < term.size(); ++i) result[i] += term[i];
    trim(result);
  }
  return result;
}

namespace {
std::vector<Rational> multiply(const std::vector<Rational>& a, const std::vector<Rational>& b) {
  std::vector<Rational> r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}
}  // namespace

Polynomial substitute_line(const IntegerPolynomial2& f, const Rational& x0, const Rational& dx,
                           const Rational& y0, const Rational& dy) {
  const auto& c = f.coefficients;
  std::size_t max_j = 0;
  for (const auto& row : c) max_j = std::max(max_j, row.size());
  std::vector<std::vector<Rational>> x_powers{{Rational(1)}}, y_powers{{Rational(1)}};
  for (std::size_t i = 1; i < c.size(); ++i) x_powers.push_back(multiply(x_powers.back(), {x0, dx}));
  for (std::size_t j = 1; j < max_j; ++j) y_powers.push_back(multiply(y_powers.back(), {y0, dy}));
  std::vector<Rational> result(1, Rational(0));
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j) {
      if (sgn(c[i][j]) == 0) continue;
      std::vector<Rational> term = multiply(x_powers[i], y_powers[j]);
      if (term.size() > result.size()) result.resize(term.size());
      for (std::size_t k = 0; k < term.size(); ++k) result[k] += Rational(c[i][j]) * term[k];
    }
  return from_rationals(result);
}

int sign_at(const IntegerPolynomial2& f, const Rational& x, const Rational& y) {
  return sign_at(substitute_x(f, x), y);
}

Polynomial univariate_x(const IntegerPolynomial2& f) {
  Polynomial p;
  for (const auto& row : f.coefficients) p.push_back(row.empty() ? mpz_class(0) : row[0]);
  trim(p);
  return p;
}

bool vanishes_at(const Polynomial& p, const Real& u) {
  if (p.empty()) return true;
  if (u.exact) return sign_at(p, u.lower) == 0;
  Polynomial g = gcd(p, u.polynomial);
  if (degree(g) < 1) return false;
  return sign_at(g, u.lower) * sign_at(g, u.upper) < 0;
}

namespace {

// The sign of p at u by the Sturm sequence of p's square-free part. \pre p(u) != 0.
int nonzero_sign_at(const Polynomial& p, const Real& u) {
  Polynomial q = square_free_part(p);
  SturmSequence sturm(q);
  Real v = u;
  for (;;) {
    if (v.exact) return sign_at(p, v.lower);
    // no root of p in (lower, upper]: p keeps the sign it has at upper
    if (sturm.count(v.lower, v.upper) == 0) return sign_at(p, v.upper);
    v.refine();
  }
}

}  // namespace

namespace {
thread_local long wide_gcds = 0;   // wide_sign_gcds()
}  // namespace

long wide_sign_gcds() { return wide_gcds; }

int sign_at(const Polynomial& p, const Real& u) {
  if (p.empty()) return 0;
  if (u.exact) return sign_at(p, u.lower);
  {
    // Filter: p over the isolating interval in certified double intervals, refined a little
    // when inconclusive; the exact path below (gcd, Sturm) only when p may vanish near u.
    std::vector<Interval> coefficients;
    coefficients.reserve(p.size());
    for (const auto& c : p) coefficients.push_back(enclose(c));
    // the first round on u itself; a copy to refine only when it is inconclusive
    std::optional<Real> refined;
    const Real* v = &u;
    for (int round = 0; round < 3; ++round) {
      if (v->exact) return sign_at(p, v->lower);
      Interval x{lower_double(v->lower), upper_double(v->upper)};
      Interval value{0, 0};
      for (auto c = coefficients.rbegin(); c != coefficients.rend(); ++c) value = value * x + *c;
      if (value.lo > 0) return 1;   // (NaN from overflow fails both tests)
      if (value.hi < 0) return -1;
      if (!refined) v = &refined.emplace(u);
      for (int k = 0; k < 4 && !refined->exact; ++k) refined->refine();
    }
  }
  // Coefficients of more than 192 bits (mixed scales): a zero by the exact gcd as before, then a
  // non-zero value by MPFR intervals over the isolating interval, and only past their precisions
  // by the Sturm sequence. Narrower coefficients keep the exact path alone: there the Sturm
  // sequence of a non-zero value costs less than the filter (measured on the examples,
  // docs/performance.md, session 40). (A modular coprimality test before the gcd would spare it
  // for coprime pairs, but costs more on the examples' zeros than it saves.)
  const MultiprecisionBits bits = multiprecision_sign_bits(p, u);
  if (bits.width <= 192) return exact_sign_at(p, u);
  // a zero only where p shares a factor with u's polynomial: a gcd certified constant modulo a
  // word-size prime excludes it without the gcd over the integers (the mixed-scale squares' wide
  // coefficients made that gcd a third of their signs' cost, session 45)
  if (!coprime_modularly(u.polynomial, p)) {
    ++wide_gcds;
    if (vanishes_at(p, u)) return 0;
  }
  if (const auto sign = multiprecision_sign(p, u, bits.start, bits.cap)) return *sign;
  return nonzero_sign_at(p, u);
}

int exact_sign_at(const Polynomial& p, const Real& u) {
  if (p.empty()) return 0;
  if (u.exact) return sign_at(p, u.lower);
  if (vanishes_at(p, u)) return 0;
  return nonzero_sign_at(p, u);
}

int sign_at(const IntegerPolynomial2& f, const Rational& x, const Real& y) {
  // a constant (e.g. a line's derivative in y): its sign, as the substitution below gives it
  // (c d^k with d > 0, whatever y is)
  bool constant = true;
  for (std::size_t i = 0; i < f.coefficients.size() && constant; ++i)
    for (std::size_t j = i == 0 ? 1 : 0; j < f.coefficients[i].size(); ++j)
      if (sgn(f.coefficients[i][j]) != 0) {
        constant = false;
        break;
      }
  if (constant) return f.coefficients.empty() || f.coefficients[0].empty() ? 0 : sgn(f.coefficients[0][0]);
  return sign_at(substitute_x(f, x), y);
}

int sign_at(const IntegerPolynomial2& f, const Real& x, const Rational& y) {
  return sign_at(substitute_y(f, y), x);
}

bool vanishes_at(const IntegerPolynomial2& f, const Rational& x, const Real& y) {
  return vanishes_at(substitute_x(f, x), y);
}

bool vanishes_at(const IntegerPolynomial2& f, const Real& x, const Rational& y) {
  return vanishes_at(substitute_y(f, y), x);
}

std::string to_string(const IntegerPolynomial2& f, const std::string& x, const std::string& y) {
  std::ostringstream out;
  bool first = true;
  const auto& c = f.coefficients;
  for (int i = static_cast<int>(c.size()) - 1; i >= 0; --i)
    for (int j = static_cast<int>(c[static_cast<std::size_t>(i)].size()) - 1; j >= 0; --j) {
      const mpz_class& v = c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      if (sgn(v) == 0) continue;
      mpz_class magnitude = abs(v);
      if (first)
        out << (sgn(v) < 0 ? "-" : "");
      else
        out << (sgn(v) < 0 ? " - " : " + ");
      first = false;
      bool has_variable = i > 0 || j > 0;
      if (!has_variable || magnitude != 1) out << magnitude.get_str() << (has_variable ? "*" : "");
      if (i > 0) out << x;
      if (i > 1) out << '^' << i;
      if (i > 0 && j > 0) out << "*";
      if (j > 0) out << y;
      if (j > 1) out << '^' << j;
    }
  return first ? "0" : out.str();
}

// ---------------------------------------------------------------- intervals

// The bounds of {lower_double(r), upper_double(r)} bit for bit, in one pass: both take the same
// nearest-towards-zero double d = r.get_d() and the same exact sign of r - d, which moves one of
// them to the next double outwards. A rational with a power-of-two denominator 2^k (every
// bisection end, every double) and a numerator of at most 53 bits is that double itself when
// k <= 1022 (no subnormal): then d is exact and both bounds are d, without the division and the
// comparison.
Interval enclose(const Rational& r) {
  const mpz_srcptr num = r.get_num_mpz_t(), den = r.get_den_mpz_t();
  if (mpz_sgn(num) == 0) return {0.0, 0.0};
  const std::size_t den_bits = mpz_sizeinbase(den, 2);
  if (mpz_sizeinbase(num, 2) <= 53 && den_bits <= 1023 && mpz_scan1(den, 0) == den_bits - 1) {
    const double d = std::ldexp(mpz_get_d(num), -static_cast<int>(den_bits - 1));   // exact
    return {d, d};
  }
  const double d = r.get_d();
  if (std::isinf(d))
    return {d > 0 ? std::numeric_limits<double>::max() : d, d < 0 ? std::numeric_limits<double>::lowest() : d};
  const int c = compare_with_double(r, d);   // sign(r - d)
  return {c < 0 ? std::nextafter(d, -std::numeric_limits<double>::infinity()) : d,
          c > 0 ? std::nextafter(d, std::numeric_limits<double>::infinity()) : d};
}
// The bounds of enclose(Rational(z)) bit for bit, without the rational copy (an allocation, and
// mpq_get_d's division): mpz_get_d truncates toward zero as mpq_get_d does (the same double, and
// the same infinity beyond the doubles' range), and mpz_cmp_d compares z with a finite double
// exactly, as compare_with_double does. So lower_double and upper_double take the same branches.
namespace {

// enclose(z) given d = z.get_d() (z truncated toward zero): the interval
// {c < 0 ? nextafter(d, -inf) : d, c > 0 ? nextafter(d, +inf) : d} with c = sign(z - d), found
// without comparing z with d: a truncation is exact exactly when z's significant bits (from its
// highest set bit to its lowest) number at most 53, and otherwise lies strictly between 0 and z,
// so c = sign(z); the neighbour away from zero of a finite non-zero double is the next bit
// pattern (the largest finite double's is the infinity, as nextafter's).
Interval enclose_truncated(const mpz_class& z, double d) {
  if (std::isinf(d))
    return {d > 0 ? std::numeric_limits<double>::max() : d, d < 0 ? std::numeric_limits<double>::lowest() : d};
  const mpz_srcptr p = z.get_mpz_t();
  const int s = mpz_sgn(p);
  if (s == 0 || mpz_sizeinbase(p, 2) - mpz_scan1(p, 0) <= 53) return {d, d};
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  ++bits;   // |d| one step up (d is finite and non-zero: |z| >= 2^53)
  double away;
  std::memcpy(&away, &bits, sizeof away);
  return s > 0 ? Interval{d, away} : Interval{away, d};
}

}  // namespace

Interval enclose(const mpz_class& z) { return enclose_truncated(z, z.get_d()); }

// ---------------------------------------------------------------- scaled enclosures (interval_shift.hpp)

bool& interval_scaling() {
  thread_local bool on = false;
  return on;
}

long interval_shift(const IntegerPolynomial2& f) {
  long bits = 0;
  for (const auto& row : f.coefficients)
    for (const mpz_class& c : row)
      if (sgn(c) != 0) bits = std::max(bits, static_cast<long>(mpz_sizeinbase(c.get_mpz_t(), 2)));
  return bits > interval_coefficient_bits ? bits - interval_coefficient_bits : 0;
}

namespace {
// z = d 2^e with d = z truncated toward zero to 53 bits, 1/2 <= |d| < 1 (z != 0): the exponent
// e - shift of z / 2^shift, and d
double truncated_mantissa(const mpz_class& z, long shift, long& exponent) {
  long e = 0;
  const double d = mpz_get_d_2exp(&e, z.get_mpz_t());
  exponent = e - shift;
  return d;
}
constexpr long least_normal_exponent = -1021;   // 2^-1022 = (1/2) 2^-1021, the least normal double
constexpr long overflow_exponent = 1024;        // (1/2) 2^1025 = 2^1024 is beyond DBL_MAX
}  // namespace

Interval enclose_shifted(const mpz_class& z, long shift) {
  if (shift == 0) return enclose(z);
  const int s = sgn(z);
  if (s == 0) return {0.0, 0.0};
  long exponent = 0;
  const double d = truncated_mantissa(z, shift, exponent);
  const double least = std::numeric_limits<double>::min(), inf = std::numeric_limits<double>::infinity();
  if (exponent < least_normal_exponent) return s > 0 ? Interval{0.0, least} : Interval{-least, 0.0};   // |z / 2^shift| < 2^-1022
  if (exponent > overflow_exponent)
    return s > 0 ? Interval{std::numeric_limits<double>::max(), inf} : Interval{-inf, std::numeric_limits<double>::lowest()};
  // d 2^exponent is a normal double (or beyond DBL_MAX: enclose_truncated's infinite case), the
  // truncation of z / 2^shift toward zero: the same enclosure as enclose(z) of the scaled z
  return enclose_truncated(z, std::ldexp(d, static_cast<int>(exponent)));
}

double nearest_shifted(const mpz_class& z, long shift) {
  if (shift == 0) return z.get_d();
  if (sgn(z) == 0) return 0.0;
  long exponent = 0;
  const double d = truncated_mantissa(z, shift, exponent);
  if (exponent < least_normal_exponent) return std::numeric_limits<double>::quiet_NaN();
  if (exponent > overflow_exponent) return d > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  return std::ldexp(d, static_cast<int>(exponent));
}

Interval scale_by_power_of_two(Interval v, long exponent) {
  if (exponent == 0) return v;
  const double inf = std::numeric_limits<double>::infinity(), least = std::numeric_limits<double>::min();
  const int e = static_cast<int>(std::clamp<long>(exponent, -4096, 4096));   // beyond: 0 or infinity either way
  double lo = std::ldexp(v.lo, e), hi = std::ldexp(v.hi, e);
  // exact but where it left the normal range: an overflowed finite bound, an underflowed one
  if (lo == inf && v.lo < inf) lo = std::numeric_limits<double>::max();
  if (hi == -inf && v.hi > -inf) hi = std::numeric_limits<double>::lowest();
  if (std::fabs(lo) < least) lo = v.lo >= 0 ? 0.0 : -least;
  if (std::fabs(hi) < least) hi = v.hi <= 0 ? 0.0 : least;
  return {lo, hi};
}

IntervalPolynomial2::IntervalPolynomial2(const IntegerPolynomial2& f) {
  // under ScaledEnclosures, f / 2^shift (interval_shift.hpp): the same signs and zero set,
  // within the doubles' range
  const long shift = interval_scaling() ? interval_shift(f) : 0;
  int dx = 0, dy = 0;
  rows_.reserve(f.coefficients.size());
  nearest_.reserve(f.coefficients.size());
  for (std::size_t i = 0; i < f.coefficients.size(); ++i) {
    rows_.emplace_back();
    nearest_.emplace_back();
    rows_.back().reserve(f.coefficients[i].size());
    nearest_.back().reserve(f.coefficients[i].size());
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j) {
      // (one conversion: the nearest_ entry is the truncation enclose starts from)
      if (shift == 0) {
        const double d = f.coefficients[i][j].get_d();
        rows_.back().push_back(enclose_truncated(f.coefficients[i][j], d));
        nearest_.back().push_back(d);
      } else {
        rows_.back().push_back(enclose_shifted(f.coefficients[i][j], shift));
        nearest_.back().push_back(nearest_shifted(f.coefficients[i][j], shift));
      }
      if (sgn(f.coefficients[i][j]) != 0) {
        dx = std::max(dx, static_cast<int>(i));
        dy = std::max(dy, static_cast<int>(j));
      }
    }
  }
  total_degree_ = dx + dy;
}

namespace {

// The sign of a variable's interval: the product by it in two end products where it is known.
enum class SignKind { nonnegative, nonpositive, mixed };

SignKind sign_kind(Interval v) {
  return v.lo >= 0 ? SignKind::nonnegative : v.hi <= 0 ? SignKind::nonpositive : SignKind::mixed;
}

// An interval in the two lanes of one two-double vector, {lo, hi}: the scalar interval
// operations above lane by lane, the same operations in the same order on each bound, so the
// same bits (baseline x86-64: no fused multiply-adds to contract into).
namespace lanes {
using v2d = double __attribute__((vector_size(16)));
using v2l = long long __attribute__((vector_size(16)));

inline v2d load(const Interval& v) { return v2d{v.lo, v.hi}; }
inline v2d swapped(v2d v) { return __builtin_shuffle(v, v2l{1, 0}); }
// end_product in each lane: 0 * inf = 0
inline v2d end_products(v2d p) { return p == p ? p : v2d{0, 0}; }
// {down(v[0]), up(v[1])}: v -+ (|v| 2^-52 + 2 denorm_min), the subtraction as the addition of the
// negated term (IEEE 754: x - y is x + (-y)); unbounded or NaN bounds by the scalar rule.
inline v2d magnitude(v2d v) {
  return reinterpret_cast<v2d>(reinterpret_cast<v2l>(v) & v2l{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
}
// both lanes finite (not NaN): the scalar rule's ordinary case
inline bool finite(v2d magnitude) {
  return __builtin_expect(__builtin_ia32_movmskpd(magnitude < v2d{__builtin_inf(), __builtin_inf()}) == 3, 1);
}
inline v2d widened(v2d v, v2d magnitude) {
  const v2d step = magnitude * v2d{2.220446049250313e-16, 2.220446049250313e-16} +
                   v2d{2 * 4.9406564584124654e-324, 2 * 4.9406564584124654e-324};
  return v + reinterpret_cast<v2d>(reinterpret_cast<v2l>(step) ^ v2l{static_cast<long long>(0x8000000000000000ULL), 0});
}
// anything not finite (-inf below included) by the scalar rule
inline v2d outward(v2d v) {
  const v2d m = magnitude(v);
  return finite(m) ? widened(v, m) : v2d{interval_detail::down(v[0]), interval_detail::up(v[1])};
}
// outward(end_products(p)): a NaN lane (0 * inf) is not finite, so only the exceptional path maps it to 0
inline v2d outward_product(v2d p) {
  const v2d m = magnitude(p);
  if (finite(m)) return widened(p, m);
  p = end_products(p);
  return v2d{interval_detail::down(p[0]), interval_detail::up(p[1])};
}

// The product by a factor b of sign S: the end products of interval_detail::times_nonnegative
// (S nonnegative), times_nonpositive (S nonpositive) or operator* (mixed), picked by a's sign as there.
// b >= 0: a >= 0 {a.lo b.lo, a.hi b.hi}, a <= 0 {a.lo b.hi, a.hi b.lo}, mixed {a.lo b.hi, a.hi b.hi};
// b <= 0: a >= 0 {a.hi b.lo, a.lo b.hi}, a <= 0 {a.hi b.hi, a.lo b.lo}, mixed {a.hi b.lo, a.lo b.lo}
// (a's lanes swapped); b mixed: operator*'s four products and its order of comparisons.
template <SignKind S>
struct Factor {
  v2d b, ends, swapped_ends, mixed;
  explicit Factor(Interval f)
      : b{f.lo, f.hi}, ends{f.lo, f.hi}, swapped_ends{f.hi, f.lo},
        mixed{S == SignKind::nonnegative ? v2d{f.hi, f.hi} : v2d{f.lo, f.lo}} {}
  v2d times(v2d a) const {
    if constexpr (S == SignKind::mixed) {
      const v2d p12 = end_products(v2d{a[0], a[0]} * b), p34 = end_products(v2d{a[1], a[1]} * b);
      // lo = p1 < p2 ? p1 : p2, hi = p1 < p2 ? p2 : p1
      v2d v = p12[0] < p12[1] ? p12 : swapped(p12);
      // lo = lo < p ? lo : p, hi = hi < p ? p : hi (no NaN here: the lane-1 test negated)
      const v2d p3{p34[0], p34[0]}, p4{p34[1], p34[1]};
      v = ((v < p3) ^ v2l{0, -1}) ? v : p3;
      v = ((v < p4) ^ v2l{0, -1}) ? v : p4;
      return outward(v);
    } else {
      const v2d& f = a[0] >= 0 ? ends : a[1] <= 0 ? swapped_ends : mixed;
      if constexpr (S == SignKind::nonnegative)
        return outward_product(a * f);
      else
        return outward_product(swapped(a) * f);
    }
  }
};
// The product 0 * f, the first product of every Horner chain: where both ends of f are finite,
// each end product is a zero (of either sign, for every sign kind's choice of ends and
// comparisons) and outward() widens a zero by 2 denorm_min on each side, so the product is
// {-2 denorm_min, 2 denorm_min} bit for bit, without the product; otherwise (an infinite or NaN
// end: 0 * inf) f.times, as before.
template <SignKind S>
[[gnu::always_inline]] inline v2d zero_times(const Factor<S>& f, Interval factor) {
  if (finite(magnitude(load(factor)))) return v2d{-2 * 4.9406564584124654e-324, 2 * 4.9406564584124654e-324};
  return f.times(v2d{0, 0});
}
}  // namespace lanes

// One row of the nested Horner at y (the sum over j of c_j y^j, enclosed) in the two lanes:
// the scalar form's steps inner = inner * y + c from inner = 0, bound for bound (the first
// product, 0 times y, is `zero_y`, the same for every row).
template <SignKind SY>
[[gnu::always_inline]] inline lanes::v2d row_at(const std::vector<Interval>& row, const lanes::Factor<SY>& fy,
                                                lanes::v2d zero_y) {
  lanes::v2d inner{0, 0};
  if (auto c = row.rbegin(); c != row.rend()) {
    inner = lanes::outward(zero_y + lanes::load(*c));
    for (++c; c != row.rend(); ++c) inner = lanes::outward(fy.times(inner) + lanes::load(*c));
  }
  return inner;
}

// The outer Horner step in x: result = result * x + inner, from result = 0 (whose product by x
// is `zero_x`) at the first row.
template <SignKind SX>
[[gnu::always_inline]] inline lanes::v2d outer_step(lanes::v2d result, bool first, const lanes::Factor<SX>& fx,
                                                    lanes::v2d zero_x, lanes::v2d inner) {
  return lanes::outward((first ? zero_x : fx.times(result)) + inner);
}

// Nested Horner (rows in x, each row in y), the same operations in the same order for every
// sign of x and y: the products by x and y are those of operator*, bound for bound — the
// intervals in two vector lanes (lanes above), each lane the scalar form's bound (the test
// compares them bit for bit with a scalar nested Horner on generic products).
template <SignKind SX, SignKind SY>
[[gnu::flatten]] Interval horner(const std::vector<std::vector<Interval>>& rows, Interval x, Interval y) {
  using lanes::v2d;
  const lanes::Factor<SX> fx(x);
  const lanes::Factor<SY> fy(y);
  // the first product of each Horner chain, 0 times the factor: the same for every chain
  const v2d zero{0, 0}, zero_x = lanes::zero_times(fx, x), zero_y = lanes::zero_times(fy, y);
  v2d result = zero;
  for (auto row = rows.rbegin(); row != rows.rend(); ++row)
    result = outer_step(result, row == rows.rbegin(), fx, zero_x, row_at(*row, fy, zero_y));
  return {result[0], result[1]};
}

template <SignKind SX>
Interval horner_x(const std::vector<std::vector<Interval>>& rows, Interval x, Interval y) {
  switch (sign_kind(y)) {
    case SignKind::nonnegative: return horner<SX, SignKind::nonnegative>(rows, x, y);
    case SignKind::nonpositive: return horner<SX, SignKind::nonpositive>(rows, x, y);
    case SignKind::mixed: break;
  }
  return horner<SX, SignKind::mixed>(rows, x, y);
}

// The two halves of horner, in the same lanes: the rows at y, then the outer Horner in x over
// them (bit for bit horner's, which keeps the rows in registers instead).
template <SignKind SY>
[[gnu::flatten]] void rows_of(const std::vector<std::vector<Interval>>& rows, Interval y, std::vector<Interval>& out) {
  const lanes::Factor<SY> fy(y);
  const lanes::v2d zero_y = lanes::zero_times(fy, y);
  out.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const lanes::v2d inner = row_at(rows[i], fy, zero_y);
    out[i] = {inner[0], inner[1]};
  }
}

// (also the one-variable Horner of horner() and horner_from_leading(): the inner values are
// the coefficients)
template <SignKind SX>
[[gnu::flatten]] Interval outer_horner(const std::vector<Interval>& inner, Interval x, bool from_leading = false) {
  auto row = inner.rbegin();
  if (row == inner.rend()) return {0, 0};
  const lanes::Factor<SX> fx(x);
  const lanes::v2d zero{0, 0};
  lanes::v2d result =
      from_leading ? lanes::load(*row) : outer_step(zero, true, fx, lanes::zero_times(fx, x), lanes::load(*row));
  for (++row; row != inner.rend(); ++row) result = outer_step(result, false, fx, zero, lanes::load(*row));
  return {result[0], result[1]};
}

Interval outer_horner_any(const std::vector<Interval>& inner, Interval x, bool from_leading) {
  switch (sign_kind(x)) {
    case SignKind::nonnegative: return outer_horner<SignKind::nonnegative>(inner, x, from_leading);
    case SignKind::nonpositive: return outer_horner<SignKind::nonpositive>(inner, x, from_leading);
    case SignKind::mixed: break;
  }
  return outer_horner<SignKind::mixed>(inner, x, from_leading);
}

}  // namespace

Interval horner(const std::vector<Interval>& c, Interval x) { return outer_horner_any(c, x, false); }

Interval horner_from_leading(const std::vector<Interval>& c, Interval x) { return outer_horner_any(c, x, true); }

void IntervalPolynomial2::rows_at(Interval y, std::vector<Interval>& rows) const {
  switch (sign_kind(y)) {
    case SignKind::nonnegative: return rows_of<SignKind::nonnegative>(rows_, y, rows);
    case SignKind::nonpositive: return rows_of<SignKind::nonpositive>(rows_, y, rows);
    case SignKind::mixed: break;
  }
  rows_of<SignKind::mixed>(rows_, y, rows);
}

Interval IntervalPolynomial2::evaluate_rows(Interval x, const std::vector<Interval>& rows) const {
  return outer_horner_any(rows, x, false);
}

Interval IntervalPolynomial2::evaluate(Interval x, Interval y) const {
  switch (sign_kind(x)) {
    case SignKind::nonnegative: return horner_x<SignKind::nonnegative>(rows_, x, y);
    case SignKind::nonpositive: return horner_x<SignKind::nonpositive>(rows_, x, y);
    case SignKind::mixed: break;
  }
  return horner_x<SignKind::mixed>(rows_, x, y);
}

double IntervalPolynomial2::evaluate(double x, double y, double* error_bound) const {
  // Nested Horner. Each term passes through at most 2(dx + dy) + 1 roundings, including the
  // conversion of its coefficient, so |computed - exact| <= gamma_k * sum |c| |x|^i |y|^j with
  // k = 2(dx + dy) + 2 (Higham, Accuracy and Stability, 5.1). The magnitude sum is itself
  // computed in double: bound it by (1 + gamma_k) and double the result for safety.
  double value = 0, magnitude = 0;
  const double ax = std::fabs(x), ay = std::fabs(y);
  for (auto row = nearest_.rbegin(); row != nearest_.rend(); ++row) {
    double inner = 0, inner_magnitude = 0;
    for (auto c = row->rbegin(); c != row->rend(); ++c) {
      inner = inner * y + *c;
      inner_magnitude = inner_magnitude * ay + std::fabs(*c);
    }
    value = value * x + inner;
    magnitude = magnitude * ax + inner_magnitude;
  }
  if (error_bound) {
    const double u = std::numeric_limits<double>::epsilon() / 2;
    const double k = 2.0 * total_degree_ + 2;
    const double gamma = k * u / (1 - k * u);
    *error_bound = 2 * gamma * magnitude * (1 + gamma) + std::numeric_limits<double>::denorm_min();
  }
  return value;
}

}  // namespace hipair::cspace::algebra
