// `hipair cspace --json` for 1-D and 2-D C-spaces, written as text (cspace_json.hpp).
#include "cli/cspace_json.hpp"

#include "core/model_scale.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

// nlohmann's own number printer (Grisu2, as dump() prints a double) and, for the rare string
// that needs escapes, its serializer: the text is nlohmann's by construction, not by imitation.
#include <nlohmann/json.hpp>

#include <mpfr.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace hipair::cli {

namespace {

constexpr std::size_t spill_size = std::size_t{1} << 16;

// A string nlohmann writes as it is: printable ASCII without '"' and '\\'.
// (Eight bytes at a time first: the polynomial texts are most of a large space's bytes. Each
// word test is exact as a yes/no answer — some byte >= 0x80, some byte < 0x20 (of bytes below
// 0x80), some byte equal to '"' or '\\' — so the answer is the byte loop's.)
bool plain(std::string_view value) {
  constexpr std::uint64_t ones = 0x0101010101010101ULL, highs = 0x8080808080808080ULL;
  auto has_zero = [](std::uint64_t v) { return ((v - ones) & ~v & highs) != 0; };
  std::size_t i = 0;
  for (; i + 8 <= value.size(); i += 8) {
    std::uint64_t w;
    std::memcpy(&w, value.data() + i, sizeof w);
    if ((w & highs) != 0) return false;                       // a byte >= 0x80
    if (((w - ones * 0x20) & ~w & highs) != 0) return false;  // a byte < 0x20 (every byte < 0x80)
    if (has_zero(w ^ (ones * '"')) || has_zero(w ^ (ones * '\\'))) return false;
  }
  for (; i < value.size(); ++i) {
    const char c = value[i];
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x80 || c == '"' || c == '\\') return false;
  }
  return true;
}

}  // namespace

JsonText::JsonText(std::ostream& out) : out_(out) { text_.reserve(spill_size + 4096); }

void JsonText::spill() {
  if (text_.size() < spill_size) return;
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void JsonText::before_value() {
  spill();
  if (depth_ == 0) return;
  Level& level = top();
  if (level.object) {
    if (!after_key_) throw Error("cspace --json: internal: an object member without a key");
    after_key_ = false;
    return;
  }
  text_ += level.empty ? "\n" : ",\n";
  level.empty = false;
  text_.append(depth_, ' ');
}

JsonText& JsonText::key(std::string_view name) {
  if (depth_ == 0 || !top().object || after_key_)
    throw Error("cspace --json: internal: a key outside an object");
  Level& level = top();
  if (!level.empty && !(std::string_view(level.last_key) < name))
    throw Error("cspace --json: internal: key '" + std::string(name) + "' after '" + level.last_key +
                "' (an object's keys are written in ascending order)");
  if (plain(name)) {
    // the member's text in one piece: [","] "\n", the indentation, the quoted name, ": "
    const std::size_t start = text_.size(), comma = level.empty ? 0 : 1;
    text_.resize(start + comma + 1 + depth_ + name.size() + 4);
    char* at = text_.data() + start;
    if (comma) *at++ = ',';
    *at++ = '\n';
    std::memset(at, ' ', depth_);
    at += depth_;
    *at++ = '"';
    std::memcpy(at, name.data(), name.size());
    at += name.size();
    std::memcpy(at, "\": ", 3);
  } else {
    text_ += level.empty ? "\n" : ",\n";
    text_.append(depth_, ' ');
    quoted(name);
    text_ += ": ";
  }
  level.empty = false;
  level.last_key.assign(name);
  after_key_ = true;
  return *this;
}

void JsonText::open(bool object, char bracket) {
  before_value();
  text_ += bracket;
  if (depth_ == levels_.size()) levels_.emplace_back();
  Level& level = levels_[depth_++];
  level.object = object;
  level.empty = true;
}

void JsonText::close(char bracket) {
  const Level& level = top();
  if (!level.empty) {
    text_ += '\n';
    text_.append(depth_ - 1, ' ');
  }
  text_ += bracket;
  --depth_;
}

void JsonText::begin_object() { open(true, '{'); }
void JsonText::begin_array() { open(false, '['); }

void JsonText::end_object() {
  if (depth_ == 0 || !top().object || after_key_) throw Error("cspace --json: internal: unbalanced object");
  close('}');
}

void JsonText::end_array() {
  if (depth_ == 0 || top().object) throw Error("cspace --json: internal: unbalanced array");
  close(']');
}

void JsonText::quoted(std::string_view value) {
  if (plain(value)) {
    text_ += '"';
    text_.append(value);
    text_ += '"';
  } else {
    text_ += nlohmann::json(std::string(value)).dump();
  }
}

void JsonText::string(std::string_view value) {
  before_value();
  quoted(value);
}

void JsonText::boolean(bool value) {
  before_value();
  text_ += value ? "true" : "false";
}

void JsonText::null() {
  before_value();
  text_ += "null";
}

void JsonText::number(std::size_t value) {
  before_value();
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
  text_.append(digits, static_cast<std::size_t>(end - digits));
}

void JsonText::number(long value) {
  before_value();
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
  text_.append(digits, static_cast<std::size_t>(end - digits));
}

void JsonText::number(double value) {
  before_value();
  if (!std::isfinite(value)) {
    text_ += "null";
    return;
  }
  char digits[64];
  const char* end = nlohmann::detail::to_chars(digits, digits + sizeof digits, value);
  text_.append(digits, static_cast<std::size_t>(end - digits));
}

void JsonText::numbers(const std::vector<std::size_t>& values) {
  begin_array();
  for (std::size_t value : values) number(value);
  end_array();
}

void JsonText::finish() {
  if (!depth_ == 0 || after_key_) throw Error("cspace --json: internal: the document is not closed");
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void append_polynomial_text(std::string& text, const std::vector<std::vector<mpz_class>>& c) {
  // x^i y^j terms, highest first
  const std::size_t start = text.size();
  char exponent[24];
  auto power = [&](char variable, int e) {
    text += variable;
    if (e > 1) {
      text += '^';
      text.append(exponent, std::to_chars(exponent, exponent + sizeof exponent, e).ptr);
    }
  };
  for (int i = static_cast<int>(c.size()) - 1; i >= 0; --i)
    for (int j = static_cast<int>(c[static_cast<std::size_t>(i)].size()) - 1; j >= 0; --j) {
      const mpz_class& v = c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      const int sign = sgn(v);
      if (sign == 0) continue;
      if (text.size() == start) {
        if (sign < 0) text += '-';
      } else {
        text += sign < 0 ? " - " : " + ";
      }
      const bool unit = mpz_cmpabs_ui(v.get_mpz_t(), 1) == 0 && (i > 0 || j > 0);
      if (!unit) {
        // |v| in decimal, in place (mpz_sizeinbase may exceed the digits by one)
        const std::size_t at = text.size();
        text.resize(at + mpz_sizeinbase(v.get_mpz_t(), 10) + 2);
        mpz_get_str(text.data() + at, 10, v.get_mpz_t());
        std::size_t length = std::char_traits<char>::length(text.data() + at);
        if (text[at] == '-') {
          text.erase(at, 1);
          --length;
        }
        text.resize(at + length);
        if (i > 0 || j > 0) text += '*';
      }
      if (i > 0) power('x', i);
      if (j > 0) {
        if (i > 0) text += '*';
        power('y', j);
      }
    }
  if (text.size() == start) text += '0';
}

const char* role_name(EdgeRole role) {
  switch (role) {
    case EdgeRole::contact: return "contact";
    case EdgeRole::spurious: return "spurious";
    case EdgeRole::seam: return "seam";
    case EdgeRole::limit: return "limit";
    case EdgeRole::touching: return "touching";
  }
  return "?";
}

const char* cell_kind_name(CellKind kind) {
  return kind == CellKind::free ? "free" : kind == CellKind::blocked ? "blocked" : "touching";
}

namespace {

const char* axis_kind_name(AxisKind kind) { return kind == AxisKind::rotation ? "rotation" : "translation"; }

// The members of every object below are written in ascending order of their keys.

// A space built with lengths in units of 2^L mm (CSpace::length_unit_exponent): the exponent
// of each chart axis's unit (L on a translation axis, 0 on a rotation axis, and 0 everywhere
// for every other space). Its numbers are written in mm: exact ones mapped exactly, a double
// d as a string holding the decimal of d * 2^exponent (17 significant digits, exponent from the
// exact product: 1e400 has no double, and JSON readers overflow on the number 1e400).
long axis_unit(const CSpace& space, AxisKind kind) {
  return kind == AxisKind::translation ? space.length_unit_exponent() : 0;
}

Rational in_mm(const Rational& value, long exponent) { return times_power_of_two(value, exponent); }

// p(x / 2^ex, y / 2^ey) times the least power of two that keeps the coefficients integers:
// the curve of p in the units 2^ex, 2^ey mm, in mm (c[i][j] of x^i y^j).
std::vector<std::vector<mpz_class>> polynomial_in_mm(std::vector<std::vector<mpz_class>> c, long ex, long ey) {
  if (ex == 0 && ey == 0) return c;
  long top = 0;
  bool any = false;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j)
      if (sgn(c[i][j]) != 0) {
        const long weight = static_cast<long>(i) * ex + static_cast<long>(j) * ey;
        top = any ? std::max(top, weight) : weight;
        any = true;
      }
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < c[i].size(); ++j)
      mpz_mul_2exp(c[i][j].get_mpz_t(), c[i][j].get_mpz_t(),
                   static_cast<mp_bitcnt_t>(top - static_cast<long>(i) * ex - static_cast<long>(j) * ey));
  return c;
}

AlgebraicNumber in_mm(const AlgebraicNumber& n, long exponent) {
  if (exponent == 0) return n;
  std::vector<std::vector<mpz_class>> c;
  for (const mpz_class& a : n.polynomial) c.push_back({a});
  AlgebraicNumber m = n;
  m.polynomial.clear();
  for (const auto& a : polynomial_in_mm(std::move(c), exponent, 0)) m.polynomial.push_back(a.front());
  m.lower = in_mm(n.lower, exponent);
  m.upper = in_mm(n.upper, exponent);
  return m;
}

// The decimal text of d * 2^exponent, rounded as `round` to 17 significant digits.
std::string decimal_in_mm(double value, long exponent, mpfr_rnd_t round) {
  mpfr_t x;
  mpfr_init2(x, 64);
  mpfr_set_d(x, value, MPFR_RNDN);           // exact (64 >= 53 bits)
  mpfr_mul_2si(x, x, exponent, MPFR_RNDN);   // exact (MPFR's exponent range is about 2^62)
  std::string text;
  if (mpfr_zero_p(x)) {
    text = "0.0";
  } else {
    mpfr_exp_t decimal_exponent = 0;
    char* digits = mpfr_get_str(nullptr, &decimal_exponent, 10, 17, x, round);
    std::string d(digits);
    mpfr_free_str(digits);
    if (d.front() == '-') {
      text = "-";
      d.erase(0, 1);
    }
    while (d.size() > 1 && d.back() == '0') d.pop_back();
    text += d.substr(0, 1) + "." + (d.size() > 1 ? d.substr(1) : std::string("0")) + "e" +
            std::to_string(static_cast<long>(decimal_exponent) - 1);
  }
  mpfr_clear(x);
  return text;
}

void write_axis(JsonText& json, AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi, long unit) {
  json.begin_object();
  json.key("chart_center").string(kind == AxisKind::rotation ? (half_turn ? "pi" : "0") : "-");
  json.key("hi").string(to_exact_string(in_mm(hi, unit)));
  json.key("kind").string(axis_kind_name(kind));
  json.key("lo").string(to_exact_string(in_mm(lo, unit)));
  json.end_object();
}

void write_decimal(JsonText& json, double value, long unit, mpfr_rnd_t round = MPFR_RNDN) {
  if (unit == 0)
    json.number(value);
  else
    json.string(decimal_in_mm(value, unit, round));   // a string: 1e400 overflows JSON readers' doubles
}

}  // namespace

// ---------------------------------------------------------------- the texts remembered per space

const ExactNumberMemo::Text* ExactNumberMemo::find(const AlgebraicNumber& given, const char* variable, long unit,
                                                   std::size_t hash) const {
  const auto it = entries_.find(hash);
  if (it == entries_.end()) return nullptr;
  for (const Entry& e : it->second)
    if (e.unit == unit && e.variable == variable && e.number.exact == given.exact && e.number.lower == given.lower &&
        e.number.upper == given.upper && e.number.polynomial == given.polynomial)
      return &e.text;
  return nullptr;
}

const ExactNumberMemo::Text& ExactNumberMemo::add(const AlgebraicNumber& given, const char* variable, long unit,
                                                  std::size_t hash, Text text) {
  auto& bucket = entries_[hash];
  bucket.push_back(Entry{given, variable, unit, std::move(text)});
  return bucket.back().text;
}

namespace {
// (a coefficient's size and lowest limb: numbers that differ only above it share a bucket and
// are told apart by the exact comparison)
void mix_limb(std::size_t& h, const mpz_t z) {
  const std::size_t limb = mpz_size(z) > 0 ? static_cast<std::size_t>(mpz_getlimbn(z, 0)) : 0;
  h = (h ^ (limb + static_cast<std::size_t>(static_cast<long>(z->_mp_size)) * 0x100000001b3ULL)) * 0x9e3779b97f4a7c15ULL;
  h ^= h >> 29;
}
}  // namespace

std::size_t ExactNumberMemo::hash(const AlgebraicNumber& n, long unit) {
  std::size_t h = std::hash<long>{}(unit) ^ (n.polynomial.size() * 0x9e3779b97f4a7c15ULL);
  for (const mpz_class& c : n.polynomial) mix_limb(h, c.get_mpz_t());
  mix_limb(h, mpq_numref(n.lower.get_mpq_t()));
  mix_limb(h, mpq_denref(n.lower.get_mpq_t()));
  mix_limb(h, mpq_numref(n.upper.get_mpq_t()));
  mix_limb(h, mpq_denref(n.upper.get_mpq_t()));
  return h;
}

std::size_t PolynomialTextMemo::hash(const Coefficients& c, long x_unit, long y_unit) {
  std::size_t h = std::hash<long>{}(x_unit) * 31 + std::hash<long>{}(y_unit) + c.size() * 0x9e3779b97f4a7c15ULL;
  for (const auto& row : c) {
    h = (h ^ row.size()) * 0x100000001b3ULL;
    for (const mpz_class& v : row) mix_limb(h, v.get_mpz_t());
  }
  return h;
}

const std::string& PolynomialTextMemo::text(const Coefficients& c, long x_unit, long y_unit) {
  auto& bucket = entries_[hash(c, x_unit, y_unit)];
  for (const Entry& e : bucket)
    if (e.x_unit == x_unit && e.y_unit == y_unit && e.coefficients == c) return e.text;
  std::string made;
  if (x_unit == 0 && y_unit == 0)
    append_polynomial_text(made, c);
  else
    append_polynomial_text(made, polynomial_in_mm(c, x_unit, y_unit));
  bucket.push_back(Entry{c, x_unit, y_unit, std::move(made)});
  return bucket.back().text;
}

namespace {

void write_exact_number(JsonText& json, const AlgebraicNumber& given, const char* variable, long unit,
                        ExactNumberMemo& memo) {
  if (!given.exact) {
    // (an irrational number: its texts remembered, see ExactNumberMemo)
    const std::size_t hash = ExactNumberMemo::hash(given, unit);
    const ExactNumberMemo::Text* text = memo.find(given, variable, unit, hash);
    if (!text) {
      std::optional<AlgebraicNumber> scaled;
      if (unit != 0) scaled = in_mm(given, unit);
      const AlgebraicNumber& n = scaled ? *scaled : given;
      ExactNumberMemo::Text made;
      made.decimal = given.approximate();
      made.exact = n.to_string(variable);
      made.lower = to_exact_string(n.lower);
      made.upper = to_exact_string(n.upper);
      text = &memo.add(given, variable, unit, hash, std::move(made));
    }
    json.begin_object();
    json.key("decimal");
    write_decimal(json, text->decimal, unit);
    json.key("exact").string(text->exact);
    json.key("interval").begin_array();
    json.string(text->lower);
    json.string(text->upper);
    json.end_array();
    json.end_object();
    return;
  }
  // (a number of a rotation axis, unit 0, is written as it is: no copy)
  std::optional<AlgebraicNumber> scaled;
  if (unit != 0) scaled = in_mm(given, unit);
  const AlgebraicNumber& n = scaled ? *scaled : given;
  json.begin_object();
  json.key("decimal");
  write_decimal(json, given.approximate(), unit);
  json.key("exact").string(n.to_string(variable));
  json.end_object();
}

void write_range(JsonText& json, const CertifiedRange& range, long unit) {
  json.begin_array();
  write_decimal(json, range.lower, unit, MPFR_RNDD);   // outward: still an enclosure
  write_decimal(json, range.upper, unit, MPFR_RNDU);
  json.end_array();
}

void write_statistics(JsonText& json, const CSpaceStatistics& s, bool with_seconds) {
  json.begin_object();
  json.key("cells").number(s.cells);
  json.key("charts").number(s.charts);
  json.key("circle_segment_charts").number(s.circle_segment_charts);
  json.key("contact_edges").number(s.contact_edges);
  json.key("curves").number(s.curves);
  json.key("edges").number(s.edges);
  json.key("faces").number(s.faces);
  json.key("feature_pairs_considered").number(s.feature_pairs_considered);
  json.key("feature_pairs_culled").number(s.feature_pairs_culled);
  json.key("pieces_inserted").number(s.pieces_inserted);
  json.key("quadratic_charts").number(s.quadratic_charts);
  json.key("region_cells").number(s.region_cells);
  json.key("region_tiles").number(s.region_tiles);
  // wall times differ from run to run: only with --stats, so that the same input gives the same bytes
  if (with_seconds) {
    json.key("seconds").begin_object();
    json.key("arrangement").number(s.seconds_arrangement);
    json.key("cells").number(s.seconds_cells);
    json.key("classification").number(s.seconds_classification);
    json.key("clipping").number(s.seconds_clipping);
    json.key("culling").number(s.seconds_culling);
    json.key("curves").number(s.seconds_curves);
    json.key("export").number(s.seconds_export);
    json.key("labelling").number(s.seconds_labelling);
    json.key("total").number(s.seconds_total);
    json.end_object();
  }
  json.key("touching_edges").number(s.touching_edges);
  json.key("touching_undecided").number(s.touching_undecided);
  json.key("touching_vertices").number(s.touching_vertices);
  json.key("vertices").number(s.vertices);
  json.end_object();
}

void write_cell(JsonText& json, const CSpace& space, const CSpaceCell& cell) {
  const CSpaceChart& chart = space.charts()[cell.sample_chart];
  json.begin_object();
  json.key("boundary_edges").numbers(cell.boundary);
  json.key("faces").number(cell.faces);
  json.key("kind").string(cell_kind_name(cell.kind));
  json.key("neighbours").numbers(cell.neighbours);
  json.key("sample").begin_object();
  json.key("chart").number(cell.sample_chart);
  json.key("x").string(to_exact_string(in_mm(cell.sample_x, axis_unit(space, chart.x_kind))));
  json.key("y").string(to_exact_string(in_mm(cell.sample_y, axis_unit(space, chart.y_kind))));
  json.end_object();
  json.key("wraps_x").boolean(cell.wraps_x);
  json.key("wraps_y").boolean(cell.wraps_y);
  json.end_object();
}

void write_vertex(JsonText& json, const CSpace& space, const CSpaceVertex& vertex, std::string& scratch,
                  ExactNumberMemo& memo) {
  json.begin_object();
  json.key("chart").number(vertex.chart);
  json.key("contact_change").boolean(vertex.contact_change);
  json.key("edges").numbers(vertex.edges);
  json.key("feature_pairs").numbers(vertex.curves);
  json.key("on_chart_boundary").boolean(vertex.on_chart_boundary);
  json.key("touching").boolean(vertex.touching);
  const CSpaceChart& chart = space.charts()[vertex.chart];
  const long x_unit = axis_unit(space, chart.x_kind), y_unit = axis_unit(space, chart.y_kind);
  json.key("x");
  write_exact_number(json, vertex.x, "x", x_unit, memo);
  if (space.dimension() == 2) {
    json.key("y");
    if (vertex.y_exact) {
      write_exact_number(json, vertex.y, "y", y_unit, memo);
    } else {
      json.begin_object();
      const Rational middle = (vertex.y_lower + vertex.y_upper) / 2;
      json.key("decimal");
      write_decimal(json, middle.get_d(), y_unit);
      scratch.assign("real root number ");
      char digits[16];
      scratch.append(digits, std::to_chars(digits, digits + sizeof digits, vertex.y_branch).ptr);
      scratch += " (ascending, from 0) in y of ";
      if (x_unit == 0 && y_unit == 0)
        append_polynomial_text(scratch, vertex.y_curve);
      else
        append_polynomial_text(scratch, polynomial_in_mm(vertex.y_curve, x_unit, y_unit));
      scratch += " at this x";
      json.key("exact").string(scratch);
      json.key("interval").begin_array();
      json.string(to_exact_string(in_mm(vertex.y_lower, y_unit)));
      json.string(to_exact_string(in_mm(vertex.y_upper, y_unit)));
      json.end_array();
      json.end_object();
    }
  }
  json.end_object();
}

void write_cell_index(JsonText& json, std::size_t cell) {
  if (cell == no_index)
    json.null();
  else
    json.number(cell);
}

void write_edge(JsonText& json, const CSpace& space, std::size_t e, PolynomialTextMemo& polynomials) {
  const CSpaceEdge& edge = space.edges()[e];
  const CSpaceChart& chart = space.charts()[edge.chart];
  const long x_unit = axis_unit(space, chart.x_kind), y_unit = axis_unit(space, chart.y_kind);
  json.begin_object();
  json.key("chart").number(edge.chart);
  json.key("extent_chart").begin_object();
  json.key("x");
  write_range(json, edge.x_chart, x_unit);
  json.key("y");
  write_range(json, edge.y_chart, y_unit);
  json.end_object();
  json.key("extent_coordinates").begin_object();
  json.key("x");
  write_range(json, edge.x_coordinate, x_unit);
  json.key("y");
  write_range(json, edge.y_coordinate, y_unit);
  json.end_object();
  json.key("feature_pairs").numbers(edge.curves);
  json.key("left_cell");
  write_cell_index(json, edge.left_cell);
  json.key("polynomial").string(polynomials.text(space.edge_polynomial_coefficients(e), x_unit, y_unit));
  json.key("real").boolean(edge.real);
  json.key("right_cell");
  write_cell_index(json, edge.right_cell);
  json.key("role").string(role_name(edge.role));
  json.key("source").number(edge.source);
  json.key("target").number(edge.target);
  json.key("vertical").boolean(edge.vertical);
  json.end_object();
}

}  // namespace

void write_space_json(std::ostream& out, const CSpace& space, bool with_seconds) {
  JsonText json(out);
  std::string scratch;
  const bool two = space.dimension() == 2;
  json.begin_object();
  json.key("cells").begin_array();
  for (const CSpaceCell& cell : space.cells()) write_cell(json, space, cell);
  json.end_array();
  json.key("charts").begin_array();
  for (const CSpaceChart& chart : space.charts()) {
    json.begin_object();
    json.key("x");
    write_axis(json, chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi, axis_unit(space, chart.x_kind));
    if (two) {
      json.key("y");
      write_axis(json, chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi, axis_unit(space, chart.y_kind));
    }
    json.end_object();
  }
  json.end_array();
  json.key("complete").boolean(space.complete());
  json.key("coordinates")
      .string("rotation charts use t = tan((theta - c)/2), c = 0 or pi; translation charts use the offset in mm");
  json.key("dimension").number(space.dimension());
  if (two) {
    json.key("edges").begin_array();
    PolynomialTextMemo polynomials;
    for (std::size_t e = 0; e < space.edges().size(); ++e) write_edge(json, space, e, polynomials);
    json.end_array();
  }
  json.key("feature_pairs").begin_array();
  for (const FeaturePair& pair : space.feature_pairs()) {
    json.begin_object();
    json.key("first_feature").string(pair.first_feature);
    json.key("first_part").string(pair.first_part);
    json.key("kind").string(to_string(pair.kind));
    json.key("label").string(pair.label);
    json.key("second_feature").string(pair.second_feature);
    json.key("second_part").string(pair.second_part);
    json.end_object();
  }
  json.end_array();
  json.key("pair").begin_array();
  json.string(space.first_part());
  json.string(space.second_part());
  json.end_array();
  json.key("statistics");
  write_statistics(json, space.statistics(), with_seconds);
  json.key("vertices").begin_array();
  ExactNumberMemo memo;
  for (const CSpaceVertex& vertex : space.vertices()) write_vertex(json, space, vertex, scratch, memo);
  json.end_array();
  json.key("x_part").string(space.x_part());
  if (two) json.key("y_part").string(space.y_part());
  json.end_object();
  json.finish();
  out << "\n";
}

}  // namespace hipair::cli
