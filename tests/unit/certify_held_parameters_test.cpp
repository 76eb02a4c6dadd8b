// A tolerance certificate that varies only some of the model's toleranced parameters (session
// 43, hunt43). Its claim holds the others at their nominal values; until session 43 the verdict
// said "within 1 x the tolerances of 25 parameters ... they never interfere" on Geneva's 26 and
// did not say which one was held fixed. Generated: toleranced parameters dropped from `varied`,
// the box and every leaf of tests/data/certificates/geneva-tolerance-no-interference.json (the
// statement's count edited to match, as a hostile producer would), chosen by a fixed seed among
// those the tree never splits; the verdict must stay valid (a weaker claim) and name every
// dropped parameter (at most three by name, then "and K more"). Control: the certificate as
// produced (all 26 varied) names none. On main 0bdc449 both generated cases fail (no names).
#include <hipair/certificate.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const std::string held_words = "toleranced parameters";

hipair::VerificationResult check(const json& certificate, const std::string& model_text) {
  return hipair::check_certificate_text(hipair::read_certificate(certificate.dump()), model_text, "geneva.json");
}

TEST(CertifyHeldParameters, TheVerdictNamesTheTolerancedParametersHeldAtNominal) {
  const json original =
      json::parse(slurp(fs::path(HIPAIR_TEST_DATA) / "certificates" / "geneva-tolerance-no-interference.json"));
  const std::string model_text = slurp(fs::path(HIPAIR_EXAMPLES) / "geneva.json");
  hipair::VerificationResult control = check(original, model_text);
  ASSERT_TRUE(control.valid) << control.reason;
  EXPECT_EQ(control.summary.find(held_words), std::string::npos) << control.summary;

  const json& tolerance = original["tolerance"];
  std::vector<std::size_t> free;   // varied parameters the tree never splits
  for (std::size_t i = 0; i < tolerance["varied"].size(); ++i) {
    bool split = false;
    for (const json& node : tolerance["tree"])
      split = split || (node.is_array() && node[0] == tolerance["varied"][i]);
    if (!split) free.push_back(i);
  }
  ASSERT_GE(free.size(), 4u);
  std::mt19937_64 random(43);
  for (std::size_t count : {std::size_t(1), std::size_t(4)}) {
    std::vector<std::size_t> pick = free;
    std::shuffle(pick.begin(), pick.end(), random);
    pick.resize(count);
    std::sort(pick.rbegin(), pick.rend());   // erase from the back
    json mutant = original;
    json& t = mutant["tolerance"];
    std::vector<std::string> dropped;
    for (std::size_t i : pick) {
      dropped.push_back(t["varied"][i].get<std::string>());
      t["varied"].erase(i);
      t["box"].erase(i);
      for (json& leaf : t["leaves"]) leaf["parameters"].erase(i);
    }
    const std::size_t n = t["varied"].size();
    std::string statement = mutant["statement"].get<std::string>();
    const std::string from = std::to_string(n + count) + " varied", to = std::to_string(n) + " varied";
    ASSERT_NE(statement.find(from), std::string::npos) << statement;
    mutant["statement"] = statement.replace(statement.find(from), from.size(), to);
    hipair::VerificationResult result = check(mutant, model_text);
    ASSERT_TRUE(result.valid) << result.reason;   // a weaker claim, still true
    const std::string expected = held_words + " (" + std::to_string(count) + ": ";
    EXPECT_NE(result.summary.find(expected), std::string::npos) << result.summary;
    // at most three are named (the first in the model's order)
    std::size_t named = 0;
    for (const std::string& name : dropped) named += result.summary.find("'" + name + "'") != std::string::npos;
    EXPECT_EQ(named, std::min<std::size_t>(3, count)) << result.summary;
    if (count > 3) EXPECT_NE(result.summary.find("and " + std::to_string(count - 3) + " more"), std::string::npos);
    EXPECT_NE(result.summary.find("held at their nominal values"), std::string::npos) << result.summary;
  }
}

}  // namespace
