// The feature templates' rules, once for the exact expansion and the tolerance box
// (template_rules.hpp). The margins keep the templates' own tolerances (their former coarse
// double checks' 1e-9, in the template's unit of length on the exact side).
#include "model/template_rules.hpp"

#include "model/parametric/number_traits.hpp"

#include <hipair/error.hpp>

namespace hipair::model_detail {

void template_rules(const std::string& name, const TemplateRuleValues& v,
                    const std::function<void(const TemplateRule&)>& check) {
  using I = kernels::Interval;
  using A = Arithmetic<I>;
  auto value = [&](const char* key) { return v.value(key); };
  auto point = [&](const char* key) { return v.point(key); };
  // an optional angle: its value, or the template's default
  auto angle_or = [&](const char* key, const I& fallback) { return v.has(key) ? v.value(key) : fallback; };
  auto c = [](double x) { return I(x, x); };
  auto rule = [&](const char* key, std::vector<const char*> reads, std::function<I()> margin, std::string text,
                  std::string refusal) {
    check(TemplateRule{key, std::move(reads), std::move(margin), std::move(text), std::move(refusal)});
  };
  auto positive = [&](std::initializer_list<const char*> keys) {
    for (const char* key : keys) rule(key, {key}, [&, key] { return value(key); }, std::string(key) + " > 0", "must be positive");
  };
  const I pi = A::pi();
  const I tiny = c(1e-9);
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
             return I(A::sqrt(I(dx * dx + y * y)) - value("lock_radius") - tiny);
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
      rule("face_angle", {"face_angle"}, [&] { return I(c(0.75) * pitch - tip() - face()); },
           "tip_angle + face_angle < 3/4 of the tooth pitch", below);
      rule("tip_angle", {"tip_angle", "face_angle"}, [&] { return I(c(0.75) * pitch - tip() - face()); },
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
    rule("lift", {"lift", "lock"}, [&] { return I(c(1.2) - angles()); }, "lift + lock + pallet_extent < 1.2 rad", sum);
    rule("pallet_extent", {"pallet_extent", "lift", "lock"}, [&] { return I(c(1.2) - angles()); },
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
      rule("pressure_angle", {"pressure_angle"}, [&] { return I(value("pressure_angle") - c(0.01)); },
           "pressure_angle > 0.01 rad", range);
      rule("pressure_angle", {"pressure_angle"}, [&] { return I(c(0.7) - value("pressure_angle")); },
           "pressure_angle < 0.7 rad", range);
    }
  } else if (name == "ratchet_wheel") {
    positive({"tip_radius", "root_radius"});
    rule("root_radius", {"root_radius", "tip_radius"}, [&] { return I(value("tip_radius") - value("root_radius")); },
         "root_radius < tip_radius", "must be less than tip_radius");
  }
}

void check_template_rules_exactly(const std::string& name, const TemplateRuleValues& values, const std::string& pointer) {
  template_rules(name, values, [&](const TemplateRule& rule) {
    bool positive = false;
    try {
      positive = rule.margin().lo > 0;
    } catch (const ModelError&) {
      throw;
    } catch (const Error&) {
      // a margin that does not evaluate (outside its functions' domains) refuses too
    }
    if (!positive) throw ModelError(pointer + "/" + rule.key, rule.refusal);
  });
}

}  // namespace hipair::model_detail
