// `hipair cspace --json` written as text (cli/cspace_json.cpp) against the oracle, the document's
// nlohmann tree dumped as the command wrote it before session 32 (that code, kept here): byte for
// byte on every example model's pairs, on a gear pair's operating region, on generated spaces
// (disks at scales 2^-1000 .. 2^1000, names and labels that need escapes) and, for the text writer
// itself, on generated documents (random doubles of every exponent, integers, strings with
// control characters, quotes and UTF-8, nested and empty containers).
#include "cli/cspace_json.hpp"
#include "algebra/exact_real.hpp"
#include "cspace/builder_impl.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>

namespace hipair {
namespace {

using nlohmann::json;

// ------------------------------------------------------------- the oracle: the tree, as before

json exact(const AlgebraicNumber& n, const std::string& variable) {
  json out;
  out["exact"] = n.to_string(variable);
  out["decimal"] = n.approximate();
  if (!n.exact) out["interval"] = {to_exact_string(n.lower), to_exact_string(n.upper)};
  return out;
}

std::string polynomial_text(const std::vector<std::vector<mpz_class>>& c) {
  // x^i y^j terms, highest first
  std::string text;
  for (int i = static_cast<int>(c.size()) - 1; i >= 0; --i)
    for (int j = static_cast<int>(c[static_cast<std::size_t>(i)].size()) - 1; j >= 0; --j) {
      const mpz_class& v = c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      if (sgn(v) == 0) continue;
      std::string term = mpz_class(abs(v)).get_str();
      bool unit = abs(v) == 1 && (i > 0 || j > 0);
      std::string monomial;
      if (i > 0) monomial += "x" + (i > 1 ? "^" + std::to_string(i) : std::string());
      if (j > 0) monomial += (monomial.empty() ? "" : "*") + std::string("y") + (j > 1 ? "^" + std::to_string(j) : std::string());
      std::string body = unit ? monomial : term + (monomial.empty() ? "" : "*" + monomial);
      if (text.empty())
        text = (sgn(v) < 0 ? "-" : "") + body;
      else
        text += (sgn(v) < 0 ? " - " : " + ") + body;
    }
  return text.empty() ? "0" : text;
}

using cli::cell_kind_name;
using cli::role_name;

json statistics_json(const CSpaceStatistics& s, bool with_seconds) {
  json out{{"feature_pairs_considered", s.feature_pairs_considered},
              {"feature_pairs_culled", s.feature_pairs_culled},
              {"curves", s.curves},
              {"charts", s.charts},
              {"pieces_inserted", s.pieces_inserted},
              {"vertices", s.vertices},
              {"edges", s.edges},
              {"faces", s.faces},
              {"cells", s.cells},
              {"contact_edges", s.contact_edges},
              {"touching_edges", s.touching_edges},
              {"touching_vertices", s.touching_vertices},
              {"touching_undecided", s.touching_undecided},
              {"circle_segment_charts", s.circle_segment_charts},
              {"quadratic_charts", s.quadratic_charts},
              {"region_tiles", s.region_tiles},
              {"region_cells", s.region_cells},
              {"seconds",
               {{"curves", s.seconds_curves},
                {"culling", s.seconds_culling},
                {"clipping", s.seconds_clipping},
                {"arrangement", s.seconds_arrangement},
                {"export", s.seconds_export},
                {"labelling", s.seconds_labelling},
                {"classification", s.seconds_classification},
                {"cells", s.seconds_cells},
                {"total", s.seconds_total}}}};
  if (!with_seconds) out.erase("seconds");
  return out;
}

json vertex_json(const CSpace& space, const CSpaceVertex& vertex) {
  json v;
  v["chart"] = vertex.chart;
  v["x"] = exact(vertex.x, "x");
  if (space.dimension() == 2) {
    if (vertex.y_exact) {
      v["y"] = exact(vertex.y, "y");
    } else {
      v["y"] = {{"exact", "real root number " + std::to_string(vertex.y_branch) + " (ascending, from 0) in y of " +
                              polynomial_text(vertex.y_curve) + " at this x"},
                {"interval", {to_exact_string(vertex.y_lower), to_exact_string(vertex.y_upper)}},
                {"decimal", Rational((vertex.y_lower + vertex.y_upper) / 2).get_d()}};
    }
  }
  v["edges"] = vertex.edges;
  v["feature_pairs"] = vertex.curves;
  v["contact_change"] = vertex.contact_change;
  v["on_chart_boundary"] = vertex.on_chart_boundary;
  v["touching"] = vertex.touching;
  return v;
}

json edge_json(const CSpace& space, std::size_t e) {
  const auto& edge = space.edges()[e];
  json j;
  j["chart"] = edge.chart;
  j["source"] = edge.source;
  j["target"] = edge.target;
  j["role"] = role_name(edge.role);
  j["real"] = edge.real;
  j["feature_pairs"] = edge.curves;
  j["left_cell"] = edge.left_cell == no_index ? json(nullptr) : json(edge.left_cell);
  j["right_cell"] = edge.right_cell == no_index ? json(nullptr) : json(edge.right_cell);
  j["vertical"] = edge.vertical;
  j["polynomial"] = polynomial_text(space.edge_polynomial_coefficients(e));
  j["extent_chart"] = {{"x", {edge.x_chart.lower, edge.x_chart.upper}}, {"y", {edge.y_chart.lower, edge.y_chart.upper}}};
  j["extent_coordinates"] = {{"x", {edge.x_coordinate.lower, edge.x_coordinate.upper}},
                             {"y", {edge.y_coordinate.lower, edge.y_coordinate.upper}}};
  return j;
}

json space_json(const CSpace& space, bool with_seconds) {
  json out;
  out["pair"] = {space.first_part(), space.second_part()};
  out["dimension"] = space.dimension();
  out["complete"] = space.complete();
  out["x_part"] = space.x_part();
  if (space.dimension() == 2) out["y_part"] = space.y_part();
  json charts = json::array();
  for (const auto& chart : space.charts()) {
    json c;
    c["x"] = {{"kind", chart.x_kind == AxisKind::rotation ? "rotation" : "translation"},
              {"chart_center", chart.x_kind == AxisKind::rotation ? (chart.x_half_turn ? "pi" : "0") : "-"},
              {"lo", to_exact_string(chart.x_lo)},
              {"hi", to_exact_string(chart.x_hi)}};
    if (space.dimension() == 2)
      c["y"] = {{"kind", chart.y_kind == AxisKind::rotation ? "rotation" : "translation"},
                {"chart_center", chart.y_kind == AxisKind::rotation ? (chart.y_half_turn ? "pi" : "0") : "-"},
                {"lo", to_exact_string(chart.y_lo)},
                {"hi", to_exact_string(chart.y_hi)}};
    charts.push_back(c);
  }
  out["charts"] = charts;
  out["coordinates"] =
      "rotation charts use t = tan((theta - c)/2), c = 0 or pi; translation charts use the offset in mm";
  json pairs = json::array();
  for (const auto& pair : space.feature_pairs())
    pairs.push_back({{"label", pair.label},
                     {"first_part", pair.first_part},
                     {"first_feature", pair.first_feature},
                     {"second_part", pair.second_part},
                     {"second_feature", pair.second_feature},
                     {"kind", std::string(to_string(pair.kind))}});
  out["feature_pairs"] = pairs;
  json cells = json::array();
  for (const auto& cell : space.cells())
    cells.push_back({{"kind", cell_kind_name(cell.kind)},
                     {"wraps_x", cell.wraps_x},
                     {"wraps_y", cell.wraps_y},
                     {"faces", cell.faces},
                     {"boundary_edges", cell.boundary},
                     {"neighbours", cell.neighbours},
                     {"sample", {{"chart", cell.sample_chart},
                                 {"x", to_exact_string(cell.sample_x)},
                                 {"y", to_exact_string(cell.sample_y)}}}});
  out["cells"] = cells;
  json vertices = json::array();
  for (const auto& vertex : space.vertices()) vertices.push_back(vertex_json(space, vertex));
  out["vertices"] = vertices;
  if (space.dimension() == 2) {
    json edges = json::array();
    for (std::size_t e = 0; e < space.edges().size(); ++e) edges.push_back(edge_json(space, e));
    out["edges"] = edges;
  }
  out["statistics"] = statistics_json(space.statistics(), with_seconds);
  return out;
}

std::string oracle_text(const CSpace& space, bool with_seconds) { return space_json(space, with_seconds).dump(1) + "\n"; }

std::string streamed_text(const CSpace& space, bool with_seconds) {
  std::ostringstream out;
  cli::write_space_json(out, space, with_seconds);
  return out.str();
}

// The first line where two texts differ, for the failure message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::size_t at = 0;
  while (at < a.size() && at < b.size() && a[at] == b[at]) ++at;
  const std::size_t line_start = a.rfind('\n', at == 0 ? 0 : at - 1);
  const std::size_t from = line_start == std::string::npos ? 0 : line_start + 1;
  return "at byte " + std::to_string(at) + ": oracle '" + a.substr(from, 120) + "' streamed '" + b.substr(from, 120) + "'";
}

void expect_same_text(const CSpace& space, const std::string& what) {
  for (bool with_seconds : {false, true}) {
    const std::string oracle = oracle_text(space, with_seconds);
    const std::string streamed = streamed_text(space, with_seconds);
    EXPECT_EQ(oracle.size(), streamed.size()) << what;
    EXPECT_TRUE(oracle == streamed) << what << (with_seconds ? " (with seconds) " : " ") << first_difference(oracle, streamed);
  }
}

// ------------------------------------------------------------- the spaces of the example models

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

TEST(CSpaceJsonText, EveryExampleModelsPairsAsTheTreeWroteThem) {
  std::size_t spaces = 0, vertices = 0, edges = 0, algebraic = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_EXAMPLES))) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().filename().string();
    // the gear pairs' whole spaces take minutes: their operating regions are the next test's
    if (name == "spur-gears.json" || name.rfind("gear-train", 0) == 0) continue;
    Model model;
    try {
      model = read_model_file(entry.path());
    } catch (const std::exception&) {
      continue;   // templates that are not models by themselves
    }
    for (const PairBuild& pair : CSpace::build_pairs(model)) {
      if (pair.status != PairBuild::Status::built) continue;
      const CSpace& space = *pair.space;
      ++spaces;
      vertices += space.vertices().size();
      edges += space.edges().size();
      for (const CSpaceVertex& v : space.vertices()) algebraic += !v.x.exact || !v.y_exact;
      expect_same_text(space, name + " " + space.first_part() + ":" + space.second_part());
    }
  }
  EXPECT_GE(spaces, 20u);
  EXPECT_GT(vertices, 1000u);
  EXPECT_GT(edges, 1000u);
  EXPECT_GT(algebraic, 100u);   // irrational coordinates: intervals, "real root number" texts
}

TEST(CSpaceJsonText, GearPairsOperatingRegionAsTheTreeWroteIt) {
  for (auto [z1, z2] : {std::pair{9L, 11L}}) {
    ReadOptions read;
    read.parameter_values["teeth-1"] = Rational(z1);
    read.parameter_values["teeth-2"] = Rational(z2);
    read.allow_out_of_tolerance = true;
    Model model = read_model_file(example("spur-gears.json"), read);
    CSpaceBuildOptions options;
    options.operating_region = true;
    for (const PairBuild& pair : CSpace::build_pairs(model, options)) {
      ASSERT_EQ(pair.status, PairBuild::Status::built);
      EXPECT_FALSE(pair.space->complete());
      EXPECT_GT(pair.space->edges().size(), 100u);
      expect_same_text(*pair.space, "spur gears " + std::to_string(z1) + "x" + std::to_string(z2));
    }
  }
}

// ------------------------------------------------------------- generated spaces

// Disks blocked inside, centres and radii of `unit` = 2^k: the curves' coefficients reach 2^2000.
CSpace disk_space(std::mt19937_64& random, long k, const std::string& first, const std::string& second,
                          const std::vector<std::string>& labels) {
  const mpz_class power = mpz_class(1) << static_cast<mp_bitcnt_t>(std::labs(k));
  // x = unit * X: with u = 2^k, a disk (X - a)^2 + (Y - b)^2 < r^2 is, in x and y,
  //   k >= 0: x^2 - 2 a u x + y^2 - 2 b u y + (a^2 + b^2 - r^2) u^2 < 0
  //   k < 0 (times 1/u^2): v^2 x^2 - 2 a v x + v^2 y^2 - 2 b v y + (a^2 + b^2 - r^2) < 0, v = 1/u
  std::vector<cspace::IntegerPolynomial2> disks;
  cspace::PairInput input;
  input.first_part = input.x_part = first;
  input.second_part = input.y_part = second;
  input.part_names = {first, second};
  cspace::ChartInput chart;
  const Rational unit = k >= 0 ? Rational(power) : Rational(mpz_class(1), power);
  using Axis = cspace::ChartAxis;
  chart.x = Axis{Axis::Kind::translation, false, Rational(-100) * unit, Rational(100) * unit};
  chart.y = Axis{Axis::Kind::translation, false, Rational(-100) * unit, Rational(100) * unit};
  for (std::size_t d = 0; d < labels.size(); ++d) {
    const long a = static_cast<long>(random() % 121) - 60, b = static_cast<long>(random() % 121) - 60;
    const long r = 5 + static_cast<long>(random() % 30);
    const mpz_class square = a * a + b * b - r * r;
    cspace::IntegerPolynomial2 f;
    f.coefficients.assign(3, std::vector<mpz_class>(3));
    if (k >= 0) {
      f.coefficients[2][0] = 1;
      f.coefficients[0][2] = 1;
      f.coefficients[1][0] = -2 * a * power;
      f.coefficients[0][1] = -2 * b * power;
      f.coefficients[0][0] = square * power * power;
    } else {
      f.coefficients[2][0] = power * power;
      f.coefficients[0][2] = power * power;
      f.coefficients[1][0] = -2 * a * power;
      f.coefficients[0][1] = -2 * b * power;
      f.coefficients[0][0] = square;
    }
    cspace::ContactCurve curve;
    curve.polynomial = f;
    curve.label = labels[d];
    curve.first = cspace::FeatureRef{0, 0, d, FeatureKind::vertex};
    curve.second = cspace::FeatureRef{1, 0, d, FeatureKind::arc};
    chart.curves.push_back(curve);
    disks.push_back(f);
  }
  chart.classify = [disks](const cspace::ChartPoint& q) {
    int least = 1;
    for (const cspace::IntegerPolynomial2& f : disks) least = std::min(least, cspace::algebra::sign_at(f, q.x, q.y));
    using cspace::Overlap;
    return least < 0 ? Overlap::overlapping : least == 0 ? Overlap::touching : Overlap::apart;
  };
  input.charts.push_back(std::move(chart));
  return cspace::build_cspace(std::move(input), {});
}

TEST(CSpaceJsonText, GeneratedSpacesAtEveryScaleAsTheTreeWroteThem) {
  std::mt19937_64 random(32);
  const std::vector<std::string> names = {"a", "gear \"one\"", "back\\slash", "tab\there", "caf\xc3\xa9", "line\nbreak",
                                          "bell\x07", "\xe2\x82\xac euro", "emoji \xf0\x9f\x98\x80", "del\x7f"};
  std::size_t exponents_seen = 0, vertices = 0;
  for (long k : {-1000L, -999L, -520L, -170L, -53L, -20L, -1L, 0L, 1L, 20L, 53L, 170L, 520L, 999L, 1000L}) {
    std::vector<std::string> labels;
    const std::size_t count = 1 + random() % 3;
    for (std::size_t d = 0; d < count; ++d) labels.push_back(names[random() % names.size()] + " / " + names[random() % names.size()]);
    CSpace space = disk_space(random, k, names[random() % names.size()], names[random() % names.size()], labels);
    vertices += space.vertices().size();
    const std::string text = streamed_text(space, false);
    exponents_seen += text.find("e+") != std::string::npos || text.find("e-") != std::string::npos;
    expect_same_text(space, "disks at 2^" + std::to_string(k));
  }
  EXPECT_GE(exponents_seen, 6u);
  EXPECT_GT(vertices, 40u);
}

// ------------------------------------------------------------- the text writer on generated documents

// Writes a tree with JsonText (objects' members in the tree's order: nlohmann's sorted keys).
void write_tree(cli::JsonText& text, const json& value) {
  switch (value.type()) {
    case json::value_t::object:
      text.begin_object();
      for (const auto& [key, member] : value.items()) {
        text.key(key);
        write_tree(text, member);
      }
      text.end_object();
      return;
    case json::value_t::array:
      text.begin_array();
      for (const json& element : value) write_tree(text, element);
      text.end_array();
      return;
    case json::value_t::string: text.string(value.get_ref<const std::string&>()); return;
    case json::value_t::boolean: text.boolean(value.get<bool>()); return;
    case json::value_t::number_unsigned: text.number(value.get<std::size_t>()); return;
    case json::value_t::number_integer: text.number(value.get<long>()); return;
    case json::value_t::number_float: text.number(value.get<double>()); return;
    default: text.null(); return;
  }
}

std::string written(const json& tree) {
  std::ostringstream out;
  cli::JsonText text(out);
  write_tree(text, tree);
  text.finish();
  return out.str();
}

double random_double(std::mt19937_64& random) {
  switch (random() % 6) {
    case 0: return std::bit_cast<double>(random());   // any bits: subnormals, NaNs, infinities
    case 1: return static_cast<double>(static_cast<long>(random() % 2000001) - 1000000);   // integers
    case 2: return std::ldexp(static_cast<double>(random() % 1000000), static_cast<int>(random() % 120) - 80);
    case 3: return std::pow(10.0, static_cast<int>(random() % 60) - 30) * (random() % 2 ? 1 : -1);   // near the format's switches
    case 4: {
      const double specials[] = {0.0, -0.0, 1e-4, 1e-5, 9.999999999999999e-5, 1e15, 1e16, 123456789012345.6,
                                 1234567890123456.0, 5e-324, std::numeric_limits<double>::max(),
                                 std::numeric_limits<double>::min(), std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
                                 0.1, 1.0 / 3.0, 2.0 / 3.0, 100.0, 1e21, 1e22};
      return specials[random() % (sizeof specials / sizeof specials[0])];
    }
    default: return std::ldexp(std::uniform_real_distribution<double>(-1, 1)(random), static_cast<int>(random() % 2100) - 1074);
  }
}

std::string random_string(std::mt19937_64& random, bool valid_utf8) {
  const std::string pieces[] = {"a", "Z", " ", "\"", "\\", "/", "\n", "\t", "\r", "\b", "\f", std::string(1, '\0'),
                                "\x01", "\x1f", "\x7f", "\xc3\xa9", "\xe2\x82\xac", "\xf0\x9f\x98\x80", "x^2 - 2 = 0",
                                "real root number 1"};
  std::string s;
  const std::size_t length = random() % 8;
  for (std::size_t i = 0; i < length; ++i) s += pieces[random() % (sizeof pieces / sizeof pieces[0])];
  if (!valid_utf8) s.insert(random() % (s.size() + 1), 1, static_cast<char>(0x80 + random() % 64));
  return s;
}

json random_tree(std::mt19937_64& random, int depth) {
  const int kind = static_cast<int>(random() % (depth > 0 ? 9 : 6));
  switch (kind) {
    case 0: return json(nullptr);
    case 1: return json(random() % 2 == 0);
    case 2: return json(static_cast<std::size_t>(random() >> (random() % 64)));
    case 3: return json(static_cast<long>(random()));
    case 4: return json(random_double(random));
    case 5: return json(random_string(random, true));
    case 6:
    case 7: {
      json object = json::object();
      const std::size_t members = random() % 5;
      for (std::size_t i = 0; i < members; ++i) object[random_string(random, true)] = random_tree(random, depth - 1);
      return object;
    }
    default: {
      json array = json::array();
      const std::size_t elements = random() % 5;
      for (std::size_t i = 0; i < elements; ++i) array.push_back(random_tree(random, depth - 1));
      return array;
    }
  }
}

TEST(CSpaceJsonText, NumbersAsNlohmannPrintsThem) {
  std::mt19937_64 random(1);
  json array = json::array();
  for (int i = 0; i < 200000; ++i) array.push_back(random_double(random));
  for (int i = 0; i < 20000; ++i) array.push_back(static_cast<std::size_t>(random() >> (random() % 64)));
  for (int i = 0; i < 20000; ++i) array.push_back(static_cast<long>(random() >> (random() % 64)) * (random() % 2 ? 1 : -1));
  array.push_back(std::numeric_limits<std::size_t>::max());
  array.push_back(std::numeric_limits<long>::min());
  array.push_back(std::numeric_limits<long>::max());
  const std::string oracle = array.dump(1);
  const std::string text = written(array);
  EXPECT_TRUE(oracle == text) << first_difference(oracle, text);
}

TEST(CSpaceJsonText, GeneratedDocumentsAsNlohmannDumpsThem) {
  std::mt19937_64 random(2);
  for (int i = 0; i < 3000; ++i) {
    const json tree = random_tree(random, 5);
    const std::string oracle = tree.dump(1);
    const std::string text = written(tree);
    ASSERT_TRUE(oracle == text) << first_difference(oracle, text);
  }
  // a document longer than the writer's buffer goes out in pieces, the same bytes
  json big = json::array();
  for (int i = 0; i < 12000; ++i) big.push_back(random_tree(random, 4));
  const std::string oracle = big.dump(1);
  ASSERT_GT(oracle.size(), std::size_t{1} << 18);
  EXPECT_TRUE(oracle == written(big)) << first_difference(oracle, written(big));
}

// Strings of 0 to 40 plain bytes with one byte of every value 0x00..0x7f (or a two-byte UTF-8
// character, or none) at every position, as keys and as values: the writer's plain-string test
// reads eight bytes at a time (session 53), so every byte position within a word and the tail
// are covered; the text is nlohmann's dump byte for byte.
TEST(CSpaceJsonText, EveryByteAtEveryPositionAsNlohmannDumpsIt) {
  std::mt19937_64 random(53);
  std::size_t strings = 0;
  for (std::size_t length = 0; length <= 40; ++length)
    for (std::size_t at = 0; at <= length; ++at) {
      json array = json::array();
      json object = json::object();
      for (int byte = -2; byte < 0x80; ++byte) {
        std::string s;
        for (std::size_t k = 0; k < length; ++k) s += static_cast<char>(0x20 + random() % 0x5f);   // printable
        if (byte == -1) s.insert(at, "\xc3\xa9");
        else if (byte >= 0) s.insert(at, 1, static_cast<char>(byte));
        array.push_back(s);
        object[s] = byte;
        ++strings;
      }
      const json tree = {{"keys", object}, {"values", array}};
      const std::string oracle = tree.dump(1);
      const std::string text = written(tree);
      ASSERT_TRUE(oracle == text) << "length " << length << ", at " << at << ": " << first_difference(oracle, text);
    }
  EXPECT_EQ(strings, 861u * 130u);
}

TEST(CSpaceJsonText, InvalidUtf8IsRefusedAsNlohmannRefusesIt) {
  std::mt19937_64 random(3);
  for (int i = 0; i < 200; ++i) {
    const std::string bad = random_string(random, false);
    EXPECT_THROW(json(bad).dump(1), json::type_error);
    std::ostringstream out;
    cli::JsonText text(out);
    text.begin_array();
    EXPECT_THROW(text.string(bad), json::type_error) << i;
  }
}

TEST(CSpaceJsonText, KeysOutOfOrderAndUnbalancedContainersAreRefused) {
  std::ostringstream out;
  {
    cli::JsonText text(out);
    text.begin_object();
    text.key("b").number(1L);
    EXPECT_THROW(text.key("a"), Error);   // nlohmann's map would put "a" first
    EXPECT_THROW(text.key("b"), Error);   // a key twice
    EXPECT_THROW(text.end_array(), Error);
    EXPECT_THROW(text.finish(), Error);
  }
  {
    cli::JsonText text(out);
    text.begin_object();
    EXPECT_THROW(text.number(1L), Error);   // a member needs a key
  }
  // keys compare as bytes, as std::string does: "a_b" < "ab" ('_' is 0x5f), "B" < "a", "\xc3\xa9" after "z"
  json tree = {{"ab", 1}, {"a_b", 2}, {"B", 3}, {"z", 4}, {"\xc3\xa9", 5}};
  EXPECT_EQ(tree.dump(1), written(tree));
}

TEST(CSpaceJsonText, PolynomialTextAsBefore) {
  std::mt19937_64 random(4);
  for (int i = 0; i < 5000; ++i) {
    std::vector<std::vector<mpz_class>> c(random() % 6);
    for (auto& row : c) {
      row.resize(random() % 6);
      for (auto& v : row) {
        switch (random() % 5) {
          case 0: v = 0; break;
          case 1: v = random() % 2 ? 1 : -1; break;
          case 2: v = static_cast<long>(random() % 2001) - 1000; break;
          default: {
            v = mpz_class(static_cast<unsigned long>(random())) << static_cast<mp_bitcnt_t>(random() % 700);
            if (random() % 2) v = -v;
          }
        }
      }
    }
    std::string text = "prefix ";
    cli::append_polynomial_text(text, c);
    ASSERT_EQ("prefix " + polynomial_text(c), text);
  }
}

// write_space_json remembers an irrational coordinate's texts and an edge polynomial's text per
// document (ExactNumberMemo, PolynomialTextMemo; session 69). The documents' bytes are checked
// against the tree above (EveryExampleModelsPairsAsTheTreeWroteThem: Geneva's 424 irrational
// coordinates are 118 numbers); here the memos themselves, on families whose hashes all collide
// (coefficients and ends equal in size and lowest limb, different above it): every number and
// polynomial gets its own texts, those it would be given anew, whatever was remembered before.
TEST(CSpaceJsonText, RememberedTextsAreEachNumbersAndPolynomialsOwn) {
  std::mt19937_64 random(test::test_seed(69));
  const mpz_class limb = mpz_class(1) << 64;
  // x^2 - a, a = k 2^64 + 2 (two limbs, the lowest 2), in (0, 2^40): the positive root sqrt(a)
  std::vector<AlgebraicNumber> numbers;
  std::vector<int> ks;
  for (int n = 0; n < 12; ++n) {
    int k = 1 + static_cast<int>(random() % 4000);
    AlgebraicNumber a;
    a.polynomial = {-(k * limb + 2), 0, 1};
    a.lower = 0;
    a.upper = Rational(mpz_class(1) << 40);
    numbers.push_back(a);
    ks.push_back(k);
  }
  const std::size_t bucket = cli::ExactNumberMemo::hash(numbers.front(), 0);
  for (const AlgebraicNumber& n : numbers) ASSERT_EQ(bucket, cli::ExactNumberMemo::hash(n, 0));   // all collide
  cli::ExactNumberMemo memo;
  std::size_t made = 0;
  for (int round = 0; round < 3; ++round)
    for (std::size_t m = 0; m < numbers.size(); ++m) {
      const AlgebraicNumber& n = numbers[(m * 5 + static_cast<std::size_t>(round)) % numbers.size()];
      for (const char* variable : {"x", "y"})
        for (long unit : {0L, -3L}) {
          const std::size_t h = cli::ExactNumberMemo::hash(n, unit);
          const cli::ExactNumberMemo::Text* text = memo.find(n, variable, unit, h);
          if (!text) {
            cli::ExactNumberMemo::Text fresh;
            fresh.decimal = n.approximate();
            fresh.exact = n.to_string(variable) + (unit != 0 ? " (mm)" : "");   // (the unit's texts differ)
            fresh.lower = to_exact_string(n.lower);
            fresh.upper = to_exact_string(n.upper);
            text = &memo.add(n, variable, unit, h, fresh);
            ++made;
          }
          SCOPED_TRACE(n.to_string(variable));
          EXPECT_EQ(n.approximate(), text->decimal);
          EXPECT_EQ(n.to_string(variable) + (unit != 0 ? " (mm)" : ""), text->exact);
          EXPECT_EQ(to_exact_string(n.lower), text->lower);
          EXPECT_EQ(to_exact_string(n.upper), text->upper);
        }
    }
  std::sort(ks.begin(), ks.end());
  const auto distinct = static_cast<std::size_t>(std::unique(ks.begin(), ks.end()) - ks.begin());
  EXPECT_EQ(distinct * 4, made);   // one per number, variable and unit: each made once
  // an exact number with the same polynomial and ends is another key
  AlgebraicNumber exact_one = numbers.front();
  exact_one.exact = true;
  EXPECT_EQ(nullptr, memo.find(exact_one, "x", 0, cli::ExactNumberMemo::hash(exact_one, 0)));

  // polynomials: c[i][j] = k_ij 2^64 + 5 (all one bucket), against append_polynomial_text
  cli::PolynomialTextMemo texts;
  std::vector<std::vector<std::vector<mpz_class>>> polynomials;
  for (int n = 0; n < 10; ++n) {
    std::vector<std::vector<mpz_class>> c(3, std::vector<mpz_class>(3));
    for (auto& row : c)
      for (auto& v : row) v = static_cast<long>(1 + random() % 3) * limb + 5;
    polynomials.push_back(c);
  }
  for (const auto& c : polynomials) ASSERT_EQ(cli::PolynomialTextMemo::hash(polynomials.front(), 0, 0),
                                              cli::PolynomialTextMemo::hash(c, 0, 0));
  for (int round = 0; round < 3; ++round)
    for (const auto& c : polynomials) {
      std::string fresh;
      cli::append_polynomial_text(fresh, c);
      if (round == 0) texts.text(c, 2, 0);   // the same coefficients in other units first
      EXPECT_EQ(fresh, texts.text(c, 0, 0));
    }
}

}  // namespace
}  // namespace hipair
