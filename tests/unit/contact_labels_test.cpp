// contact_label_can_contain (include/hipair/contact_labels.hpp), what `hipair analyze --expect`
// checks its patterns against (session 45), compared with its definition: every label
// cspace::curve_label gives a feature pair of the model's pairs (both orders, every feature
// part_features lists, the contact types the two kinds allow), made one by one, and searched.
// Patterns are substrings of real labels (each must be found: across the " / " and " (" joins
// too), the same with one character changed, two labels' pieces joined, and fixed words.
#include <hipair/contact_labels.hpp>
#include <hipair/model.hpp>

#include "curves/contact_curves.hpp"
#include "curves/pose.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace {

using namespace hipair;

// Every label a contact of one of the model's pairs can carry (the definition).
std::vector<std::string> every_label(const Model& model) {
  using cspace::ContactType;
  using K = FeatureKind;
  struct Type {
    ContactType type;
    K first, second;
  };
  const std::vector<Type> types = {{ContactType::vertex_segment, K::vertex, K::segment},
                                   {ContactType::segment_vertex, K::segment, K::vertex},
                                   {ContactType::vertex_arc, K::vertex, K::arc},
                                   {ContactType::arc_vertex, K::arc, K::vertex},
                                   {ContactType::arc_arc, K::arc, K::arc},
                                   {ContactType::arc_segment, K::arc, K::segment},
                                   {ContactType::segment_arc, K::segment, K::arc}};
  std::vector<std::string> labels;
  for (const PairSpec& pair : model.pairs)
    for (auto [a, b] : {std::pair{pair.first, pair.second}, std::pair{pair.second, pair.first}}) {
      auto fa = cspace::part_features(model, a), fb = cspace::part_features(model, b);
      for (const auto& f : fa)
        for (const auto& g : fb)
          for (const Type& t : types)
            if (f.ref.kind == t.first && g.ref.kind == t.second) labels.push_back(cspace::curve_label(model, f.ref, g.ref, t.type));
    }
  return labels;
}

bool some_label_contains(const std::vector<std::string>& labels, const std::string& pattern) {
  for (const std::string& label : labels)
    if (label.find(pattern) != std::string::npos) return true;
  return false;
}

class ContactLabels : public ::testing::TestWithParam<const char*> {};

TEST_P(ContactLabels, AgreeWithEveryLabelSearched) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + GetParam());
  std::vector<std::string> labels = every_label(model);
  ASSERT_FALSE(labels.empty());
  std::mt19937 random(45);
  auto uniform = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(random); };
  auto piece = [&](const std::string& label) {
    std::size_t start = uniform(label.size());
    return label.substr(start, 1 + uniform(label.size() - start));
  };
  std::size_t found = 0, absent = 0, spanning = 0;
  for (int round = 0; round < 300; ++round) {
    const std::string& label = labels[uniform(labels.size())];
    std::string pattern = piece(label);
    // a piece of a real label: always there
    EXPECT_TRUE(contact_label_can_contain(model, pattern)) << "'" << pattern << "' of '" << label << "'";
    spanning += pattern.find(" / ") != std::string::npos || pattern.find(" (") != std::string::npos;
    // one character changed, or two labels' pieces joined: as the labels say
    std::string changed = pattern;
    changed[uniform(changed.size())] = "ax3 /(_-Zq"[uniform(10)];
    std::string joined = piece(label) + piece(labels[uniform(labels.size())]);
    for (const std::string& candidate : {changed, joined}) {
      bool expected = some_label_contains(labels, candidate);
      (expected ? found : absent) += 1;
      EXPECT_EQ(contact_label_can_contain(model, candidate), expected) << "'" << candidate << "'";
    }
  }
  EXPECT_GT(spanning, 30u);   // the joins between a label's pieces are tried
  EXPECT_GT(found, 20u);
  EXPECT_GT(absent, 20u);
  for (const char* word : {"nobody", "motion limit of", "/ /", "(vertex on vertex)", "(segment on segment)"})
    EXPECT_EQ(contact_label_can_contain(model, word), some_label_contains(labels, word)) << word;
  EXPECT_FALSE(contact_label_can_contain(model, "nobody"));
  EXPECT_TRUE(contact_label_can_contain(model, ""));
}

INSTANTIATE_TEST_SUITE_P(Examples, ContactLabels,
                         ::testing::Values("geneva.json", "lever-stop.json", "ratchet.json", "cam-follower-lever.json",
                                           "escapement.json", "peg-in-slot.json"));

}  // namespace
