// One public vertex's exact numbers written on its first read (session 46): CSpace::vertex(id)
// copies only vertex id's numbers from its raw vertex (CSpace::Impl::vertex_number); vertices()
// copies every vertex not yet copied (CSpace::Impl::vertex_numbers). The simulator reads a few
// vertices of a space (its ordinate filter), so it no longer pays for all of them. Checked here,
// against the raw arrangement's vertices (the exact route: the numbers are copies of them), on
// generated translating polygon pairs (grids of 1, 1/16, 1/97; scales 1, 2^-100, 2^100) and on
// the degenerate corpus' rotating and mixed pairs and the escapement's and Geneva's pairs (several
// charts, irrational vertices):
//   - vertex(id) read in a random order, some twice: each equals its raw vertex field by field,
//     the same storage each time; only the vertices read are copied (counted), each once;
//   - then vertices(): every vertex equals its raw vertex, the ones read before are not copied
//     again (the count reaches the number of vertices exactly) and kept their storage and
//     numbers;
//   - threads reading random vertices of a fresh space through vertex(id) while others read
//     vertices() all see the raw vertices' numbers, and every vertex is copied exactly once.
#include "cspace/builder_impl.hpp"
#include "star_slider_pairs.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace hipair {
namespace {


// Whether public vertex i's numbers are its raw vertex's (the exact route), field by field.
::testing::AssertionResult equals_raw(const CSpace& space, const CSpaceVertex& vertex, std::size_t i) {
  const CSpace::Impl& impl = implementation(space);
  auto [c, v] = impl.vertex_local[i];
  if (vertex.chart != c) return ::testing::AssertionFailure() << "vertex " << i << ": chart";
  const cspace::raw::Vertex& raw = impl.charts[c].arrangement.vertices[v];
  auto same = [](const AlgebraicNumber& n, const cspace::algebra::Real& r) {
    return n.exact == r.exact && n.lower == r.lower && n.upper == r.upper && n.polynomial == r.polynomial;
  };
  if (!same(vertex.x, raw.x)) return ::testing::AssertionFailure() << "vertex " << i << ": x";
  if (vertex.y_exact != raw.y_exact) return ::testing::AssertionFailure() << "vertex " << i << ": y_exact";
  if (raw.y_exact && !same(vertex.y, raw.y)) return ::testing::AssertionFailure() << "vertex " << i << ": y";
  if (vertex.y_lower != raw.y_lower || vertex.y_upper != raw.y_upper)
    return ::testing::AssertionFailure() << "vertex " << i << ": y_lower / y_upper";
  if (vertex.y_curve != raw.y_curve.coefficients) return ::testing::AssertionFailure() << "vertex " << i << ": y_curve";
  if (vertex.y_branch != raw.y_branch) return ::testing::AssertionFailure() << "vertex " << i << ": y_branch";
  return ::testing::AssertionSuccess();
}

std::string text_of(const CSpaceVertex& v) {
  return v.x.lower.get_str() + " " + v.x.upper.get_str() + " " + v.y_lower.get_str() + " " + v.y_upper.get_str() + " " +
         std::to_string(v.y_curve.size()) + " " + std::to_string(v.y_branch);
}

// A fresh space: vertices read one by one in a random order (some twice), then all. Returns the
// number of vertices read one by one.
std::size_t check_fresh_space(const CSpace& space, std::mt19937_64& random) {
  const std::size_t n = implementation(space).vertices.size();
  if (n == 0) return 0;
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), random);
  order.resize(std::max<std::size_t>(1, (2 * n) / 3));   // a third left for vertices() alone
  std::vector<const CSpaceVertex*> address(n, nullptr);
  std::vector<std::string> text(n);
  const std::size_t copied_before = cspace::vertex_numbers_copied();
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    const CSpaceVertex& v = space.vertex(VertexId{i});
    EXPECT_TRUE(equals_raw(space, v, i));
    address[i] = &v;
    text[i] = text_of(v);
    ++distinct;
    // read again, and an earlier one again: the same storage, nothing copied
    const std::size_t j = order[random() % (k + 1)];
    EXPECT_EQ(&space.vertex(VertexId{i}), address[i]);
    EXPECT_EQ(&space.vertex(VertexId{j}), address[j]);
    // only the vertices read so far are copied
    EXPECT_EQ(cspace::vertex_numbers_copied() - copied_before, distinct) << "after reading vertex " << i;
  }
  const std::vector<CSpaceVertex>& all = space.vertices();
  EXPECT_EQ(cspace::vertex_numbers_copied() - copied_before, n) << "each vertex copied once";
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_TRUE(equals_raw(space, all[i], i));
    if (address[i]) {
      EXPECT_EQ(&all[i], address[i]);
      EXPECT_EQ(text_of(all[i]), text[i]);
    }
    EXPECT_EQ(&space.vertex(VertexId{i}), &all[i]);
  }
  EXPECT_EQ(cspace::vertex_numbers_copied() - copied_before, n) << "nothing copied after vertices()";
  return order.size();
}

TEST(CSpaceVertexNumberLazy, OneVertexReadCopiesThatVertexOnlyAndEqualsTheRawVertex) {
  std::mt19937_64 random(4646);
  int checked = 0;
  std::size_t read = 0;
  for (int instance = 0; instance < 30; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const test_loops::StarPair pair = test_loops::generated_star_pair(random, instance, false);
    const std::optional<CSpace> space = test_loops::star_slider_space(pair.a, pair.b);
    if (!space) continue;
    read += check_fresh_space(*space, random);
    ++checked;
  }
  EXPECT_GE(checked, 24);
  EXPECT_GE(read, 250u);
}

TEST(CSpaceVertexNumberLazy, DegenerateCorpusSpacesOfSeveralChartsReadOneByOne) {
  std::mt19937_64 random(46);
  std::size_t spaces = 0, multi_chart = 0, algebraic = 0, read = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate"))
    files.push_back(entry.path());
  // and the simulator's examples whose vertices its ordinate filter reads one by one
  for (const char* name : {"escapement.json", "geneva.json"}) files.push_back(std::filesystem::path(HIPAIR_EXAMPLES) / name);
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    Model model = read_model_file(file);
    for (const CSpace& space : CSpace::build_all(model)) {
      if (space.dimension() != 2) {
        // a 1-D space's vertices are written by the build: nothing is copied on a read
        const std::size_t before = cspace::vertex_numbers_copied();
        if (!space.vertices().empty()) EXPECT_EQ(&space.vertex(VertexId{0}), &space.vertices()[0]);
        EXPECT_EQ(cspace::vertex_numbers_copied(), before);
        continue;
      }
      read += check_fresh_space(space, random);
      ++spaces;
      multi_chart += space.charts().size() > 1;
      for (const CSpaceVertex& v : space.vertices()) algebraic += !v.x.exact;
    }
  }
  EXPECT_GE(spaces, 5u);
  EXPECT_GE(multi_chart, 2u);   // vertices of later charts: mapped through vertex_local
  EXPECT_GE(algebraic, 1u);     // irrational vertices (their polynomial and isolating interval)
  EXPECT_GE(read, 500u);
}

TEST(CSpaceVertexNumberLazy, ThreadsReadingOneVertexAndAllAtOnceSeeTheRawNumbers) {
  std::mt19937_64 random(846);
  int checked = 0;
  for (int instance = 0; instance < 8; ++instance) {
    const std::optional<CSpace> built = test_loops::random_star_slider_space(random);
    if (!built) continue;
    const CSpace& space = *built;
    const std::size_t n = implementation(space).vertices.size();
    ASSERT_GT(n, 0u);
    std::atomic<std::size_t> copied{0}, wrong{0};
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < 4; ++t) {
      const std::uint64_t seed = random();
      threads.emplace_back([&, t, seed] {
        std::mt19937_64 mine(seed);
        const std::size_t before = cspace::vertex_numbers_copied();
        for (int k = 0; k < 200; ++k) {
          const std::size_t i = mine() % n;
          const CSpaceVertex& v = (t == 3 && k == 100) ? space.vertices()[i] : space.vertex(VertexId{i});
          if (!equals_raw(space, v, i)) ++wrong;
        }
        copied += cspace::vertex_numbers_copied() - before;
      });
    }
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(wrong.load(), 0u);
    const std::size_t before = cspace::vertex_numbers_copied();
    for (std::size_t i = 0; i < n; ++i) EXPECT_TRUE(equals_raw(space, space.vertices()[i], i));
    copied += cspace::vertex_numbers_copied() - before;
    EXPECT_EQ(copied.load(), n) << "each vertex copied exactly once over all threads";
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

}  // namespace
}  // namespace hipair
