// `hipair cspace --json` for 1-D and 2-D C-spaces, written as text (cspace_json.hpp).
#include "cli/cspace_json.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

// nlohmann's own number printer (Grisu2, as dump() prints a double) and, for the rare string
// that needs escapes, its serializer: the text is nlohmann's by construction, not by imitation.
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>

namespace hipair::cli {

namespace {

constexpr std::size_t spill_size = std::size_t{1} << 16;

// A string nlohmann writes as it is: printable ASCII without '"' and '\\'.
bool plain(std::string_view value) {
  for (char c : value) {
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
  text_ += level.empty ? "\n" : ",\n";
  level.empty = false;
  text_.append(depth_, ' ');
  quoted(name);
  text_ += ": ";
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

void write_axis(JsonText& json, AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
  json.begin_object();
  json.key("chart_center").string(kind == AxisKind::rotation ? (half_turn ? "pi" : "0") : "-");
  json.key("hi").string(to_exact_string(hi));
  json.key("kind").string(axis_kind_name(kind));
  json.key("lo").string(to_exact_string(lo));
  json.end_object();
}

void write_exact_number(JsonText& json, const AlgebraicNumber& n, const char* variable) {
  json.begin_object();
  json.key("decimal").number(n.approximate());
  json.key("exact").string(n.to_string(variable));
  if (!n.exact) {
    json.key("interval").begin_array();
    json.string(to_exact_string(n.lower));
    json.string(to_exact_string(n.upper));
    json.end_array();
  }
  json.end_object();
}

void write_range(JsonText& json, const CertifiedRange& range) {
  json.begin_array();
  json.number(range.lower);
  json.number(range.upper);
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

void write_cell(JsonText& json, const CSpaceCell& cell) {
  json.begin_object();
  json.key("boundary_edges").numbers(cell.boundary);
  json.key("faces").number(cell.faces);
  json.key("kind").string(cell_kind_name(cell.kind));
  json.key("neighbours").numbers(cell.neighbours);
  json.key("sample").begin_object();
  json.key("chart").number(cell.sample_chart);
  json.key("x").string(to_exact_string(cell.sample_x));
  json.key("y").string(to_exact_string(cell.sample_y));
  json.end_object();
  json.key("wraps_x").boolean(cell.wraps_x);
  json.key("wraps_y").boolean(cell.wraps_y);
  json.end_object();
}

void write_vertex(JsonText& json, const CSpace& space, const CSpaceVertex& vertex, std::string& scratch) {
  json.begin_object();
  json.key("chart").number(vertex.chart);
  json.key("contact_change").boolean(vertex.contact_change);
  json.key("edges").numbers(vertex.edges);
  json.key("feature_pairs").numbers(vertex.curves);
  json.key("on_chart_boundary").boolean(vertex.on_chart_boundary);
  json.key("touching").boolean(vertex.touching);
  json.key("x");
  write_exact_number(json, vertex.x, "x");
  if (space.dimension() == 2) {
    json.key("y");
    if (vertex.y_exact) {
      write_exact_number(json, vertex.y, "y");
    } else {
      json.begin_object();
      const Rational middle = (vertex.y_lower + vertex.y_upper) / 2;
      json.key("decimal").number(middle.get_d());
      scratch.assign("real root number ");
      char digits[16];
      scratch.append(digits, std::to_chars(digits, digits + sizeof digits, vertex.y_branch).ptr);
      scratch += " (ascending, from 0) in y of ";
      append_polynomial_text(scratch, vertex.y_curve);
      scratch += " at this x";
      json.key("exact").string(scratch);
      json.key("interval").begin_array();
      json.string(to_exact_string(vertex.y_lower));
      json.string(to_exact_string(vertex.y_upper));
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

void write_edge(JsonText& json, const CSpace& space, std::size_t e, std::string& scratch) {
  const CSpaceEdge& edge = space.edges()[e];
  json.begin_object();
  json.key("chart").number(edge.chart);
  json.key("extent_chart").begin_object();
  json.key("x");
  write_range(json, edge.x_chart);
  json.key("y");
  write_range(json, edge.y_chart);
  json.end_object();
  json.key("extent_coordinates").begin_object();
  json.key("x");
  write_range(json, edge.x_coordinate);
  json.key("y");
  write_range(json, edge.y_coordinate);
  json.end_object();
  json.key("feature_pairs").numbers(edge.curves);
  json.key("left_cell");
  write_cell_index(json, edge.left_cell);
  scratch.clear();
  append_polynomial_text(scratch, space.edge_polynomial_coefficients(e));
  json.key("polynomial").string(scratch);
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
  for (const CSpaceCell& cell : space.cells()) write_cell(json, cell);
  json.end_array();
  json.key("charts").begin_array();
  for (const CSpaceChart& chart : space.charts()) {
    json.begin_object();
    json.key("x");
    write_axis(json, chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi);
    if (two) {
      json.key("y");
      write_axis(json, chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi);
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
    for (std::size_t e = 0; e < space.edges().size(); ++e) write_edge(json, space, e, scratch);
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
  for (const CSpaceVertex& vertex : space.vertices()) write_vertex(json, space, vertex, scratch);
  json.end_array();
  json.key("x_part").string(space.x_part());
  if (two) json.key("y_part").string(space.y_part());
  json.end_object();
  json.finish();
  out << "\n";
}

}  // namespace hipair::cli
