// The Taylor models' recycled coefficient storage (src/tolerance/recycling_allocator.hpp,
// session 70, tol70): memory only, so what is tested is that no two live vectors ever share a
// block and no value is lost or changed, whatever the order of making, growing, shrinking,
// copying, moving and freeing, within a thread and across threads; that a freed block is handed
// out again for its size class (the point of it); and that a thread's lists stay bounded. The
// arithmetic on top is the same code as before on the same operands (taylor_jet_prepared_test,
// tolerance_taylor_model_test and the chain tests compare the results bit for bit).
#include "test_seed.hpp"
#include "tolerance/taylor_model.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <thread>
#include <vector>

namespace hipair::tolerance_detail {
namespace {

using Interval = kernels::Interval;
using Coefficients = TaylorModel1::Coefficients;

// The pattern of vector `id`: entry i is [id + i / 1024, id + i / 1024] (exact in doubles).
Interval entry(std::uint64_t id, std::size_t i) {
  double v = static_cast<double>(id) + static_cast<double>(i) / 1024.0;
  return Interval(v, v);
}
Coefficients pattern(std::uint64_t id, std::size_t n) {
  Coefficients c;
  for (std::size_t i = 0; i < n; ++i) c.push_back(entry(id, i));
  return c;
}
// The first mismatch of `c` against the pattern of `id` of length `n`, or -1.
long mismatch(const Coefficients& c, std::uint64_t id, std::size_t n) {
  if (c.size() != n) return static_cast<long>(c.size() == 0 ? 0 : c.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!(c[i].lo == entry(id, i).lo && c[i].hi == entry(id, i).hi)) return static_cast<long>(i);
  return -1;
}

struct Live {
  std::uint64_t id;
  std::size_t n;
  Coefficients c;
};

// Random operations on up to 160 live vectors of 0 to 300 coefficients (every size class from 64
// bytes to 8 kB, and sizes that straddle the class boundaries), each checked against its pattern.
void shuffle_vectors(std::mt19937_64& random, std::vector<Live>& live, std::uint64_t& next_id, int operations) {
  std::uniform_int_distribution<int> op(0, 6);
  auto size = [&]() {
    int kind = std::uniform_int_distribution<int>(0, 3)(random);
    if (kind == 0) return std::uniform_int_distribution<std::size_t>(0, 8)(random);
    if (kind == 1) {   // next to a class boundary: 2^k / 16 bytes per interval, +-1
      std::size_t k = std::uniform_int_distribution<std::size_t>(2, 9)(random);
      return (std::size_t(1) << k) + std::uniform_int_distribution<std::size_t>(0, 2)(random) - 1;
    }
    return std::uniform_int_distribution<std::size_t>(0, 300)(random);
  };
  for (int step = 0; step < operations; ++step) {
    int o = live.empty() ? 0 : op(random);
    std::size_t at = live.empty() ? 0 : std::uniform_int_distribution<std::size_t>(0, live.size() - 1)(random);
    switch (o) {
      case 0:
      case 1: {   // a new one
        if (live.size() >= 160) break;
        std::size_t n = size();
        std::uint64_t id = next_id++;
        live.push_back({id, n, pattern(id, n)});
        break;
      }
      case 2:   // freed
        live.erase(live.begin() + static_cast<std::ptrdiff_t>(at));
        break;
      case 3: {   // grown or shrunk in place (the pattern's entries kept, the new ones appended)
        Live& l = live[at];
        std::size_t n = size();
        if (n < l.n) l.c.resize(n);
        else
          for (std::size_t i = l.n; i < n; ++i) l.c.push_back(entry(l.id, i));
        l.n = n;
        break;
      }
      case 4: {   // copied
        if (live.size() >= 160) break;
        Live copy{live[at].id, live[at].n, live[at].c};
        live.push_back(std::move(copy));
        break;
      }
      case 5: {   // moved into another (whose storage is freed)
        std::size_t to = std::uniform_int_distribution<std::size_t>(0, live.size() - 1)(random);
        if (to == at) break;
        live[to].c = std::move(live[at].c);
        live[to].id = live[at].id;
        live[to].n = live[at].n;
        live.erase(live.begin() + static_cast<std::ptrdiff_t>(at));
        break;
      }
      case 6: {   // overwritten by a new pattern of another size (assign)
        Live& l = live[at];
        l.id = next_id++;
        l.n = size();
        Coefficients fresh = pattern(l.id, l.n);
        l.c.assign(fresh.begin(), fresh.end());
        break;
      }
    }
    for (const Live& l : live) ASSERT_EQ(mismatch(l.c, l.id, l.n), -1) << "vector " << l.id << " after step " << step;
  }
}

TEST(ToleranceRecyclingAllocator, GeneratedVectorsKeepTheirValuesAndNeverShareABlock) {
  std::mt19937_64 random(test::test_seed(70));
  std::vector<Live> live;
  std::uint64_t next_id = 1;
  shuffle_vectors(random, live, next_id, 6000);
  // no two live vectors' storage overlaps
  std::map<const char*, const char*> spans;
  for (const Live& l : live) {
    if (l.c.empty()) continue;
    const char* begin = reinterpret_cast<const char*>(l.c.data());
    spans[begin] = begin + l.c.size() * sizeof(Interval);
  }
  const char* end = nullptr;
  for (const auto& [begin, stop] : spans) {
    EXPECT_TRUE(end == nullptr || begin >= end) << "two live vectors share storage";
    end = stop;
  }
}

TEST(ToleranceRecyclingAllocator, VectorsMadeInOneThreadAreReadAndFreedInAnother) {
  std::mt19937_64 random(test::test_seed(7070));
  for (int round = 0; round < 4; ++round) {
    std::vector<Live> live;
    std::uint64_t next_id = 1000000 * static_cast<std::uint64_t>(round + 1);
    std::mt19937_64 first(random()), second(random());
    std::thread maker([&]() { shuffle_vectors(first, live, next_id, 1500); });
    maker.join();   // its lists released at its exit; its vectors live on
    std::thread user([&]() {
      for (const Live& l : live) ASSERT_EQ(mismatch(l.c, l.id, l.n), -1) << "vector " << l.id << " in the second thread";
      shuffle_vectors(second, live, next_id, 1500);   // frees the first thread's blocks into this thread's lists
    });
    user.join();
    for (const Live& l : live) ASSERT_EQ(mismatch(l.c, l.id, l.n), -1) << "vector " << l.id << " in the main thread";
  }
}

TEST(ToleranceRecyclingAllocator, AFreedBlockIsHandedOutAgainAndTheListsAreBounded) {
  RecyclingAllocator<Interval> allocator;
  // run in a thread of its own: its lists start empty
  std::thread([&]() {
    for (std::size_t n : {1u, 4u, 5u, 100u, 128u, 129u, 2000u}) {
      SCOPED_TRACE(std::to_string(n) + " intervals");
      Interval* p = allocator.allocate(n);
      allocator.deallocate(p, n);
      Interval* q = allocator.allocate(n);
      EXPECT_EQ(p, q) << "a freed block of its class not reused";
      // a block of the same class (power-of-two bytes, at least 64) is the same block too
      std::size_t bytes = n * sizeof(Interval), size = 0;
      recycling_detail::class_of(bytes, size);
      std::size_t same = size / sizeof(Interval);
      allocator.deallocate(q, n);
      Interval* r = allocator.allocate(same);
      EXPECT_EQ(q, r) << same << " intervals, the class of " << size << " bytes";
      for (std::size_t i = 0; i < same; ++i) r[i] = Interval::point(static_cast<double>(i));   // the whole class is usable
      allocator.deallocate(r, same);
    }
    // the bound: freeing more blocks of a class than it keeps
    const std::size_t n = 100;   // 1 600 bytes: the 2 kB class
    std::size_t size = 0;
    const std::size_t k = recycling_detail::class_of(n * sizeof(Interval), size);
    const std::size_t limit = recycling_detail::limit(k);
    std::vector<Interval*> blocks;
    for (std::size_t i = 0; i < limit + 50; ++i) blocks.push_back(allocator.allocate(n));
    for (Interval* b : blocks) allocator.deallocate(b, n);
    EXPECT_EQ(recycling_detail::lists.count[k], limit);
    // larger blocks than the largest class are not kept
    const std::size_t huge = (std::size_t(1) << (recycling_detail::smallest_shift + recycling_detail::classes)) / sizeof(Interval) + 1;
    Interval* h = allocator.allocate(huge);
    h[huge - 1] = Interval(1);
    allocator.deallocate(h, huge);
  }).join();
}

}  // namespace
}  // namespace hipair::tolerance_detail
