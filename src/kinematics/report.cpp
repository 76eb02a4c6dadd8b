// Reports of a kinematic analysis: plain text for mechanism designers, JSON, CSV.
#include <hipair/kinematics.hpp>

#include "core/length_display.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

namespace hipair {
namespace {

constexpr double degrees_per_radian = 180 / std::numbers::pi;

std::string format(double value, int decimals = 3) {
  if (!std::isfinite(value)) return value > 0 ? "inf" : value < 0 ? "-inf" : "nan";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string out = text;
  if (out[0] == '-' && out.find_first_not_of("0.", 1) == std::string::npos) out.erase(0, 1);   // no "-0.000"
  return out;
}

// A driver or follower coordinate for people: degrees or mm (a length in units of 10^E mm
// written with its exponent, core/length_display.hpp).
std::string quantity(double value, bool rotation, int decimals = 3) {
  return rotation ? format(value * degrees_per_radian, decimals) + "°" : length_in_mm(format(value, decimals)) + " mm";
}

// The unit word of the CSV header's length columns: "mm", or "1e400mm" in units of 10^400 mm.
std::string csv_length_unit() {
  std::string unit = length_unit_name();
  unit.erase(std::remove(unit.begin(), unit.end(), ' '), unit.end());
  return unit;
}

double display(double value, bool rotation) { return rotation ? value * degrees_per_radian : value; }

// A certified driver range (rad or mm) for report.json's "certified", still certified in degrees:
// 180 / pi lies between the doubles next to degrees_per_radian (its rounding), and each product,
// rounded to nearest (within half an ulp), is moved one double outwards (0 stays 0: exact). Until
// session 50 the ends were rounded to nearest: an end could lie an ulp inside the exact range.
std::pair<double, double> certified_display(const CertifiedRange& range, bool rotation) {
  if (!rotation) return {range.lower, range.upper};
  constexpr double infinite = std::numeric_limits<double>::infinity();
  const double low_factor = std::nextafter(degrees_per_radian, 0.0), high_factor = std::nextafter(degrees_per_radian, infinite);
  auto outwards = [&](double end, double towards) {
    if (end == 0) return 0.0;
    double product = towards < 0 ? std::min(end * low_factor, end * high_factor) : std::max(end * low_factor, end * high_factor);
    return std::nextafter(product, towards);
  };
  return {outwards(range.lower, -infinite), outwards(range.upper, infinite)};
}

std::string join(const std::vector<ContactLabel>& contacts) {
  std::string out;
  for (const ContactLabel& contact : contacts) {
    if (!out.empty()) out += "; ";
    out += contact.label;
  }
  return out;
}

std::string direction_word(const KinematicsResult& result) {
  if (result.driver_rotates) return result.direction > 0 ? "counter-clockwise" : "clockwise";
  return result.direction > 0 ? "in the + direction" : "in the - direction";
}

std::string load_text(const FollowerLoad& load) {
  switch (load.kind) {
    case FollowerLoad::Kind::none: return "moved only when pushed (no load)";
    case FollowerLoad::Kind::negative: return "held towards decreasing coordinate by " + load.source;
    case FollowerLoad::Kind::positive: return "held towards increasing coordinate by " + load.source;
    case FollowerLoad::Kind::spring: return "held by a " + load.source;
  }
  return "";
}

std::string event_kind(KinematicEvent::Kind kind) {
  switch (kind) {
    case KinematicEvent::Kind::contact_start: return "contact_start";
    case KinematicEvent::Kind::contact_end: return "contact_end";
    case KinematicEvent::Kind::contact_change: return "contact_change";
    case KinematicEvent::Kind::drop: return "drop";
    case KinematicEvent::Kind::jam: return "jam";
    case KinematicEvent::Kind::limit: return "limit";
    case KinematicEvent::Kind::end_of_range: return "end_of_range";
  }
  return "event";
}

std::size_t follower_index(const KinematicsResult& result, const std::string& part) {
  auto found = std::find(result.followers.begin(), result.followers.end(), part);
  return static_cast<std::size_t>(found - result.followers.begin());
}

}  // namespace

std::string kinematics_text_report(const KinematicsResult& result) {
  std::ostringstream out;
  bool rot = result.driver_rotates;
  out << "Kinematic analysis of \"" << result.model_name << "\"\n";
  out << "Driver: " << result.driver << ", moved " << direction_word(result) << " from " << quantity(result.start, rot)
      << " to " << quantity(result.end, rot);
  if (rot) out << " (" << format(std::abs(result.end - result.start) / (2 * std::numbers::pi), 3) << " turn)";
  out << ".\n";
  for (std::size_t f = 0; f < result.followers.size(); ++f)
    out << "Driven part: " << result.followers[f] << " (" << (result.follower_rotates[f] ? "rotates" : "translates")
        << "), " << load_text(result.loads[f]) << ".\n";
  for (const std::string& name : result.unconnected) out << "Not connected to the driver (stays put): " << name << ".\n";
  for (const std::string& warning : result.warnings) out << "Note: " << warning << "\n";
  out << "\n";

  if (result.initial_interference.empty()) out << "Initial configuration: no parts overlap.\n";
  // A jam that names no contact and leaves no follower piece: no position of the driven part is
  // free at the start (every one overlaps), so there is no touching position to start from
  // (until session 47 the report said it started from one, then stopped with an empty list).
  const bool no_free_start = result.jam && result.jam->before.empty() && result.pieces.empty();
  for (const Interference& interference : result.initial_interference)
    out << "INTERFERENCE at the initial configuration: " << interference.pair << ": " << interference.description
        << (no_free_start ? ". No position where they only touch exists at the initial driver position: the analysis "
                            "stops there.\n"
                          : ". The analysis starts from the nearest position where they only touch.\n");

  for (std::size_t f = 0; f < result.followers.size(); ++f) {
    const std::string& name = result.followers[f];
    bool frot = result.follower_rotates[f];
    out << "\nMotion of " << name << " (driver " << (rot ? "angle" : "offset") << " -> " << name << " "
        << (frot ? "angle" : "offset") << "):\n";
    int drives = 0, dwells = 0;
    double drive_travel = 0;
    bool last_moving = false, first = true;
    const KinematicPiece* previous = nullptr;
    for (const KinematicPiece& piece : result.pieces) {
      if (piece.part != name) continue;
      if (previous && std::abs(piece.start_position - previous->end_position) > 1e-9)
        out << "  snap   at " << quantity(piece.start.value(), rot) << ": " << name << " jumps "
            << quantity(previous->end_position, frot) << " -> " << quantity(piece.start_position, frot)
            << " through free space (released by " << join(previous->contacts) << ")\n";
      previous = &piece;
      std::string range = quantity(piece.start.value(), rot) + " .. " + quantity(piece.end.value(), rot);
      if (piece.moving) {
        out << "  drive  " << range << ": " << name << " moves " << quantity(piece.start_position, frot) << " -> "
            << quantity(piece.end_position, frot) << " (" << (piece.end_position >= piece.start_position ? "+" : "")
            << quantity(piece.end_position - piece.start_position, frot) << ")";
        // a piece that goes out and comes back (a cam's rise and return) shows its full sweep
        if (piece.highest_position - piece.lowest_position >
            std::abs(piece.end_position - piece.start_position) + 1e-9)
          out << ", sweeping " << quantity(piece.lowest_position, frot) << " .. " << quantity(piece.highest_position, frot);
        out << (piece.mode == KinematicPiece::Mode::touching ? ", guided with zero clearance by "
                : result.loads[f].kind == FollowerLoad::Kind::none ? ", pushed by "
                                                                    : ", held by its load against ")
            << join(piece.contacts);
        if (piece.unresolved_length)
          out << " (shorter than the events' resolution: its ends are located to overlapping driver intervals; its "
                 "length is positive, decided exactly)";
        out << "\n";
        if (first || !last_moving) ++drives;
        drive_travel += std::abs(piece.end.value() - piece.start.value());
      } else {
        out << "  dwell  " << range << ": " << name << " stays at " << quantity(piece.start_position, frot);
        if (piece.contacts.empty()) out << " (free: no contact holds it)";
        else out << " (held by " << join(piece.contacts) << ")";
        out << "\n";
        if (first || last_moving) ++dwells;
      }
      last_moving = piece.moving;
      first = false;
    }
    out << "  In all: " << drives << " drive period" << (drives == 1 ? "" : "s") << " (" << quantity(drive_travel, rot)
        << " of driver travel) and " << dwells << " dwell period" << (dwells == 1 ? "" : "s") << ".\n";
    // velocity ratio extremes
    double largest = 0, at = 0;
    for (const KinematicSample& sample : result.samples) {
      double ratio = sample.velocity_ratios[f];
      if (std::isfinite(ratio) && std::abs(ratio) > std::abs(largest)) {
        largest = ratio;
        at = sample.driver;
      }
    }
    if (largest != 0) {
      std::string unit = frot == rot ? "" : frot ? " rad/mm" : " mm/rad";
      std::string ratio = frot == rot ? format(largest, 4) : frot ? per_length_in_mm(format(largest, 4)) : length_in_mm(format(largest, 4));
      out << "  Largest velocity ratio (" << name << " speed / driver speed): " << ratio << unit << " at driver "
          << quantity(at, rot) << ".\n";
    }
    bool play_measured = false;
    for (const PlaySummary& play : result.play) play_measured = play_measured || play.part == name;
    if (!play_measured)
      out << "  Play: not measured: the analysis has no position of " << name << " on the path.\n";
    for (const PlaySummary& play : result.play)
      if (play.part == name) {
        if (std::isnan(play.minimum))
          out << "  Play: " << name << " is never held on both sides.\n";
        else if (!play.unbounded && play.maximum - play.minimum < 1e-9)
          out << "  Play (backlash, the free motion " << name << " has with the driver held): " << quantity(play.minimum, frot)
              << " all along.\n";
        else
          out << "  Play (backlash, the free motion " << name << " has with the driver held): from " << quantity(play.minimum, frot)
              << " (at driver " << quantity(play.at_minimum, rot) << ") to " << quantity(play.maximum, frot) << " (at driver "
              << quantity(play.at_maximum, rot) << ")" << (play.unbounded ? "; somewhere it is held on one side only" : "")
              << ".\n";
      }
    for (const ReversalCheck& check : result.reversals)
      if (check.part == name) {
        if (check.follower_moved)
          out << "  If the driver reverses at " << quantity(check.driver, rot) << ", it travels back " << quantity(check.lost_motion, rot)
              << " before " << name << " moves (lost motion).\n";
        else
          out << "  If the driver reverses at " << quantity(check.driver, rot) << ", " << name << " does not move within "
              << quantity(check.lost_motion, rot) << " of reverse travel.\n";
      }
  }

  out << "\nContacts engaged:\n";
  if (result.contacts.empty()) out << "  none\n";
  for (const ContactUse& use : result.contacts) {
    out << "  " << use.contact.label;
    if (!use.contact.limit) out << " (" << to_string(use.contact.kind) << ")";
    out << ", driver ";
    for (std::size_t i = 0; i < use.intervals.size(); ++i)
      out << (i ? ", " : "") << quantity(use.intervals[i].first, rot) << " .. " << quantity(use.intervals[i].second, rot);
    out << "\n";
  }
  std::vector<const ContactUse*> unintended;
  for (const ContactUse& use : result.contacts)
    if (use.unintended) unintended.push_back(&use);
  out << "\nUnintended contacts: " << (unintended.empty() ? "none" : "") << "\n";
  // repeated teeth repeat the same finding: show the first few, count the rest
  const std::size_t shown = 6;
  for (std::size_t u = 0; u < unintended.size() && u < shown; ++u)
    out << "  " << unintended[u]->contact.label << ": " << unintended[u]->reason << "\n";
  if (unintended.size() > shown)
    out << "  ... and " << unintended.size() - shown << " more (report.json lists them all; --expect LABEL marks intended ones)\n";

  out << "\nBlocking: ";
  if (result.jam) {
    out << "the driver is BLOCKED at " << quantity(result.jam->at.value(), rot) << " (" << result.jam->description << ").\n";
    if (result.jam->before.empty())
      out << "  Blocking contacts: none bounds it: no position of " << result.jam->part
          << " is free at this driver position (every position overlaps)\n";
    else
      out << "  Blocking contacts: " << join(result.jam->before) << "\n";
  } else {
    out << "none: the driver completes its range.\n";
  }
  const std::string resolution = format(certified_display(CertifiedRange{0, result.event_resolution}, rot).second, 12);
  out << "\nContact changes are located to within " << (rot ? resolution + "°" : length_in_mm(resolution) + " mm") << " of driver travel (certified); positions are exact at those driver positions.\n";
  return out.str();
}

std::string kinematics_json_report(const KinematicsResult& result) {
  using nlohmann::json;
  bool rot = result.driver_rotates;
  auto location = [&](const DriverLocation& at) {
    return json{{"value", display(at.value(), rot)},
                {"certified", certified_display(at.coordinate, rot)},
                {"chart", at.chart},
                {"chart_interval", {to_exact_string(at.chart_lower), to_exact_string(at.chart_upper)}}};
  };
  auto contacts = [](const std::vector<ContactLabel>& list) {
    json out = json::array();
    for (const ContactLabel& contact : list)
      out.push_back(json{{"pair", contact.pair},
                         {"label", contact.label},
                         {"kind", contact.limit ? "limit" : std::string(to_string(contact.kind))}});
    return out;
  };
  json report;
  report["model"] = result.model_name;
  report["units"] = {{"angle", "deg"}, {"length", length_unit_name()}};   // "1e400 mm": core/length_display.hpp
  report["driver"] = {{"part", result.driver},
                      {"motion", rot ? "rotation" : "translation"},
                      {"direction", direction_word(result)},
                      {"start", display(result.start, rot)},
                      {"end", display(result.end, rot)},
                      {"reached", display(result.reached, rot)}};
  json followers = json::array();
  for (std::size_t f = 0; f < result.followers.size(); ++f)
    followers.push_back(json{{"part", result.followers[f]},
                             {"motion", result.follower_rotates[f] ? "rotation" : "translation"},
                             {"load", load_text(result.loads[f])}});
  report["followers"] = followers;
  report["unconnected"] = result.unconnected;
  report["slice_methods"] = result.slice_methods;
  json interference = json::array();
  for (const Interference& i : result.initial_interference)
    interference.push_back(json{{"pair", i.pair}, {"description", i.description}});
  report["initial_interference"] = interference;
  json pieces = json::array();
  for (const KinematicPiece& piece : result.pieces) {
    std::size_t f = follower_index(result, piece.part);
    bool frot = f < result.follower_rotates.size() && result.follower_rotates[f];
    pieces.push_back(json{{"part", piece.part},
                          {"type", piece.moving ? "drive" : "dwell"},
                          {"mode", piece.mode == KinematicPiece::Mode::contact   ? "contact"
                                   : piece.mode == KinematicPiece::Mode::touching ? "touching"
                                                                                  : "free"},
                          {"side", piece.side},
                          {"start", location(piece.start)},
                          {"end", location(piece.end)},
                          {"start_position", display(piece.start_position, frot)},
                          {"end_position", display(piece.end_position, frot)},
                          {"lowest_position", display(piece.lowest_position, frot)},
                          {"highest_position", display(piece.highest_position, frot)},
                          {"contacts", contacts(piece.contacts)},
                          {"closed_form", piece.equation}});
    if (piece.unresolved_length) pieces.back()["unresolved_length"] = true;
  }
  report["pieces"] = pieces;
  json events = json::array();
  for (const KinematicEvent& event : result.events) {
    std::size_t f = follower_index(result, event.part);
    bool frot = f < result.follower_rotates.size() ? bool(result.follower_rotates[f]) : rot;
    events.push_back(json{{"kind", event_kind(event.kind)},
                          {"part", event.part},
                          {"at", location(event.at)},
                          {"position", display(event.position, frot)},
                          {"before", contacts(event.before)},
                          {"after", contacts(event.after)},
                          {"description", event.description}});
  }
  report["events"] = events;
  if (result.jam) {
    report["blocked"] = {{"at", location(result.jam->at)},
                         {"part", result.jam->part},
                         {"description", result.jam->description},
                         {"contacts", contacts(result.jam->before)}};
  } else {
    report["blocked"] = nullptr;
  }
  json uses = json::array();
  for (const ContactUse& use : result.contacts) {
    json intervals = json::array();
    for (auto [a, b] : use.intervals) intervals.push_back({display(a, rot), display(b, rot)});
    uses.push_back(json{{"part", use.part},
                        {"contact", contacts({use.contact})[0]},
                        {"driver_intervals", intervals},
                        {"unintended", use.unintended},
                        {"reason", use.reason}});
  }
  report["contacts"] = uses;
  json play = json::array();
  for (const PlaySummary& p : result.play) {
    std::size_t f = follower_index(result, p.part);
    bool frot = f < result.follower_rotates.size() && result.follower_rotates[f];
    play.push_back(json{{"part", p.part},
                        {"minimum", display(p.minimum, frot)},
                        {"at_minimum", display(p.at_minimum, rot)},
                        {"maximum", display(p.maximum, frot)},
                        {"at_maximum", display(p.at_maximum, rot)},
                        {"one_sided_somewhere", p.unbounded}});
  }
  report["play"] = play;
  json reversals = json::array();
  for (const ReversalCheck& check : result.reversals)
    reversals.push_back(json{{"part", check.part},
                             {"driver", display(check.driver, rot)},
                             {"lost_motion", display(check.lost_motion, rot)},
                             {"follower_moved", check.follower_moved}});
  report["reversals"] = reversals;
  report["warnings"] = result.warnings;
  report["event_resolution"] = certified_display(CertifiedRange{0, result.event_resolution}, rot).second;
  report["samples"] = result.samples.size();
  report["seconds"] = result.seconds;
  return report.dump(2) + "\n";
}

std::string kinematics_csv(const KinematicsResult& result) {
  std::ostringstream out;
  bool rot = result.driver_rotates;
  const std::string mm = csv_length_unit();   // "mm", or "1e400mm" (core/length_display.hpp)
  out << (rot ? "driver_angle_deg" : "driver_offset_" + mm);
  bool accelerations = !result.samples.empty() && !result.samples.front().accelerations.empty();
  for (std::size_t f = 0; f < result.followers.size(); ++f) {
    const std::string& name = result.followers[f];
    bool frot = result.follower_rotates[f];
    out << "," << name << (frot ? "_angle_deg" : "_offset_" + mm) << "," << name << "_velocity_ratio";
    if (accelerations) out << "," << name << "_acceleration";
    out << "," << name << (frot ? "_play_deg" : "_play_" + mm) << "," << name << "_contacts";
  }
  out << "\n";
  for (const KinematicSample& sample : result.samples) {
    out << format(display(sample.driver, rot), 9);
    for (std::size_t f = 0; f < result.followers.size(); ++f) {
      bool frot = result.follower_rotates[f];
      // ratio in displayed units: (deg or mm) per (deg or mm)
      double scale = (frot ? degrees_per_radian : 1.0) / (rot ? degrees_per_radian : 1.0);
      out << "," << format(display(sample.positions[f], frot), 9) << "," << format(sample.velocity_ratios[f] * scale, 9);
      if (accelerations) out << "," << format(sample.accelerations[f] * scale / (rot ? degrees_per_radian : 1.0), 9);
      double play = sample.play[f];
      out << "," << (std::isfinite(play) ? format(display(play, frot), 9) : std::string("inf"));
      std::string labels = join(sample.contacts[f]);
      std::replace(labels.begin(), labels.end(), '"', '\'');
      out << ",\"" << labels << "\"";
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace hipair
