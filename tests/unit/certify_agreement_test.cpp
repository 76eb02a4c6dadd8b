// The verifier's own geometry agrees with the library's exact overlap predicate
// (src/oracle/overlap) on random rational configurations of every example pair: where the
// library says the parts overlap, the verifier finds evidence (an exact transversal crossing or
// a vertex strictly inside); where it says they are apart, the verifier finds none and
// certifies a positive distance lower bound (MPFI). Witness points of the library are
// strictly inside both parts for the verifier's exact point location.
#include "certify/exact_geometry.hpp"
#include "certify/interval_geometry.hpp"
#include "oracle/overlap.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace hipair;

constexpr int configurations_per_pair = 1000;

verify::ExactMap random_map(const Part& part, std::mt19937_64& random) {
  verify::ExactMap map;
  if (part.motion.kind == Motion::Kind::rotation) {
    // t = tan((theta - c)/2) in [-1, 1], c in {0, pi}: every angle.
    Rational t(long(random() % 2001) - 1000, 1000 + long(random() % 997));
    int sign = random() % 2 ? -1 : 1;
    map.c = sign * (1 - t * t) / (1 + t * t);
    map.s = sign * 2 * t / (1 + t * t);
    map.pivot = part.motion.pivot;
  } else if (part.motion.kind == Motion::Kind::translation) {
    Rational lo(-40), hi(40);
    if (part.motion.translation_limits) lo = part.motion.translation_limits->lo, hi = part.motion.translation_limits->hi;
    Rational offset = lo + (hi - lo) * Rational(long(random() % 100001), 100000);
    map.shift = Point{Rational(offset * part.motion.direction.x), Rational(offset * part.motion.direction.y)};
  }
  return map;
}

cspace::RigidMap rigid(const verify::ExactMap& map) {
  cspace::RigidMap result;
  result.c = map.c;
  result.s = map.s;
  Point rotated = map.rotate(map.pivot);
  result.offset = Point{Rational(map.pivot.x - rotated.x + map.shift.x), Rational(map.pivot.y - rotated.y + map.shift.y)};
  return result;
}

bool fixed_axis(const Part& part) {
  // fixed-axis pairs only (a planar part's 3-DOF pair is sliced: tests/unit/sliced_test.cpp; a
  // pin-slot part's pairs are stacks of slices: tests/unit/pin_slot_test.cpp)
  return part.motion.kind != Motion::Kind::planar && part.motion.kind != Motion::Kind::pin_slot;
}

std::vector<std::string> example_files() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(HIPAIR_EXAMPLES))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// One test per example file and shard, so that ctest runs them side by side, each within its
// own time limit (all examples in one test took 2-5 minutes, the spur gears alone 170 s). Each
// shard draws configurations_per_pair / shards configurations per pair with its own seed,
// derived from the file's name and the shard, so a file's configurations do not depend on which
// other examples exist; the shards together test configurations_per_pair per pair.
constexpr int shards = 4;
static_assert(configurations_per_pair % shards == 0);

struct Shard {
  std::string file;
  int index;
};

std::vector<Shard> example_shards() {
  std::vector<Shard> result;
  for (const std::string& file : example_files())
    for (int index = 0; index < shards; ++index) result.push_back({file, index});
  return result;
}

class CertifyAgreement : public ::testing::TestWithParam<Shard> {};

TEST_P(CertifyAgreement, VerifierGeometryAgreesWithTheLibraryOverlapPredicate) {
  const std::string file = GetParam().file;
  std::uint64_t seed = 20240605 + GetParam().index;
  for (unsigned char c : file) seed = seed * 1099511628211ULL + c;
  std::mt19937_64 random(seed);
  constexpr int configurations = configurations_per_pair / shards;
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
  for (const PairSpec& pair : model.pairs) {
    const Part &a = model.parts[pair.first], &b = model.parts[pair.second];
    if (!fixed_axis(a) || !fixed_axis(b)) continue;
    std::string name = file + " " + a.name + ":" + b.name;
    int overlapping = 0, apart = 0, touching = 0;
    verify::IntervalPart shape_a = verify::shape_of(a), shape_b = verify::shape_of(b);
    for (int i = 0; i < configurations; ++i) {
      verify::ExactMap map_a = random_map(a, random), map_b = random_map(b, random);
      cspace::OverlapOptions options;
      options.want_witness = true;
      cspace::OverlapReport report = cspace::analyse_overlap(a, rigid(map_a), b, rigid(map_b), options);
      verify::PlacedPart placed_a = verify::place(a, map_a), placed_b = verify::place(b, map_b);
      std::string evidence = verify::overlap_evidence(placed_a, placed_b);
      if (report.relation == cspace::Overlap::overlapping) {
        ++overlapping;
        EXPECT_FALSE(evidence.empty()) << name << " configuration " << i << ": the library says overlapping";
        if (report.witness) {
          EXPECT_EQ(verify::locate(placed_a, *report.witness), 1) << name << " configuration " << i;
          EXPECT_EQ(verify::locate(placed_b, *report.witness), 1) << name << " configuration " << i;
        }
      } else if (report.relation == cspace::Overlap::apart) {
        ++apart;
        EXPECT_EQ(evidence, "") << name << " configuration " << i << ": the library says apart";
        Rational bound = verify::boundary_distance_lower_bound(shape_a, verify::to_interval_map(map_a), shape_b, verify::to_interval_map(map_b),
                                                               Rational(1000));
        EXPECT_GT(bound, 0) << name << " configuration " << i << ": apart, but no positive distance bound";
      } else {
        ++touching;   // measure zero for random configurations
      }
    }
    EXPECT_EQ(overlapping + apart + touching, configurations);
    std::cout << "[ agreement ] " << name << " (shard " << GetParam().index << "): " << overlapping << " overlapping, " << apart << " apart, " << touching
              << " touching\n";
  }
}

std::string test_name(const ::testing::TestParamInfo<Shard>& info) {
  std::string name = std::filesystem::path(info.param.file).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name + "_" + std::to_string(info.param.index);
}

INSTANTIATE_TEST_SUITE_P(Examples, CertifyAgreement, ::testing::ValuesIn(example_shards()), test_name);

// The distance bound from shapes and maps (edges posed lazily, pairs nearest first) equals the
// bound of the posed parts, is 0 where two edges cross, and never exceeds the exact distance of
// two boundary vertices; on every fixed-axis example pair, at exact poses and over rotation and
// translation ranges.
TEST(CertifyDistanceBound, ShapesAndMapsGiveTheBoundOfThePosedPartsAndStayBelowVertexDistances) {
  std::mt19937_64 random(20261129);
  int compared = 0, crossing = 0, positive = 0;
  for (const std::string& file : example_files()) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
    for (const PairSpec& pair : model.pairs) {
      const Part &a = model.parts[pair.first], &b = model.parts[pair.second];
      if (!fixed_axis(a) || !fixed_axis(b)) continue;
      verify::IntervalPart shape_a = verify::shape_of(a), shape_b = verify::shape_of(b);
      for (int i = 0; i < 12; ++i) {
        SCOPED_TRACE(file + " " + a.name + ":" + b.name + " configuration " + std::to_string(i));
        verify::ExactMap map_a = random_map(a, random), map_b = random_map(b, random);
        verify::IntervalMap over_a = verify::to_interval_map(map_a), over_b = verify::to_interval_map(map_b);
        if (i % 3 == 2) {   // a range of poses for a moving part
          const Part& mover = a.motion.kind != Motion::Kind::fixed ? a : b;
          verify::IntervalMap& over = &mover == &a ? over_a : over_b;
          Rational lo(long(random() % 600) - 300, 100), width(1 + long(random() % 20), 1000);
          if (mover.motion.kind == Motion::Kind::rotation) over = verify::rotation_over({lo, Rational(lo + width)});
          else if (mover.motion.kind == Motion::Kind::translation)
            over = verify::translation_over(mover.motion.direction, {Rational(10 * lo), Rational(10 * lo + width)});
        }
        Rational enough(1000);
        Rational lazy = verify::boundary_distance_lower_bound(shape_a, over_a, shape_b, over_b, enough);
        Rational posed = verify::boundary_distance_lower_bound(verify::place_over(shape_a, over_a),
                                                               verify::place_over(shape_b, over_b), enough);
        EXPECT_EQ(lazy, posed);
        ++compared;
        if (i % 3 == 2) continue;
        verify::PlacedPart placed_a = verify::place(a, map_a), placed_b = verify::place(b, map_b);
        std::string evidence = verify::overlap_evidence(placed_a, placed_b);
        if (evidence.rfind("loop", 0) == 0) {   // two edges cross: the boundaries meet
          EXPECT_EQ(lazy, 0) << evidence;
          ++crossing;
        }
        Rational nearest2 = enough * enough;
        for (const auto& loop_a : placed_a.loops)
          for (const verify::PlacedEdge& e : loop_a)
            for (const auto& loop_b : placed_b.loops)
              for (const verify::PlacedEdge& g : loop_b) {
                Rational dx = e.source.x - g.source.x, dy = e.source.y - g.source.y;
                nearest2 = std::min(nearest2, Rational(dx * dx + dy * dy));
              }
        EXPECT_LE(Rational(lazy * lazy), nearest2);
        positive += sgn(lazy) > 0;
      }
    }
  }
  EXPECT_GE(compared, 120);
  EXPECT_GT(crossing, 10);
  EXPECT_GT(positive, 10);
}

// The agreement above must cover the examples' fixed-axis pairs: at least ten of them.
TEST(CertifyAgreementCoverage, AtLeastTenFixedAxisExamplePairs) {
  int pairs = 0;
  for (const std::string& file : example_files()) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
    for (const PairSpec& pair : model.pairs)
      if (fixed_axis(model.parts[pair.first]) && fixed_axis(model.parts[pair.second])) ++pairs;
  }
  EXPECT_GE(pairs, 10);
}

}  // namespace
