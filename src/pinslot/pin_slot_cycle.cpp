// The work cycle of a driver, a pin-in-slot follower and a translating target it pushes
// (include/hipair/pin_slot.hpp, pin_slot_cycle): the film advance's claw entering a
// perforation, pulling the film and retracting. Exact at every sample (see the header): the
// follower's pose is rational and located exactly against the driver in the 1-D slice of the
// driver-fixed pin-slot pair; the target's offset comes from the exact 1-D C-space of the target
// against the follower placed at that pose. Doubles only choose the follower's pose (the middle
// of its largest free slide interval) and label angles for display.
#include <hipair/pin_slot.hpp>

#include <hipair/error.hpp>
#include <hipair/motion_words.hpp>

#include "algebra/nearest_double.hpp"
#include "core/angle_limits.hpp"
#include "pinslot/moved_part.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <map>
#include <optional>
#include <set>

namespace hipair {

std::string_view to_string(CyclePhase phase) {
  switch (phase) {
    case CyclePhase::clear: return "clear";
    case CyclePhase::engaged: return "engaged";
    case CyclePhase::pushing: return "pushing";
    case CyclePhase::jammed: return "jammed";
  }
  return "?";
}

namespace {

Rational near_rational(double value, long den = 4096) {
  Rational r(static_cast<long>(std::llround(value * static_cast<double>(den))), den);
  r.canonicalize();
  return r;
}

Part placed_fixed(const Part& part, const Placement& placement) {
  Part out = pinslot_detail::moved_part(part, placement);
  out.motion = Motion{};
  out.motion.kind = Motion::Kind::fixed;
  out.initial = PartConfiguration{};
  out.dynamics.reset();
  return out;
}

// The two parts as a model of their own; the reader's rounding records of the original model
// go with them (their pointers are the parts' own), so that the pin-slot part's limits are
// decided as in the original (pin_slot_whole_turn).
Model two_parts(const std::string& name, Part a, Part b, const std::vector<Rounding>& roundings = {}) {
  Model m;
  m.name = name;
  m.roundings = roundings;
  m.angle_unit = "rad";
  m.source = "<" + name + ">";
  a.dynamics.reset();
  b.dynamics.reset();
  m.parts = {std::move(a), std::move(b)};
  m.pairs.push_back(PairSpec{0, 1, std::nullopt, std::nullopt, "", std::nullopt});
  m.pairs_explicit = true;
  return m;
}

// An end of a 1-D interval: a vertex (exact) or the chart's end.
struct End {
  bool contact = false;           // a contact vertex (else the chart's end)
  std::size_t vertex = no_index;
  Rational value;                 // exact when the vertex is exact or the chart end
  bool exact = true;
  Rational free_side;             // a rational on the interval's side within its isolating interval
  double approx = 0;
};

struct Interval1 {
  CellKind kind = CellKind::free;
  std::size_t cell = no_index;
  End lower, upper;
};

std::vector<Interval1> intervals_of(const CSpace& space) {
  std::vector<Interval1> out;
  const CSpaceChart& chart = space.charts().at(0);
  for (const CSpaceFace& face : space.faces(0)) {
    Interval1 in;
    in.kind = face.kind;
    in.cell = face.cell.valid() ? face.cell.index() : no_index;
    auto end = [&](VertexId v, bool upper) {
      End e;
      if (!v.valid()) {
        e.value = upper ? chart.x_hi : chart.x_lo;
        e.free_side = e.value;
        e.approx = to_double(e.value);
        return e;
      }
      const CSpaceVertex& vertex = space.vertices()[v.index()];
      e.contact = !vertex.curves.empty();
      e.vertex = v.index();
      e.exact = vertex.x.exact;
      e.value = vertex.x.lower;
      // the interval lies above a lower end and below an upper end
      e.free_side = vertex.x.exact ? vertex.x.lower : (upper ? vertex.x.lower : vertex.x.upper);
      e.approx = vertex.x.approximate();
      return e;
    };
    in.lower = end(face.lower, false);
    in.upper = end(face.upper, true);
    out.push_back(in);
  }
  return out;
}

std::vector<std::string> labels_at(const CSpace& space, const End& end) {
  std::vector<std::string> out;
  if (end.vertex == no_index) return out;
  for (std::size_t f : space.vertices()[end.vertex].curves) out.push_back(space.feature_pairs()[f].label);
  return out;
}

}  // namespace

PinSlotCycle pin_slot_cycle(const Model& model, const PinSlotCycleOptions& options) {
  auto start = std::chrono::steady_clock::now();
  if (options.steps < 8) throw GeometryError("pin-slot cycle: at least 8 steps per turn");
  // ---- the parts
  auto partner_of = [&](std::size_t follower, Motion::Kind kind) -> std::optional<std::size_t> {
    std::optional<std::size_t> found;
    for (const PairSpec& p : model.pairs) {
      std::size_t other = p.first == follower ? p.second : p.second == follower ? p.first : no_index;
      if (other == no_index || model.parts[other].motion.kind != kind) continue;
      if (found && *found != other)
        throw GeometryError("pin-slot cycle: part '" + model.parts[follower].name + "' is paired with several " +
                            motion_adjective(kind) + " parts: name the driver and the target");
      found = other;
    }
    return found;
  };
  auto named = [&](const std::string& name) {
    auto index = model.find_part(name);
    if (!index) throw ModelError("", "pin-slot cycle: no part named '" + name + "'");
    return *index;
  };
  std::size_t follower = no_index;
  if (!options.follower.empty()) {
    follower = named(options.follower);
  } else {
    for (std::size_t i = 0; i < model.parts.size(); ++i)
      if (model.parts[i].motion.kind == Motion::Kind::pin_slot) {
        if (follower != no_index)
          throw GeometryError("pin-slot cycle: the model has several pin_slot parts: name the follower");
        follower = i;
      }
    if (follower == no_index) throw GeometryError("pin-slot cycle: the model has no pin_slot part");
  }
  const Part& pin = model.parts[follower];
  if (pin.motion.kind != Motion::Kind::pin_slot)
    throw GeometryError("pin-slot cycle: part '" + pin.name + "' (" + pin.pointer + ") has no pin_slot motion");
  std::size_t driver = options.driver.empty() ? partner_of(follower, Motion::Kind::rotation).value_or(no_index)
                                              : named(options.driver);
  std::size_t target = options.target.empty() ? partner_of(follower, Motion::Kind::translation).value_or(no_index)
                                              : named(options.target);
  if (driver == no_index)
    throw GeometryError("pin-slot cycle: no rotating part is paired with '" + pin.name + "' to drive it");
  if (target == no_index)
    throw GeometryError("pin-slot cycle: no translating part is paired with '" + pin.name + "' for it to push");
  if (model.parts[driver].motion.kind != Motion::Kind::rotation)
    throw GeometryError("pin-slot cycle: the driver '" + model.parts[driver].name + "' does not rotate");
  if (model.parts[target].motion.kind != Motion::Kind::translation)
    throw GeometryError("pin-slot cycle: the target '" + model.parts[target].name + "' does not translate");
  const Part& cam = model.parts[driver];
  const Part& film = model.parts[target];

  PinSlotCycle cycle;
  cycle.driver = cam.name;
  cycle.follower = pin.name;
  cycle.target = film.name;

  // the follower's angle range in tau (inside its limits)
  double psi_lo = -std::numbers::pi * 0.999, psi_hi = std::numbers::pi * 0.999;
  // (limits are angles modulo whole turns, and a whole turn or more is no limit: as in
  // PinSlotSpace::build, core/angle_limits.hpp: the same exact decision, the reader's rounding
  // of the limits allowed for)
  if (!pin_slot_whole_turn(model.roundings, pin.motion)) {
    const ReducedLimits reduced = reduced_limits(*pin.motion.angle_limits);
    psi_lo = std::max(psi_lo, reduced.lo);
    psi_hi = std::min(psi_hi, reduced.hi);
  }
  // a margin keeps the chosen poses clear of the limits (the choice is in doubles)
  const double tau_lo = std::tan(psi_lo / 2) + 1e-9, tau_hi = std::tan(psi_hi / 2) - 1e-9;
  PinSlotBuildOptions light;
  light.slices = 2;
  light.refine_steps = 0;
  light.connections = false;
  light.stack = false;   // slices on demand only

  Rational film_offset = film.initial.offset;
  std::optional<Rational> tau_previous, tau_before;
  const double sense = options.clockwise ? -1 : 1;
  const double phi0 = to_double(cam.initial.angle);
  for (std::size_t j = 0; j <= options.steps; ++j) {
    if (options.progress)
      options.progress("sample " + std::to_string(j + 1) + " of " + std::to_string(options.steps + 1));
    CycleSample sample;
    double phi = phi0 + sense * 2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(options.steps);
    sample.driver_degrees = phi * 180 / std::numbers::pi;
    double wrapped = std::remainder(phi, 2 * std::numbers::pi);
    if (std::abs(std::abs(wrapped) - std::numbers::pi) < 1e-9) {
      sample.driver.kind = PartCoordinate::Kind::half_turn;
    } else {
      sample.driver.value = near_rational(std::tan(wrapped / 2));
    }
    // ---- the follower's pose: the driver fixed at phi, slices in s at follower angles tau
    Model fixed_driver = two_parts("cycle driver", placed_fixed(cam, part_placement(cam, sample.driver)), pin, model.roundings);
    PinSlotSpace around = PinSlotSpace::build(fixed_driver, cam.name, pin.name, light);
    struct Best {
      double length = 0;
      Rational tau, slide;
      bool found = false;
      std::vector<std::string> bounds;   // the driver contacts at the ends of the chosen interval
    };
    auto best_at = [&](const Rational& tau) {
      Best b;
      b.tau = tau;
      auto slice = around.slice(tau);
      for (const Interval1& in : intervals_of(*slice)) {
        if (in.kind != CellKind::free) continue;
        double length = in.upper.approx - in.lower.approx;
        if (!b.found || length > b.length) {
          b.found = true;
          b.length = length;
          b.slide = near_rational((in.upper.approx + in.lower.approx) / 2);
          b.bounds.clear();
          for (const End* e : {&in.lower, &in.upper}) {
            std::vector<std::string> labels = labels_at(*slice, *e);
            if (!e->contact) labels = {"slide limit"};
            b.bounds.insert(b.bounds.end(), labels.begin(), labels.end());
          }
        }
      }
      return b;
    };
    // tau in steps of 2^-13 (psi within about 0.014 deg of the search's choice)
    auto tau_of = [](double t) { return near_rational(t, 8192); };
    std::map<Rational, Best> seen;
    Best best;
    auto consider = [&](const Rational& tau) {
      if (to_double(tau) < tau_lo || to_double(tau) > tau_hi) return;
      auto it = seen.find(tau);
      if (it == seen.end()) it = seen.emplace(tau, best_at(tau)).first;
      const Best& b = it->second;
      if (b.found && (!best.found || b.length > best.length)) best = b;
    };
    // start where the previous two poses point to, then at the previous pose; else scan
    double h = (tau_hi - tau_lo) / 192;
    int levels = 3;
    if (tau_previous && tau_before) consider(tau_of(2 * to_double(*tau_previous) - to_double(*tau_before)));
    if (tau_previous) consider(*tau_previous);
    for (int k = 1; k <= 6 && tau_previous && !best.found; ++k)   // widening search around it
      for (int side : {-1, 1}) consider(tau_of(to_double(*tau_previous) + side * k * h));
    if (!best.found) {   // scan the whole range
      for (int k = 0; k <= 48; ++k) consider(tau_of(tau_lo + (tau_hi - tau_lo) * k / 48.0));
      h = (tau_hi - tau_lo) / 96;
      levels = 5;
    }
    if (best.found) {
      for (int level = 0; level < levels; ++level, h /= 2) {
        for (bool improved = true; improved;) {
          improved = false;
          double centre = to_double(best.tau);
          for (double candidate : {centre - h, centre + h}) {
            double before = best.length;
            consider(tau_of(candidate));
            if (best.length > before) improved = true;
          }
        }
      }
    }
    if (!best.found) {
      sample.phase = CyclePhase::jammed;
      sample.follower_free = false;
      sample.target_offset = film_offset;
      cycle.samples.push_back(sample);
      continue;
    }
    sample.tau = best.tau;
    sample.slide = best.slide;
    sample.clearance = best.length;
    sample.driver_bounds = best.bounds;
    sample.psi_degrees = cspace::algebra::half_angle_degrees(best.tau);   // correctly rounded
    tau_before = tau_previous;
    tau_previous = best.tau;
    {
      auto slice = around.slice(best.tau);
      Location at = slice->locate(PartCoordinate{PartCoordinate::Kind::offset, best.slide});
      sample.follower_free = at.kind == Location::Kind::free ||
                             ((at.kind == Location::Kind::edge || at.kind == Location::Kind::vertex) &&
                              at.cell != no_index && slice->cells()[at.cell].kind == CellKind::free);
    }
    // ---- the target against the follower at that pose
    Model pushed = two_parts("cycle target", film, placed_fixed(pin, pin_slot_placement(pin, best.slide, best.tau)));
    CSpace space = CSpace::build(pushed, film.name, pin.name);
    std::vector<Interval1> intervals = intervals_of(space);
    // the free interval holding the offset (closed at contact ends)
    auto holding = [&](const Rational& f) -> const Interval1* {
      for (const Interval1& in : intervals) {
        if (in.kind != CellKind::free) continue;
        bool above_lower = in.lower.exact ? f >= in.lower.value : f >= in.lower.free_side;
        bool below_upper = in.upper.exact ? f <= in.upper.value : f <= in.upper.free_side;
        if (above_lower && below_upper) return &in;
      }
      return nullptr;
    };
    const Interval1* in = holding(film_offset);
    if (in) {
      bool touching = (in->lower.contact && in->lower.exact && in->lower.value == film_offset) ||
                      (in->upper.contact && in->upper.exact && in->upper.value == film_offset);
      if (in->lower.contact || in->upper.contact) {
        sample.phase = CyclePhase::engaged;
        if (touching) {
          sample.contacts = labels_at(space, in->lower.value == film_offset ? in->lower : in->upper);
        } else {
          for (const End* e : {&in->lower, &in->upper})
            if (e->contact)
              for (auto& l : labels_at(space, *e)) sample.bounds.push_back(l);
        }
      } else {
        sample.phase = CyclePhase::clear;
      }
    } else {
      // pushed to the nearest free offset: the nearest end of a free interval (exact when the
      // ends are exact; otherwise their isolating intervals decide, or the nearer free side)
      const End* nearest = nullptr;
      Rational nearest_distance;
      for (const Interval1& candidate : intervals) {
        if (candidate.kind != CellKind::free) continue;
        for (const End* e : {&candidate.lower, &candidate.upper}) {
          Rational d = abs(e->free_side - film_offset);
          if (!nearest || d < nearest_distance) {
            nearest = e;
            nearest_distance = d;
          }
        }
      }
      if (!nearest) {
        sample.phase = CyclePhase::jammed;
      } else {
        sample.phase = CyclePhase::pushing;
        film_offset = nearest->free_side;
        sample.target_offset_exact = nearest->exact;
        sample.contacts = labels_at(space, *nearest);
      }
    }
    sample.target_offset = film_offset;
    cycle.samples.push_back(sample);
  }
  // ---- runs
  for (std::size_t i = 0; i < cycle.samples.size(); ++i) {
    const CycleSample& s = cycle.samples[i];
    if (cycle.runs.empty() || cycle.runs.back().phase != s.phase) {
      CycleRun run;
      run.phase = s.phase;
      run.first = run.last = i;
      cycle.runs.push_back(run);
    }
    CycleRun& run = cycle.runs.back();
    run.last = i;
    const Rational& before = cycle.samples[run.first == 0 ? 0 : run.first - 1].target_offset;
    run.target_moved = s.target_offset - before;
  }
  if (!cycle.samples.empty()) cycle.advance = cycle.samples.back().target_offset - film.initial.offset;
  cycle.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return cycle;
}

}  // namespace hipair
