// The feature templates' rules, once for the exact expansion and the tolerance box
// (template_rules.hpp). The margins keep the templates' own tolerances (their former coarse
// double checks' 1e-9, in the template's unit of length on the exact side).
#include "model/template_rules.hpp"

#include "model/parametric/mpfi_arithmetic.hpp"
#include "model/parametric/number_traits.hpp"

#include <hipair/error.hpp>

#include <gmp.h>
#include <mpfi.h>

#include <memory>
#include <optional>

namespace hipair::model_detail {

namespace {

// An exact real for the exact expansion's margins (session 61, tol61b): an expression DAG over
// the template's exact rational arguments, knowing its value exactly as a + b sqrt(s) (a, b, s
// rational, s not a rational square when b != 0) whenever the operations keep that form, and
// otherwise enclosed by MPFI at a precision raised until the sign is decided.
struct Quadratic {
  Rational a, b, s;   // a + b sqrt(s)
  bool rational() const { return sgn(b) == 0; }
};

struct Node;
using NodePtr = std::shared_ptr<const Node>;

enum class Op { known, pi, add, sub, mul, div, sqrt, sin, cos, atan2 };

struct Node {
  Op op;
  NodePtr x, y;
  std::optional<Quadratic> form;   // the exact value, when of that form (always for Op::known)
};

constexpr mpfr_prec_t first_precision = 64;
constexpr mpfr_prec_t last_precision = 65536;

bool is_square(const Rational& q) {
  return sgn(q) >= 0 && mpz_perfect_square_p(q.get_num_mpz_t()) != 0 && mpz_perfect_square_p(q.get_den_mpz_t()) != 0;
}

Rational square_root(const Rational& q) {   // q a rational square
  mpz_class n, d;
  mpz_sqrt(n.get_mpz_t(), q.get_num_mpz_t());
  mpz_sqrt(d.get_mpz_t(), q.get_den_mpz_t());
  Rational r(n, d);
  r.canonicalize();
  return r;
}

// The exact sign of a + b sqrt(s).
int sign_of(const Quadratic& f) {
  const int sa = sgn(f.a), sb = f.rational() ? 0 : sgn(f.b);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  const int c = cmp(Rational(f.a * f.a), Rational(f.b * f.b * f.s));   // |a| against |b| sqrt(s)
  return c > 0 ? sa : c < 0 ? sb : 0;
}

void enclose(const Node& n, mpfi_t out, mpfr_prec_t precision);

class Real {
 public:
  Real() : Real(Rational(0)) {}
  Real(const Rational& q) : node_(known(Quadratic{q, Rational(0), Rational(0)})) {}   // NOLINT(google-explicit-constructor)
  explicit Real(NodePtr node) : node_(std::move(node)) {}
  const Node& node() const { return *node_; }
  const NodePtr& pointer() const { return node_; }
  const std::optional<Quadratic>& form() const { return node_->form; }
  bool is_zero() const { return form() && sign_of(*form()) == 0; }

  static NodePtr known(Quadratic f) {
    if (sgn(f.b) == 0) f.s = 0;
    return std::make_shared<const Node>(Node{Op::known, nullptr, nullptr, std::move(f)});
  }
  static Real make(Op op, const Real& x, const Real& y = Real()) {
    return Real(std::make_shared<const Node>(Node{op, x.node_, y.node_, std::nullopt}));
  }

  friend Real operator+(const Real& x, const Real& y) {
    if (x.form() && y.form()) {
      const Quadratic &p = *x.form(), &q = *y.form();
      if (p.rational()) return Real(known({p.a + q.a, q.b, q.s}));
      if (q.rational()) return Real(known({p.a + q.a, p.b, p.s}));
      if (p.s == q.s) return Real(known({p.a + q.a, p.b + q.b, p.s}));
    }
    return make(Op::add, x, y);
  }
  friend Real operator-(const Real& x) { return Real(Rational(0)) - x; }
  friend Real operator-(const Real& x, const Real& y) {
    if (y.form()) return x + Real(known({-y.form()->a, -y.form()->b, y.form()->s}));
    return make(Op::sub, x, y);
  }
  friend Real operator*(const Real& x, const Real& y) {
    if (x.is_zero() || y.is_zero()) return Real(Rational(0));
    if (x.form() && y.form()) {
      const Quadratic &p = *x.form(), &q = *y.form();
      if (p.rational()) return Real(known({p.a * q.a, p.a * q.b, q.s}));
      if (q.rational()) return Real(known({q.a * p.a, q.a * p.b, p.s}));
      if (p.s == q.s) return Real(known({p.a * q.a + p.b * q.b * p.s, p.a * q.b + p.b * q.a, p.s}));
    }
    return make(Op::mul, x, y);
  }
  friend Real operator/(const Real& x, const Real& y) {
    if (y.is_zero()) throw NumericError("a template rule divides by zero");
    if (x.form() && y.form()) {
      const Quadratic &p = *x.form(), &q = *y.form();
      // (a + b r)(c - d r) / (c^2 - d^2 s), r = sqrt(s): c^2 != d^2 s as s is not a square
      if (q.rational()) return Real(known({p.a / q.a, p.b / q.a, p.s}));
      if (p.rational() || p.s == q.s) {
        const Rational d = q.a * q.a - q.b * q.b * q.s;
        const Rational b = p.rational() ? Rational(0) : p.b;
        return Real(known({(p.a * q.a - b * q.b * q.s) / d, (b * q.a - p.a * q.b) / d, q.s}));
      }
    }
    return make(Op::div, x, y);
  }

 private:
  NodePtr node_;
};

// The exact sign of x: from its exact form, else from MPFI enclosures of rising precision.
// \throws NumericError when 65536 bits do not decide it.
int sign(const Real& x) {
  if (x.form()) return sign_of(*x.form());
  mpfi_t v;
  mpfi_init2(v, first_precision);
  for (mpfr_prec_t precision = first_precision; precision <= last_precision; precision *= 2) {
    mpfi_set_prec(v, precision);
    enclose(x.node(), v, precision);
    if (mpfi_is_strictly_pos(v) > 0) {
      mpfi_clear(v);
      return 1;
    }
    if (mpfi_is_strictly_neg(v) > 0) {
      mpfi_clear(v);
      return -1;
    }
  }
  mpfi_clear(v);
  throw NumericError("a template rule's margin is not decided at 65536 bits");
}

void enclose(const Node& n, mpfi_t out, mpfr_prec_t precision) {
  if (n.form) {
    const Quadratic& f = *n.form;
    mpfi_set_q(out, f.a.get_mpq_t());
    if (f.rational()) return;
    mpfi_t r;
    mpfi_init2(r, precision);
    mpfi_set_q(r, f.s.get_mpq_t());
    mpfi_sqrt(r, r);
    mpfi_mul_q(r, r, f.b.get_mpq_t());
    mpfi_add(out, out, r);
    mpfi_clear(r);
    return;
  }
  if (n.op == Op::pi) {
    mpfi_const_pi(out);
    return;
  }
  mpfi_t a, b;
  mpfi_init2(a, precision);
  mpfi_init2(b, precision);
  enclose(*n.x, a, precision);
  if (n.y) enclose(*n.y, b, precision);
  switch (n.op) {
    case Op::add: mpfi_add(out, a, b); break;
    case Op::sub: mpfi_sub(out, a, b); break;
    case Op::mul: mpfi_mul(out, a, b); break;
    case Op::div: mpfi_div(out, a, b); break;
    case Op::sqrt:
      // the argument is positive (checked exactly when the node was made)
      if (mpfr_sgn(&a->left) < 0) mpfr_set_zero(&a->left, 1);
      mpfi_sqrt(out, a);
      break;
    case Op::sin: mpfi_sin(out, a); break;
    case Op::cos: mpfi_cos(out, a); break;
    case Op::atan2: mpfi_atan2(out, a, b); break;
    case Op::known:
    case Op::pi: break;
  }
  mpfi_clear(a);
  mpfi_clear(b);
}

// The arithmetic of the rules in number type T.
template <class T>
struct RuleArithmetic;

template <>
struct RuleArithmetic<kernels::Interval> {
  using I = kernels::Interval;
  using A = Arithmetic<I>;
  static I exactly(double x) { return I(x, x); }
  static I constant(const Rational& q) { return A::constant(q); }
  static I pi() { return A::pi(); }
  static I sqrt(const I& x) { return A::sqrt(x); }
  static I sin(const I& x) { return A::sin(x); }
  static I cos(const I& x) { return A::cos(x); }
  static I atan2(const I& y, const I& x) { return A::atan2(y, x); }
};

template <>
struct RuleArithmetic<Interval> {
  using A = Arithmetic<Interval>;
  static Interval exactly(double x) { return Interval(Rational(x)); }
  static Interval constant(const Rational& q) { return Interval(q); }
  static Interval pi() { return Interval::pi(); }
  static Interval sqrt(const Interval& x) { return A::sqrt(x); }
  static Interval sin(const Interval& x) { return A::sin(x); }
  static Interval cos(const Interval& x) { return A::cos(x); }
  static Interval atan2(const Interval& y, const Interval& x) { return A::atan2(y, x); }
};

template <>
struct RuleArithmetic<Real> {
  static Real exactly(double x) { return Real(Rational(x)); }
  static Real constant(const Rational& q) { return Real(q); }
  static Real pi() { return Real(std::make_shared<const Node>(Node{Op::pi, nullptr, nullptr, std::nullopt})); }
  static Real sqrt(const Real& x) {
    const int s = sign(x);
    if (s < 0) throw NumericError("a template rule takes the square root of a negative value");
    if (s == 0) return Real(Rational(0));
    if (x.form() && x.form()->rational()) {
      const Rational& q = x.form()->a;
      if (is_square(q)) return Real(square_root(q));
      return Real(Real::known({Rational(0), Rational(1), q}));
    }
    return Real::make(Op::sqrt, x);
  }
  static Real sin(const Real& x) { return x.is_zero() ? Real(Rational(0)) : Real::make(Op::sin, x); }
  static Real cos(const Real& x) { return x.is_zero() ? Real(Rational(1)) : Real::make(Op::cos, x); }
  static Real atan2(const Real& y, const Real& x) {
    if (sign(y) == 0) {
      const int sx = sign(x);
      if (sx == 0) throw NumericError("a template rule takes atan2(0, 0)");
      return sx > 0 ? Real(Rational(0)) : pi();
    }
    return Real::make(Op::atan2, y, x);
  }
};

}  // namespace

template <class I>
void rules_in(const std::string& name, const BasicTemplateRuleValues<I>& v,
              const std::function<void(const BasicTemplateRule<I>&)>& check) {
  using A = RuleArithmetic<I>;
  auto value = [&](const char* key) { return v.value(key); };
  auto point = [&](const char* key) { return v.point(key); };
  // an optional angle: its value, or the template's default
  auto angle_or = [&](const char* key, const I& fallback) { return v.has(key) ? v.value(key) : fallback; };
  auto c = [](double x) { return A::exactly(x); };
  auto rule = [&](const char* key, std::vector<const char*> reads, std::function<I()> margin, std::string text,
                  std::string refusal) {
    check(BasicTemplateRule<I>{key, std::move(reads), std::move(margin), std::move(text), std::move(refusal)});
  };
  auto positive = [&](std::initializer_list<const char*> keys) {
    for (const char* key : keys) rule(key, {key}, [&, key] { return value(key); }, std::string(key) + " > 0", "must be positive");
  };
  const I pi = A::pi();
  const I tiny = A::constant(Rational(1, 1000000000));
  if (name == "geneva_wheel") {
    positive({"slot_width", "slot_inner_radius", "slot_outer_radius", "lock_center_radius", "lock_radius"});
    rule("slot_inner_radius", {"slot_inner_radius", "slot_width"},
         [&] { return I(value("slot_inner_radius") - value("slot_width") / c(2)); },
         "slot_inner_radius > slot_width / 2 (the slot bottom clear of the wheel centre)",
         "the slot bottom (a half circle of radius slot_width/2 centred at slot_inner_radius) would reach the wheel "
         "centre");
    rule("slot_outer_radius", {"slot_outer_radius", "slot_inner_radius", "slot_width"}, [&] {
      I half = value("slot_width") / c(2), outer = value("slot_outer_radius"), inner = value("slot_inner_radius");
      return I(outer * outer - half * half - inner * inner);
    }, "slot_outer_radius^2 > slot_inner_radius^2 + (slot_width/2)^2 (the slot walls reach beyond the slot bottom)",
         "the slot walls must reach beyond the slot bottom: slot_outer_radius^2 must exceed slot_inner_radius^2 + "
         "(slot_width/2)^2");
    const std::string span_refusal = "must lie strictly between 0 and 180 degrees";
    rule("lock_span", {"lock_span"}, [&] { return value("lock_span"); }, "lock_span > 0", span_refusal);
    rule("lock_span", {"lock_span"}, [&] { return I(pi - tiny - value("lock_span")); }, "lock_span < 180 degrees",
         span_refusal);
    rule("lock_radius", {"lock_radius", "lock_center_radius"},
         [&] { return I(value("lock_center_radius") - value("lock_radius")); },
         "lock_radius < lock_center_radius (the locking arc clear of the wheel centre)",
         "must be less than lock_center_radius (the locking arc would enclose the wheel centre)");
    auto lock_end = [&] {   // the locking arc's end (x, y) in the lock frame's wheel coordinates
      I d = value("lock_center_radius"), r = value("lock_radius"), half = value("lock_span") / c(2);
      return kernels::Vector<I>{I(d - r * A::cos(half)), I(r * A::sin(half))};
    };
    rule("lock_span", {"lock_center_radius", "lock_radius", "lock_span"}, [&] { return lock_end().x; },
         "the locking arc ends in front of the wheel centre (lock_center_radius > lock_radius cos(lock_span/2))",
         "the locking arc ends behind the wheel centre: lock_span is too large");
    if (v.count > 0) {
      const I sector = pi / c(static_cast<double>(v.count));
      auto wall_angle = [&] {
        I half = value("slot_width") / c(2), outer = value("slot_outer_radius");
        return A::atan2(half, A::sqrt(I(outer * outer - half * half)));
      };
      rule("slot_width", {"slot_width", "slot_outer_radius"}, [&] { return I(sector - tiny - wall_angle()); },
           "the slots fit the wheel (asin(slot_width / 2 / slot_outer_radius) < 180 degrees / slots)",
           "the slots are too wide for " + std::to_string(v.count) + " slots at slot_outer_radius");
      rule("lock_span", {"lock_center_radius", "lock_radius", "lock_span", "slot_width", "slot_outer_radius"}, [&] {
        kernels::Vector<I> end = lock_end();
        return I(sector - wall_angle() - tiny - A::atan2(end.y, end.x));
      }, "the locking arcs end before the slots (lock_span and slot_width)",
           "the locking arcs run into the slots: reduce lock_span or slot_width");
      rule("lock_radius", {"lock_center_radius", "lock_radius", "slot_width", "slot_outer_radius", "slot_inner_radius"},
           [&] {
             // the next slot's right wall end, in the lock frame, outside the lock circle
             I half = value("slot_width") / c(2), outer = value("slot_outer_radius");
             I wx = A::sqrt(I(outer * outer - half * half)), wy = -half;
             I x = wx * A::cos(sector) - wy * A::sin(sector), y = wx * A::sin(sector) + wy * A::cos(sector);
             I dx = x - value("lock_center_radius");
             // 1e-9 of lock_radius: the same in any unit of length (the box reads mm)
             return I(A::sqrt(I(dx * dx + y * y)) - value("lock_radius") * I(c(1) + tiny));
           },
           "the locking arcs clear of the slot walls (lock_radius and slot_outer_radius)",
           "the locking arcs cut into the slot walls: reduce lock_radius or slot_outer_radius");
    }
  } else if (name == "geneva_driver") {
    positive({"pin_radius", "pin_center_radius", "lock_outer_radius"});
    rule("lock_inner_radius", {"lock_inner_radius", "lock_outer_radius"},
         [&] { return I(value("lock_outer_radius") - value("lock_inner_radius")); }, "lock_inner_radius < lock_outer_radius",
         "must be less than lock_outer_radius");
    const std::string span_refusal = "must lie strictly between 0 and 360 degrees";
    rule("lock_span", {"lock_span"}, [&] { return value("lock_span"); }, "lock_span > 0", span_refusal);
    rule("lock_span", {"lock_span"}, [&] { return I(c(2) * pi - tiny - value("lock_span")); }, "lock_span < 360 degrees",
         span_refusal);
  } else if (name == "escape_wheel") {
    positive({"tip_radius", "root_radius"});
    rule("root_radius", {"root_radius", "tip_radius"}, [&] { return I(value("tip_radius") - value("root_radius")); },
         "root_radius < tip_radius", "must be less than tip_radius");
    if (v.count > 0) {
      const I pitch = c(2) * pi / c(static_cast<double>(v.count));
      auto tip = [&] { return angle_or("tip_angle", c(0)); };
      auto face = [&] { return angle_or("face_angle", c(0)); };
      const std::string below = "tip_angle + face_angle must stay below 3/4 of the tooth pitch";
      rule("face_angle", {"face_angle"}, [&] { return I(A::constant(Rational(3, 4)) * pitch - tip() - face()); },
           "tip_angle + face_angle < 3/4 of the tooth pitch", below);
      rule("tip_angle", {"tip_angle", "face_angle"}, [&] { return I(A::constant(Rational(3, 4)) * pitch - tip() - face()); },
           "tip_angle + face_angle < 3/4 of the tooth pitch", below);
      if (v.has("back_angle")) {   // absent: ratchet teeth, no root arc (the back is pitch + face_angle)
        const std::string base = "must exceed face_angle and tip_angle (the tooth needs a base)";
        rule("back_angle", {"back_angle", "face_angle"}, [&] { return I(value("back_angle") - face() - tiny); },
             "back_angle > face_angle", base);
        rule("back_angle", {"back_angle", "tip_angle"}, [&] { return I(value("back_angle") - tip() - tiny); },
             "back_angle > tip_angle", base);
        rule("back_angle", {"back_angle", "face_angle"}, [&] { return I(pitch + face() - tiny - value("back_angle")); },
             "back_angle < the tooth pitch + face_angle",
             "must be less than the tooth pitch + face_angle (omit it for ratchet teeth without a root arc)");
      }
    }
  } else if (name == "anchor") {
    positive({"wheel_radius", "pallet_width", "fork_length", "fork_width", "fork_slot_width", "fork_slot_depth"});
    auto angles = [&] {
      return I(angle_or("lift", c(0)) + angle_or("lock", c(0)) +
               angle_or("pallet_extent", A::constant(Rational(174533, 500000))));   // the template's default extent
    };
    const std::string sum = "lift + lock + pallet_extent must stay below 1.2 rad";
    rule("lift", {"lift", "lock"}, [&] { return I(A::constant(Rational(6, 5)) - angles()); }, "lift + lock + pallet_extent < 1.2 rad", sum);
    rule("pallet_extent", {"pallet_extent", "lift", "lock"}, [&] { return I(A::constant(Rational(6, 5)) - angles()); },
         "lift + lock + pallet_extent < 1.2 rad", sum);
    auto distance_squared = [&] {
      kernels::Vector<I> d = point("center") - point("wheel_center");
      return I(kernels::dot(d, d));
    };
    auto tangent = [&] {
      I R = value("wheel_radius");
      return A::sqrt(I(distance_squared() - R * R));
    };
    rule("center", {"center", "wheel_center", "wheel_radius"}, [&] {
      I R = value("wheel_radius");
      return I(distance_squared() - R * R);
    }, "the anchor pivot outside the escape wheel (|center - wheel_center| > wheel_radius)",
         "the anchor pivot must lie outside the escape wheel");
    rule("pallet_width", {"center", "wheel_center", "wheel_radius", "pallet_width"},
         [&] { return I(tangent() - value("pallet_width") / c(2)); },
         "pallet_width < twice the pallet radius (the tangent length from the pivot to the wheel)",
         "is wider than twice the pallet radius (the tangent length from the pivot to the wheel)");
    rule("fork_width", {"center", "wheel_center", "wheel_radius", "pallet_width", "fork_width"},
         [&] { return I(tangent() + value("pallet_width") / c(2) - value("fork_width") / c(2)); },
         "fork_width / 2 < the pallet circle's outer radius", "is wider than the anchor's pallet circle");
    rule("fork_slot_width", {"fork_slot_width", "fork_width"}, [&] { return I(value("fork_width") - value("fork_slot_width")); },
         "fork_slot_width < fork_width", "must be less than fork_width");
    rule("fork_slot_depth", {"center", "wheel_center", "wheel_radius", "pallet_width", "fork_length", "fork_slot_depth"},
         [&] { return I(value("fork_length") - value("fork_slot_depth") - tangent() - value("pallet_width") / c(2)); },
         "the fork slot ends outside the pallet circle (fork_length - fork_slot_depth > tangent length + pallet_width/2)",
         "the fork slot must end outside the pallet circle (fork_length - fork_slot_depth > tangent length + "
         "pallet_width/2)");
  } else if (name == "balance") {
    positive({"radius", "pin_radius", "pin_center_radius"});
    rule("pin_center_radius", {"radius", "pin_radius", "pin_center_radius"},
         [&] { return I(value("pin_center_radius") + value("pin_radius") - value("radius")); },
         "the pin sticks out of the disc (pin_center_radius + pin_radius > radius)",
         "the pin lies inside the disc: it must stick out (pin_center_radius + pin_radius > radius)");
    rule("pin_center_radius", {"radius", "pin_radius", "pin_center_radius"},
         [&] { return I(value("radius") - value("pin_center_radius") + value("pin_radius")); },
         "the pin is attached to the disc (pin_center_radius - pin_radius < radius)",
         "the pin is detached from the disc (pin_center_radius - pin_radius must be less than radius)");
    rule("pin_radius", {"radius", "pin_radius", "pin_center_radius"},
         [&] { return I(value("radius") + value("pin_center_radius") - value("pin_radius")); },
         "the pin does not swallow the disc (pin_radius < radius + pin_center_radius)", "the pin would swallow the disc");
  } else if (name == "spur_gear") {
    positive({"pitch_radius", "addendum", "dedendum", "tooth_thickness"});
    rule("dedendum", {"dedendum", "pitch_radius"}, [&] { return I(value("pitch_radius") - value("dedendum")); },
         "dedendum < pitch_radius", "must be less than pitch_radius");
    if (v.has("pressure_angle")) {   // absent: 20 degrees
      const std::string range = "must lie between 0.01 and 0.7 rad (about 0.6 to 40 degrees)";
      rule("pressure_angle", {"pressure_angle"}, [&] { return I(value("pressure_angle") - A::constant(Rational(1, 100))); },
           "pressure_angle > 0.01 rad", range);
      rule("pressure_angle", {"pressure_angle"}, [&] { return I(A::constant(Rational(7, 10)) - value("pressure_angle")); },
           "pressure_angle < 0.7 rad", range);
    }
  } else if (name == "ratchet_wheel") {
    positive({"tip_radius", "root_radius"});
    rule("root_radius", {"root_radius", "tip_radius"}, [&] { return I(value("tip_radius") - value("root_radius")); },
         "root_radius < tip_radius", "must be less than tip_radius");
  }
}

void template_rules(const std::string& name, const TemplateRuleValues& values,
                    const std::function<void(const TemplateRule&)>& check) {
  rules_in<kernels::Interval>(name, values, check);
}

void template_rules(const std::string& name, const BasicTemplateRuleValues<Interval>& values,
                    const std::function<void(const BasicTemplateRule<Interval>&)>& check) {
  rules_in<Interval>(name, values, check);
}

void check_template_rules_exactly(const std::string& name, const ExactTemplateRuleValues& values,
                                  const std::string& pointer) {
  BasicTemplateRuleValues<Real> exact;
  exact.has = values.has;
  exact.value = [&](const char* key) { return Real(values.value(key)); };
  exact.point = [&](const char* key) {
    kernels::Vector<Rational> p = values.point(key);
    return kernels::Vector<Real>{Real(p.x), Real(p.y)};
  };
  exact.count = values.count;
  rules_in<Real>(name, exact, [&](const BasicTemplateRule<Real>& rule) {
    bool positive = false;
    try {
      positive = sign(rule.margin()) > 0;
    } catch (const ModelError&) {
      throw;
    } catch (const Error&) {
      // a margin that does not evaluate (outside its functions' domains) or is not decided refuses
    }
    if (!positive) throw ModelError(pointer + "/" + rule.key, rule.refusal);
  });
}

}  // namespace hipair::model_detail
