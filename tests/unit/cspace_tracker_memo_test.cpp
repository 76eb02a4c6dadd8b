// The scan memo's per-edge tracker data and its last exact edge ordinates (src/cspace/
// cspace_queries.cpp: tracker_data_of / tracker_data_slot, edge_ordinate; switches
// cspace::tracker_memo() and cspace::ordinate_at_memo() in src/cspace/scan_memo.hpp). Oracle: the
// same calls with both memos off. On every non-vertical real edge of the example spaces (the
// Geneva drive, the escapement's pairs, the cam and follower) and the sliding pairs' (cam
// follower, Scotch yoke), at generated abscissae inside the edge, at its ends' doubles, a few
// ulps inside and outside them: the simulator's pattern at a new contact —
// edge_coordinate_slope at the rational abscissa, then a tracker placed there (a fresh one: its
// placement is what the memos serve) and walked by small steps, jumps and a few ulps — and
// CSpace::derivatives at the same abscissa; every answer (and every exception's message) equal
// by its bits, with the two memos off and on, in a random order.
#include "cspace/scan_memo.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/edge_slope.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string bits(double a) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", a);
  return buffer;
}
void put(std::ostringstream& out, const CertifiedRange& r) { out << " [" << bits(r.lower) << " " << bits(r.upper) << "]"; }

// Everything one new contact at x asks, written out by its bits (exceptions by their messages).
std::string contact_at(const CSpace& space, std::size_t edge, double x, std::mt19937_64& walk_random) {
  std::ostringstream out;
  const Rational rx(x);
  try {
    put(out, edge_coordinate_slope(space, EdgeId(edge), rx));
  } catch (const Error& e) {
    out << " slope throws " << e.what();
  }
  EdgeTracker tracker;
  double at = x;
  for (int i = 0; i < 12; ++i) {
    std::optional<EdgeSlopes> s = track_derivatives(space, EdgeId(edge), at, tracker);
    if (!s) {
      out << " none";
    } else {
      for (const CertifiedRange* r : {&s->y, &s->dy, &s->d2y, &s->coordinate_dy, &s->coordinate_d2y}) put(out, *r);
    }
    // the next abscissa: a small step, a few ulps, or a jump (the same draws with the memos on
    // and off: the caller gives both the same generator state)
    const std::uint64_t r = walk_random();
    const double scale = std::max(1e-12, std::abs(at));
    if (r % 4 == 0) {
      for (int k = 0, n = static_cast<int>(r / 4 % 5) + 1; k < n; ++k) at = std::nextafter(at, r % 8 < 4 ? -1e300 : 1e300);
    } else if (r % 4 == 1) {
      at += scale * 1e-2 * (static_cast<double>(r >> 11) / 9007199254740992.0 - 0.5);
    } else {
      at += scale * 1e-6 * (static_cast<double>(r >> 11) / 9007199254740992.0 - 0.5);
    }
  }
  try {
    EdgeDerivatives d = space.derivatives(EdgeId(edge), rx);
    for (const CertifiedRange* r : {&d.dy, &d.d2y, &d.coordinate_dy, &d.coordinate_d2y}) put(out, *r);
    out << " y " << d.y.approximate();
  } catch (const Error& e) {
    out << " derivatives throw " << e.what();
  }
  return out.str();
}

TEST(CSpaceTrackerMemo, NewContactsAnswerAsWithoutTheMemos) {
  std::mt19937_64 random(4242);
  std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
  for (const test::SlidingPair& c : test::sliding_pairs)
    if (std::string(c.file) != "geneva-drive.json")
      spaces.push_back(std::make_unique<CSpace>(
          CSpace::build(read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.file), c.first, c.second)));
  std::size_t compared = 0, placed_hits = 0, ordinate_hits = 0, answered = 0, differing = 0;
  for (std::size_t s = 0; s < spaces.size(); ++s) {
    const CSpace& space = *spaces[s];
    if (space.dimension() != 2) continue;
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.real || edge.vertical) continue;
      double lo = space.vertices()[edge.source].x.approximate(), hi = space.vertices()[edge.target].x.approximate();
      if (lo > hi) std::swap(lo, hi);
      std::uniform_real_distribution<double> inside(lo, hi);
      double earlier[2] = {lo, hi};
      for (int k = 0; k < 8; ++k) {
        double x = inside(random);
        if (k == 5) x = random() % 2 ? lo : hi;
        if (k == 6) x = std::nextafter(random() % 2 ? lo : hi, random() % 2 ? -1e300 : 1e300);
        // k == 7: the abscissa of k - 1 or k - 2 again (the memo's entries asked once more)
        if (k == 7) x = earlier[random() % 2];
        earlier[k % 2] = x;
        const std::uint64_t walk_seed = random();
        const std::size_t tracker_hits = cspace::tracker_memo_hits(), ordinate_memo = cspace::ordinate_at_memo_hits();
        auto [with, without] = test::on_and_off<&cspace::tracker_memo>(random, [&](bool on) {
          test::FlagSwitch<&cspace::ordinate_at_memo> both(on);
          std::mt19937_64 walk(walk_seed);
          return contact_at(space, e, x, walk);
        });
        if (with != without && ++differing <= 3)
          ADD_FAILURE() << "space " << s << " edge " << e << " x " << bits(x) << "\nwith the memos:    " << with
                        << "\nwithout the memos: " << without;
        ++compared;
        placed_hits += cspace::tracker_memo_hits() - tracker_hits;
        ordinate_hits += cspace::ordinate_at_memo_hits() - ordinate_memo;
        answered += with.find('[') != std::string::npos;
      }
    }
  }
  std::printf("%zu new contacts compared (%zu with an answer), %zu placements and %zu exact ordinates from the memos\n",
              compared, answered, placed_hits, ordinate_hits);
  EXPECT_EQ(differing, 0u) << "new contacts answered differently with the memos";
  EXPECT_GT(compared, 500u);
  EXPECT_GT(answered, compared / 2);
  EXPECT_GT(placed_hits, compared / 2);     // the tracker data memo is used
  EXPECT_GT(ordinate_hits, compared / 2);   // and the ordinate memo
}

}  // namespace
}  // namespace hipair
