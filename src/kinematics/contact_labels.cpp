// contact_label_can_contain: does a contact label of the model's pairs contain a pattern? A
// label is A + B + C with A = "<first part> <feature> / ", B = "<second part> <feature> (" and
// C = "<how they touch>)" (cspace::curve_label), where the kinds of the two features decide C.
// Every label is not made (a gear pair has about 10^6): the pattern is placed across the three
// pieces instead — within one piece, across A and B, across B and C, or across all three.
#include <hipair/contact_labels.hpp>

#include "curves/contact_curves.hpp"
#include "kinematics/engine.hpp"
#include "curves/pose.hpp"

#include <array>
#include <string>
#include <unordered_set>
#include <vector>

namespace hipair {
namespace {

using Kind = FeatureKind;
constexpr std::array<Kind, 3> kinds{Kind::vertex, Kind::segment, Kind::arc};
std::size_t index_of(Kind kind) { return kind == Kind::vertex ? 0 : kind == Kind::segment ? 1 : 2; }

// how two features of these kinds touch (cspace::contact_word), or nullptr where they cannot
// (a vertex on a vertex, a segment along a segment: no contact curve of their own)
const char* word_of(Kind first, Kind second) {
  using cspace::ContactType;
  if (first == Kind::vertex && second == Kind::segment) return cspace::contact_word(ContactType::vertex_segment);
  if (first == Kind::segment && second == Kind::vertex) return cspace::contact_word(ContactType::segment_vertex);
  if (first == Kind::vertex && second == Kind::arc) return cspace::contact_word(ContactType::vertex_arc);
  if (first == Kind::arc && second == Kind::vertex) return cspace::contact_word(ContactType::arc_vertex);
  if (first == Kind::arc && second == Kind::arc) return cspace::contact_word(ContactType::arc_arc);
  if (first == Kind::arc && second == Kind::segment) return cspace::contact_word(ContactType::arc_segment);
  if (first == Kind::segment && second == Kind::arc) return cspace::contact_word(ContactType::segment_arc);
  return nullptr;
}

bool ends_with_prefix(const std::string& piece, const std::string& pattern, std::size_t length) {
  return length <= piece.size() && piece.compare(piece.size() - length, length, pattern, 0, length) == 0;
}
bool starts_with_rest(const std::string& piece, const std::string& pattern, std::size_t from) {
  std::size_t length = pattern.size() - from;
  return length <= piece.size() && piece.compare(0, length, pattern, from, length) == 0;
}

// The pieces of one ordered pair's labels, by feature kind.
struct Pieces {
  std::array<std::vector<std::string>, 3> first, second;   // A pieces, B pieces
};

Pieces pieces_of(const Model& model, std::size_t a, std::size_t b) {
  Pieces pieces;
  for (const cspace::BodyFeature& feature : cspace::part_features(model, a))
    pieces.first[index_of(feature.ref.kind)].push_back(model.parts[a].name + " " + feature.label + " / ");
  for (const cspace::BodyFeature& feature : cspace::part_features(model, b))
    pieces.second[index_of(feature.ref.kind)].push_back(model.parts[b].name + " " + feature.label + " (");
  return pieces;
}

// some A + B + C of these sets contains the pattern
bool contains(const std::vector<std::string>& as, const std::vector<std::string>& bs, const std::string& c,
              const std::string& pattern) {
  if (as.empty() || bs.empty()) return false;
  const std::size_t n = pattern.size();
  for (const std::vector<std::string>* set : {&as, &bs})
    for (const std::string& piece : *set)
      if (piece.find(pattern) != std::string::npos) return true;
  if (c.find(pattern) != std::string::npos) return true;
  // where the pattern's head ends an A piece, and where its tail starts a B piece or C
  std::vector<char> ends_a(n + 1, 0), ends_b(n + 1, 0), starts_b(n + 1, 0), starts_c(n + 1, 0);
  for (std::size_t i = 1; i < n; ++i) {
    for (const std::string& piece : as)
      if (ends_with_prefix(piece, pattern, i)) { ends_a[i] = 1; break; }
    for (const std::string& piece : bs)
      if (ends_with_prefix(piece, pattern, i)) { ends_b[i] = 1; break; }
    for (const std::string& piece : bs)
      if (starts_with_rest(piece, pattern, i)) { starts_b[i] = 1; break; }
    starts_c[i] = starts_with_rest(c, pattern, i);
  }
  for (std::size_t i = 1; i < n; ++i)
    if ((ends_a[i] && starts_b[i]) || (ends_b[i] && starts_c[i])) return true;
  // A's end, a whole B piece, C's start
  std::unordered_set<std::string> whole(bs.begin(), bs.end());
  for (std::size_t i = 1; i < n; ++i) {
    if (!ends_a[i]) continue;
    for (std::size_t j = i + 1; j < n; ++j)
      if (starts_c[j] && whole.count(pattern.substr(i, j - i))) return true;
  }
  return false;
}

}  // namespace

bool contact_label_can_contain(const Model& model, const std::string& pattern, const std::vector<std::size_t>& pairs) {
  if (pattern.empty()) return true;
  for (std::size_t p : pairs) {
    const PairSpec& pair = model.pairs.at(p);
    for (auto [a, b] : {std::pair{pair.first, pair.second}, std::pair{pair.second, pair.first}}) {
      Pieces pieces = pieces_of(model, a, b);
      for (Kind first : kinds)
        for (Kind second : kinds)
          if (const char* word = word_of(first, second))
            if (contains(pieces.first[index_of(first)], pieces.second[index_of(second)], std::string(word) + ")", pattern))
              return true;
    }
  }
  return false;
}

bool contact_label_can_contain(const Model& model, const std::string& pattern) {
  std::vector<std::size_t> every(model.pairs.size());
  for (std::size_t p = 0; p < every.size(); ++p) every[p] = p;
  return contact_label_can_contain(model, pattern, every);
}

std::vector<std::size_t> driven_pairs(const Model& model, std::size_t driver) {
  return kinematics_detail::chain_pairs(model, driver);
}

}  // namespace hipair
