// claimed_clearance's search for a distance closer than the 256-bit bound resolves (session 75,
// fine75): cap 2^-e for the least e that holds exactly, found by doubling e, now bounded by
// clearance_search_limit (4096 + 8 S, S the bits of the maps' entries and of the parts' largest
// coordinates). Two fixed squares g apart (g = m 10^-k, k up to 1000): the claim is at most g and
// within a factor 2 of it (oracle: the exact gap); with a cap (an upper bound of the distance)
// 2^(limit + 64) times the gap, the least e lies beyond the limit: refused naming --distance.
// (base75 had no bound: the doubling carried on with ever larger numbers.)
#include "certificates/producer.hpp"
#include "core/model_scale.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace hipair {
namespace {

// a fixed unit square at [0, 1]^2 and one at [1 + g, 2 + g] x [0, 1], g written exactly
Model squares(const Rational& g) {
  const std::string left = "1 + " + g.get_str(), right = "2 + " + g.get_str();
  return read_model(R"({ "hipair": 1, "name": "gap", "parts": [
  { "name": "a", "motion": "fixed", "loops": [ { "start": [0, 0], "edges": [ { "line_to": [1, 0] }, { "line_to": [1, 1] },
      { "line_to": [0, 1] }, { "line_to": [0, 0] } ] } ] },
  { "name": "b", "motion": "fixed", "loops": [ { "start": [")" + left + R"(", 0], "edges": [ { "line_to": [")" + right + R"(", 0] },
      { "line_to": [")" + right + R"(", 1] }, { "line_to": [")" + left + R"(", 1] }, { "line_to": [")" + left + R"(", 0] } ] } ] } ] })");
}

TEST(ClearanceSearchLimit, ClaimsAtMostTheGapWithinAFactorTwoAndRefusesBeyondTheLimit) {
  std::mt19937_64 random(test::test_seed(75));
  const verify::ExactMap identity;
  for (int round = 0; round < 6; ++round) {
    const long k = round == 0 ? 1000 : 60 + static_cast<long>(random() % 900);
    const Rational g = Rational(1 + static_cast<long>(random() % 9)) * test_numbers::power_of_ten(-k);
    const Model model = squares(g);
    const Part &a = model.parts.at(0), &b = model.parts.at(1);
    SCOPED_TRACE("gap " + g.get_str().substr(0, 40) + " (10^-" + std::to_string(k) + ")");
    // the bound not positive (closer than the enclosures resolve), the cap 2 mm: found
    const std::optional<Rational> claimed =
        certify_detail::claimed_clearance(Rational(0), std::nullopt, a, identity, b, identity, Rational(2));
    ASSERT_TRUE(claimed.has_value());
    EXPECT_GT(*claimed, 0);
    EXPECT_LE(*claimed, g);
    EXPECT_GE(*claimed * 3, g);   // cap 2^-e within a factor 2 of g, then 6 digits down
    // a cap 2^(limit + 64) g: the least e is beyond the limit
    const long limit = certify_detail::clearance_search_limit(a, identity, b, identity);
    EXPECT_GT(limit, 4096);
    const Rational huge_cap = times_power_of_two(g, limit + 64);
    try {
      certify_detail::claimed_clearance(Rational(0), std::nullopt, a, identity, b, identity, huge_cap);
      ADD_FAILURE() << "a distance 2^-" << limit + 64 << " of the cap was searched for";
    } catch (const GeometryError& error) {
      EXPECT_NE(std::string(error.what()).find("--distance"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("'a' and 'b'"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace hipair
