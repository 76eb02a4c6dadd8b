// The memo of certified part disks (src/oracle/blocked_tester.hpp, part_disk_memo()): a tester
// constructed with the memo on has, disk by disk and bit by bit, the disks of a tester
// constructed with it off (each part certified afresh), on the examples' pairs and on variants
// of them that share some parts and change others in each of the things the disks depend on:
//  - a rotating part's pivot moved (its disks' offsets from the pivot change, its loops not);
//  - the pair's other part scaled by 2^k (the pair's scale exponent changes, the part not);
//  - one vertex of a part moved by 2^-20 mm (one edge's target and the next edge's source);
//  - a loop's hole flag flipped.
// The variants are constructed in a random order, each several times (the memo answers the
// repeats), and concurrently from several threads on a key no earlier test has seen.
#include "oracle/blocked_tester.hpp"
#include "curves/contact_curves.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_interval(const kernels::Interval& a, const kernels::Interval& b) {
  return same_bits(a.lo, b.lo) && same_bits(a.hi, b.hi);
}

bool same_core(const cspace::BlockedTester::CertifiedCore& a, const cspace::BlockedTester::CertifiedCore& b) {
  return same_interval(a.x, b.x) && same_interval(a.y, b.y) && same_interval(a.rx, b.rx) &&
         same_interval(a.ry, b.ry) && same_bits(a.r, b.r) && same_bits(a.rho, b.rho) && same_bits(a.cx, b.cx) &&
         same_bits(a.cy, b.cy) && same_bits(a.rx_m, b.rx_m) && same_bits(a.ry_m, b.ry_m) &&
         same_bits(a.r_error, b.r_error) && same_bits(a.magnitude, b.magnitude) &&
         same_bits(a.centre_error, b.centre_error);
}

// The first index at which the two testers' disks of `part` differ, or -1.
long first_difference(const cspace::BlockedTester& a, const cspace::BlockedTester& b, int part) {
  const auto& x = a.disks(part);
  const auto& y = b.disks(part);
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (!same_core(x[i], y[i])) return static_cast<long>(i);
  return x.size() == y.size() ? -1 : static_cast<long>(std::min(x.size(), y.size()));
}

struct MemoSwitch {
  explicit MemoSwitch(bool on) : before(cspace::part_disk_memo().load()) { cspace::part_disk_memo() = on; }
  ~MemoSwitch() { cspace::part_disk_memo() = before; }
  bool before;
};

// Every length of the part multiplied by 2^k (exact).
void scale_part(Part& part, int k) {
  auto scale = [k](Rational& v, int power) {
    mpq_mul_2exp(v.get_mpq_t(), v.get_mpq_t(), static_cast<mp_bitcnt_t>(k * power));
  };
  for (Loop& loop : part.loops)
    for (Edge& edge : loop.edges) {
      for (Point* p : {&edge.source, &edge.target, &edge.center}) {
        scale(p->x, 1);
        scale(p->y, 1);
      }
      scale(edge.radius_squared, 2);
    }
  scale(part.motion.pivot.x, 1);
  scale(part.motion.pivot.y, 1);
  if (part.motion.translation_limits) {
    scale(part.motion.translation_limits->lo, 1);
    scale(part.motion.translation_limits->hi, 1);
  }
}

// Moves the vertex between two consecutive segments of the part (chosen at random) by
// (2^-20, -2^-20) mm; false when the part has no such vertex.
bool move_a_vertex(Part& part, Random& random) {
  std::vector<std::pair<std::size_t, std::size_t>> vertices;
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const auto& edges = part.loops[l].edges;
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (!edges[i].is_arc() && !edges[(i + 1) % edges.size()].is_arc()) vertices.emplace_back(l, i);
  }
  if (vertices.empty()) return false;
  auto [l, i] = vertices[random() % vertices.size()];
  auto& edges = part.loops[l].edges;
  const Rational d(1, 1 << 20);
  for (Point* p : {&edges[i].target, &edges[(i + 1) % edges.size()].source}) {
    p->x += d;
    p->y -= d;
  }
  return true;
}

struct Case {
  std::string what;
  std::shared_ptr<const Model> model;
  cspace::PairAxes axes;
};

TEST(BlockedTesterMemo, MemoisedPartDisksAreTheCertifiedOnes) {
  Random random(20261129);
  std::vector<Case> cases;
  for (const char* file : {"escapement.json", "geneva.json", "ratchet.json", "scotch-yoke.json"}) {
    std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
    if (!std::filesystem::exists(path)) continue;
    const Model base = read_model_file(path);
    for (const PairSpec& pair : base.pairs) {
      if (base.parts[pair.first].motion.degrees_of_freedom() > 1 ||
          base.parts[pair.second].motion.degrees_of_freedom() > 1)
        continue;
      const std::string name = std::string(file) + " " + base.parts[pair.first].name + ":" + base.parts[pair.second].name;
      auto add = [&](const std::string& what, Model model) {
        cspace::PairAxes axes = cspace::pair_axes(model, pair.first, pair.second);
        cases.push_back({name + " " + what, std::make_shared<const Model>(std::move(model)), axes});
      };
      add("as is", base);
      for (std::size_t part : {pair.first, pair.second}) {
        const std::string which = " (" + base.parts[part].name + ")";
        if (base.parts[part].motion.kind == Motion::Kind::rotation) {
          Model moved = base;
          moved.parts[part].motion.pivot.x += Rational(1, 3);
          moved.parts[part].motion.pivot.y -= Rational(1, 7);
          add("pivot moved" + which, std::move(moved));
        }
        Model partner = base;
        scale_part(partner.parts[part == pair.first ? pair.second : pair.first], 12);
        add("partner scaled by 2^12" + which, std::move(partner));
        Model vertex = base;
        if (move_a_vertex(vertex.parts[part], random)) add("a vertex moved" + which, std::move(vertex));
        Model hole = base;
        if (!hole.parts[part].loops.empty()) {
          hole.parts[part].loops.back().is_hole = !hole.parts[part].loops.back().is_hole;
          add("hole flag flipped" + which, std::move(hole));
        }
      }
    }
  }
  ASSERT_GT(cases.size(), 20u) << "examples not found";
  // the certified disks of every case, each part afresh
  std::vector<std::unique_ptr<cspace::BlockedTester>> fresh;
  {
    MemoSwitch off(false);
    for (const Case& c : cases) fresh.push_back(std::make_unique<cspace::BlockedTester>(*c.model, c.axes));
  }
  // with the memo: every case three times, in a random order
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (int repeat = 0; repeat < 3; ++repeat) order.push_back(i);
  std::shuffle(order.begin(), order.end(), random);
  MemoSwitch on(true);
  const std::size_t hits_before = cspace::part_disk_memo_hits().load();
  std::size_t disks = 0;
  for (std::size_t i : order) {
    const cspace::BlockedTester memoised(*cases[i].model, cases[i].axes);
    for (int part = 0; part < 2; ++part) {
      disks += memoised.disks(part).size();
      ASSERT_EQ(first_difference(memoised, *fresh[i], part), -1)
          << cases[i].what << ": part " << part << " has " << memoised.disks(part).size() << " disks, certified "
          << fresh[i]->disks(part).size();
    }
    EXPECT_EQ(memoised.usable(), fresh[i]->usable()) << cases[i].what;
  }
  const std::size_t hits = cspace::part_disk_memo_hits().load() - hits_before;
  std::cout << cases.size() << " cases, " << order.size() << " testers, " << disks << " disks compared, " << hits
            << " parts from the memo\n";
  // at least every repeat of every part came from the memo (2 parts, 2 repeats per case)
  EXPECT_GE(hits, 4 * cases.size());
  EXPECT_LT(hits, 2 * order.size());   // and not every part: the first construction of a key certifies

  // concurrently: four threads construct testers of a pair with a key nobody has seen (a pivot
  // moved by a fraction no other test uses); each equals the fresh certification
  for (const Case& c : cases) {
    if (c.what.find("as is") == std::string::npos) continue;
    Model model = *c.model;
    std::size_t part = c.axes.first_moves ? c.axes.first : c.axes.second;
    model.parts[part].motion.pivot.x += Rational(1, 1000003);
    std::unique_ptr<cspace::BlockedTester> certified;
    {
      MemoSwitch off(false);
      certified = std::make_unique<cspace::BlockedTester>(model, c.axes);
    }
    std::vector<std::unique_ptr<cspace::BlockedTester>> built(4);
    std::vector<std::thread> threads;
    for (auto& b : built) threads.emplace_back([&] { b = std::make_unique<cspace::BlockedTester>(model, c.axes); });
    for (auto& t : threads) t.join();
    for (const auto& b : built)
      for (int k = 0; k < 2; ++k) ASSERT_EQ(first_difference(*b, *certified, k), -1) << c.what << " concurrently, part " << k;
    break;
  }
}

}  // namespace
}  // namespace hipair
