#include <hipair/error.hpp>
#include <hipair/rational.hpp>
#include "core/decimal_text.hpp"
#include "core/exact_literal.hpp"

#include <mpfr.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <sstream>

namespace hipair {
namespace {

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

mpz_class power_of_ten(unsigned long exponent) {
  mpz_class result;
  mpz_ui_pow_ui(result.get_mpz_t(), 10, exponent);
  return result;
}

// The text for a message: at most 40 characters, longer ones cut with "..." and their length.
std::string excerpt(std::string_view text) {
  if (text.size() <= 40) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, 40)) + "...' (" + std::to_string(text.size()) + " characters)";
}

// Exact value of an unsigned decimal "123", "1.25", "1.25e-7", ".5", "5.".
Rational parse_unsigned_decimal(std::string_view text, std::string_view whole) {
  auto fail = [&] { throw NumericError(excerpt(whole) + " is not a number"); };
  std::string_view mantissa = text;
  long long exponent = 0;
  if (auto e = text.find_first_of("eE"); e != std::string_view::npos) {
    mantissa = text.substr(0, e);
    std::string_view exp_text = text.substr(e + 1);
    bool negative = false;
    if (!exp_text.empty() && (exp_text[0] == '+' || exp_text[0] == '-')) {
      negative = exp_text[0] == '-';
      exp_text.remove_prefix(1);
    }
    if (!all_digits(exp_text) || exp_text.size() > 6) fail();
    exponent = std::stoll(std::string(exp_text));
    if (negative) exponent = -exponent;
  }
  std::string_view int_part = mantissa, frac_part;
  if (auto dot = mantissa.find('.'); dot != std::string_view::npos) {
    int_part = mantissa.substr(0, dot);
    frac_part = mantissa.substr(dot + 1);
  }
  if (int_part.empty() && frac_part.empty()) fail();
  if ((!int_part.empty() && !all_digits(int_part)) || (!frac_part.empty() && !all_digits(frac_part)))
    fail();
  std::string digits = std::string(int_part) + std::string(frac_part);
  exponent -= static_cast<long long>(frac_part.size());
  if (exponent > 100000 || exponent < -100000) fail();
  mpz_class numerator(digits.empty() ? std::string("0") : digits, 10);
  Rational value;
  if (exponent >= 0) {
    value = Rational(numerator * power_of_ten(static_cast<unsigned long>(exponent)));
  } else {
    value = Rational(numerator, power_of_ten(static_cast<unsigned long>(-exponent)));
    value.canonicalize();
  }
  return value;
}

}  // namespace

Rational parse_rational(std::string_view text) {
  std::string_view whole = text;
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  if (text.empty()) throw NumericError("empty number");
  bool negative = false;
  if (text[0] == '+' || text[0] == '-') {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  Rational value;
  if (auto slash = text.find('/'); slash != std::string_view::npos) {
    Rational numerator = parse_unsigned_decimal(text.substr(0, slash), whole);
    Rational denominator = parse_unsigned_decimal(text.substr(slash + 1), whole);
    if (denominator == 0) throw NumericError(excerpt(whole) + " divides by zero");
    value = numerator / denominator;
  } else {
    value = parse_unsigned_decimal(text, whole);
  }
  return negative ? Rational(-value) : value;
}

namespace {

// Length of the unsigned decimal at the start of `text` (digits, '.', exponent), 0 if none.
std::size_t unsigned_decimal_length(std::string_view text) {
  auto digit = [&](std::size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
  std::size_t i = 0;
  while (digit(i)) ++i;
  std::size_t integer_digits = i;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (digit(i)) ++i;
  }
  if (i - integer_digits <= 1 && integer_digits == 0) return 0;  // "", "." : no digit
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t k = i + 1;
    if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
    if (!digit(k)) return 0;  // "1e", "1e+": an exponent without digits
    while (digit(k)) ++k;
    i = k;
  }
  return i;
}

}  // namespace

Rational parse_exact_literal(std::string_view text) {
  auto refuse = [&](const std::string& why) {
    throw NumericError(excerpt(text) + " is not an exact literal: " + why);
  };
  if (text.empty()) throw NumericError("empty number");
  if (std::isspace(static_cast<unsigned char>(text.front())) || std::isspace(static_cast<unsigned char>(text.back())))
    refuse("a space before or after it");
  if (text.front() == '+') refuse("a '+' sign (write the number without it)");
  std::string_view rest = text;
  if (rest.front() == '-') rest.remove_prefix(1);
  std::size_t length = unsigned_decimal_length(rest);
  bool well_formed = length > 0;
  if (well_formed && length < rest.size()) {
    std::string_view denominator = rest.substr(length);
    well_formed = denominator.front() == '/' && unsigned_decimal_length(denominator.substr(1)) == denominator.size() - 1;
  }
  if (!well_formed)
    refuse("digits with an optional '-', '.', exponent and '/' expected ('3/7', '-2', '0.125', '1e-9')");
  // Each part's decimal exponent within exact_literal_max_exponent, the numerator's and the
  // denominator's alike ("1200/20e-4958" is a 16 473-bit number, not a typing slip to carry on).
  for (std::size_t e = rest.find_first_of("eE"); e != std::string_view::npos; e = rest.find_first_of("eE", e + 1)) {
    std::size_t k = e + 1;
    if (rest[k] == '+' || rest[k] == '-') ++k;
    while (k + 1 < rest.size() && rest[k] == '0' && rest[k + 1] >= '0' && rest[k + 1] <= '9') ++k;
    long magnitude = 0;
    for (; k < rest.size() && rest[k] >= '0' && rest[k] <= '9' && magnitude <= exact_literal_max_exponent; ++k)
      magnitude = magnitude * 10 + (rest[k] - '0');
    if (magnitude > exact_literal_max_exponent)
      refuse("the decimal exponent is limited to " + std::to_string(exact_literal_max_exponent) + " in magnitude");
  }
  return parse_rational(text);
}

std::string to_exact_string(const Rational& value) {
  // a denominator 1, or a power of two over an odd numerator, is canonical already (positive: a
  // gmpxx rational's denominator is, unless made by hand): no copy and no gcd
  const mpz_srcptr den = value.get_den_mpz_t(), num = value.get_num_mpz_t();
  if (mpz_sgn(den) > 0 && mpz_scan1(den, 0) + 1 == mpz_sizeinbase(den, 2) && (mpz_cmp_ui(den, 1) == 0 || mpz_odd_p(num)))
    return value.get_str(10);
  Rational canonical = value;
  canonical.canonicalize();
  return canonical.get_str(10);
}

std::string to_decimal_string(const Rational& value, int digits) {
  // enough bits for `digits` decimal digits (and never fewer than the 256 used so far)
  mpf_class f(value, std::max<mp_bitcnt_t>(256, static_cast<mp_bitcnt_t>(digits) * 4 + 64));
  mp_exp_t exponent = 0;
  std::string mantissa = f.get_str(exponent, 10, static_cast<size_t>(digits));
  if (mantissa.empty()) return "0";
  bool negative = mantissa[0] == '-';
  if (negative) mantissa.erase(0, 1);
  std::string out;
  if (exponent < -20 || exponent > 30) {
    // tiny or huge (below 1e-21, 1e30 and above): an exponent, not hundreds of zeros (a
    // 1e-300 mm offset was written with 300 zeros until session 29)
    out = mantissa.substr(0, 1) + (mantissa.size() > 1 ? "." + mantissa.substr(1) : std::string()) + "e" +
          std::to_string(static_cast<long>(exponent) - 1);
  } else if (exponent <= 0) {
    out = "0." + std::string(static_cast<size_t>(-exponent), '0') + mantissa;
  } else if (static_cast<size_t>(exponent) >= mantissa.size()) {
    out = mantissa + std::string(static_cast<size_t>(exponent) - mantissa.size(), '0');
  } else {
    out = mantissa.substr(0, static_cast<size_t>(exponent)) + "." +
          mantissa.substr(static_cast<size_t>(exponent));
  }
  return negative ? "-" + out : out;
}

std::pair<std::string, std::string> to_decimal_strings_apart(const Rational& a, const Rational& b, int digits) {
  std::string sa = to_decimal_string(a, digits), sb = to_decimal_string(b, digits);
  // Different rationals of at most a few thousand bits differ within a few thousand digits.
  for (int more = digits * 2; a != b && sa == sb && more <= 40000; more *= 2) {
    sa = to_decimal_string(a, more);
    sb = to_decimal_string(b, more);
  }
  if (a != b && sa == sb) return {to_exact_string(a), to_exact_string(b)};
  return {sa, sb};
}

double to_double(const Rational& value) {
  // mpq_get_d truncates; MPFR at 53 bits rounds the exact quotient to nearest. That is the
  // double nearest the value unless the result is subnormal (or 0): there the doubles have
  // fewer bits, and rounding the 53-bit number again could round twice.
  mpfr_t rounded;
  mpfr_init2(rounded, 53);
  mpfr_set_q(rounded, value.get_mpq_t(), MPFR_RNDN);
  double result = mpfr_get_d(rounded, MPFR_RNDN);
  mpfr_clear(rounded);
  if (std::fabs(result) >= std::numeric_limits<double>::min() || sgn(value) == 0) return result;
  // below the normal doubles: enclose the value by directed roundings until both ends round to
  // the same double (RN is monotone); a tie is a dyadic number, exact at 64 bits already
  for (mpfr_prec_t precision = 64;; precision *= 2) {
    mpfr_t lo, hi;
    mpfr_init2(lo, precision);
    mpfr_init2(hi, precision);
    const bool exact = mpfr_set_q(lo, value.get_mpq_t(), MPFR_RNDD) == 0;
    mpfr_set_q(hi, value.get_mpq_t(), MPFR_RNDU);
    const double a = mpfr_get_d(lo, MPFR_RNDN), b = mpfr_get_d(hi, MPFR_RNDN);
    mpfr_clear(lo);
    mpfr_clear(hi);
    if (exact || a == b) return a;
  }
}

}  // namespace hipair

namespace hipair {
namespace {

// GMP's small blocks (1 to 8 limbs: most of an exact computation's numbers) kept per thread
// for reuse: a freed block of 8, 16, ..., 64 bytes goes on its thread's list for its size (up
// to `pool_depth` blocks a size), and an allocation of that size takes one from there before
// asking malloc. Every block is a malloc'ed block of exactly its size, so a block may be freed
// on any thread, and whatever is kept is released with std::free when the thread ends (the
// thread's lists are then closed: later frees go to std::free). GMP passes every block's size
// to free and realloc; other sizes (strings) are not pooled. (malloc and free took ≈ 35
// instructions each per call here, a list ≈ 10.)
//
// The fast paths test one counter: `room[k]`, the blocks list k may still take, is 0 until the
// thread's first pooled free has registered the release (`open_block_pool`, out of line) and
// again once the pool is closed, so neither path reads the pool's state or a guard variable.
constexpr std::size_t pool_sizes = 8;     // blocks of 8 * (k + 1) bytes, k < pool_sizes
// (8 192 since session 53, ≤ 2.4 MB a thread: a tile's or a chart's numbers are freed in bursts
// that overflowed 512-block lists to free(), and the next numbers came back from malloc)
constexpr std::uint32_t pool_depth = 8192;

struct FreeBlock {
  FreeBlock* next;
};

struct BlockPool {
  FreeBlock* head[pool_sizes] = {};
  std::uint32_t room[pool_sizes] = {};   // pool_depth minus the blocks kept; 0 while not open
  int state = 0;   // 0: nothing kept yet, 1: keeping (released at the thread's end), 2: closed
};
// Trivially destructible: no guard on the fast paths. Initial-exec: the library is compiled as
// position-independent code, whose default (general-dynamic) access is a call that made the
// fast paths save registers around it even where the link relaxed it away (a few bytes of
// static TLS, as allocators take, also when the library is loaded as a shared object).
[[gnu::tls_model("initial-exec")]] thread_local BlockPool block_pool;

struct BlockPoolRelease {
  ~BlockPoolRelease() {
    BlockPool& pool = block_pool;
    pool.state = 2;
    for (std::size_t k = 0; k < pool_sizes; ++k) {
      pool.room[k] = 0;
      while (FreeBlock* block = pool.head[k]) {
        pool.head[k] = block->next;
        std::free(block);
      }
    }
  }
};

// The pool's size index of a block of `size` bytes: below pool_sizes exactly when the block
// is pooled (8, 16, ..., 64 bytes; sizes 0 to 7 wrap around to a huge index).
inline std::size_t pool_index(std::size_t size) { return (size >> 3) - 1; }
inline bool pooled(std::size_t size, std::size_t k) { return k < pool_sizes && (size & 7) == 0; }

// block p onto list k, which has room
inline void push_block(BlockPool& pool, std::size_t k, void* p) {
  auto* block = static_cast<FreeBlock*>(p);
  block->next = pool.head[k];
  pool.head[k] = block;
  --pool.room[k];
}

// A pooled free that found its list without room: the thread's first pooled free (the release
// registered, every list opened), a full list, or a closed pool (then std::free).
[[gnu::noinline]] void free_unpooled(void* p, std::size_t k) {
  BlockPool& pool = block_pool;
  if (pool.state == 0) {
    thread_local BlockPoolRelease release;   // constructed here, once per thread
    (void)&release;
    pool.state = 1;
    for (std::uint32_t& room : pool.room) room = pool_depth;
  }
  if (pool.room[k] != 0) return push_block(pool, k, p);
  std::free(p);
}

// Set by the first allocation GMP could not get; from then on GMP's frees do nothing. GMP's C code
// is not exception-safe: mpz_mul (and others) free a number's limbs, record its new size and only
// then allocate, so the throw below leaves a freed block in the number, which its destructor
// freed again — into the pool twice, and a later allocation or free crashed (SIGSEGV under
// `ulimit -v` on the spur gears, session 70, where exit 4 and one line were due). After such a
// failure the computation ends (use_throwing_gmp_allocation's contract): leaking is harmless,
// freeing is not.
std::atomic<bool> gmp_failed{false};

[[gnu::noinline]] void* allocate_unpooled(std::size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) {
    gmp_failed.store(true, std::memory_order_relaxed);
    throw std::bad_alloc();
  }
  return p;
}

void* gmp_allocate(std::size_t size) {
  const std::size_t k = pool_index(size);
  if (pooled(size, k)) {
    BlockPool& pool = block_pool;
    if (FreeBlock* block = pool.head[k]) {
      pool.head[k] = block->next;
      ++pool.room[k];
      return block;
    }
  }
  return allocate_unpooled(size);
}

void gmp_free(void* p, std::size_t size) {
  if (gmp_failed.load(std::memory_order_relaxed)) [[unlikely]]
    return;   // after a failed allocation: a number's block may be freed already (gmp_failed)
  const std::size_t k = pool_index(size);
  if (pooled(size, k) && p) {
    BlockPool& pool = block_pool;
    if (pool.room[k] != 0) return push_block(pool, k, p);
    return free_unpooled(p, k);
  }
  std::free(p);
}

// A GMP number's limbs grown (or shrunk) to `size` bytes: a new block, the first
// min(old_size, size) bytes copied (GMP passes the block's exact size), the old block freed.
// (The allocator's realloc took ≈ 480 instructions a call here, against ≈ 100 for a malloc,
// a copy of a few limbs and a free: most GMP reallocations grow a fresh number by a limb or
// two, into another size class.)
void* gmp_reallocate(void* old, std::size_t old_size, std::size_t size) {
  void* p = gmp_allocate(size);   // throws std::bad_alloc: `old` stays valid, owned by its number
  if (old) {
    std::memcpy(p, old, std::min(old_size, size));
    gmp_free(old, old_size);
  }
  return p;
}

}  // namespace

void use_throwing_gmp_allocation() { mp_set_memory_functions(gmp_allocate, gmp_reallocate, gmp_free); }

}  // namespace hipair
