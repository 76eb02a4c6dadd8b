// `hipair simulate MODEL --t-end T [--accuracy EPS] [--max-step H] [--set P=V] [--out DIR]`:
// dynamical simulation (docs/simulation.md). Prints a summary and the event log; with --out
// writes, all or nothing, trajectory.csv, events.json, events.txt, positions.svg,
// velocities.svg, animation.svg (the mechanism playing in a browser: SMIL, frames sampled at a
// fixed rate) and, per two-dimensional pair, the path over its C-space (cspace-X-Y.svg, like
// Joskowicz & Sacks 1997, Figure 6b).
#include "cli/commands.hpp"
#include "core/length_display.hpp"
#include "core/model_scale.hpp"

#include "io/output_directory.hpp"
#include "io/output_paths.hpp"
#include "model/simulation_reading.hpp"
#include "render/cspace_svg.hpp"
#include "render/mechanism_svg.hpp"
#include "render/time_plot_svg.hpp"

#include <hipair/error.hpp>
#include <hipair/pin_slot_simulation.hpp>
#include <hipair/simulation.hpp>
#include <hipair/simulation_stop.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>
#include <ctime>
#include <unistd.h>

namespace hipair::cli {
namespace {

struct SimulateOptions {
  std::string model;
  double t_end = 0;
  double accuracy = 0;
  double max_step = 0;
  std::size_t max_steps = SimulationOptions{}.max_steps;   // --max-steps: the step budget
  std::string out;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string rounding;
  std::string region = "auto";   // --region: full, operating, or auto (operating for a large pair)
  bool quiet = false;            // --quiet: no progress on the terminal
  bool no_pictures = false;
  std::string sweep;
  unsigned jobs = 0;
  std::string works_period;                 // --works-period PART[:TOL]
  std::vector<std::string> works_advance;   // --works-advance PART=STEP[:TOL] (repeatable)
  double works_max_decay = -1;              // --works-max-decay RATE; < 0: not given
  double fps = 25;                  // animation frames per second of playback
  bool fps_given = false;           // --fps on the command line
  double animation_duration = 0;    // playback seconds; 0: the simulated time (real time), at least 1 s
};

// The run's accuracy and step limits (--accuracy, --max-step, --max-steps), as every simulator
// takes them.
SimulationOptions stepping_options(const SimulateOptions& options) {
  SimulationOptions sim_options;
  sim_options.accuracy = options.accuracy;
  sim_options.max_step = options.max_step;
  sim_options.max_steps = options.max_steps;
  return sim_options;
}

// --region: `operating` builds every pair's operating region, `full` every pair's whole space,
// `auto` (the default) the operating region of a pair whose two parts have more than 120
// boundary edges (a gear pair: its whole torus holds z1 z2 tooth encounters and takes minutes,
// its channel seconds; the size above which `analyze` draws an operating region) and the
// whole space of the others.
void set_region(SimulationOptions& sim_options, const SimulateOptions& options) {
  sim_options.operating_region = options.region == "operating";
  sim_options.operating_region_above_edges = options.region == "auto" ? 120 : 0;
}

// Seconds per time unit of the model ("s" or "ms").
double seconds_per_unit(const std::string& time_unit) { return time_unit == "ms" ? 1e-3 : 1.0; }

std::string file_name_part(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '-';
  return out;
}

// A positive finite number (CLI::PositiveNumber let nan and inf through: nan <= 0 is false).
CLI::Validator positive_finite() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(input, value)) return "Value " + input + " is not a number";
        if (!(value > 0) || !std::isfinite(value)) return "Value " + input + " is not a positive finite number";
        return {};
      },
      "POSITIVE FINITE");
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.12g", v);
  return buffer;
}

// A quantity of the run in the unit (10^E mm)^power of a model simulated on its copy rescaled by
// 10^-E (decimal_scaled_dynamics_model; E = length_display_exponent()), written in the model's
// own unit: the decimal number() prints with its exponent moved by power * E ("0.5" -> "0.5e400",
// "5.4e-07" -> "5.4e393"), exactly. power 1: lengths, speeds, forces, impulses (mass and time are
// unchanged); 2: energies. number(v) when E = 0 (every ordinary model) or power = 0.
std::string shown(double v, int power) {
  std::string text = number(v);
  const long shift = power * length_display_exponent();
  if (shift == 0 || !std::isfinite(v)) return text;
  std::size_t e = text.find('e');
  long exponent = 0;
  if (e != std::string::npos) {
    exponent = std::stol(text.substr(e + 1));
    text.erase(e);
  }
  return text + "e" + std::to_string(exponent + shift);
}

// The run's energy line's value and unit: "0.2 N·mm", or, when a term of it is beyond the doubles
// (kinetic and potential energies of a part thrown by a load of 1e308 overflow, their sum
// printed "-nan" until session 63, hunt63), a sentence saying so.
std::string energy_text(double energy, const std::string& force_unit) {
  if (std::isfinite(energy)) return shown(energy, 2) + " " + force_unit + "·mm";
  return "beyond the doubles' range (a term of it overflows)";
}

// The unit name `unit` in units of (10^E mm)^power: "N" or "1e400 N" (see shown()).
std::string scaled_unit(const std::string& unit, int power) {
  const long shift = power * length_display_exponent();
  return shift == 0 ? unit : "1e" + std::to_string(shift) + " " + unit;
}

std::string event_line(const SimulationEvent& e, const std::string& time_unit, const std::string& force_unit) {
  std::ostringstream out;
  out << "t = " << number(e.time) << " " << time_unit << "  " << to_string(e.kind) << "  " << e.first_part << " / "
      << e.second_part;
  if (!e.features.empty()) {
    out << "  [";
    for (std::size_t i = 0; i < e.features.size(); ++i) out << (i ? "; " : "") << e.features[i];
    out << "]";
  }
  if (e.kind == SimulationEvent::Kind::impact)
    out << "  impulse " << shown(e.impulse, 1) << " " << force_unit << "·" << time_unit << ", normal speed "
        << shown(e.normal_speed_before, 1) << " -> " << shown(e.normal_speed_after, 1) << " mm/" << time_unit;
  if (e.kind == SimulationEvent::Kind::impact && e.tangential_impulse != 0)
    out << ", tangential impulse " << shown(e.tangential_impulse, 1) << " " << force_unit << "·" << time_unit;
  if (e.kind == SimulationEvent::Kind::stick || e.kind == SimulationEvent::Kind::slip)
    out << "  normal force " << shown(e.normal_force, 1) << " " << force_unit << ", friction force "
        << shown(e.friction_force, 1) << " " << force_unit << (e.exact_decision ? ", decided exactly" : ", decided approximately");
  return out.str();
}

// CPU time of the calling thread, seconds (a sweep runs several simulations in threads).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// ------------------------------------------------------------------ --sweep NAME=A:B:N
// Status of one run of a sweep (docs/simulation.md, "Sweep status"):
//   failed   the simulator threw (the message is reported);
//   stopped  it stopped early by a property of the mechanism (session 71, jam71: a jam,
//            hipair::SimulationJam, or a part at its own motion limit, SimulationLimit — was
//            "failed"): its reason, time and message are reported, its parts' data up to the
//            stop; or it reached t-end, and over the rest window, the last quarter of the run
//            [3/4 t-end, t-end] (W = t-end / 4), every moving part (drivers included) stayed
//            at rest: at every state recorded in the window (and the last state before it) its
//            speed is at most v_rest = sqrt(accuracy) * V, V its largest speed over the whole
//            run, and its position range there is at most v_rest * W (what that speed could
//            travel in the window);
//   running  it reached t-end and did not stop.
// The threshold is relative to the run's own motion (rad or mm per time unit, whatever the
// units), in the form of the simulator's own "no separating speed" test (sqrt(accuracy) times
// a speed scale): at the default accuracy 1e-9, 3.2e-5 of the part's top speed. A part held
// in sustained contact keeps a creep far below it (the escapement at -1000 N mm: the balance
// pressed on a fork horn creeps at 2e-4 rad/s after reaching 51 rad/s, 1/8 of the threshold),
// and a moving mechanism is far above it.
enum class RunStatus { running, stopped, failed };

// "a jam", "a jam, approximate", "a motion limit", "a numeric error", "a geometry error"
std::string stop_words(const std::string& kind, bool exact) {
  return "a " + kind + (kind == "jam" && !exact ? ", approximate" : "");
}

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::running: return "running";
    case RunStatus::stopped: return "stopped";
    case RunStatus::failed: return "failed";
  }
  return "failed";
}

// Watches the moving parts over the run and over the rest window [t_window, t_end].
class RestWindow {
 public:
  RestWindow(std::size_t parts, double t_window, double window, double relative)
      : t_window_(t_window), window_(window), relative_(relative), low_(parts), high_(parts), speed_(parts, 0.0),
        top_speed_(parts, 0.0), last_before_(parts), last_before_speed_(parts, 0.0) {}

  // Called with every recorded state, in time order.
  void record(double time, const std::vector<double>& position, const std::vector<double>& velocity) {
    for (std::size_t k = 0; k < top_speed_.size(); ++k) top_speed_[k] = std::max(top_speed_[k], std::abs(velocity[k]));
    if (time < t_window_) {
      before_ = true;
      last_before_ = position;
      last_before_speed_ = velocity;
      return;
    }
    if (!inside_) {
      inside_ = true;
      low_ = high_ = before_ ? last_before_ : position;
      for (std::size_t k = 0; k < speed_.size(); ++k) speed_[k] = before_ ? std::abs(last_before_speed_[k]) : 0.0;
    }
    for (std::size_t k = 0; k < speed_.size(); ++k) {
      low_[k] = std::min(low_[k], position[k]);
      high_[k] = std::max(high_[k], position[k]);
      speed_[k] = std::max(speed_[k], std::abs(velocity[k]));
    }
  }
  double speed_limit(std::size_t k) const { return relative_ * top_speed_[k]; }
  bool at_rest() const {
    if (!inside_) return false;
    for (std::size_t k = 0; k < speed_.size(); ++k)
      if (!(speed_[k] <= speed_limit(k)) || !(high_[k] - low_[k] <= speed_limit(k) * window_)) return false;
    return true;
  }
  // per part: position range and largest speed over the window
  double range(std::size_t k) const { return inside_ ? high_[k] - low_[k] : 0; }
  double speed(std::size_t k) const { return speed_[k]; }
  double top_speed(std::size_t k) const { return top_speed_[k]; }

 private:
  double t_window_, window_, relative_;
  std::vector<double> low_, high_, speed_, top_speed_, last_before_, last_before_speed_;
  bool inside_ = false, before_ = false;
};

struct SweepRow {
  double value = 0;
  RunStatus status = RunStatus::failed;
  std::string error;
  std::vector<double> window_range, window_speed;  // per moving part, over the rest window
  std::vector<double> top_speed;                    // per moving part, over the run
  double reached = 0, cpu = 0;
  std::size_t steps = 0, events = 0;
  std::vector<double> advance;        // per moving part: final - initial position
  std::vector<std::size_t> swings;    // per moving part: sign changes of the velocity
  std::vector<std::vector<double>> reversals;   // per moving part: times of those sign changes
  // per moving part, per sign change: the positions of every moving part at that state
  std::vector<std::vector<std::vector<double>>> reversal_positions;
  // a run stopped early (status stopped, not at t-end): "jam" or "motion limit" (events.json's
  // "stopped" reasons), a jam's verdict exact or approximate, the stop's time and message
  // (session 71, jam71)
  std::string stop_reason, stop_message;
  bool stop_exact = true;
  double stop_time = 0;
};

// A part's periods over the second half of a run, [t_end / 2, t_end]: the times between every
// other sign change of its velocity (an oscillation's full period), as {count, min, median, max};
// count 0 when fewer than three sign changes fall in that half. The escapement's torque band is
// judged on them (docs/simulation.md, "Torque band").
// `first`: the index of the first sign change in the second half (reversals.size() if none).
std::vector<double> second_half_period_list(const std::vector<double>& reversals, double t_end, std::size_t& first) {
  first = 0;
  while (first < reversals.size() && reversals[first] < t_end / 2) ++first;
  std::vector<double> periods;
  for (std::size_t i = first + 2; i < reversals.size(); ++i) periods.push_back(reversals[i] - reversals[i - 2]);
  return periods;
}

nlohmann::json second_half_periods(const std::vector<double>& reversals, double t_end) {
  std::size_t first = 0;
  std::vector<double> periods = second_half_period_list(reversals, t_end, first);
  nlohmann::json j{{"count", periods.size()}};
  if (periods.empty()) return j;
  std::sort(periods.begin(), periods.end());
  j["min"] = periods.front();
  j["median"] = periods[periods.size() / 2];
  j["max"] = periods.back();
  return j;
}

// ------------------------------------------------------------------ works / fails verdict
// The sweep's verdict per value (docs/simulation.md, "Sweep verdict"), from the criteria
// --works-period PART[:TOL], --works-advance PART=STEP[:TOL] and --works-max-decay RATE; all
// judged over the second half of the run, [t_end / 2, t_end], from the sign changes of the
// period part's velocity (an oscillation's period: every other sign change).
struct PeriodCriterion {
  std::size_t part = 0;     // index among the moving parts
  double tolerance = 0.02;  // relative to the median period
};
struct AdvanceCriterion {
  std::size_t part = 0;
  std::string name;
  double step = 0;          // per period, signed, in the part's unit (rad or mm)
  double tolerance = 0.5;   // in steps, over all the second half's periods
};
struct Verdict {
  std::optional<PeriodCriterion> period;
  std::vector<AdvanceCriterion> advance;
  double max_decay = -1;    // relative amplitude decay per time unit; < 0: not checked
  bool any() const { return period.has_value(); }
};

double parse_number(const std::string& text, const std::string& option, const std::string& what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw ModelError("", option + ": " + what + " must be a number, got '" + text + "'");
  return v;
}

std::size_t moving_part(const Model& model, const std::vector<std::size_t>& moving, const std::string& name,
                        const std::string& option) {
  for (std::size_t k = 0; k < moving.size(); ++k)
    if (model.parts[moving[k]].name == name) return k;
  throw ModelError("", option + ": '" + name + "' is not a moving part of the model");
}

// Checks the criteria's syntax and parts; throws a ModelError naming the option.
// A translating part's STEP is in mm; on a model run in units of 10^E mm (length_display_exponent(),
// a sweep of a mechanism at an extreme scale) it is read exactly and divided by 10^E.
Verdict parse_verdict(const SimulateOptions& options, const Model& model, const std::vector<std::size_t>& moving) {
  Verdict verdict;
  if (options.works_period.empty()) {
    if (!options.works_advance.empty()) throw ModelError("", "--works-advance needs --works-period (its period)");
    if (options.works_max_decay >= 0) throw ModelError("", "--works-max-decay needs --works-period (its part)");
    return verdict;
  }
  const std::string period_option = "--works-period " + options.works_period;
  PeriodCriterion period;
  std::string part = options.works_period;
  if (auto colon = part.find(':'); colon != std::string::npos) {
    period.tolerance = parse_number(part.substr(colon + 1), period_option, "TOL");
    part = part.substr(0, colon);
    if (!(period.tolerance > 0 && period.tolerance < 1))
      throw ModelError("", period_option + ": TOL must lie in (0, 1) (a fraction of the median period)");
  }
  period.part = moving_part(model, moving, part, period_option);
  verdict.period = period;
  for (const std::string& text : options.works_advance) {
    const std::string option = "--works-advance " + text;
    auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0) throw ModelError("", option + ": expected PART=STEP[:TOL]");
    AdvanceCriterion advance;
    advance.name = text.substr(0, equals);
    advance.part = moving_part(model, moving, advance.name, option);
    std::string step = text.substr(equals + 1);
    if (auto colon = step.find(':'); colon != std::string::npos) {
      advance.tolerance = parse_number(step.substr(colon + 1), option, "TOL");
      step = step.substr(0, colon);
      if (!(advance.tolerance > 0 && advance.tolerance < 1))
        throw ModelError("", option + ": TOL must lie in (0, 1) (a fraction of STEP)");
    }
    bool degrees = step.size() > 3 && step.compare(step.size() - 3, 3, "deg") == 0;
    if (degrees) {
      if (model.parts[moving[advance.part]].motion.kind != Motion::Kind::rotation)
        throw ModelError("", option + ": STEP in deg needs a rotating part");
      step = step.substr(0, step.size() - 3);
    }
    const long exponent = length_display_exponent();
    if (exponent != 0 && model.parts[moving[advance.part]].motion.kind != Motion::Kind::rotation) {
      Rational exact;
      try {
        exact = parse_rational(step);
      } catch (const Error&) {
        throw ModelError("", option + ": STEP must be a number, got '" + step + "'");
      }
      advance.step = Rational(exact / power_of_ten_rational(exponent)).get_d();
      if (!std::isfinite(advance.step) || (advance.step != 0 && std::abs(advance.step) < 2.2250738585072014e-308))
        throw ModelError("", option + ": STEP " + step + " mm is beyond the doubles' range in the unit the runs use (1e" +
                                 std::to_string(exponent) + " mm)");
    } else {
      advance.step = parse_number(step, option, "STEP");
    }
    if (degrees) advance.step *= M_PI / 180;
    if (advance.step == 0) throw ModelError("", option + ": STEP must not be zero");
    verdict.advance.push_back(advance);
  }
  if (options.works_max_decay >= 0) {
    if (!std::isfinite(options.works_max_decay)) throw ModelError("", "--works-max-decay must be a finite number");
    verdict.max_decay = options.works_max_decay;
  }
  return verdict;
}

// The period part's swings over the second half: half-swing amplitudes |x_i - x_{i-1}| / 2 at
// its sign changes i with both in [t_end / 2, t_end]; their mean, and their least-squares
// slope against time relative to that mean (per time unit). Also the first half's mean.
struct Amplitudes {
  std::size_t count = 0;
  double first_half = 0, second_half = 0, trend = 0;
};

Amplitudes amplitudes(const SweepRow& row, std::size_t part, double t_end) {
  Amplitudes out;
  const auto& times = row.reversals[part];
  const auto& positions = row.reversal_positions[part];
  std::vector<double> t, a;
  double first = 0;
  std::size_t first_count = 0;
  for (std::size_t i = 1; i < times.size(); ++i) {
    double amplitude = std::abs(positions[i][part] - positions[i - 1][part]) / 2;
    if (times[i - 1] >= t_end / 2) {
      t.push_back(times[i]);
      a.push_back(amplitude);
    } else if (times[i] < t_end / 2) {
      first += amplitude;
      ++first_count;
    }
  }
  if (first_count) out.first_half = first / static_cast<double>(first_count);
  out.count = a.size();
  if (a.empty()) return out;
  double tm = 0, am = 0;
  for (std::size_t i = 0; i < a.size(); ++i) tm += t[i], am += a[i];
  tm /= static_cast<double>(a.size());
  am /= static_cast<double>(a.size());
  out.second_half = am;
  double stt = 0, sta = 0;
  for (std::size_t i = 0; i < a.size(); ++i) stt += (t[i] - tm) * (t[i] - tm), sta += (t[i] - tm) * (a[i] - am);
  out.trend = stt > 0 && am > 0 ? sta / stt / am : 0;
  return out;
}

// "works", or "fails (reasons)"; `details` gets the measured quantities for sweep.json.
std::string judge(const Verdict& verdict, const SweepRow& row, double t_end, const Model& model,
                  const std::vector<std::size_t>& moving, nlohmann::json& details) {
  if (row.status == RunStatus::failed) return "fails (run failed)";
  std::vector<std::string> reasons;
  if (row.status == RunStatus::stopped)
    reasons.push_back(row.stop_reason.empty() ? "stopped" : "stopped early (" + stop_words(row.stop_reason, row.stop_exact) + ")");
  const PeriodCriterion& period = *verdict.period;
  const std::string& name = model.parts[moving[period.part]].name;
  const auto& times = row.reversals[period.part];
  // sign changes in the second half; periods between every other one
  std::size_t first = 0;
  std::vector<double> periods = second_half_period_list(times, t_end, first);
  std::size_t whole = times.size() > first ? (times.size() - 1 - first) / 2 : 0;  // whole periods from `first`
  char buffer[200];
  if (periods.size() < 2) {
    reasons.push_back(name + ": fewer than two periods in the second half");
  } else {
    std::vector<double> sorted = periods;
    std::sort(sorted.begin(), sorted.end());
    double median = sorted[sorted.size() / 2];
    double spread = std::max(median - sorted.front(), sorted.back() - median) / median;
    details["period"] = {{"part", name}, {"count", periods.size()}, {"median", median}, {"spread", spread},
                         {"tolerance", period.tolerance}};
    if (!(spread <= period.tolerance)) {
      std::snprintf(buffer, sizeof buffer, "%s: periods %.4g-%.4g, %.2g %% off their median %.4g (tolerance %.2g %%)",
                    name.c_str(), sorted.front(), sorted.back(), 100 * spread, median, 100 * period.tolerance);
      reasons.push_back(buffer);
    }
  }
  for (const AdvanceCriterion& advance : verdict.advance) {
    if (whole == 0) {
      reasons.push_back(advance.name + ": no whole period of " + name + " to measure its advance over");
      continue;
    }
    const auto& positions = row.reversal_positions[period.part];
    double moved = positions[first + 2 * whole][advance.part] - positions[first][advance.part];
    double steps = moved / advance.step;
    double periods_count = static_cast<double>(whole);
    details["advance"][advance.name] = {{"step", advance.step}, {"steps", steps}, {"periods", whole},
                                        {"tolerance", advance.tolerance}};
    if (!(std::abs(steps - periods_count) <= advance.tolerance)) {
      std::snprintf(buffer, sizeof buffer, "%s: %.3g steps in %zu periods (tolerance %.2g)", advance.name.c_str(),
                    steps, whole, advance.tolerance);
      reasons.push_back(buffer);
    }
  }
  Amplitudes amplitude = amplitudes(row, period.part, t_end);
  if (amplitude.count > 0)
    details["amplitude"] = {{"part", name}, {"first_half_mean", amplitude.first_half},
                            {"second_half_mean", amplitude.second_half}, {"second_half_swings", amplitude.count},
                            {"trend_per_time_unit", amplitude.trend}};
  if (verdict.max_decay >= 0) {
    if (amplitude.count < 2) {
      reasons.push_back(name + ": fewer than two swings in the second half for the amplitude trend");
    } else if (!(amplitude.trend >= -verdict.max_decay)) {
      std::snprintf(buffer, sizeof buffer, "%s: amplitude trend %.3g %% per time unit, below -%.3g %%", name.c_str(),
                    100 * amplitude.trend, 100 * verdict.max_decay);
      reasons.push_back(buffer);
    }
  }
  if (reasons.empty()) return "works";
  std::string out = "fails (";
  for (std::size_t i = 0; i < reasons.size(); ++i) out += (i ? "; " : "") + reasons[i];
  return out + ")";
}

// The model's own fastest motion against the step budget, before anything is built
// (docs/simulation.md, "Stiff inputs"): a spring of stiffness 1e300 (or gravity of 1e300 on a
// part hung from one) made steps of 1e-152 s, and the run went on for hours towards its budget.
// An explicit integrator takes at least about one step per period 2π/ω of the fastest motion it
// resolves, so a run whose T·ω/2π exceeds the budget is refused at once, naming the data.
void check_own_frequency(const Model& model, const SimulateOptions& options) {
  OwnFrequency f = own_frequency(model);
  if (!(f.omega > 0)) return;
  // ω beyond the doubles' range (a spring attached 1e308 mm from a pivot): the period is below
  // 2π/DBL_MAX; until session 61 (hunt61) such a period, and one whose ω² overflowed (a
  // stiffness of 1 on an inertia of 3e-308), was shown as "2π/ω = 0 s", with "a --t-end of at most 0 s"
  const bool beyond = !std::isfinite(f.omega);
  const double period = 2 * std::numbers::pi / (beyond ? std::numeric_limits<double>::max() : f.omega);
  const double steps = options.t_end / period;
  if (!(steps > static_cast<double>(options.max_steps))) return;
  const std::string tu = model.simulation ? model.simulation->time_unit : SimulationSpec{}.time_unit;
  const bool many = beyond || !std::isfinite(steps);
  throw ModelError(f.pointer, f.what + " sets the model's own period 2π/ω " + (beyond ? "below " : "= ") + number(period) +
                                  " " + tu + ": --t-end " + number(options.t_end) + " " + tu + " needs " +
                                  (many ? "more than " + number(std::isfinite(steps) ? steps : std::numeric_limits<double>::max())
                                        : "at least about " + number(steps)) +
                                  " integration steps (one per period), beyond the step budget (--max-steps " +
                                  std::to_string(options.max_steps) + "); nothing was run: give a --t-end of " +
                                  (beyond ? "below " : "at most ") +
                                  number(period * static_cast<double>(options.max_steps)) + " " + tu +
                                  ", a larger --max-steps, or a softer spring (a lighter load)");
}


Model simulated_model(const SimulateOptions& options, const ReadOptions& overrides, long& exponent);

int run_sweep(const SimulateOptions& options) {
  // NAME=A:B:N
  auto equals = options.sweep.find('=');
  std::vector<std::string> fields;
  if (equals != std::string::npos && equals > 0) {
    std::string rest = options.sweep.substr(equals + 1);
    std::size_t start = 0;
    for (std::size_t colon; (colon = rest.find(':', start)) != std::string::npos; start = colon + 1)
      fields.push_back(rest.substr(start, colon - start));
    fields.push_back(rest.substr(start));
  }
  if (fields.size() != 3) throw ModelError("", "--sweep expects NAME=A:B:N, got '" + options.sweep + "'");
  std::string name = options.sweep.substr(0, equals);
  Rational a, b;
  long n = 0;
  try {
    a = exact_option_literal(fields[0], "--sweep " + options.sweep);
    b = exact_option_literal(fields[1], "--sweep " + options.sweep);
    std::size_t used = 0;
    n = std::stol(fields[2], &used);
    if (used != fields[2].size()) throw std::invalid_argument("N");
  } catch (const ModelError&) {
    throw;
  } catch (const std::exception&) {
    // (1e9 and 99999999999999999999 are whole numbers too: the message says what is taken)
    throw ModelError("", "--sweep " + options.sweep + ": N must be a whole number written in digits, from 1 to 10000");
  }
  if (n < 1 || n > 10000) throw ModelError("", "--sweep " + options.sweep + ": N must lie in [1, 10000]");
  if (n == 1 && a != b) throw ModelError("", "--sweep " + options.sweep + ": N = 1 needs A = B");
  // the swept parameter given by --set as well: the sweep's values would silently win
  refuse_repeated_names(options.overrides, "--set", "parameter");
  OnceEach once("--sweep", "parameter");
  for (const std::string& assignment : options.overrides)
    once.add(assignment.substr(0, assignment.find('=')), "--set " + assignment);
  once.add(name, "--sweep " + options.sweep);
  std::vector<Rational> values;
  for (long i = 0; i < n; ++i) values.push_back(n == 1 ? a : Rational(a + (b - a) * Rational(i, n - 1)));
  // a name the model lacks, named as the option that gave it (until session 45 the reader's
  // "/parameters: cannot override unknown parameter", also for the --sweep parameter)
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  refuse_unknown_parameters(options.model, {options.sweep}, "--sweep");
  // every model is read (and checked) before any run starts: a bad value stops the sweep at once
  // (a refusal names the sweep's value too: until session 52 it named only the model's pointer,
  // `/parts/0/features/0/escape_wheel/teeth: must be at least 3`, with no word of --sweep)
  // A mechanism drawn at an extreme scale runs, as a single simulation does (simulated_model),
  // on its copy rescaled exactly by 10^-E with its dynamics data: every run of the sweep in the
  // same unit 10^E mm (its lengths, speeds and forces shown in mm and N: shown()). Until session
  // 54 a sweep was not rescaled (refused at the first inertia beyond the doubles).
  std::vector<Model> models;
  long length_exponent = 0;
  std::string first_assignment;
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::vector<std::string> overrides = options.overrides;
    overrides.push_back(name + "=" + values[i].get_str());
    try {
      long exponent = 0;
      models.push_back(simulated_model(options, parameter_overrides(overrides, options.allow_out_of_tolerance), exponent));
      if (i == 0) {
        length_exponent = exponent;
        first_assignment = overrides.back();
      } else if (exponent != length_exponent) {
        auto unit = [](long e) { return e == 0 ? std::string("mm") : "1e" + std::to_string(e) + " mm"; };
        throw ModelError("", "its lengths lie at another scale than the first run's (" + first_assignment +
                                 "): the runs would be simulated in units of " + unit(length_exponent) + " and " +
                                 unit(exponent) + "; sweep a range within one scale");
      }
      check_simulator_range(models.back());
      check_own_frequency(models.back(), options);
    } catch (const ModelError& error) {
      throw ModelError(error.pointer(), error.reason() + " (--sweep " + options.sweep + ": the model of run " +
                                            std::to_string(i + 1) + " of " + std::to_string(values.size()) + ", " +
                                            overrides.back() + " ; nothing was run)");
    }
  }
  LengthDisplayScope length_display(length_exponent);   // shown(), the STEP of --works-advance
  SimulationOptions sim_options = stepping_options(options);
  set_region(sim_options, options);
  std::vector<std::size_t> moving;
  for (std::size_t p = 0; p < models.front().parts.size(); ++p)
    if (models.front().parts[p].motion.kind != Motion::Kind::fixed) moving.push_back(p);
  const Verdict verdict = parse_verdict(options, models.front(), moving);
  std::vector<SweepRow> rows(values.size());
  std::mutex mutex;
  std::size_t next = 0;
  auto worker = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= values.size()) return;
        i = next++;
      }
      SweepRow& row = rows[i];
      row.value = values[i].get_d();
      double cpu_start = thread_cpu_seconds();
      try {
        Simulation simulation = Simulation::create(models[i], sim_options);
        std::vector<double> start, last_velocity;
        for (std::size_t p : moving) {
          start.push_back(simulation.state().position[p]);
          last_velocity.push_back(simulation.state().velocity[p]);
        }
        row.swings.assign(moving.size(), 0);
        row.reversals.assign(moving.size(), {});
        row.reversal_positions.assign(moving.size(), {});
        // the accuracy the simulation uses (as Simulation::create resolves it)
        double accuracy = 1e-9;
        if (sim_options.accuracy > 0)
          accuracy = sim_options.accuracy;
        else if (models[i].simulation && models[i].simulation->accuracy)
          accuracy = models[i].simulation->accuracy->get_d();
        double window = options.t_end / 4;
        RestWindow rest(moving.size(), options.t_end - window, window, std::sqrt(accuracy));
        std::vector<double> position(moving.size()), velocity(moving.size());
        auto record = [&] {
          for (std::size_t k = 0; k < moving.size(); ++k) {
            position[k] = simulation.state().position[moving[k]];
            velocity[k] = simulation.state().velocity[moving[k]];
          }
          rest.record(simulation.state().time, position, velocity);
        };
        record();
        try {
          simulation.run_until(options.t_end, [&](double) {
            record();
            for (std::size_t k = 0; k < moving.size(); ++k) {
              double velocity = simulation.state().velocity[moving[k]];
              if (velocity != 0) {
                if (last_velocity[k] != 0 && (velocity > 0) != (last_velocity[k] > 0)) {
                  ++row.swings[k];
                  row.reversals[k].push_back(simulation.state().time);
                  row.reversal_positions[k].push_back(position);
                }
                last_velocity[k] = velocity;
              }
            }
          });
        } catch (const SimulationJam& jam) {   // a stop of the mechanism (session 71): its state is the stop's
          row.stop_reason = "jam";
          row.stop_exact = jam.exact();
          row.stop_message = jam.what();
          row.stop_time = jam.time();
        } catch (const SimulationLimit& limit) {
          row.stop_reason = "motion limit";
          row.stop_message = limit.what();
          row.stop_time = limit.time();
        } catch (const Error&) {
          // how far the failed run got (the message names the time)
          row.steps = simulation.steps();
          row.events = simulation.events().size();
          throw;
        }
        for (std::size_t k = 0; k < moving.size(); ++k)
          row.advance.push_back(simulation.state().position[moving[k]] - start[k]);
        row.reached = simulation.state().time;
        row.steps = simulation.steps();
        row.events = simulation.events().size();
        row.status = !row.stop_reason.empty() || rest.at_rest() ? RunStatus::stopped : RunStatus::running;
        for (std::size_t k = 0; k < moving.size(); ++k) {
          row.window_range.push_back(rest.range(k));
          row.window_speed.push_back(rest.speed(k));
          row.top_speed.push_back(rest.top_speed(k));
        }
      } catch (const Error& error) {
        row.error = error.what();
      }
      row.cpu = thread_cpu_seconds() - cpu_start;
    }
  };
  unsigned jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, values.size()));
  std::vector<std::thread> threads;
  for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (std::thread& thread : threads) thread.join();

  const Model& model = models.front();
  std::cout << "sweep of " << name << " over " << values.size() << " values, t-end " << number(options.t_end) << "\n";
  std::cout << "status: failed (simulator error), stopped (early, by a jam or a part at its motion limit: the row says "
               "which; or over the last quarter of the run every moving part's speed stayed below sqrt(accuracy) "
               "times its top speed in the run), running (otherwise)\n";
  if (verdict.any())
    std::cout << "verdict: works when " << model.parts[moving[verdict.period->part]].name
              << " has at least two periods in the second half of the run, all within "
              << number(100 * verdict.period->tolerance) << " % of their median"
              << (verdict.advance.empty() ? "" : ", each --works-advance part advances one STEP per period")
              << (verdict.max_decay >= 0 ? ", its swing amplitude does not decay faster than --works-max-decay" : "")
              << "; a failed or stopped run fails\n";
  std::cout << name << "\tstatus" << (verdict.any() ? "\tverdict" : "") << "\tsteps\tevents\tcpu_s";
  for (std::size_t p : moving) std::cout << "\t" << model.parts[p].name << "_advance\t" << model.parts[p].name << "_swings";
  std::cout << "\n";
  nlohmann::json doc = nlohmann::json::array();
  for (const SweepRow& row : rows) {
    const bool ran = row.status != RunStatus::failed;   // the parts' data: to t-end, or to an early stop
    const bool completed = ran && row.stop_reason.empty();   // reached t-end
    nlohmann::json j{
        {"value", row.value}, {"status", to_string(row.status)}, {"completes", completed}, {"cpu_seconds", row.cpu}};
    std::cout << number(row.value) << "\t" << to_string(row.status);
    if (verdict.any()) {
      nlohmann::json details = nlohmann::json::object();
      std::string said = judge(verdict, row, options.t_end, model, moving, details);
      std::cout << "\t" << said;
      j["verdict"] = said;
      j["works"] = said == "works";
      if (!details.empty()) j["verdict_measures"] = details;
    }
    std::cout << "\t" << row.steps << "\t" << row.events << "\t" << number(row.cpu);
    j["steps"] = row.steps;    // a failed run: up to its failure
    j["events"] = row.events;
    if (ran) {
      for (std::size_t k = 0; k < moving.size(); ++k) {
        const bool rotates = model.parts[moving[k]].motion.kind == Motion::Kind::rotation;
        std::cout << "\t" << shown(row.advance[k], rotates ? 0 : 1) << "\t" << row.swings[k];
        j["parts"][model.parts[moving[k]].name] = {{"advance", row.advance[k]},
                                                   {"velocity_sign_changes", row.swings[k]},
                                                   {"rest_window_position_range", row.window_range[k]},
                                                   {"rest_window_max_speed", row.window_speed[k]},
                                                   {"max_speed", row.top_speed[k]},
                                                   {"second_half_periods", second_half_periods(row.reversals[k], options.t_end)}};
      }
      if (!completed) {   // stopped early: when, why (as events.json's "stopped" of a single run)
        std::cout << "\tstopped early at t = " << number(row.stop_time) << " (" << stop_words(row.stop_reason, row.stop_exact)
                  << "): " << row.stop_message;
        j["stopped"] = {{"time", row.stop_time}, {"reason", row.stop_reason}};
        if (row.stop_reason == "jam") j["stopped"]["decision"] = row.stop_exact ? "exact" : "approximate";
        j["stopped"]["message"] = row.stop_message;
      }
    } else {
      std::cout << "\t" << row.error;
      j["error"] = row.error;
    }
    std::cout << "\n";
    doc.push_back(j);
  }
  if (!options.out.empty()) {
    std::filesystem::path directory(options.out);
    nlohmann::json sweep{{"model", model.name}, {"parameter", name}, {"t_end", options.t_end}, {"runs", doc}};
    // a translating part's advance, ranges and speeds (and --works-advance steps) in units of
    // 10^E mm: named so (absent for every ordinary model)
    if (length_exponent != 0) sweep["units"] = {{"length", length_unit_name()}};
    if (verdict.any()) {
      sweep["works_period"] = options.works_period;
      sweep["works_advance"] = options.works_advance;
      if (verdict.max_decay >= 0) sweep["works_max_decay"] = verdict.max_decay;
    }
    std::vector<io::RunFile> files{{"sweep.json", sweep.dump(1) + "\n"}};
    std::vector<io::PlannedOutput> planned{{directory / "sweep.json", "--out"}};
    io::refuse_overwriting_inputs(planned, {options.model});
    io::publish_directory(directory, files, [](const std::string& file) { return file == "sweep.json"; },
                          {options.model});
    std::cout << "wrote " << (directory / "sweep.json").string() << "\n";
  }
  return 0;
}

// ------------------------------------------------------------------ shared by both runs

// The animation's frame times (k / N of t-end, k = 1..N) and its playback time; none without
// pictures. Too many frames is a usage error.
std::vector<double> frame_times(const SimulateOptions& options, const std::string& time_unit, double& playback) {
  playback = 0;
  if (options.out.empty() || options.no_pictures) return {};
  playback = options.animation_duration > 0 ? options.animation_duration
                                            : std::max(1.0, options.t_end * seconds_per_unit(time_unit));
  double count = std::ceil(playback * options.fps);
  if (count > 20000) {
    // name the option that set the playback: --animation-duration, or --t-end (its default)
    if (options.animation_duration > 0)
      throw ModelError("", "the animation would have " + number(count) + " frames (more than 20000): --animation-duration " +
                               number(options.animation_duration) + " s at --fps " + number(options.fps) +
                               "; lower --animation-duration or --fps");
    throw ModelError("", "the animation would have " + number(count) + " frames (more than 20000): its playback is --t-end " +
                             number(options.t_end) + " " + time_unit + " (" + number(playback) + " s) at --fps " +
                             number(options.fps) + "; give a shorter --t-end, or --animation-duration SECONDS (or --no-pictures)");
  }
  auto frame_count = static_cast<std::size_t>(std::max(1.0, count));
  std::vector<double> times;
  for (std::size_t k = 1; k <= frame_count; ++k)
    times.push_back(k == frame_count ? options.t_end
                                     : options.t_end * static_cast<double>(k) / static_cast<double>(frame_count));
  return times;
}

// The progress line on a terminal, at most every 200 ms.
// Runs `run` (the run's run_until calls). A run that uses up the step budget (the simulator
// throws "more than N steps" after --max-steps steps) ends with one message saying where it
// stopped, that nothing was written, and what lets it finish; until session 33 the message was
// the simulator's alone, after minutes (`--t-end 1e300` of the scotch yoke: 2 000 000 steps).
template <class Sim, class Run>
void run_within_budget(const Sim& simulation, const SimulateOptions& options, const std::string& time_unit, Run&& run) {
  try {
    run();
  } catch (const SimulationStepBudget&) {   // (session 71, jam71: its own type; was steps() >= max_steps)
    const double t = simulation.state().time;
    throw SimulationStepBudget("simulate: the run used up its step budget (--max-steps " + std::to_string(options.max_steps) +
                       ") at t = " + number(t) + " " + time_unit + " of --t-end " + number(options.t_end) + " " + time_unit +
                       ", and nothing was written: give a --t-end of at most about " + number(t) + " " + time_unit +
                       " or a larger --max-steps");
  }
}

// A run that stopped before --t-end keeps what it computed (session 69, jam69: a jam; session
// 70, stop70: every stop after the run began). Its summary, trajectory, events and pictures up to
// the stop are reported and written (whole, as every run's files: staged and renamed into --out,
// io::publish_directory), the report and events.json say it stopped early, when, why and of what
// kind, and the command still exits 3 with the stop's message saying what was written
// (`stopped_run`). The kinds:
//  - "jam" (hipair::SimulationJam): the contacts locked against a driver; the simulator's state
//    is the jam's;
//  - "motion limit" (hipair::SimulationLimit): a part at one of its own motion limits (not a
//    contact); the simulator's state is the stop's (the last step's, or the state at the limit);
//  - "numeric error" (NumericError: an impact refused as inconsistent, a contact problem with no
//    solution, a non-finite state or energy, a contact change without progress) and "geometry
//    error" (GeometryError: a pair leaving its built C-space or operating region, a contact
//    without a normal): the results up to the last completed step (its sample, its energy, the
//    events up to its time), not the failed step's partial state.
// Not stops (nothing written, as before): bad input (ModelError, exit 2: refused before the run,
// or found in it), and a run out of its step budget (--max-steps: the user's own limit, whose
// message says what lets it finish).
struct RunStop {
  double time = 0;        // the time of the last state written (set by kept_stop_state)
  std::string message;
  std::string kind;       // "jam", "motion limit", "numeric error", "geometry error"
  bool exact = true;      // a jam's verdict decided exactly (SimulationJam::exact), or approximate
  bool at_state = true;   // the simulator's state() is the stop's; false: the last completed step's sample
  std::string part, limit;   // a motion limit's part and limit
};

// run_within_budget, a stop after the run began kept as the run's stop
template <class Sim, class Run>
std::optional<RunStop> run_to_end_or_stop(const Sim& simulation, const SimulateOptions& options, const std::string& time_unit,
                                          Run&& run) {
  try {
    run_within_budget(simulation, options, time_unit, std::forward<Run>(run));
  } catch (const SimulationJam& jam) {
    return RunStop{jam.time(), jam.what(), "jam", jam.exact(), true, {}, {}};
  } catch (const SimulationLimit& limit) {
    return RunStop{limit.time(), limit.what(), "motion limit", true, true, limit.part(), limit.limit()};
  } catch (const ModelError&) {
    throw;
  } catch (const SimulationStepBudget&) {
    throw;   // the step budget (run_within_budget's message)
  } catch (const NumericError& error) {
    return RunStop{0, error.what(), "numeric error", true, false, {}, {}};
  } catch (const GeometryError& error) {
    return RunStop{0, error.what(), "geometry error", true, false, {}, {}};
  }
  return std::nullopt;
}

// The stop's time: its last state's, `last` (the samples' last, after the stop's own state was
// added where it is the simulator's). A run whose initial state's energy is already not finite
// (an initial velocity or load beyond the doubles' range) stops at its initial state, which is
// written with "energy": null (session 71: jam71 made it bad input, exit 2; reverted at
// integration — its message named no pointer as its place, and the seeded fuzz of `simulate`
// holds exit 2 to one).
void kept_stop_state(std::optional<RunStop>& stop, double last) {
  if (!stop) return;
  stop->time = last;
}

// The events a run's outputs hold: all of them; for a stopped run those up to its time (a
// failed step's events are not results). Every kind of stop (session 71, jam71; session 70
// filtered only the stops after the last completed step): a motion limit found by the step's
// end check keeps the last step's state, while the failing step may already have recorded an
// impact after it.
const std::vector<SimulationEvent>& kept_events(const std::vector<SimulationEvent>& all, const std::optional<RunStop>& stop,
                                                std::vector<SimulationEvent>& storage) {
  if (!stop) return all;
  for (const SimulationEvent& e : all)
    if (e.time <= stop->time) storage.push_back(e);
  return storage;
}

// The summary's line of a stopped run (after its "simulated ... to t = ..." line)
void print_stop(const std::optional<RunStop>& stop, const std::string& tu) {
  if (stop)
    std::cout << "  stopped early at t = " << number(stop->time) << " " << tu << " (" << stop_words(stop->kind, stop->exact)
              << "): " << stop->message << "\n";
}

// events.json's "stopped" member of a stopped run: its time, its kind ("reason"), a jam's
// decision, a motion limit's part and limit, and the message
void add_stop(nlohmann::json& summary, const std::optional<RunStop>& stop) {
  if (!stop) return;
  summary["stopped"] = {{"time", stop->time}, {"reason", stop->kind}};
  if (stop->kind == "jam") summary["stopped"]["decision"] = stop->exact ? "exact" : "approximate";
  if (stop->kind == "motion limit") {
    summary["stopped"]["part"] = stop->part;
    summary["stopped"]["limit"] = stop->limit;
  }
  summary["stopped"]["message"] = stop->message;
}

// The end of a run: 0, or for a stopped run its error (exit 3), saying what was written
int stopped_run(const std::optional<RunStop>& stop, const SimulateOptions& options, const std::string& tu) {
  if (!stop) return 0;
  throw NumericError(stop->message + (options.out.empty()
                                          ? std::string()
                                          : "; the run stopped there: its results up to t = " + number(stop->time) + " " +
                                                tu + " were written to " + options.out));
}

struct ProgressLine {
  explicit ProgressLine(const SimulateOptions& options) : terminal(isatty(2) && !options.quiet) {}
  bool terminal;
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  void show(double t, const SimulateOptions& options, const std::string& time_unit, std::size_t steps,
            std::size_t events) {
    if (!terminal) return;
    auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::milliseconds(200)) return;
    last = now;
    std::fprintf(stderr, "\rsimulate: t = %-12.6g of %g %s (%3.0f%%), %zu steps, %zu events   ", t, options.t_end,
                 time_unit.c_str(), 100 * t / options.t_end, steps, events);
  }
};

// events.json (the log with `summary`'s members) and events.txt.
void add_event_files(std::vector<io::RunFile>& files, const Model& model, const std::vector<SimulationEvent>& events,
                     const std::string& tu, const std::string& fu, nlohmann::json summary) {
  nlohmann::json log = nlohmann::json::array();
  std::string text;
  for (const SimulationEvent& e : events) {
    nlohmann::json j{{"time", e.time},
                     {"kind", to_string(e.kind)},
                     {"pair", {e.first_part, e.second_part}},
                     {"features", e.features}};
    if (e.edge.valid()) j["edge"] = e.edge.index();
    if (e.kind == SimulationEvent::Kind::impact) {
      j["impulse"] = e.impulse;
      j["normal_speed_before"] = e.normal_speed_before;
      j["normal_speed_after"] = e.normal_speed_after;
      j["point"] = e.point;
      j["normal"] = e.normal;
      if (e.tangential_impulse != 0) j["tangential_impulse"] = e.tangential_impulse;
    }
    if (e.kind == SimulationEvent::Kind::stick || e.kind == SimulationEvent::Kind::slip) {
      j["normal_force"] = e.normal_force;
      j["friction_force"] = e.friction_force;
      if (e.kind == SimulationEvent::Kind::slip) j["slip_direction"] = e.slip_direction;
      // how stick vs slip was decided: exact rationals, or floating point to the stated accuracy
      j["decision"] = e.exact_decision ? "exact" : "approximate";
    }
    if (e.kind == SimulationEvent::Kind::contact && e.normal_force != 0) j["normal_force"] = e.normal_force;
    log.push_back(j);
    text += event_line(e, tu, fu) + "\n";
  }
  nlohmann::json doc{{"model", model.name},
                     {"units", {{"time", tu}, {"force", scaled_unit(fu, 1)}, {"length", length_unit_name()}, {"angle", "rad"}, {"mass", "kg"}}}};
  // a model simulated in units of 10^E mm (E != 0): its numbers are in those units, the energy in 10^(2E) N mm
  if (length_display_exponent() != 0) doc["units"]["energy"] = scaled_unit(fu + "·mm", 2);
  for (auto& [key, value] : summary.items()) doc[key] = value;
  doc["events"] = log;
  if (summary.contains("stopped"))   // (sessions 69, 70) the stop, after the events up to it
    text += "t = " + number(summary["stopped"]["time"].get<double>()) + " " + tu + ": stopped early (" +
            stop_words(summary["stopped"]["reason"].get<std::string>(),
                       !summary["stopped"].contains("decision") || summary["stopped"]["decision"] == "exact") +
            "): " + summary["stopped"]["message"].get<std::string>() + "\n";
  files.push_back({"events.json", doc.dump(1) + "\n"});
  files.push_back({"events.txt", text});
}

// The first 20 events on standard output.
void print_events(const std::vector<SimulationEvent>& events, const std::string& tu, const std::string& fu) {
  for (std::size_t i = 0; i < events.size(); ++i) {
    if (i == 20) {
      std::cout << "  ... " << events.size() - 20 << " more events (see events.txt)\n";
      break;
    }
    std::cout << "  " << event_line(events[i], tu, fu) << "\n";
  }
}

// Writes the run's files into --out, all or nothing, and says so.
void publish_run(const std::vector<io::RunFile>& files, const SimulateOptions& options) {
  std::filesystem::path directory(options.out);
  std::vector<io::PlannedOutput> planned;
  for (const io::RunFile& file : files) planned.push_back({directory / file.name, "--out"});
  io::refuse_overwriting_inputs(planned, {options.model});
  auto earlier_output = [](const std::string& name) {
    return name == "trajectory.csv" || name == "events.json" || name == "events.txt" || name == "positions.svg" ||
           name == "velocities.svg" || name == "animation.svg" || (name.rfind("cspace-", 0) == 0 && name.size() > 4 &&
                                        name.compare(name.size() - 4, 4, ".svg") == 0);
  };
  io::publish_directory(directory, files, earlier_output, {options.model});
  std::cout << "wrote";
  for (const io::RunFile& file : files) std::cout << " " << (directory / file.name).string();
  std::cout << "\n";
}

// The planar parts a planar simulation moves and their states (model order of `parts`).
std::vector<std::size_t> planar_parts(const PlanarSimulation& s) { return {s.part()}; }
std::vector<std::size_t> planar_parts(const PlanarSystemSimulation& s) { return s.state().parts; }
std::vector<PlanarState> planar_states(const PlanarSimulation& s) { return {s.state()}; }
std::vector<PlanarState> planar_states(const PlanarSystemSimulation& s) { return s.state().states; }
double state_time(const PlanarSimulation& s) { return s.state().time; }
double state_time(const PlanarSystemSimulation& s) { return s.state().time; }

// A model with parts free in the plane (docs/simulation.md, "Parts free in the plane" and
// "Several planar parts"): PlanarSimulation for one planar part, PlanarSystemSimulation for
// several. Same outputs as the fixed-axis run except the C-space pictures (a planar pair's
// C-space is three-dimensional): trajectory.csv, events.json/.txt, positions.svg,
// velocities.svg, animation.svg.
template <class PlanarRun>
int run_planar(const Model& model, const SimulateOptions& options) {
  SimulationOptions sim_options = stepping_options(options);
  if (options.region == "operating") throw ModelError("", "--region: a planar part's C-space has no operating region");
  PlanarRun simulation = PlanarRun::create(model, sim_options);
  const std::string& tu = simulation.time_unit();
  const std::string& fu = simulation.force_unit();
  const std::vector<std::size_t> parts = planar_parts(simulation);
  struct Sample {
    double time;
    std::vector<PlanarState> states;
  };
  std::vector<Sample> samples{{state_time(simulation), planar_states(simulation)}};
  double sample_energy = simulation.energy();   // the last sample's (a stop after it: session 70)
  double cpu_start = thread_cpu_seconds();
  ProgressLine line(options);
  auto progress = [&](double t) {
    samples.push_back({state_time(simulation), planar_states(simulation)});
    sample_energy = simulation.energy();
    line.show(t, options, tu, simulation.steps(), simulation.events().size());
  };
  std::vector<render::MechanismFrame> frames;
  double playback = 0;
  auto record_frame = [&] {
    render::MechanismFrame frame;
    frame.time = state_time(simulation);
    for (const Part& p : model.parts) frame.configurations.push_back(p.initial);
    std::vector<PlanarState> states = planar_states(simulation);
    for (std::size_t k = 0; k < parts.size(); ++k) {
      PartConfiguration& c = frame.configurations[parts[k]];
      c.x = Rational(states[k].x);
      c.y = Rational(states[k].y);
      c.angle = Rational(states[k].angle);
    }
    frames.push_back(std::move(frame));
  };
  std::vector<double> times = frame_times(options, tu, playback);
  if (!times.empty()) record_frame();
  std::optional<RunStop> stop = run_to_end_or_stop(simulation, options, tu, [&] {
    for (double t : times) {
      simulation.run_until(t, progress);
      record_frame();
    }
    simulation.run_until(options.t_end, progress);
  });
  if (stop && stop->at_state && state_time(simulation) > samples.back().time) {   // the stop's state, the last one
    samples.push_back({state_time(simulation), planar_states(simulation)});
    if (!times.empty()) record_frame();
  }
  kept_stop_state(stop, samples.back().time);
  std::vector<SimulationEvent> kept;
  const std::vector<SimulationEvent>& events = kept_events(simulation.events(), stop, kept);
  const bool at_sample = stop && !stop->at_state;   // a stop after the last completed step: its sample is the end
  const double end_time = at_sample ? samples.back().time : state_time(simulation);
  const double energy = at_sample ? sample_energy : simulation.energy();
  double seconds = thread_cpu_seconds() - cpu_start;
  if (line.terminal) std::cerr << "\r" << std::string(90, ' ') << "\r" << std::flush;
  const std::vector<PlanarState> end = at_sample ? samples.back().states : planar_states(simulation);
  const PlanarStatistics& stats = simulation.statistics();
  std::cout << "simulated " << shown_name(model.name) << " to t = " << number(end_time) << " " << tu << " in "
            << simulation.steps() << " steps, " << events.size() << " events, " << number(seconds)
            << " s CPU\n";
  print_stop(stop, tu);
  for (std::size_t k = 0; k < parts.size(); ++k)
    std::cout << "  " << model.parts[parts[k]].name << ": x " << shown(end[k].x, 1) << " mm, y " << shown(end[k].y, 1)
              << " mm, angle " << number(end[k].angle) << " rad; velocity (" << shown(end[k].vx, 1) << ", "
              << shown(end[k].vy, 1) << ") mm/" << tu << ", " << number(end[k].omega) << " rad/" << tu
              << (end[k].resting ? " (at rest)" : "") << "\n";
  std::cout << "  energy " << energy_text(energy, fu) << "\n";
  std::cout << "  collision tests: " << stats.advancement_steps << " advancement steps, " << stats.distance_queries
            << " distance queries, " << stats.chord_tests << " exact chord tests (chord deviation "
            << shown(simulation.chord_deviation(), 1) << " mm)\n";
  if (stats.restitution_limited > 0)
    std::cout << "  " << stats.restitution_limited
              << " frictional impacts with their restitution limited (Newton's law would have created energy)\n";
  print_events(events, tu, fu);
  if (options.out.empty()) return stopped_run(stop, options, tu);

  std::vector<io::RunFile> files;
  const char* names[6] = {"x", "y", "angle", "vx", "vy", "omega"};
  auto column = [](const PlanarState& s, int i) {
    double values[6] = {s.x, s.y, s.angle, s.vx, s.vy, s.omega};
    return values[i];
  };
  {
    std::ostringstream csv;
    csv << "time_" << tu;
    // in units of 10^E mm (E != 0): x, y and their rates name it ("_1e400mm", "_1e400mm_per_s")
    const std::string unit = length_display_exponent() != 0 ? "_1e" + std::to_string(length_display_exponent()) + "mm" : "";
    for (std::size_t p : parts)
      for (int i = 0; i < 6; ++i)
        csv << "," << model.parts[p].name << "_" << names[i]
            << (i == 2 || i == 5 || unit.empty() ? std::string() : i < 2 ? unit : unit + "_per_" + tu);
    csv << "\n";
    for (const Sample& s : samples) {
      csv << number(s.time);
      for (const PlanarState& state : s.states)
        for (int i = 0; i < 6; ++i) csv << "," << number(column(state, i));
      csv << "\n";
    }
    files.push_back({"trajectory.csv", csv.str()});
  }
  nlohmann::json summary{{"t_end", end_time},
                         {"steps", simulation.steps()},
                         {"energy", energy},
                         {length_display_exponent() != 0 ? "chord_deviation_1e" + std::to_string(length_display_exponent()) + "mm"
                                                         : std::string("chord_deviation_mm"),
                          simulation.chord_deviation()}};
  add_stop(summary, stop);
  add_event_files(files, model, events, tu, fu, std::move(summary));
  if (!options.no_pictures) {
    std::vector<double> event_times;
    for (const SimulationEvent& e : events) event_times.push_back(e.time);
    std::string part_names;
    for (std::size_t p : parts) part_names += (part_names.empty() ? "" : ", ") + model.parts[p].name;
    for (int which = 0; which < 2; ++which) {
      render::TimePlot plot;
      plot.title = model.name + (which == 0 ? ": position of " : ": velocity of ") + part_names;
      plot.x_label = "t (" + tu + ")";
      plot.y_label = which == 0 ? length_unit_name() + " or rad" : length_unit_name() + " or rad per " + tu;
      plot.event_times = event_times;
      for (const Sample& s : samples) plot.times.push_back(s.time);
      for (std::size_t k = 0; k < parts.size(); ++k)
        for (int i = 3 * which; i < 3 * which + 3; ++i) {
          render::TimeSeries series;
          series.label = model.parts[parts[k]].name + " " + names[i];
          series.unit = (i % 3 == 2 ? std::string("rad") : length_unit_name()) + (which == 0 ? "" : " per " + tu);
          for (const Sample& s : samples) series.values.push_back(column(s.states[k], i));
          plot.series.push_back(series);
        }
      files.push_back({which == 0 ? "positions.svg" : "velocities.svg", render::time_plot_svg(plot)});
    }
    render::MechanismAnimationOptions animation;
    animation.duration = playback;
    animation.time_unit = tu;
    animation.drawing.title = model.name + ": simulated";
    if (length_display_exponent() != 0) animation.drawing.title += " (lengths in units of " + length_unit_name() + ")";
    for (const SimulationEvent& e : events)
      if (e.kind == SimulationEvent::Kind::impact)
        animation.marks.push_back({e.time, e.point[0], e.point[1], event_line(e, tu, fu)});
    // (session 70) a run stopped before its second frame has nothing to animate: no animation.svg
    if (frames.size() >= 2 || !stop)
      files.push_back({"animation.svg", render::mechanism_animation_svg(model, frames, animation)});
  }
  publish_run(files, options);
  return stopped_run(stop, options, tu);
}

// A model with a pin-in-slot part (docs/simulation.md, "Pin-in-slot parts"): PinSlotSimulation.
// Outputs: trajectory.csv (s, psi and their rates, the drivers' angles; a torque-driven part's
// angle rate and a translating part's offset and its rate), events.json/.txt, positions.svg and
// velocities.svg.
int run_pin_slot(const Model& model, const SimulateOptions& options) {
  SimulationOptions sim_options = stepping_options(options);
  if (options.region == "operating") throw ModelError("", "--region: a pin-slot part's C-space has no operating region");
  // Each step's chord turns the pair's relative angle by at most π/4 (docs/simulation.md,
  // "Pin-in-slot parts"): a driver at 10^300 rad/s made steps of 10^-300 s, each with its exact
  // chord tests, and the run went on for hours towards its budget. Refused at once, naming it.
  if (model.simulation)
    for (const SimulationSpec::Driver& driver : model.simulation->drivers) {
      if (!driver.profile.empty()) continue;   // (refused by the simulator)
      const double speed = std::abs(driver.speed.get_d()), steps = options.t_end * speed / (std::numbers::pi / 4);
      if (!(steps > static_cast<double>(options.max_steps))) continue;
      const std::string& tu = model.simulation->time_unit;
      throw ModelError(driver.pointer, "driver '" + model.parts[driver.part].name + "' turns at " + number(speed) +
                                           " rad/" + tu + ": a pin-slot run's chords turn the pair by at most π/4, so --t-end " +
                                           number(options.t_end) + " " + tu + " needs at least about " +
                                           (std::isfinite(steps) ? number(steps) : std::string("1e308")) +
                                           " steps, beyond the step budget (--max-steps " +
                                           std::to_string(options.max_steps) + "); nothing was run: give a --t-end of at most " +
                                           number(static_cast<double>(options.max_steps) * std::numbers::pi / 4 / speed) +
                                           " " + tu + ", a larger --max-steps or a slower driver");
    }
  PinSlotSimulation simulation = PinSlotSimulation::create(model, sim_options);
  const std::string& tu = simulation.time_unit();
  const std::string& fu = simulation.force_unit();
  std::vector<PinSlotState> samples{simulation.state()};
  double sample_energy = simulation.energy();   // the last sample's (a stop after it: session 70)
  double cpu_start = thread_cpu_seconds();
  ProgressLine line(options);
  auto progress = [&](double t) {
    samples.push_back(simulation.state());
    sample_energy = simulation.energy();
    line.show(t, options, tu, simulation.steps(), simulation.events().size());
  };
  std::optional<RunStop> stop =
      run_to_end_or_stop(simulation, options, tu, [&] { simulation.run_until(options.t_end, progress); });
  if (stop && stop->at_state && simulation.state().time > samples.back().time)
    samples.push_back(simulation.state());   // the stop's state
  kept_stop_state(stop, samples.back().time);
  std::vector<SimulationEvent> kept;
  const std::vector<SimulationEvent>& events = kept_events(simulation.events(), stop, kept);
  const bool at_sample = stop && !stop->at_state;   // a stop after the last completed step: its sample is the end
  const double energy = at_sample ? sample_energy : simulation.energy();
  double seconds = thread_cpu_seconds() - cpu_start;
  if (line.terminal) std::cerr << "\r" << std::string(90, ' ') << "\r" << std::flush;
  const PinSlotState& end = at_sample ? samples.back() : simulation.state();
  const std::string& name = model.parts[simulation.part()].name;
  std::cout << "simulated " << shown_name(model.name) << " to t = " << number(end.time) << " " << tu << " in "
            << simulation.steps() << " steps, " << events.size() << " events, " << number(seconds)
            << " s CPU\n";
  print_stop(stop, tu);
  std::cout << "  " << name << ": slide " << shown(end.slide, 1) << " mm, angle " << number(end.angle)
            << " rad; rates " << shown(end.slide_rate, 1) << " mm/" << tu << ", " << number(end.angle_rate) << " rad/"
            << tu << "\n";
  std::cout << "  energy " << energy_text(energy, fu) << "\n";
  std::cout << "  collision tests: " << simulation.chord_tests() << " exact chord tests (chord deviation "
            << shown(simulation.chord_deviation(), 1) << " mm)\n";
  print_events(events, tu, fu);
  if (options.out.empty()) return stopped_run(stop, options, tu);
  // moving: every moving part beside the pin-slot part (its coordinate); dynamic: those moved by
  // their dynamics, not prescribed (a torque-driven cam, a pushed translating part: their rates too)
  std::vector<std::size_t> moving, dynamic;
  auto translates = [&](std::size_t p) { return model.parts[p].motion.kind == Motion::Kind::translation; };
  auto coordinate = [&](std::size_t p) { return std::string(translates(p) ? "_offset" : "_angle"); };
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (p != simulation.part() && model.parts[p].motion.kind != Motion::Kind::fixed) {
      moving.push_back(p);
      const bool prescribed = model.simulation && std::any_of(model.simulation->drivers.begin(), model.simulation->drivers.end(),
                                                              [&](const SimulationSpec::Driver& d) { return d.part == p; });
      if (!prescribed) dynamic.push_back(p);
    }
  std::vector<io::RunFile> files;
  const char* names[4] = {"slide", "angle", "slide_rate", "angle_rate"};
  auto column = [](const PinSlotState& s, int i) {
    const double values[4] = {s.slide, s.angle, s.slide_rate, s.angle_rate};
    return values[i];
  };
  {
    std::ostringstream csv;
    csv << "time_" << tu;
    for (int i = 0; i < 4; ++i) csv << "," << name << "_" << names[i];
    for (std::size_t p : moving) csv << "," << model.parts[p].name << coordinate(p);
    for (std::size_t p : dynamic) csv << "," << model.parts[p].name << coordinate(p) << "_rate";
    csv << "\n";
    for (const PinSlotState& s : samples) {
      csv << number(s.time);
      for (int i = 0; i < 4; ++i) csv << "," << number(column(s, i));
      for (std::size_t p : moving) csv << "," << number(s.position[p]);
      for (std::size_t p : dynamic) csv << "," << number(s.rate[p]);
      csv << "\n";
    }
    files.push_back({"trajectory.csv", csv.str()});
  }
  nlohmann::json summary{{"t_end", end.time},
                         {"steps", simulation.steps()},
                         {"energy", energy},
                         {"chord_deviation_mm", simulation.chord_deviation()}};
  add_stop(summary, stop);
  add_event_files(files, model, events, tu, fu, std::move(summary));
  if (!options.no_pictures) {
    std::vector<double> event_times;
    for (const SimulationEvent& e : events) event_times.push_back(e.time);
    std::string plotted = name;   // the pin-slot part and the parts plotted beside it (session 60)
    for (std::size_t p : dynamic) plotted += ", " + model.parts[p].name;
    for (int which = 0; which < 2; ++which) {
      render::TimePlot plot;
      plot.title = model.name + (which == 0 ? ": position of " : ": velocity of ") + plotted;
      plot.x_label = "t (" + tu + ")";
      plot.y_label = which == 0 ? "mm or rad" : "mm or rad per " + tu;
      plot.event_times = event_times;
      for (const PinSlotState& s : samples) plot.times.push_back(s.time);
      for (int i = 2 * which; i < 2 * which + 2; ++i) {
        render::TimeSeries series;
        series.label = name + " " + names[i];
        series.unit = std::string(i % 2 == 0 ? "mm" : "rad") + (which == 0 ? "" : " per " + tu);
        for (const PinSlotState& s : samples) series.values.push_back(column(s, i));
        plot.series.push_back(series);
      }
      for (std::size_t p : dynamic) {   // its angle or offset and rate
        render::TimeSeries series;
        series.label = model.parts[p].name + " " + coordinate(p).substr(1) + (which == 0 ? "" : "_rate");
        series.unit = std::string(translates(p) ? "mm" : "rad") + (which == 0 ? "" : " per " + tu);
        for (const PinSlotState& s : samples) series.values.push_back(which == 0 ? s.position[p] : s.rate[p]);
        plot.series.push_back(series);
      }
      files.push_back({which == 0 ? "positions.svg" : "velocities.svg", render::time_plot_svg(plot)});
    }
  }
  publish_run(files, options);
  return stopped_run(stop, options, tu);
}

// --t-end and --max-step, before anything is read or built: T positive and finite, H (when
// given; CLI11 has checked it is a positive finite number) no smaller than T over the
// simulator's step budget (SimulationOptions::max_steps, 2 000 000): a run that needs more
// steps than that stops with "more than max_steps steps" after all of them (until session 32
// `--max-step 1e-300` ran for hours with no progress off a terminal).
void check_times(const SimulateOptions& options) {
  if (!(options.t_end > 0) || !std::isfinite(options.t_end))
    throw ModelError("", "--t-end must be a positive finite number of time units");
  // a subnormal T (below 2.2e-308) keeps a few digits only: the run's times and states were off
  // in their 4th digit (--t-end 1e-320: v = -g t printed as -9.805e-317 for -9.81e-317; session 52)
  if (options.t_end < std::numeric_limits<double>::min())
    throw ModelError("", "--t-end " + number(options.t_end) +
                             ": below the least normal double 2.2250738585072014e-308 the simulator's times lose "
                             "their digits; give a larger --t-end (or smaller units)");
  const std::size_t budget = options.max_steps;
  if (options.max_step > 0 && options.t_end / options.max_step > static_cast<double>(budget))
    throw ModelError("", "--max-step " + number(options.max_step) + ": T / H = " + number(options.t_end / options.max_step) +
                             " steps exceed the simulator's budget of " + std::to_string(budget) +
                             " steps (--max-steps): give H >= " + number(options.t_end / static_cast<double>(budget)));
}

// The model `hipair simulate` runs and the exponent E of the length unit 10^E mm it runs in.
// A mechanism without a pin-slot part (parts fixed, rotating, translating, free in the plane), drawn at an extreme
// scale (kinematic_decimal_exponent: lengths outside about 1e-9 .. 1e9 mm with a translating
// part, 1e-9 .. 1e18 mm rotating only), runs on its copy rescaled exactly by 10^-E with its
// dynamics data (decimal_scaled_dynamics_model: mass and time unchanged, forces with the
// lengths, inertias and torques with their squares): a model scaled by 10^E from an ordinary one
// runs as that one, to the last bit, and its outputs show lengths, speeds, forces, impulses and
// energies in mm and N times the powers of 10^E (shown()). Until session 53 (scale53b) such a
// model was refused (its inertias, 1e800 kg mm^2, do not fit a double). E = 0 otherwise, and the
// model is read as before (read_model_file_for_simulation: out-of-range dynamics data refused at
// its pointer). Pin-slot parts are not rescaled (their data beyond the doubles is refused); a
// --sweep's runs are, each like this (session 54).
Model simulated_model(const SimulateOptions& options, const ReadOptions& overrides, long& exponent) {
  exponent = 0;
  auto rescaled_exponent = [](const Model& model) -> long {
    for (const Part& part : model.parts)
      if (part.motion.kind == Motion::Kind::pin_slot) return 0;
    return kinematic_decimal_exponent(model);
  };
  std::optional<Model> read;
  try {
    read = read_model_file_for_simulation(options.model, overrides);
  } catch (const ModelError&) {
    // dynamics data beyond the doubles (a 1e400 mm model's inertias): simulated in 10^E mm when it rescales
    Model exact = read_model_file(options.model, overrides);
    const long e = rescaled_exponent(exact);
    if (e == 0) throw;
    require_feature_spread(exact);   // before work (session 53)
    Model scaled = decimal_scaled_dynamics_model(exact, e);
    require_dynamics_in_double_range(scaled, "1e" + std::to_string(e) + " mm");
    require_internal_units_in_double_range(scaled);
    exponent = e;
    return scaled;
  }
  require_feature_spread(*read);   // a 1e-999 mm feature on a 40 mm part: refused before work (session 53)
  const long e = rescaled_exponent(*read);
  if (e == 0) return std::move(*read);
  Model scaled = decimal_scaled_dynamics_model(*read, e);
  require_dynamics_in_double_range(scaled, "1e" + std::to_string(e) + " mm");
  require_internal_units_in_double_range(scaled);
  exponent = e;
  return scaled;
}

int run(const SimulateOptions& options) {
  auto rounding = rounding_scope(options.rounding);
  check_times(options);
  io::refuse_unusable_output_directory(options.out, "--out");   // before any run (hours, for a long one)
  // refused before the run when a file every run writes is the model, as analyze and tolerance do
  // (session 75, hostile75 L1: the whole run or sweep was made and printed, then refused); the
  // whole list of the run's files is checked again before anything is written
  if (!options.out.empty()) {
    const std::vector<std::string> always = options.sweep.empty()
                                                ? std::vector<std::string>{"trajectory.csv", "events.json", "events.txt"}
                                                : std::vector<std::string>{"sweep.json"};
    for (const std::string& name : always)
      io::refuse_overwriting_input(std::filesystem::path(options.out) / name, "--out", options.model);
  }
  // options that do not apply (session 63, hunt63; until then taken and ignored, against the
  // rule of session 45): --jobs without a sweep, the animation's playback where no animation.svg
  // is written (a sweep writes sweep.json only)
  if (options.jobs > 0 && options.sweep.empty())
    throw ModelError("", "--jobs sets the parallel runs of a --sweep: give --sweep, or leave --jobs out");
  if (options.fps_given || options.animation_duration > 0) {
    const char* why = !options.sweep.empty() ? "a --sweep writes no animation (sweep.json only)"
                      : options.out.empty()  ? "without --out no animation.svg is written"
                      : options.no_pictures  ? "--no-pictures writes no animation.svg"
                                             : nullptr;
    if (why)
      throw ModelError("", std::string(options.fps_given ? "--fps" : "--animation-duration") +
                               " sets animation.svg's playback, but " + why);
  }
  if (!options.sweep.empty()) return run_sweep(options);
  if (!options.works_period.empty() || !options.works_advance.empty() || options.works_max_decay >= 0)
    throw ModelError("", "--works-period, --works-advance and --works-max-decay judge a --sweep's runs: give --sweep");
  ReadOptions overrides = parameter_overrides(options.overrides, options.allow_out_of_tolerance);
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  long length_exponent = 0;
  Model model = simulated_model(options, overrides, length_exponent);   // in units of 10^E mm: see there
  LengthDisplayScope length_display(length_exponent);   // shown(), scaled_unit(), length_unit_name()
  check_simulator_range(model);   // before anything converts the model to doubles (also in create())
  check_own_frequency(model, options);
  // parts free in the plane: one (PlanarSimulation) or several (PlanarSystemSimulation)
  std::size_t planar_count = 0;
  for (const Part& part : model.parts) planar_count += part.motion.kind == Motion::Kind::planar;
  if (planar_count == 1) return run_planar<PlanarSimulation>(model, options);
  if (planar_count > 1) return run_planar<PlanarSystemSimulation>(model, options);
  for (const Part& part : model.parts)
    if (part.motion.kind == Motion::Kind::pin_slot) return run_pin_slot(model, options);
  bool terminal = isatty(2) && !options.quiet;
  SimulationOptions sim_options = stepping_options(options);
  set_region(sim_options, options);
  // the builds' own progress line (per chart or tile of each pair: a gear pair's operating
  // region takes seconds, a whole torus minutes), wiped when each build is done
  if (terminal) std::cerr << "simulate: building the pairs' C-spaces..." << std::flush;
  if (terminal) sim_options.build_progress = stderr_progress();
  Simulation simulation = Simulation::create(model, sim_options);
  if (terminal) std::cerr << "\r" << std::string(50, ' ') << "\r" << std::flush;

  std::vector<std::size_t> moving;
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (model.parts[p].motion.kind != Motion::Kind::fixed) moving.push_back(p);
  std::vector<SimulationState> samples{simulation.state()};
  double sample_energy = simulation.energy();   // the last sample's (a stop after it: session 70)
  double cpu_start = thread_cpu_seconds();
  ProgressLine line(options);
  auto progress = [&](double t) {
    samples.push_back(simulation.state());
    sample_energy = simulation.energy();
    line.show(t, options, simulation.time_unit(), simulation.steps(), simulation.events().size());
  };
  // The animation's frames are states at a fixed rate: the run stops exactly at each frame time
  // (run_until ends its last step there), so every frame is a state of the simulation itself,
  // not an interpolation. Without pictures the run goes straight to t-end.
  std::vector<render::MechanismFrame> frames;
  double playback = 0;
  std::vector<double> times = frame_times(options, simulation.time_unit(), playback);
  std::optional<RunStop> stop;
  {
    auto record_frame = [&] {
      render::MechanismFrame frame;
      frame.time = simulation.state().time;
      for (std::size_t p = 0; p < model.parts.size(); ++p) {
        PartConfiguration c = model.parts[p].initial;
        if (model.parts[p].motion.kind == Motion::Kind::rotation) c.angle = Rational(simulation.state().position[p]);
        if (model.parts[p].motion.kind == Motion::Kind::translation)
          c.offset = Rational(simulation.state().position[p]);
        frame.configurations.push_back(c);
      }
      frames.push_back(std::move(frame));
    };
    if (!times.empty()) record_frame();
    stop = run_to_end_or_stop(simulation, options, simulation.time_unit(), [&] {
      for (double t : times) {
        simulation.run_until(t, progress);
        record_frame();
      }
      simulation.run_until(options.t_end, progress);
    });
    if (stop && stop->at_state && simulation.state().time > samples.back().time) {   // the stop's state, the last one
      samples.push_back(simulation.state());
      if (!times.empty()) record_frame();
    }
  }
  kept_stop_state(stop, samples.back().time);
  std::vector<SimulationEvent> kept;
  const std::vector<SimulationEvent>& events = kept_events(simulation.events(), stop, kept);
  const bool at_sample = stop && !stop->at_state;   // a stop after the last completed step: its sample is the end
  const SimulationState& end = at_sample ? samples.back() : simulation.state();
  const double energy = at_sample ? sample_energy : simulation.energy();
  double seconds = thread_cpu_seconds() - cpu_start;
  if (terminal) std::cerr << "\r" << std::string(90, ' ') << "\r" << std::flush;

  const std::string& tu = simulation.time_unit();
  const std::string& fu = simulation.force_unit();
  std::cout << "simulated " << shown_name(model.name) << " to t = " << number(end.time) << " " << tu << " in "
            << simulation.steps() << " steps, " << events.size() << " events, " << number(seconds)
            << " s CPU\n";
  print_stop(stop, tu);
  for (std::size_t p : moving)
    std::cout << "  " << model.parts[p].name << ": position "
              << shown(end.position[p], model.parts[p].motion.kind == Motion::Kind::rotation ? 0 : 1)
              << (model.parts[p].motion.kind == Motion::Kind::rotation ? " rad" : " mm") << ", velocity "
              << shown(end.velocity[p], model.parts[p].motion.kind == Motion::Kind::rotation ? 0 : 1)
              << " per " << tu << "\n";
  // kinetic + potential, the potential of a constant torque T (or force F) being -T theta
  // (-F x): the total is negative once a driving torque has given less kinetic energy than the
  // work it did (spur-gears.json: -132.6 N·mm at 0.3 s, kinetic 240.0, the torque's -372.6)
  std::cout << "  energy " << energy_text(energy, fu)
            << " (kinetic + potential; a constant torque's potential is -T·angle)\n";
  print_events(events, tu, fu);
  if (options.out.empty()) return stopped_run(stop, options, tu);

  std::vector<io::RunFile> files;
  {
    std::ostringstream csv;
    csv << "time_" << tu;
    for (std::size_t p : moving) {
      // in units of 10^E mm (E != 0): a translating part's columns name it ("_1e400mm", "_1e400mm_per_s")
      const std::string unit = length_exponent != 0 && model.parts[p].motion.kind != Motion::Kind::rotation
                                   ? "_1e" + std::to_string(length_exponent) + "mm"
                                   : std::string();
      csv << "," << model.parts[p].name << "_position" << unit << "," << model.parts[p].name << "_velocity"
          << (unit.empty() ? unit : unit + "_per_" + tu);
    }
    csv << "\n";
    for (const SimulationState& s : samples) {
      csv << number(s.time);
      for (std::size_t p : moving) csv << "," << number(s.position[p]) << "," << number(s.velocity[p]);
      csv << "\n";
    }
    files.push_back({"trajectory.csv", csv.str()});
  }
  nlohmann::json summary{{"t_end", end.time}, {"steps", simulation.steps()}, {"energy", energy}};
  add_stop(summary, stop);
  add_event_files(files, model, events, tu, fu, std::move(summary));
  if (!options.no_pictures) {
    std::vector<double> event_times;
    for (const SimulationEvent& e : events) event_times.push_back(e.time);
    for (int which = 0; which < 2; ++which) {
      render::TimePlot plot;
      plot.title = model.name + (which == 0 ? ": positions" : ": velocities");
      plot.x_label = "t (" + tu + ")";
      plot.y_label = which == 0 ? "rad or " + length_unit_name() : "rad or " + length_unit_name() + " per " + tu;
      plot.event_times = event_times;
      for (const SimulationState& s : samples) plot.times.push_back(s.time);
      for (std::size_t p : moving) {
        render::TimeSeries series;
        series.label = model.parts[p].name;
        series.unit = (model.parts[p].motion.kind == Motion::Kind::translation ? length_unit_name() : std::string("rad")) +
                      (which == 0 ? "" : " per " + tu);
        for (const SimulationState& s : samples) series.values.push_back(which == 0 ? s.position[p] : s.velocity[p]);
        plot.series.push_back(series);
      }
      files.push_back({which == 0 ? "positions.svg" : "velocities.svg", render::time_plot_svg(plot)});
    }
    for (const auto& space : simulation.spaces()) {
      if (!space || space->dimension() != 2) continue;
      std::size_t x = *model.find_part(space->x_part()), y = *model.find_part(space->y_part());
      render::CSpaceSvgOptions picture;
      // in contact where an event's sustained contact holds: approximated by the samples'
      // neighbourhood of contact events of this pair
      for (const SimulationState& s : samples) picture.path.push_back({s.position[x], s.position[y], false});
      for (const SimulationEvent& e : events) {
        if (e.kind != SimulationEvent::Kind::impact) continue;
        if (!((e.first_part == space->first_part() && e.second_part == space->second_part()) ||
              (e.first_part == space->second_part() && e.second_part == space->first_part())))
          continue;
        // mark the sample nearest the impact as a contact
        for (std::size_t i = 0; i < samples.size(); ++i)
          if (samples[i].time >= e.time) {
            picture.path[i].contact = true;
            break;
          }
      }
      if (!samples.empty()) picture.marks.push_back({samples.front().position[x], samples.front().position[y], "start"});
      picture.title = model.name + ": simulated path over the C-space of " + space->x_part() + " / " + space->y_part();
      if (length_exponent != 0) picture.title += " (lengths in units of " + length_unit_name() + ")";
      files.push_back({"cspace-" + file_name_part(space->x_part()) + "-" + file_name_part(space->y_part()) + ".svg",
                       render::cspace_svg(*space, picture)});
    }
    render::MechanismAnimationOptions animation;
    animation.duration = playback;
    animation.time_unit = tu;
    animation.drawing.title = model.name + ": simulated";
    if (length_exponent != 0) animation.drawing.title += " (lengths in units of " + length_unit_name() + ")";
    for (const SimulationEvent& e : events) {
      bool located = e.point[0] != 0 || e.point[1] != 0 || e.normal[0] != 0 || e.normal[1] != 0;
      if (e.kind != SimulationEvent::Kind::impact || !located) continue;
      animation.marks.push_back({e.time, e.point[0], e.point[1], event_line(e, tu, fu)});
    }
    // (session 70) a run stopped before its second frame has nothing to animate: no animation.svg
    if (frames.size() >= 2 || !stop)
      files.push_back({"animation.svg", render::mechanism_animation_svg(model, frames, animation)});
  }
  publish_run(files, options);
  return stopped_run(stop, options, tu);
}

}  // namespace

void register_simulate(CLI::App& app, Action& action) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command =
      app.add_subcommand("simulate", "Simulate the mechanism's dynamics with certified contact detection");
  command->add_option("model", options->model, "Model file (JSON)")->required()->check(CLI::ExistingFile);
  command->add_option("--t-end", options->t_end, "End time, in the model's time unit")->required();
  command->add_option("--accuracy", options->accuracy,
                      "Relative and absolute error tolerance per step (default: the model's, or 1e-9)")
      ->check(real_range(1e-15, 0.1));
  command->add_option("--max-step", options->max_step,
                      "Largest integration step (time unit; default: none): a positive finite number, at least "
                      "T / the step budget (--max-steps, 2000000)")
      ->check(positive_finite());
  command->add_option("--max-steps", options->max_steps,
                      "Step budget: a run that needs more steps stops with an error naming the time it reached, "
                      "and writes nothing (default 2000000; 1 to 1e9)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000000}));
  command->add_option("--out", options->out,
                      "Output directory: trajectory.csv, events.json/.txt, positions.svg, velocities.svg, animation.svg, cspace-*.svg")
      ->check(output_path());
  command->add_option("--region", options->region,
                      "auto: the operating region of a pair of more than 120 boundary edges (gears), the whole "
                      "C-space of the others (default); full: whole C-spaces; operating: operating regions around "
                      "the initial configuration")
      ->check(CLI::IsMember({"auto", "full", "operating"}));
  command->add_flag("--quiet", options->quiet, "No progress on the terminal");
  command->add_flag("--no-pictures", options->no_pictures, "Write the CSV and the event log only");
  CLI::Option* fps = command->add_option("--fps", options->fps, "Frames per second of animation.svg's playback (default 25)")
                         ->check(real_range(1.0, 240.0));
  command->add_option("--animation-duration", options->animation_duration,
                      "Playback time of animation.svg in seconds (default: the simulated time, at least 1 s)")
      ->check(real_range(0.01, 3600.0));
  command->add_option("--sweep", options->sweep,
                      "NAME=A:B:N: run N simulations with parameter NAME from A to B (exact literals, mm or rad), "
                      "in parallel; report per value the run's status (running, stopped: every part at rest over "
                      "the last quarter of the run, failed: with the error), each part's advance and velocity sign "
                      "changes (--out: sweep.json)");
  command->add_option("--works-period", options->works_period,
                      "PART[:TOL]: a sweep's verdict per value: works when PART has at least two oscillation periods in "
                      "the second half of the run, all within TOL (default 0.02) of their median; a failed or stopped "
                      "run fails");
  command->add_option("--works-advance", options->works_advance,
                      "PART=STEP[:TOL]: with --works-period, PART must also advance STEP (rad or mm, signed; or Ndeg) "
                      "per period, within TOL steps (default 0.5) over the second half's whole periods (repeatable)");
  command->add_option("--works-max-decay", options->works_max_decay,
                      "RATE: with --works-period, its part's swing amplitude must not decay faster than RATE "
                      "(a fraction per time unit) over the second half")
      ->check(real_range(0.0, 1e6));
  command->add_option("--jobs", options->jobs, "Parallel runs of a sweep (default: the number of cores)")
      ->check(CLI::Range(1, 256));
  add_parameter_options(command, options->overrides, options->allow_out_of_tolerance);
  add_rounding_option(command, options->rounding);
  command->callback([options, fps, &action] {
    options->fps_given = fps->count() > 0;
    action = [options] { return run(*options); };
  });
}

}  // namespace hipair::cli
