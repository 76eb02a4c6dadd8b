// Certificates for the findings of a kinematic analysis (interference at the initial
// configuration, jamming), for `hipair analyze`.
#include <hipair/certificate.hpp>
#include <hipair/kinematics.hpp>

#include <hipair/closing_jam.hpp>
#include "certificates/producer.hpp"
#include "core/model_scale.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <string>

namespace hipair {
namespace {

Rational rational_of(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.12g", value);
  return parse_rational(text);
}

// The piece tests (certify_detail::certify_found_jam_within) a jam's trap search may make.
constexpr std::size_t jam_search_tests = 2000;

bool moves(const Part& part) { return part.motion.kind != Motion::Kind::fixed; }
bool rotates(const Part& part) { return part.motion.kind == Motion::Kind::rotation; }

// The follower's position (unwrapped) at the last sample before `driver` in the driving direction.
std::optional<double> follower_position(const KinematicsResult& result, const std::string& follower, double driver) {
  auto index = std::find(result.followers.begin(), result.followers.end(), follower);
  if (index == result.followers.end()) return std::nullopt;
  std::size_t k = std::size_t(index - result.followers.begin());
  std::optional<double> position;
  for (const KinematicSample& sample : result.samples)
    if ((sample.driver - driver) * result.direction <= 1e-12 && k < sample.positions.size()) position = sample.positions[k];
  return position;
}

// The jam of `jam.part` where its free range closes, certified with a trap around the closing
// (certify_detail::certify_closing_jam) for the pair of the driver and that part; nullopt when
// no trap is certified.
std::optional<Certificate> certify_closing(const Model& model, const KinematicsResult& result,
                                                const KinematicEvent& jam, const Part& driver,
                                                const CertifyContext& context) {
  // only where the follower's free range closed (the engine's reason, src/kinematics/engine.cpp):
  // a dead point ("would have to jump", the escapement's anchor) is no closing channel
  if (jam.description.find("its free range closed") == std::string::npos) return std::nullopt;
  auto index = std::find(result.followers.begin(), result.followers.end(), jam.part);
  if (index == result.followers.end()) return std::nullopt;
  std::size_t k = std::size_t(index - result.followers.begin());
  double at = result.direction > 0 ? jam.at.coordinate.lower : jam.at.coordinate.upper;
  if (!std::isfinite(at) || !std::isfinite(jam.position)) return std::nullopt;
  // the samples before the closing where the follower has play, the nearest first (two at most)
  // (the analysis samples its driver grid and every event: a sample of a closing channel has
  // play, narrowing to 0 at the closing)
  std::vector<certify_detail::ClosingStart> starts;
  for (auto sample = result.samples.rbegin(); sample != result.samples.rend() && starts.size() < 4; ++sample) {   // two starts a sample
    if ((at - sample->driver) * result.direction <= 0 || k >= sample->positions.size() || k >= sample->play.size())
      continue;
    double position = sample->positions[k], play = sample->play[k];
    if (!std::isfinite(position) || !std::isfinite(play) || play <= 1e-9 * std::max(1.0, std::abs(position))) continue;
    // the sample's position is one end of its free interval (the contact that pushes it) or,
    // free, somewhere inside: both halves are tried, the piece's side first (pushed from above,
    // +1: the interval lies below the position); the start is checked exactly
    int side = 0;
    for (const KinematicPiece& piece : result.pieces)
      if (piece.part == jam.part && (sample->driver - piece.start.value()) * result.direction >= 0 &&
          (piece.end.value() - sample->driver) * result.direction >= 0)
        side = piece.side;
    Rational x = rational_of(sample->driver);
    certify_detail::ClosingStart above{x, rational_of(position), rational_of(position + play)},
        below{x, rational_of(position - play), rational_of(position)};
    starts.push_back(side > 0 ? below : above);
    starts.push_back(side > 0 ? above : below);
  }
  if (starts.empty()) return std::nullopt;
  for (const PairSpec& pair : model.pairs) {
    const Part &a = model.parts[pair.first], &b = model.parts[pair.second];
    bool ours = (a.name == driver.name && b.name == jam.part) || (b.name == driver.name && a.name == jam.part);
    if (!ours) continue;
    try {
      return certify_detail::certify_closing_jam(model, a.name, b.name, driver.name, result.direction, rational_of(at),
                                                 rational_of(jam.position), starts, context);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception&) {
      return std::nullopt;   // the note of the search above stands
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<Certificate> certify_closing_jam(const Model& model, const KinematicsResult& result,
                                               const CertifyContext& context) {
  if (!result.jam) return std::nullopt;
  std::optional<std::size_t> driver = model.find_part(result.driver);
  if (!driver || result.jam->part == result.driver) return std::nullopt;
  return certify_closing(model, result, *result.jam, model.parts[*driver], context);
}

std::vector<CertifiedFinding> certify_kinematic_findings(const Model& model, const KinematicsResult& result,
                                                         const CertifyContext& context) {
  // A mechanism far from the origin for its size, or rotation-only at an extreme scale, is
  // analysed on its normalised copy (analyze_kinematics), and its findings are certified there
  // too: the claims are angles, offsets and edge references, the same on the copy, which keeps
  // the model's name, content hash and roundings; an interference's witness point, the one
  // world point a finding's certificate holds, is mapped back to the model's exactly (the copy
  // is the model moved and scaled by a power of two: a point strictly inside both copied parts
  // maps to one strictly inside both parts). Before, the search ran on the model as given (the
  // escapement + 10^400: 26 s in the exact oracle on 10^400-mm coordinates).
  // Each certificate is then checked by the verifier's code on the model as given (what
  // hipair-verify will do): its interval filters may not decide a far jam's pieces (a 10 mm
  // part at 10^100 mm), and a certificate it rejects is not given, with the reason as the note.
  if (std::optional<NormalisedMechanism> copy = normalised_mechanism(model)) {
    std::vector<CertifiedFinding> findings = certify_kinematic_findings(copy->model, result, context);
    for (CertifiedFinding& finding : findings) {
      if (!finding.certificate) continue;
      if (finding.certificate->witness_point)
        finding.certificate->witness_point = copy->to_model(*finding.certificate->witness_point);
      VerificationResult check = check_certificate(*finding.certificate, model);
      if (check.valid) continue;
      finding.certificate.reset();
      finding.note = "certified on the mechanism moved to the origin (or rescaled), but the verifier cannot check it on "
                     "the model as given: " + check.reason;
    }
    return findings;
  }
  std::vector<CertifiedFinding> findings;
  for (const Interference& interference : result.initial_interference) {
    CertifiedFinding finding{"interference of " + interference.pair + " at the initial configuration", std::nullopt, ""};
    auto colon = interference.pair.find(':');
    std::string first = interference.pair.substr(0, colon), second = interference.pair.substr(colon + 1);
    try {
      std::map<std::string, ExactPosition> positions;
      for (const std::string& name : {first, second}) {
        const Part& part = model.parts.at(*model.find_part(name));
        if (moves(part))
          positions[name] = rotates(part) ? exact_position_from_angle(part.initial.angle)
                                          : ExactPosition{part.initial.offset, true, false, {}, {}};
      }
      finding.certificate = certify_interference(model, first, second, positions, context);
      if (!finding.certificate) finding.note = "the parts only touch there: no overlap to certify";
    } catch (const std::bad_alloc&) {
      throw;   // out of memory ends the run (exit 4), it is no note
    } catch (const std::exception& error) {
      finding.note = error.what();
    }
    findings.push_back(std::move(finding));
  }
  if (result.jam) {
    const KinematicEvent& jam = *result.jam;
    CertifiedFinding finding{"jam: " + jam.description, std::nullopt, ""};
    // stopped at the start with no bounding contact: no position of the part is free there, so a
    // trap (which needs a free start) cannot express it; the interference finding above holds
    // the proof (until session 47 the note said the stop came from the quasi-static model)
    if (jam.before.empty() && result.pieces.empty() && !result.initial_interference.empty()) {
      finding.note = "no position of " + jam.part + " is free at the initial driver position, and a jam certificate "
                     "needs a free start; the interference at the initial configuration is the finding";
      findings.push_back(std::move(finding));
      return findings;
    }
    const Part& driver = model.parts.at(*model.find_part(result.driver));
    double margin = rotates(driver) ? 0.02 : 0.2;
    double at = result.direction > 0 ? jam.at.coordinate.lower : jam.at.coordinate.upper;
    // The search starts at a configuration the analysis sampled (the last sample at least `margin`
    // before the jam: its driver and follower positions belong together), else at the range's
    // start, and its driver grid puts the located jam half a step past a grid point. Until
    // session 75 it started `margin` before the jam with steps of margin / 20: a grid point on the
    // jam itself, so the trap's cut was the closing, where the parts barely overlap, and its cover
    // took pieces of 1e-6 rad, hundreds of thousands of them (hostile75 M2: > 110 s where the
    // analysis takes 0.2 s); and the follower's position was the sample's before the start, which
    // a fast-driven follower had left (the parts overlapped at the start).
    double from = result.start;
    for (const KinematicSample& sample : result.samples)
      if ((sample.driver - result.start) * result.direction >= 0 && (at - sample.driver) * result.direction >= margin)
        from = sample.driver;
    const double span = (at - from) * result.direction, grid = margin / 20;
    Rational start = rational_of(from), step = rational_of(grid), travel = Rational(3) * rational_of(margin);
    if (span > 0) {
      step = rational_of(span / (std::max(0.0, std::round(span / grid - 0.5)) + 0.5));
      travel = rational_of(span + 2 * margin);
    }
    // The covers of the traps found are bounded together: jam_search_tests piece tests (about a
    // millisecond each), where a certified jam takes tens to a few thousand (the cut of a trap at
    // the closing itself took over 10^5, session 75)
    std::size_t tests = jam_search_tests;
    // The follower's free range closes (a zero-backlash mesh): its channel is too narrow for the
    // search's follower grid, and the analysis's samples put the search's start into the parts
    // (session 53). A trap around the closing, from the last samples before it where the
    // follower has play (the middle of its free interval, checked exactly as the start), is tried
    // first since session 75 (its own bound: 300 marches): the grid search's trap cost 13 s of
    // CPU on 18 x 16 zero-backlash gears driven backwards (2000 piece tests of many features
    // each) where the closing's took 0.5 s.
    if (jam.part != driver.name) finding.certificate = certify_closing(model, result, jam, driver, context);
    // Candidate pairs: the driver with the jammed follower, or (driver jammed) with a fixed part.
    for (const PairSpec& pair : model.pairs) {
      if (finding.certificate) break;
      const Part &a = model.parts[pair.first], &b = model.parts[pair.second];
      if (a.name != driver.name && b.name != driver.name) continue;
      const Part& other = a.name == driver.name ? b : a;
      if (moves(other) && other.name != jam.part) continue;
      std::optional<double> position = moves(other) ? follower_position(result, other.name, from)
                                                    : std::optional<double>(0.0);
      if (!position) continue;
      try {
        auto query = find_jam(model, a.name, b.name, driver.name, start, rational_of(*position), result.direction, step,
                              travel);
        if (query) {
          finding.certificate = certify_detail::certify_found_jam_within(model, a.name, b.name, *query, step, context, tests);
          if (!finding.certificate && tests == 0)
            finding.note = "the trap the jam search found (driver " + to_decimal_string(query->trap.driver.lo) + " .. " +
                           to_decimal_string(query->trap.driver.hi) + (rotates(driver) ? " rad" : " mm") +
                           ") was not covered within " + std::to_string(jam_search_tests) +
                           " piece tests, the bound of the search";
        }
      } catch (const std::bad_alloc&) {
        throw;
      } catch (const std::exception& error) {
        // the search's start is its own (the driver `margin` before the jam, the follower where
        // the analysis's double samples put it), not the model's initial configuration: say so
        // (until session 47 the note read "the parts overlap at the start" next to the report's
        // "Initial configuration: no parts overlap")
        finding.note = std::string("the jam search starting at driver ") + std::to_string(from) +
                       (rotates(driver) ? " rad" : " mm") +
                       (moves(other) ? ", " + other.name + " " + std::to_string(*position) + (rotates(other) ? " rad" : " mm")
                                     : std::string()) +
                       " (from the analysis's samples, not the initial configuration): " + error.what();
      }
      if (finding.certificate) break;
    }
    if (!finding.certificate && finding.note.empty())
      finding.note = "no pair geometrically traps the motion near the jam: the stop comes from the quasi-static "
                     "model (a contact that cannot turn the part, or a jam through several parts), which a "
                     "trap certificate does not express";
    findings.push_back(std::move(finding));
  }
  return findings;
}

}  // namespace hipair
