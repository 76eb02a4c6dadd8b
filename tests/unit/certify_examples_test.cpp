// Every certificate produced for every example model verifies: clearance, interference (parts
// posed into each other), free passage and jams, each written to a file and re-checked the way
// hipair-verify does it (hash, parameters, claim). Crossing witnesses are checked too, and a
// crossing of two edges that do not cross is rejected.
#include <hipair/certificate.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include "certify/exact_geometry.hpp"
#include "certify/planar_check.hpp"
#include "core/sha256.hpp"
#include "oracle/overlap.hpp"
#include "io/atomic_file.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include <array>
#include <chrono>
#include <filesystem>
#include <random>
#include <string>

#include <unistd.h>

namespace {

using namespace hipair;
namespace fs = std::filesystem;

int verified = 0;

// Writes the certificate, re-reads it and verifies it against the model file.
void expect_verifies(const Certificate& certificate, const fs::path& model_path, const std::string& what) {
  std::string text = write_certificate(certificate);
  EXPECT_EQ(write_certificate(read_certificate(text)), text) << what << ": the format does not round-trip";
  // one file per process: test runs in parallel (ctest -j, several checkouts) never share it
  fs::path file = fs::path(testing::TempDir()) / (std::string("hipair_certificate_") + std::to_string(::getpid()) + ".json");
  io::write_file_atomically(file, text);
  VerificationResult result = verify_certificate_file(file, model_path);
  fs::remove(file);
  EXPECT_TRUE(result.valid) << what << ": " << result.reason << "\n" << text.substr(0, 3000);
  if (result.valid) ++verified;
}

bool moves(const Part& part) { return part.motion.kind != Motion::Kind::fixed; }
bool rotates(const Part& part) { return part.motion.kind == Motion::Kind::rotation; }

// A random coordinate of a part: angle (rad, within limits) or offset (mm, within limits).
Rational random_coordinate(const Part& part, std::mt19937_64& random) {
  std::optional<RationalInterval> limits = rotates(part) ? part.motion.angle_limits : part.motion.translation_limits;
  RationalInterval range = limits ? *limits : (rotates(part) ? RationalInterval{-3, 3} : RationalInterval{-30, 30});
  return range.lo + (range.hi - range.lo) * Rational(long(random() % 10001), 10000);
}

ExactPosition position_of(const Part& part, const Rational& value) {
  return rotates(part) ? exact_position_from_angle(value) : ExactPosition{value, true, false, {}, {}};
}

std::map<std::string, ExactPosition> positions(const Part& a, const Rational& x, const Part& b, const Rational& y) {
  std::map<std::string, ExactPosition> result;
  if (moves(a)) result[a.name] = position_of(a, x);
  if (moves(b)) result[b.name] = position_of(b, y);
  return result;
}

TEST(CertifyExamples, EveryCertificateOfEveryExampleVerifies) {
  std::mt19937_64 random(7);
  int interference = 0, clearance = 0, free = 0, crossings = 0;
  for (const auto& entry : fs::directory_iterator(HIPAIR_EXAMPLES)) {
    if (entry.path().extension() != ".json") continue;
    Model model = read_model_file(entry.path());
    for (const PairSpec& pair : model.pairs) {
      const Part &a = model.parts[pair.first], &b = model.parts[pair.second];
      // fixed-axis pairs only (a planar part's 3-DOF pair is sliced: tests/unit/sliced_test.cpp)
      auto fixed_axis = [](const Part& part) {
        return part.motion.kind != Motion::Kind::planar && part.motion.kind != Motion::Kind::pin_slot;
      };
      if (!fixed_axis(a) || !fixed_axis(b)) continue;
      std::string name = entry.path().filename().string() + " " + a.name + ":" + b.name;
      int found_interference = 0, found_clearance = 0, found_free = 0, never_overlapping = 0;
      for (int attempt = 0; attempt < 400 && (found_interference < 2 || !found_clearance || !found_free); ++attempt) {
        Rational x = random_coordinate(a, random), y = random_coordinate(b, random);
        auto at = positions(a, x, b, y);
        if (found_interference < 2) {
          auto c = certify_interference(model, a.name, b.name, at);
          // The producer certifies exactly the configurations the library finds overlapping.
          auto map_of = [&](const Part& part) {
            cspace::RigidMap map;
            if (!moves(part)) return map;
            const ExactPosition& p = at.at(part.name);
            if (p.is_offset) {
              map.offset = Point{Rational(p.value * part.motion.direction.x), Rational(p.value * part.motion.direction.y)};
              return map;
            }
            Rational t = p.value, w = 1 + t * t;
            int sign = p.half_turn ? -1 : 1;
            map.c = sign * (1 - t * t) / w;
            map.s = sign * 2 * t / w;
            Point rotated{Rational(map.c * part.motion.pivot.x - map.s * part.motion.pivot.y),
                          Rational(map.s * part.motion.pivot.x + map.c * part.motion.pivot.y)};
            map.offset = Point{Rational(part.motion.pivot.x - rotated.x), Rational(part.motion.pivot.y - rotated.y)};
            return map;
          };
          bool overlapping = cspace::analyse_overlap(a, map_of(a), b, map_of(b)).relation == cspace::Overlap::overlapping;
          EXPECT_EQ(bool(c), overlapping) << name;
          if (!overlapping) ++never_overlapping;
          if (c) {
            expect_verifies(*c, entry.path(), name + " interference");
            ++found_interference;
            // The same claim with a crossing witness, when two edges cross there.
            auto [map_a, map_b] = std::pair{verify::ExactMap{}, verify::ExactMap{}};
            Certificate crossing = *c;
            crossing.witness_point.reset();
            for (const Part* part : {&a, &b}) {
              if (!moves(*part)) continue;
              const ExactPosition& p = c->configuration.at(part->name);
              verify::ExactMap& map = part == &a ? map_a : map_b;
              if (p.is_offset) {
                map.shift = Point{Rational(p.value * part->motion.direction.x), Rational(p.value * part->motion.direction.y)};
              } else {
                Rational t = p.value, w = 1 + t * t;
                int sign = p.half_turn ? -1 : 1;
                map.c = sign * (1 - t * t) / w;
                map.s = sign * 2 * t / w;
                map.pivot = part->motion.pivot;
              }
            }
            verify::PlacedPart pa = verify::place(a, map_a), pb = verify::place(b, map_b);
            for (std::size_t i = 0; i < pa.loops.size() && !crossing.witness_crossing; ++i)
              for (std::size_t j = 0; j < pa.loops[i].size() && !crossing.witness_crossing; ++j)
                for (std::size_t k = 0; k < pb.loops.size() && !crossing.witness_crossing; ++k)
                  for (std::size_t l = 0; l < pb.loops[k].size() && !crossing.witness_crossing; ++l)
                    if (verify::edges_cross(pa.loops[i][j], pb.loops[k][l]))
                      crossing.witness_crossing = CrossingWitness{{a.name, i, j, a.loops[i].edges[j].label},
                                                                  {b.name, k, l, b.loops[k].edges[l].label}, std::nullopt};
            if (crossing.witness_crossing) {
              expect_verifies(crossing, entry.path(), name + " interference (crossing)");
              ++crossings;
              // Another edge of the second part that does not cross there is rejected.
              for (std::size_t l = 0; l < pb.loops[0].size(); ++l) {
                auto& across = crossing.witness_crossing->across;
                if (verify::edges_cross(pa.loops[crossing.witness_crossing->edge.loop][crossing.witness_crossing->edge.edge],
                                        pb.loops[0][l]))
                  continue;
                across = EdgeReference{b.name, 0, l, b.loops[0].edges[l].label};
                VerificationResult result = check_certificate(crossing, model);
                EXPECT_FALSE(result.valid) << name;
                EXPECT_NE(result.reason.find("do not cross"), std::string::npos) << result.reason;
                break;
              }
            }
          }
        }
        if (!found_clearance) {
          if (auto c = certify_clearance(model, a.name, b.name, at)) {
            expect_verifies(*c, entry.path(), name + " clearance");
            found_clearance = 1;
          }
        }
        if (!found_free) {
          const Part& driver = moves(a) ? a : b;
          const Part& other = &driver == &a ? b : a;
          Rational start = &driver == &a ? x : y, follower = &driver == &a ? y : x;
          Rational span = rotates(driver) ? Rational(1, 20) : Rational(1, 2);
          auto limits = rotates(driver) ? driver.motion.angle_limits : driver.motion.translation_limits;
          if (limits && start + span > limits->hi) continue;
          PassagePath path{driver.name, moves(other) ? other.name : "", {start, start + span}, {}};
          if (moves(other)) path.polyline = {{start, follower}, {start + span, follower}};
          if (auto c = certify_free_passage(model, a.name, b.name, path)) {
            expect_verifies(*c, entry.path(), name + " free passage");
            found_free = 1;
          }
        }
      }
      if (!found_free && entry.path().filename() == "spur-gears.json") {
        // Meshing gears pass freely only along the gear ratio (18:27), from the initial position.
        PassagePath path{"pinion", "gear", {Rational(0), Rational(1, 20)}, {{0, 0}, {Rational(1, 20), Rational(-1, 30)}}};
        if (auto c = certify_free_passage(model, a.name, b.name, path)) {
          expect_verifies(*c, entry.path(), name + " free passage along the gear ratio");
          found_free = 1;
        }
      }
      if (!found_free && entry.path().filename().string().rfind("gear-train", 0) == 0) {
        // The idler gear trains (gear-train*.json, written by gear-train.py): gears "gear-X" of
        // "X-teeth" teeth, meshing from the initial position; pass along the ratio -z_a / z_b.
        const Parameter* za = model.find_parameter(a.name.substr(5) + "-teeth");
        const Parameter* zb = model.find_parameter(b.name.substr(5) + "-teeth");
        ASSERT_TRUE(za && zb) << name;
        Rational span(1, 20);
        PassagePath path{a.name, b.name, {Rational(0), span}, {{0, 0}, {span, Rational(-span * za->nominal / zb->nominal)}}};
        if (auto c = certify_free_passage(model, a.name, b.name, path)) {
          expect_verifies(*c, entry.path(), name + " free passage along the gear ratio");
          found_free = 1;
        }
      }
      // Pairs whose motions cannot make them overlap (a follower sliding in its guide) have none.
      if (found_interference < 2) {
        EXPECT_EQ(never_overlapping, 400) << name;
      }
      EXPECT_EQ(found_clearance, 1) << name;
      EXPECT_EQ(found_free, 1) << name;
      interference += found_interference;
      clearance += found_clearance;
      free += found_free;
    }
  }
  std::cout << "[ certify ] verified " << verified << " certificates: " << interference << " interference (+" << crossings
            << " with crossing witnesses), " << clearance << " clearance, " << free << " free passage\n";
  EXPECT_GE(interference, 18);   // 2 per pair, except the 2 followers sliding in guides
}

TEST(CertifyExamples, JamsOfTheLeverAndTheRatchetVerify) {
  fs::path lever_path = fs::path(HIPAIR_EXAMPLES) / "lever-stop.json";
  Model lever = read_model_file(lever_path);
  auto query = find_jam(lever, "lever", "stop", "lever", 0, 0, +1, Rational(1, 500), Rational(2));
  ASSERT_TRUE(query);
  auto certificate = certify_jam(lever, "lever", "stop", *query);
  ASSERT_TRUE(certificate);
  expect_verifies(*certificate, lever_path, "lever jam");
  // Driven backwards from 0 the lever meets only its limit (-30 deg): no jam within 0.5 rad.
  EXPECT_FALSE(find_jam(lever, "lever", "stop", "lever", 0, 0, -1, Rational(1, 500), Rational(1, 2)));

  fs::path ratchet_path = fs::path(HIPAIR_EXAMPLES) / "ratchet.json";
  Model ratchet = read_model_file(ratchet_path);
  auto backward = find_jam(ratchet, "wheel", "pawl", "wheel", 0, 0, -1, Rational(1, 500), Rational(1));
  ASSERT_TRUE(backward);
  auto jam = certify_jam(ratchet, "wheel", "pawl", *backward);
  ASSERT_TRUE(jam);
  EXPECT_FALSE(jam->cut.empty());
  expect_verifies(*jam, ratchet_path, "ratchet jam");
  // Forward, the pawl rides up the tooth backs: no jam over a tooth pitch (30 deg).
  EXPECT_FALSE(find_jam(ratchet, "wheel", "pawl", "wheel", 0, 0, +1, Rational(1, 500), Rational(1, 2)));
}

// A cam pushes its follower at every step of the search: the follower's new position is sought
// nearest its last one (session 20: the search extended the whole free run of the follower first,
// some 40 000 exact tests per driver step, so `hipair certify --claim jam` on the cam-follower ran
// for minutes without an answer). Over a turn it is not trapped; with the follower's travel
// limited to 4 mm the cam drives it onto the limit, and that jam is certified and verifies.
TEST(CertifyExamples, CamPushingItsFollowerIsTrackedAndItsLimitJamVerifies) {
  fs::path path = fs::path(HIPAIR_EXAMPLES) / "cam-follower.json";
  Model model = read_model_file(path);
  EXPECT_FALSE(find_jam(model, "cam", "follower", "cam", 0, Rational(1, 2), +1, Rational(1, 500), Rational(6283, 1000)));
  std::string text = io::read_file(path);
  auto at = text.find("\"limits\": [-12, 12]");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 20, "\"limits\": [-12, 4]");
  fs::path limited = fs::path(testing::TempDir()) / ("hipair_cam_limited_" + std::to_string(::getpid()) + ".json");
  io::write_file_atomically(limited, text);
  Model stopped = read_model_file(limited);
  auto query = find_jam(stopped, "cam", "follower", "cam", 0, Rational(1, 2), +1, Rational(1, 500), Rational(6283, 1000));
  ASSERT_TRUE(query);
  ASSERT_TRUE(query->trap.follower);
  // The face sits at the cam's radius, so the cam holds the follower at s = 8 sin(theta): it
  // reaches the 4 mm limit at theta = pi/6, within one search step of the trap.
  double pi_6 = std::numbers::pi / 6;
  EXPECT_LE(query->trap.driver.lo.get_d(), pi_6);
  EXPECT_GE(query->trap.driver.hi.get_d(), pi_6);
  EXPECT_EQ(query->trap.driver.hi - query->trap.driver.lo, Rational(1, 500));
  EXPECT_EQ(query->trap.follower->hi, Rational(4));
  EXPECT_LT(query->trap.follower->lo, Rational(4));
  // The search's own trap, one step wide: at its cut the cam's top is above the limit by
  // less than 8 cos(pi/6) / 500 mm, a dip the crossing search's samples do not see.
  auto certificate = certify_jam(stopped, "cam", "follower", *query);
  ASSERT_TRUE(certificate);
  expect_verifies(*certificate, limited, "cam onto the follower's limit");
  // and a wider trap about it
  JamQuery wider = *query;
  wider.trap.driver = RationalInterval{Rational(1, 2), Rational(53, 100)};
  wider.trap.follower = RationalInterval{Rational(35, 10), Rational(4)};
  certificate = certify_jam(stopped, "cam", "follower", wider);
  ASSERT_TRUE(certificate);
  expect_verifies(*certificate, limited, "cam onto the follower's limit, wider trap");
  fs::remove(limited);
}

// Generated cams pushing their followers onto a travel limit: eccentricity, cam radius, the
// limit and the search's step at random. The cam holds the follower at s = e sin(theta), so the
// search's trap is the step holding theta* = asin(L / e), and at its cut the cam's top stands
// above the limit by e cos(theta*) x (a random fraction of the step): from a fraction of a
// micrometre to tens. Every trap the search finds is certified and verifies.
TEST(CertifyExamples, GeneratedCamsPushingFollowersOntoTheirLimitsJamCertifiably) {
  fs::path path = fs::path(HIPAIR_EXAMPLES) / "cam-follower.json";
  const std::string original = io::read_file(path);
  std::mt19937_64 random(20261129);
  int certified = 0;
  for (int trial = 0; trial < 10; ++trial) {
    long e = 3 + long(random() % 10);                              // eccentricity 3 .. 12 mm
    long radius = e + 10 + long(random() % 30);                    // cam radius
    long thousandths = e * long(100 + random() % 899);              // the limit, in [e/10, e)
    Rational limit(thousandths, 1000);
    limit.canonicalize();
    std::string digits = std::to_string(1000 + thousandths % 1000).substr(1);
    std::string limit_text = std::to_string(thousandths / 1000) + "." + digits;
    Rational step = std::vector<Rational>{Rational(1, 500), Rational(1, 2000), Rational(1, 10000), Rational(3, 1000)}[random() % 4];
    std::string text = original;
    auto replace = [&](const std::string& from, const std::string& to) {
      auto at = text.find(from);
      ASSERT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    };
    replace("\"limits\": [-12, 12]", "\"limits\": [-" + std::to_string(e + 4) + ", " + limit_text + "]");
    replace("\"offset\": 0.5", "\"offset\": 0.1");
    replace("\"cam-radius\": { \"nominal\": 25", "\"cam-radius\": { \"nominal\": " + std::to_string(radius));
    replace("\"eccentricity\": { \"nominal\": 8", "\"eccentricity\": { \"nominal\": " + std::to_string(e));
    fs::path file = fs::path(testing::TempDir()) / ("hipair_cam_generated_" + std::to_string(::getpid()) + ".json");
    io::write_file_atomically(file, text);
    Model model = read_model_file(file);
    double theta = std::asin(limit.get_d() / double(e));
    // the cut lands (1 - u) of a step past theta*: from 5 % to 95 % of a step
    double u = 0.05 + 0.9 * double(random() % 1000) / 1000;
    Rational start = Rational(theta - (20 + u) * step.get_d());
    Rational follower = Rational(double(e) * std::sin(start.get_d()) + 0.001);
    SCOPED_TRACE("e " + std::to_string(e) + ", radius " + std::to_string(radius) + ", limit " + limit.get_str() + ", step " +
                 step.get_str());
    auto query = find_jam(model, "cam", "follower", "cam", start, follower, +1, step, 60 * step);
    ASSERT_TRUE(query);
    ASSERT_TRUE(query->trap.follower);
    EXPECT_EQ(query->trap.follower->hi, limit);
    EXPECT_LE(query->trap.driver.lo.get_d(), theta + 1e-9);
    EXPECT_GE(query->trap.driver.hi.get_d(), theta - 1e-9);
    auto certificate = certify_jam(model, "cam", "follower", *query);
    ASSERT_TRUE(certificate) << "trap [" << query->trap.driver.lo.get_d() << ", " << query->trap.driver.hi.get_d() << "]";
    expect_verifies(*certificate, file, "generated cam onto its limit");
    ++certified;
    // The search started so that the cut lands within a rounding past theta*: there the one-step
    // trap's cut is a touch, and the trap certified is the one whose far end moved on.
    start = Rational(theta - 20 * step.get_d());
    follower = Rational(double(e) * std::sin(start.get_d()) + 0.001);
    query = find_jam(model, "cam", "follower", "cam", start, follower, +1, step, 60 * step);
    ASSERT_TRUE(query);
    certificate = certify_found_jam(model, "cam", "follower", *query, step);
    ASSERT_TRUE(certificate) << "touching cut at " << query->trap.driver.hi.get_d() << "; the search's start: "
                             << verify::jam_start_failure(model.parts[0], model.parts[1], query->trap, query->start);
    EXPECT_LE(certificate->trap.driver.hi - query->trap.driver.hi, 8 * step);
    expect_verifies(*certificate, file, "generated cam onto its limit, touching cut");
    ++certified;
    fs::remove(file);
  }
  EXPECT_EQ(certified, 20);
}

TEST(CertifyExamples, ParameterValuesInsideTheTolerancesAreCertified) {
  fs::path path = fs::path(HIPAIR_EXAMPLES) / "lever-stop.json";
  ReadOptions options;
  options.parameter_values["stop-gap"] = Rational(19, 10);   // tolerance [1.9, 2.1]
  Model model = read_model_file(path, options);
  auto c = certify_clearance(model, "lever", "stop", {{"lever", ExactPosition{0, false, false, {}, {}}}}, std::nullopt,
                             CertifyContext{options.parameter_values});
  ASSERT_TRUE(c);
  EXPECT_LE(c->distance, Rational(19, 10));   // the bound, rounded down to 6 digits
  EXPECT_GE(c->distance, Rational(18999, 10000));
  expect_verifies(*c, path, "lever clearance with stop-gap 1.9");
}

}  // namespace

namespace {

TEST(CertifyExamples, FindingsOfTheKinematicAnalysisAreCertified) {
  // The ratchet driven backwards jams; the analysis's jam gets a certificate.
  fs::path ratchet_path = fs::path(HIPAIR_EXAMPLES) / "ratchet.json";
  Model ratchet = read_model_file(ratchet_path);
  KinematicsOptions options;
  options.driver = "wheel";
  options.direction = -1;
  options.range = std::make_pair(Rational(0), Rational(-1, 10));
  KinematicsResult result = analyze_kinematics(ratchet, options);
  ASSERT_TRUE(result.jam);
  auto findings = certify_kinematic_findings(ratchet, result);
  ASSERT_EQ(findings.size(), 1u);
  ASSERT_TRUE(findings[0].certificate) << findings[0].note;
  EXPECT_EQ(findings[0].certificate->claim, ClaimKind::jam);
  expect_verifies(*findings[0].certificate, ratchet_path, "ratchet jam from the analysis");

  // The Geneva pair posed into each other at the initial configuration: certified interference.
  std::string text = io::read_file(fs::path(HIPAIR_EXAMPLES) / "geneva.json");
  std::size_t from = 0;
  for (const char* angle : {"1.2", "0.3"}) {   // driver, then wheel
    from = text.find("\"initial\"", from);
    auto at = text.find("\"angle\": 0", from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 10, std::string("\"angle\": ") + angle);
    from = at;
  }
  Model geneva = read_model(text, "geneva-posed.json");
  KinematicsOptions geneva_options;
  geneva_options.range = std::make_pair(Rational(12, 10), Rational(13, 10));
  KinematicsResult geneva_result = analyze_kinematics(geneva, geneva_options);
  ASSERT_FALSE(geneva_result.initial_interference.empty());
  auto interference = certify_kinematic_findings(geneva, geneva_result);
  ASSERT_FALSE(interference.empty());
  ASSERT_TRUE(interference[0].certificate) << interference[0].note;
  EXPECT_TRUE(check_certificate(*interference[0].certificate, geneva).valid);
}

}  // namespace

namespace {
// 10^exponent, exactly; 2 pi to 60 decimals (whole-turn shifts of generated angles).
Rational exact_power_of_ten(int exponent) {
  mpz_class power;
  mpz_ui_pow_ui(power.get_mpz_t(), 10, unsigned(std::abs(exponent)));
  return exponent >= 0 ? Rational(power) : Rational(mpz_class(1), power);
}
Rational two_pi_to_60_digits() {
  return Rational("6283185307179586476925286766559005768394338798750211641949889/1000000000000000000000000000000000000000000000000000000000000");
}
// A lever (pivot at the origin, angle limits [lo, hi], its underside from (0, -1) to (10, -1))
// above a slider (x from 5 to 6, y from -5 to -2, sliding along +y, or all mirrored in y when not
// `up`) that pushes up into it, scaled by `scale`; the lever can swing out upward.
std::string slider_lever_text(const Rational& scale, bool up, const Rational& lo, const Rational& hi) {
  auto number = [&](const Rational& v) { return "\"" + to_exact_string(v) + "\""; };
  auto p = [&](long x, long y) {   // mirrored in y when the lever swings out downward
    return "[" + number(Rational(x * scale)) + ", " + number(Rational((up ? y : -y) * scale)) + "]";
  };
  return "{\"hipair\": 1, \"name\": \"slider-lever\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"},"
      "\"parts\": [{\"name\": \"lever\", \"motion\": {\"rotation\": {\"pivot\": [0, 0], \"limits\": [" + number(lo) + ", " +
      number(hi) + "]}}, \"loops\": [{\"start\": " + p(0, -1) + ", \"edges\": [{\"line_to\": " + p(10, -1) +
      ", \"label\": \"underside\"}, {\"line_to\": " + p(10, 1) + "}, {\"line_to\": " + p(0, 1) + "}, {\"line_to\": " + p(0, -1) +
      "}]}]}, {\"name\": \"slider\", \"motion\": {\"translation\": {\"direction\": [0, " + (up ? "1" : "-1") + "], \"limits\": [" +
      number(Rational(-10 * scale)) + ", " + number(Rational(10 * scale)) + "]}}, \"loops\": [{\"start\": " + p(5, -5) +
      ", \"edges\": [{\"line_to\": " + p(6, -5) + "}, {\"line_to\": " + p(6, -2) + ", \"label\": \"side\"}, {\"line_to\": " +
      p(5, -2) + "}, {\"line_to\": " + p(5, -5) + "}]}]}], \"pairs\": [{\"parts\": [\"slider\", \"lever\"]}]}";
}

// A jam certificate of the slider-lever by hand: the slider's side crosses the lever's
// underside at the cut and on each wall given (`walls`: lower, upper); the start as given.
Certificate slider_lever_jam(const Model& model, const std::string& text, bool up, const JamQuery& query,
                             const std::array<bool, 2>& walls, const std::optional<JamStart>& start) {
  Certificate c;
  c.claim = ClaimKind::jam;
  c.model_name = "slider-lever";
  c.content_hash = detail::sha256_hex(text);
  c.first = "slider", c.second = "lever", c.driver = "slider", c.follower = "lever";
  c.trap = query.trap;
  c.start = start;
  auto edge_labelled = [&](std::size_t part, const std::string& label) {   // a mirrored loop is read reversed
    for (std::size_t e = 0; e < model.parts[part].loops[0].edges.size(); ++e)
      if (model.parts[part].loops[0].edges[e].label == label) return EdgeReference{model.parts[part].name, 0, e, label};
    ADD_FAILURE() << "no edge " << label;
    return EdgeReference{};
  };
  // the witness piece starts at an end that moves little over the piece's configurations
  // (the verifier's enclosures of a point along an edge widen with the distance from its
  // source): the lever's underside from the pivot (about x = 6, the slider's side) when the
  // slider comes from below; mirrored (the loops read reversed), the slider's side from its end
  // at the lever
  EdgeReference underside = edge_labelled(0, "underside"), side = edge_labelled(1, "side");
  CrossingWitness crossing = up ? CrossingWitness{underside, side, RationalInterval{Rational(59, 100), Rational(61, 100)}}
                                : CrossingWitness{side, underside, RationalInterval{Rational(0), Rational(1, 5)}};
  c.cut.push_back(BlockedPiece{*query.trap.follower, crossing});
  if (walls[0]) c.lower_wall.push_back(BlockedPiece{query.trap.driver, crossing});
  if (walls[1]) c.upper_wall.push_back(BlockedPiece{query.trap.driver, crossing});
  c.statement = certificate_statement(c, model);
  return c;
}
}  // namespace

// Session 34 (hunt34): a jam's wall "closed by the follower's motion limit" when the trap's
// follower range lies a whole turn away from the limits. A slider (direction +-y) pushes into a
// lever that is free to swing out of its way on one side; the trap's follower range is the
// lever's [-w, w] shifted by k whole turns (a rational within 1e-60 of 2 pi k: the same poses).
// The cut is blocked (the slider into the lever's underside), so is the wall on the side the
// lever cannot swing to, but the lever swings away on the other side: the slider passes, the
// claim "jam" is false. Until session 34 a band shifted up (k > 0) had its upper end "beyond" the
// upper limit (one shifted down its lower end below the lower limit), so that wall went
// unchecked: `certify_jam` produced the false certificate and the verifier accepted it. The exact
// overlap predicate shows the way out: free configurations from the trap's open side past the cut.
// Every fourth case is a control: the band not shifted, its end at the limit (the wall closed).
TEST(CertifyExamples, AJamWallIsClosedByAMotionLimitOnlyInTheLimitsOwnTurn) {
  const Rational two_pi = two_pi_to_60_digits();
  std::mt19937_64 random(20261201);
  int false_claims = 0, controls = 0;
  for (int trial = 0; trial < 16; ++trial) {
    int exponent = std::vector<int>{-300, -120, 0, 0, 40, 300}[random() % 6];
    Rational scale = exact_power_of_ten(exponent);
    int turns = int(random() % 3) + 1;
    bool up = random() % 2 == 0;              // the lever swings out upward (the slider from below)
    Rational w(1, long(100 + 50 * (random() % 3)));  // the band [-w, w] before the shift
    bool control = trial % 4 == 3;
    Rational shift = control ? Rational(0) : Rational((up ? turns : -turns) * two_pi);
    Rational lo = control && !up ? Rational(-w) : Rational(-1, 10), hi = control && up ? w : Rational(1, 10);
    std::string text = slider_lever_text(scale, up, lo, hi);
    Model model = read_model(text, "slider-lever.json");
    ASSERT_TRUE(model.roundings.empty());
    JamQuery query{"slider", "lever", +1, {}, std::nullopt};
    query.trap.driver = RationalInterval{Rational(Rational(98, 100) * scale), Rational(Rational(120, 100) * scale)};
    query.trap.follower = RationalInterval{Rational(-w + shift), Rational(w + shift)};
    SCOPED_TRACE("scale 1e" + std::to_string(exponent) + ", turns " + std::to_string(up ? turns : -turns) + ", w " +
                 to_exact_string(w) + (control ? " (control)" : ""));
    auto certificate = certify_jam(model, "slider", "lever", query, {}, IntervalSearchOptions{200});
    // the evidence by hand: the slider's side crosses the lever's underside at the cut and on
    // the wall the lever cannot swing through; no pieces for the wall it swings out through;
    // the start: the slider at the trap's start (0.02 below the lever), the lever at 0 (k turns)
    Certificate c = slider_lever_jam(model, text, up, query, {up, !up}, JamStart{query.trap.driver.lo, shift});
    VerificationResult result = check_certificate_text(c, text, "slider-lever.json");
    if (control) {
      ASSERT_TRUE(certificate);
      EXPECT_TRUE(check_certificate_text(*certificate, text, "slider-lever.json").valid);
      EXPECT_TRUE(result.valid) << result.reason;
      EXPECT_TRUE((up ? certificate->upper_wall : certificate->lower_wall).empty());
      ++controls;
      continue;
    }
    EXPECT_FALSE(certificate) << "a false jam certified";
    EXPECT_FALSE(result.valid) << "a false jam verified: " << result.summary;
    EXPECT_NE(result.reason.find("wall"), std::string::npos) << result.reason;
    // the oracle: the lever swung out to 2 atan(1/25) (about 0.08 rad, within its limits) lets
    // the slider go from the trap's start to 1.5 trap lengths on; the lever gets there from
    // inside the trap with the slider at the trap's start
    auto relation = [&](const Rational& s, const Rational& tangent) {
      Rational t2 = tangent * tangent;
      Placement lever{Rational((1 - t2) / (1 + t2)), Rational(2 * tangent / (1 + t2)), Point{Rational(0), Rational(0)}};
      Placement slider{Rational(1), Rational(0), Point{Rational(0), Rational(up ? s : -s)}};
      return part_overlap(model.parts[1], slider, model.parts[0], lever).relation;
    };
    Rational out = up ? Rational(1, 25) : Rational(-1, 25), inside = up ? Rational(w / 2) : Rational(-w / 2);
    for (int i = 0; i <= 8; ++i) {
      Rational s = query.trap.driver.lo + (query.trap.driver.hi - query.trap.driver.lo) * Rational(3 * i, 16);
      EXPECT_EQ(relation(s, out), PartRelation::apart) << "slider at " << s.get_d();
      Rational tangent = inside + (out - inside) * Rational(i, 8);
      EXPECT_EQ(relation(query.trap.driver.lo, tangent), PartRelation::apart) << "lever at tangent " << tangent.get_d();
    }
    ++false_claims;
  }
  EXPECT_GE(false_claims, 10);
  EXPECT_GE(controls, 4);
}

// Session 36 (hunt36; hunt35's open finding): a jam trap whose follower range lies wholly
// outside the follower's motion limits, in every turn, holds no configuration of the mechanism:
// the claim is empty. `certify_jam` refuses it (an input error naming the part and its limits)
// and the verifier rejects it (verify::band_meets_limits, shared). Generated: the slider-lever at
// scales 1e-300 ... 1e300, the lever's limits [a, b] (or [-b, -a]) with 0.3 <= a < b <= 3, the
// trap's follower range [-w, w] + 2 pi k (k = -2 ... 2), where the lever blocks the slider; the
// certificate is made for the model without limits (the geometry holds: it verifies there) and
// checked against the one with them. Oracle: in doubles, the band shifted by every turn -5 ... 5
// misses the limits by more than 0.1 rad. Controls (every fourth case): limits that meet the band
// (at its end, from -w/2 on), certified and verified with the limits.
TEST(CertifyExamples, AJamTrapWhollyOutsideTheFollowersLimitsIsRefused) {
  std::mt19937_64 random(20261236);
  const Rational two_pi = two_pi_to_60_digits();
  int empty_claims = 0, controls = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const int exponent = std::vector<int>{-300, -120, 0, 0, 40, 300}[random() % 6];
    const int turns = int(random() % 5) - 2;
    Rational scale = exact_power_of_ten(exponent);
    Rational w(1, long(100 + 50 * (random() % 3)));
    Rational a = std::vector<Rational>{Rational(3, 10), Rational(1, 2), Rational(1)}[random() % 3];
    Rational b = a + std::vector<Rational>{Rational(1, 10), Rational(1), Rational(2)}[random() % 3];
    bool below = random() % 2 == 0, control = trial % 4 == 3;
    Rational lo = control ? Rational(-w / 2) : below ? Rational(-b) : a, hi = control ? Rational(1) : below ? Rational(-a) : b;
    Rational shift = Rational(turns * two_pi);
    SCOPED_TRACE("scale 1e" + std::to_string(exponent) + ", limits [" + to_exact_string(lo) + ", " + to_exact_string(hi) +
                 "], turns " + std::to_string(turns) + ", w " + to_exact_string(w) + (control ? " (control)" : ""));
    std::string free_text = slider_lever_text(scale, true, Rational(-100), Rational(100));
    std::string limited_text = slider_lever_text(scale, true, lo, hi);
    Model free = read_model(free_text, "slider-lever.json"), limited = read_model(limited_text, "slider-lever.json");
    // the limits of the free model lie far beyond every band: read without limits' effect
    free.parts[0].motion.angle_limits.reset();
    JamQuery query{"slider", "lever", +1, {}, std::nullopt};
    query.trap.driver = RationalInterval{Rational(Rational(11, 10) * scale), Rational(Rational(12, 10) * scale)};
    query.trap.follower = RationalInterval{Rational(-w + shift), Rational(w + shift)};
    bool misses = true;   // the oracle
    for (int k = -5; k <= 5; ++k) {
      double band_lo = query.trap.follower->lo.get_d() + k * 2 * std::numbers::pi, band_hi = query.trap.follower->hi.get_d() + k * 2 * std::numbers::pi;
      misses = misses && (band_hi < lo.get_d() - 0.1 || band_lo > hi.get_d() + 0.1);
    }
    ASSERT_EQ(misses, !control);
    // The trap lies wholly inside the parts' overlap (the slider 0.1 ... 0.2 into the lever at
    // angle 0; the lever within 0.01 rad of it): since session 42 (hunt42) a jam needs a free
    // start in its trap, so this one, blocked on every side, is certified by no one. The
    // evidence by hand (cut and walls blocked by the slider's side across the lever's underside,
    // a start at the lever's angle 0) is refused for the band before the start is looked at.
    auto produced = certify_jam(free, "slider", "lever", query, {}, IntervalSearchOptions{200});
    EXPECT_FALSE(produced) << "a jam certified in a trap without a free configuration";
    Certificate hand = slider_lever_jam(free, free_text, true, query, {true, true},
                                        JamStart{query.trap.driver.lo, shift});
    Certificate* certificate = &hand;
    VerificationResult unlimited = check_certificate(*certificate, free);
    EXPECT_FALSE(unlimited.valid);
    EXPECT_NE(unlimited.reason.find("not certainly apart at the trap's start"), std::string::npos) << unlimited.reason;
    VerificationResult result = check_certificate(*certificate, limited);
    if (control) {   // the band meets the limits: refused for its start, not for the band
      EXPECT_FALSE(result.valid);
      EXPECT_NE(result.reason.find("not certainly apart at the trap's start"), std::string::npos) << result.reason;
      EXPECT_FALSE(certify_jam(limited, "slider", "lever", query, {}, IntervalSearchOptions{200}));
      ++controls;
      continue;
    }
    EXPECT_FALSE(result.valid) << "an empty jam verified: " << result.summary;
    EXPECT_NE(result.reason.find("lies outside the follower's limits"), std::string::npos) << result.reason;
    try {
      certify_jam(limited, "slider", "lever", query, {}, IntervalSearchOptions{200});
      ADD_FAILURE() << "an empty jam certified";
    } catch (const ModelError& error) {
      EXPECT_NE(std::string(error.what()).find("lies outside its motion limits"), std::string::npos) << error.what();
    } catch (const std::exception& error) {
      ADD_FAILURE() << "not an input error: " << error.what();
    }
    ++empty_claims;
  }
  EXPECT_GE(empty_claims, 10);
  EXPECT_GE(controls, 4);
}

// A free passage is a motion of the mechanism only when the follower's path stays within the
// follower's motion limits, all of it in one turn (a continuous motion keeps its turn). Until
// session 35 (hunt35) neither `certify_free_passage` nor the verifier looked at the path's
// values (only box 0's centre, about the start, met the limits, and that up to whole turns): a
// path far beyond the limits, or around a whole turn, was certified and verified. Generated: a
// slider far from a small square follower (they never come near, so the geometry holds for any
// follower position), scales 1e-300 ... 1e300, the follower rotating (limits [-a, b]) or
// translating; the certificate is made for the same model without limits (every claim's
// geometry holds) and checked against the model with them. Oracle, by construction: a vertex of
// the path lies beyond the limits in the start's turn (exactly, or by more than 1 rad). Controls:
// a path wholly within the limits shifted by 2 pi k turns, and one that ends exactly at a
// limit (non-dyadic: decided exactly in the limits' own turn), certified and verified.
TEST(CertifyExamples, AFreePassagePathMustStayWithinTheFollowersLimitsInOneTurn) {
  const Rational two_pi = two_pi_to_60_digits();
  std::mt19937_64 random(20261202);
  int false_claims = 0, controls = 0;
  for (int trial = 0; trial < 24; ++trial) {
    int exponent = std::vector<int>{-300, -120, 0, 0, 40, 300}[random() % 6];
    Rational scale = exact_power_of_ten(exponent);
    bool rotating = trial % 3 != 2;
    int kind = trial / 3 % 6;   // 0-3 false paths, 4-5 controls (each rotating twice, translating once)
    int turns = (random() % 2 ? 1 : -1) * int(random() % 3 + 1);
    Rational lo = rotating ? Rational(-long(random() % 7 + 1), 10) : Rational(-10 * scale);
    Rational hi = rotating ? Rational(long(random() % 7 + 1), 10) : Rational(10 * scale);
    Rational c = lo / 3, tiny = rotating ? exact_power_of_ten(-20) : Rational(scale * exact_power_of_ten(-40));
    Rational shift = rotating ? Rational(turns * two_pi) : Rational(0);
    std::vector<std::pair<Rational, Rational>> values;   // (fraction of the range, follower value)
    Rational beyond;   // a path value beyond the limits in the start's turn (false paths)
    bool control = kind >= 4;
    if (kind == 0 && rotating) {   // once around: c to c + 2 pi k through c + pi sgn(k)
      beyond = c + (turns > 0 ? 1 : -1) * two_pi / 2;
      values = {{0, c}, {Rational(1, 2), beyond}, {1, Rational(c + shift)}};
    } else if (kind <= 1) {        // just past the upper limit in its own turn
      beyond = hi + tiny;
      values = {{0, c}, {1, beyond}};
    } else if (kind == 2) {        // just past the lower limit, the whole path a turn (or more) away
      beyond = lo - tiny;
      values = {{0, Rational(c + shift)}, {1, Rational(beyond + shift)}};
    } else if (kind == 3) {        // far beyond, turned back within the range's end
      beyond = hi + (rotating ? Rational(2) : Rational(50 * scale));
      values = {{0, c}, {Rational(1, 3), beyond}, {1, c}};
    } else if (kind == 4) {        // control: within the limits, shifted by whole turns
      values = {{0, Rational(c + shift)}, {1, Rational(hi / 2 + shift)}};
    } else {                       // control: ends exactly at the upper limit
      values = {{0, c}, {1, hi}};
    }
    auto number = [&](const Rational& v) { return "\"" + to_exact_string(v) + "\""; };
    auto p = [&](long x, long y) { return "[" + number(Rational(x * scale)) + ", " + number(Rational(y * scale)) + "]"; };
    auto square = [&](long x0, long y0, long x1, long y1) {
      return "[{\"start\": " + p(x0, y0) + ", \"edges\": [{\"line_to\": " + p(x1, y0) + "}, {\"line_to\": " + p(x1, y1) +
             "}, {\"line_to\": " + p(x0, y1) + "}, {\"line_to\": " + p(x0, y0) + "}]}]";
    };
    auto text_of = [&](bool limited) {
      std::string limits = limited ? ", \"limits\": [" + number(lo) + ", " + number(hi) + "]" : "";
      std::string motion = rotating ? "{\"rotation\": {\"pivot\": [0, 0]" + limits + "}}"
                                    : "{\"translation\": {\"direction\": [0, 1]" + limits + "}}";
      return "{\"hipair\": 1, \"name\": \"slider-square\", \"units\": {\"length\": \"mm\", \"angle\": \"rad\"},"
             "\"parts\": [{\"name\": \"slider\", \"motion\": {\"translation\": {\"direction\": [1, 0]}}, \"loops\": " +
             square(100, -1, 102, 1) + "}, {\"name\": \"follower\", \"motion\": " + motion + ", \"loops\": " +
             square(-1, -1, 1, 1) + "}], \"pairs\": [{\"parts\": [\"slider\", \"follower\"]}]}";
    };
    const std::string limited = text_of(true), free = text_of(false);
    Model with_limits = read_model(limited, "slider-square.json"), without = read_model(free, "slider-square.json");
    ASSERT_TRUE(with_limits.roundings.empty());
    PassagePath path{"slider", "follower", RationalInterval{Rational(0), Rational(10 * scale)}, {}};
    for (const auto& [at, value] : values) path.polyline.push_back({Rational(at * path.range.hi), value});
    SCOPED_TRACE("trial " + std::to_string(trial) + ", scale 1e" + std::to_string(exponent) + (rotating ? ", rotating" : ", translating") +
                 ", kind " + std::to_string(kind) + ", turns " + std::to_string(turns) + ", limits [" + to_exact_string(lo) +
                 ", " + to_exact_string(hi) + "]");
    // the geometry holds with the follower anywhere: certified on the model without limits
    auto geometric = certify_free_passage(without, "slider", "follower", path, std::nullopt, {});
    ASSERT_TRUE(geometric);
    Certificate moved = *geometric;
    moved.content_hash = detail::sha256_hex(limited);
    VerificationResult result = check_certificate_text(moved, limited, "slider-square.json");
    if (control) {
      auto certificate = certify_free_passage(with_limits, "slider", "follower", path, std::nullopt, {});
      ASSERT_TRUE(certificate);
      EXPECT_TRUE(check_certificate_text(*certificate, limited, "slider-square.json").valid);
      EXPECT_TRUE(result.valid) << result.reason;
      ++controls;
      continue;
    }
    // the oracle: `beyond` (the path's value shifted back to the start's turn) lies outside the
    // limits: exactly for the tiny overshoots, by more than 1/2 rad in every turn for the others
    EXPECT_TRUE(beyond > hi || beyond < lo);
    if (rotating && (kind == 0 || kind == 3))
      for (int j = -4; j <= 4; ++j) {
        double v = Rational(beyond - j * two_pi).get_d();
        EXPECT_TRUE(v > hi.get_d() + 0.5 || v < lo.get_d() - 0.5) << "turn " << j;
      }
    EXPECT_FALSE(result.valid) << "a path beyond the follower's limits verified: " << result.summary;
    EXPECT_NE(result.reason.find("not within the follower's limits"), std::string::npos) << result.reason;
    EXPECT_THROW(certify_free_passage(with_limits, "slider", "follower", path, std::nullopt, {}), ModelError);
    ++false_claims;
  }
  EXPECT_GE(false_claims, 10);
  EXPECT_GE(controls, 4);
}

// An angle of a forged certificate far beyond any model's (10^1100 ... 10^100000 rad) made MPFR
// reduce it exactly before the sine and cosine, in time growing with its exponent: a jam trap
// starting at -1e100000 rad, or a tolerance leaf's follower interval ending there, kept the
// verifier busy for minutes (session 35, hunt35; main took > 30 s for each). Now the enclosure is
// [-1, 1] beyond 2^1100 (sound: it only widens), and the verifier answers at once, invalid.
// Generated: the exponent and the number's form drawn at random; controls: the certificates as
// written stay valid.
TEST(CertifyExamples, AnAngleFarBeyondAnyModelsIsRejectedAtOnce) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(HIPAIR_SOURCE_DIR) / "tests" / "data" / "certificates";
  struct Case {
    const char* certificate;
    const char* model;
    const char* key;   // the number replaced: in the jam's trap, or leaf 0's follower interval
    const char* value_before;
  };
  const Case cases[] = {{"ratchet-jam.json", "examples/models/ratchet.json", "\"driver\": [\"", "-3/250"},
                        {"geneva-tolerance-no-interference.json", "examples/models/geneva.json", "\"follower\": [\"0\", \"", "0"}};
  std::mt19937_64 random(35);
  fs::path work = fs::temp_directory_path() / ("hipair-huge-angle-" + std::to_string(::getpid()));
  fs::create_directories(work);
  for (const Case& c : cases) {
    const std::string text = io::read_file(folder / c.certificate);
    EXPECT_TRUE(verify_certificate_file(folder / c.certificate, fs::path(HIPAIR_SOURCE_DIR) / c.model).valid) << c.certificate;
    const std::string target = std::string(c.key) + c.value_before + "\"";
    std::size_t at = text.find(target);
    ASSERT_NE(at, std::string::npos) << c.certificate;
    for (int trial = 0; trial < 3; ++trial) {
      int exponent = std::vector<int>{1200, 5000, 20000, 100000}[random() % 4];
      std::string huge = random() % 2 ? "1e" + std::to_string(exponent) : "1" + std::string(std::size_t(exponent), '0') + "/7";
      if (std::string(c.certificate) == "ratchet-jam.json") huge = "-" + huge;
      std::string forged = text;
      forged.replace(at, target.size(), std::string(c.key) + huge + "\"");
      fs::path file = work / ("forged-" + std::to_string(trial) + ".json");
      io::write_file_atomically(file, forged);
      auto start = std::chrono::steady_clock::now();
      VerificationResult result = verify_certificate_file(file, fs::path(HIPAIR_SOURCE_DIR) / c.model);
      double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      EXPECT_FALSE(result.valid) << c.certificate << " with " << huge.substr(0, 12) << "...";
      EXPECT_LT(seconds, 5.0) << c.certificate << " with an angle of 10^" << exponent;
      // the reason names the forged number rounded, not as a line of 10^exponent digits
      EXPECT_LT(result.reason.size(), 600u) << c.certificate << ": " << result.reason.substr(0, 300);
    }
  }
  fs::remove_all(work);
}
