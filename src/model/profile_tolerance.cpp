// Geometric profile tolerances translated into parametric offsets (see profile_tolerance.hpp,
// docs/model-format.md "Profile tolerances").
//
// Corners. The whole loop is offset by one parameter δ, so every corner has a closed form and
// the loop stays closed by construction (each vertex is written once, as an expression):
//   segment/segment  v' = v + δ (n1 + n2) / (1 + n1·n2)   (the intersection of the two
//                    offset lines; n1, n2 the outward unit normals, written with sqrt of the
//                    edge's squared length so that they follow the other parameters);
//   a corner with an arc must be tangent (smooth) at nominal, decided exactly:
//                    v' = v + δ n with n the arc's outward radial unit vector there, which
//                    keeps v' on the offset circle(s) of radius R ± δ;
//   a full circle    radius R ± δ.
// Exactness: a coordinate is an exact rational whenever the normal is (axis-parallel or
// Pythagorean edges; arcs whose nominal radius is rational, which is required); otherwise the
// reader's expression evaluation encloses it and rounds it to 10^-12 with a recorded
// Rounding, like every irrational value of a model. δ·(anything) at δ = 0 is exactly 0, so
// the nominal geometry is exactly the one the file gives.
#include "model/profile_tolerance.hpp"

#include "model/reader.hpp"

#include <hipair/error.hpp>

#include <gmp.h>

#include <optional>

namespace hipair::model_detail {
namespace {

JsonValue string_value(std::string text, std::string pointer) {
  JsonValue value;
  value.type = JsonValue::Type::string;
  value.text = std::move(text);
  value.pointer = std::move(pointer);
  return value;
}

JsonValue* find_mutable(JsonValue& object, std::string_view key) {
  for (JsonMember& member : object.members)
    if (member.key == key) return &member.value;
  return nullptr;
}

std::string paren(const std::string& text) { return "(" + text + ")"; }

bool is_rational_square(const Rational& value) {
  return value >= 0 && mpz_perfect_square_p(value.get_num_mpz_t()) && mpz_perfect_square_p(value.get_den_mpz_t());
}

struct PointText {
  std::string x, y;
};

PointText point_text(const JsonValue& value, const std::string& entry) {
  if (!value.is_array() || value.items.size() != 2)
    throw ModelError(value.pointer, "a profile tolerance (" + entry +
                                        ") needs the loop's points written as [x, y] (polar points are not supported)");
  return PointText{paren(value.items[0].text), paren(value.items[1].text)};
}

// Written edge i of a loop: what the offset needs.
struct WrittenEdge {
  bool arc = false;
  bool ccw = true;   // as written
  Point center;      // nominal value
  PointText center_text;
};

struct Normal {
  std::string x, y;  // texts of the outward unit normal
};

}  // namespace

bool has_profile_tolerances(const JsonValue& root) {
  const JsonValue* parts = root.find("parts");
  if (!parts || !parts->is_array()) return false;
  for (const JsonValue& part : parts->items)
    if (part.find("profile_tolerances")) return true;
  return false;
}

JsonValue strip_profile_tolerances(const JsonValue& root) {
  JsonValue copy = root;
  for (JsonMember& member : copy.members) {
    if (member.key != "parts" || !member.value.is_array()) continue;
    for (JsonValue& part : member.value.items)
      std::erase_if(part.members, [](const JsonMember& m) { return m.key == "profile_tolerances"; });
  }
  return copy;
}

namespace {

class Translator {
 public:
  Translator(JsonValue& root, const Model& nominal) : root_(root), nominal_(nominal) {}

  std::vector<ProfileTolerance> run() {
    JsonValue* parts = find_mutable(root_, "parts");
    for (std::size_t p = 0; p < parts->items.size(); ++p) {
      JsonValue& part = parts->items[p];
      JsonValue* entries = find_mutable(part, "profile_tolerances");
      if (!entries) continue;
      JsonValue list = *entries;
      std::erase_if(part.members, [](const JsonMember& m) { return m.key == "profile_tolerances"; });
      if (!list.is_array())
        throw ModelError(list.pointer, "profile_tolerances is an array of {\"loop\": k, \"tolerance\": t}");
      for (const JsonValue& entry : list.items) translate(part, p, entry);
    }
    return std::move(result_);
  }

 private:
  void translate(JsonValue& part, std::size_t p, const JsonValue& entry) {
    if (!entry.is_object())
      throw ModelError(entry.pointer, "a profile tolerance is an object {\"loop\": k, \"tolerance\": t}");
    for (const JsonMember& member : entry.members)
      if (member.key != "loop" && member.key != "feature" && member.key != "edge" && member.key != "tolerance" &&
          member.key != "distribution" && member.key != "parameter")
        throw ModelError(member.value.pointer, "unknown key '" + escape_pointer_token(member.key) +
                                                   "' (allowed: loop, feature, edge, tolerance, distribution, parameter)");
    const JsonValue* loop_index = entry.find("loop");
    const JsonValue* feature_index = entry.find("feature");
    if (!loop_index == !feature_index)
      throw ModelError(entry.pointer, "a profile tolerance names exactly one of 'loop' or 'feature'");
    const JsonValue* tolerance = entry.find("tolerance");
    if (!tolerance) throw ModelError(entry.pointer, "missing key 'tolerance' (the band's total width t, mm)");
    if (!tolerance->is_number() && !tolerance->is_string())
      throw ModelError(tolerance->pointer, "expected a number or expression (the band's total width, mm)");
    // A literal band is checked here (an expression is checked by the parameter reader, whose
    // message names the same pointer but the half width).
    std::optional<Rational> literal;
    if (tolerance->is_number()) {
      literal = parse_literal(tolerance->text, tolerance->pointer);
    } else {
      try {
        literal = parse_literal(tolerance->text, tolerance->pointer);
      } catch (const ModelError&) {  // not a literal: an expression such as "e" or "2*t"
      }
    }
    if (literal && *literal < 0)
      throw ModelError(tolerance->pointer, "a profile tolerance (band width) must not be negative (got " +
                                               decimal(*literal) + ")");
    const Part& read = nominal_.parts[p];
    bool is_loop = loop_index != nullptr;
    const JsonValue& index_value = is_loop ? *loop_index : *feature_index;
    const char* list_key = is_loop ? "loops" : "features";
    JsonValue* list = find_mutable(part, list_key);
    std::size_t count = list && list->is_array() ? list->items.size() : 0;
    std::size_t k = 0;
    bool ok = index_value.is_number();
    if (ok) {
      Rational r = parse_literal(index_value.text, index_value.pointer);
      ok = r >= 0 && r.get_den() == 1 && r < Rational(static_cast<long>(count));
      if (ok) k = r.get_num().get_ui();
    }
    if (!ok)
      throw ModelError(index_value.pointer, "part '" + read.name + "' has no " + (is_loop ? "loop " : "feature ") +
                                                quoted_excerpt(index_value.text) + " (it has " + std::to_string(count) +
                                                " " + list_key + ", numbered from 0)");
    JsonValue& target = list->items[k];
    // "edge": one segment of the loop instead of the whole loop.
    const JsonValue* edge_index = entry.find("edge");
    std::size_t edge = 0;
    if (edge_index) {
      if (!is_loop) throw ModelError(edge_index->pointer, "'edge' needs 'loop' (an edge of a written loop)");
      const JsonValue* written = target.find("edges");
      std::size_t edges = written && written->is_array() ? written->items.size() : 0;
      bool valid = edge_index->is_number();
      if (valid) {
        Rational r = parse_literal(edge_index->text, edge_index->pointer);
        valid = r >= 0 && r.get_den() == 1 && r < Rational(static_cast<long>(edges));
        if (valid) edge = r.get_num().get_ui();
      }
      if (!valid)
        throw ModelError(edge_index->pointer, "loop " + std::to_string(k) + " of part '" + read.name + "' has no edge " +
                                                  quoted_excerpt(edge_index->text) + " (it has " + std::to_string(edges) +
                                                  " written edges, numbered from 0)");
    }

    std::string name = "profile-" + std::to_string(p) + (is_loop ? "-loop-" : "-feature-") + std::to_string(k) +
                       (edge_index ? "-edge-" + std::to_string(edge) : std::string());
    if (const JsonValue* given = entry.find("parameter")) {
      if (!given->is_string()) throw ModelError(given->pointer, "expected a parameter name (a string)");
      name = given->text;
      bool valid = !name.empty() && std::isalpha(static_cast<unsigned char>(name[0]));
      for (char c : name) valid = valid && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
      if (!valid || name.back() == '-')
        throw ModelError(given->pointer, "invalid parameter name " + quoted_excerpt(name) +
                                             " (letters, digits, _ and -, starting with a letter)");
    }
    add_parameter(name, entry, *tolerance);
    std::string delta = paren(name);
    std::string what = entry.pointer;

    if (!is_loop) {
      if (!target.is_object() || target.members.size() != 1 ||
          (target.members.front().key != "circle" && target.members.front().key != "pin"))
        throw ModelError(index_value.pointer, "a profile tolerance on a feature needs a circle or pin template (" +
                                                  (target.is_object() && !target.members.empty()
                                                       ? "'" + target.members.front().key + "'"
                                                       : std::string("this feature")) +
                                                  " is not supported: write its loops explicitly)");
      JsonValue& arguments = target.members.front().value;
      const Loop* loop = find_loop(read, arguments.pointer, index_value);
      JsonValue* radius = find_mutable(arguments, "radius");
      if (!radius) throw ModelError(arguments.pointer, "template needs argument 'radius'");
      *radius = string_value(paren(radius->text) + (loop->is_hole ? " - " : " + ") + delta, radius->pointer);
      result_.push_back(ProfileTolerance{name, p, arguments.pointer, entry.pointer});
      return;
    }
    const Loop* loop = find_loop(read, target.pointer, index_value);
    if (edge_index) {
      if (find_mutable(target, "circle"))
        throw ModelError(edge_index->pointer, "a circle loop has no segment edge: band the whole loop instead");
      offset_edge(target, *loop, delta, what, edge, *edge_index);
      result_.push_back(ProfileTolerance{name, p, target.pointer, entry.pointer});
      return;
    }
    if (JsonValue* circle = find_mutable(target, "circle")) {
      JsonValue* radius = find_mutable(*circle, "radius");
      *radius = string_value(paren(radius->text) + (loop->is_hole ? " - " : " + ") + delta, radius->pointer);
      result_.push_back(ProfileTolerance{name, p, target.pointer, entry.pointer});
      return;
    }
    offset_loop(target, *loop, delta, what);
    result_.push_back(ProfileTolerance{name, p, target.pointer, entry.pointer});
  }

  const Loop* find_loop(const Part& read, const std::string& pointer, const JsonValue& index_value) {
    for (const Loop& loop : read.loops)
      if (loop.pointer == pointer) return &loop;
    throw ModelError(index_value.pointer, "internal error: the loop " + pointer + " was not read");
  }

  void add_parameter(const std::string& name, const JsonValue& entry, const JsonValue& tolerance) {
    JsonValue* parameters = find_mutable(root_, "parameters");
    if (!parameters) {
      JsonMember member;
      member.key = "parameters";
      member.value.type = JsonValue::Type::object;
      member.value.pointer = "/parameters";
      root_.members.push_back(std::move(member));
      parameters = &root_.members.back().value;
    }
    if (!parameters->is_object()) return;  // the reader reports the wrong type
    if (parameters->find(name))
      throw ModelError(entry.pointer, "the profile tolerance's parameter '" + name +
                                          "' is already a parameter (name it with \"parameter\")");
    for (const ProfileTolerance& earlier : result_)
      if (earlier.parameter == name)
        throw ModelError(entry.pointer, "the parameter '" + name + "' is also made by " + earlier.pointer);
    JsonValue definition;
    definition.type = JsonValue::Type::object;
    definition.pointer = entry.pointer;
    JsonValue nominal;
    nominal.type = JsonValue::Type::number;
    nominal.text = "0";
    nominal.pointer = entry.pointer;
    definition.members.push_back(JsonMember{"nominal", nominal});
    definition.members.push_back(JsonMember{"tolerance", string_value(paren(tolerance.text) + "/2", tolerance.pointer)});
    if (const JsonValue* distribution = entry.find("distribution"))
      definition.members.push_back(JsonMember{"distribution", *distribution});
    parameters->members.push_back(JsonMember{name, definition});
  }

  // Outward unit normal (texts) of written edge i at written vertex j (j = i or i + 1).
  Normal normal(const std::vector<PointText>& v, const std::vector<WrittenEdge>& edges, std::size_t i,
                std::size_t j, int sigma) {
    std::size_t n = edges.size();
    if (!edges[i].arc) {
      const PointText& a = v[i];
      const PointText& b = v[(i + 1) % n];
      std::string dx = paren(b.x + "-" + a.x), dy = paren(b.y + "-" + a.y);
      std::string length = "sqrt(" + dx + "^2+" + dy + "^2)";
      // Material on the left (sigma = 1): outward is the right-hand normal (dy, -dx).
      return Normal{paren(std::string(sigma > 0 ? "" : "-") + dy + "/" + length),
                    paren(std::string(sigma > 0 ? "-" : "") + dx + "/" + length)};
    }
    const PointText& c = edges[i].center_text;
    const PointText& p = v[j % n];
    std::string rx = paren(p.x + "-" + c.x), ry = paren(p.y + "-" + c.y);
    std::string length = "sqrt(" + rx + "^2+" + ry + "^2)";
    int kappa = sigma * (edges[i].ccw ? 1 : -1);
    std::string sign = kappa > 0 ? "" : "-";
    return Normal{paren(sign + rx + "/" + length), paren(sign + ry + "/" + length)};
  }

  // A written loop as the offsets need it: nominal vertices, edges, the vertices' texts, and
  // sigma = 1 when the material is on the left of the loop as written.
  struct WrittenLoop {
    std::size_t n = 0;
    int sigma = 1;
    std::vector<Point> values;
    std::vector<WrittenEdge> edges;
    std::vector<PointText> texts;
    JsonValue* start = nullptr;
    JsonValue* edge_list = nullptr;
  };

  WrittenLoop written_loop(JsonValue& target, const Loop& read, const std::string& what) {
    JsonValue* start = find_mutable(target, "start");
    JsonValue* edge_list = find_mutable(target, "edges");
    std::size_t n = edge_list->items.size();
    if (read.edges.size() != n)
      throw ModelError(target.pointer, "internal error: the loop read has a different number of edges");
    bool reversed = n >= 2 ? read.edges[0].pointer != edge_list->items[0].pointer
                           : read.edges[0].ccw != (edge_list->items[0].find("dir")->text == "ccw");
    int sigma = reversed ? -1 : 1;  // material on the left of the loop as written
    std::vector<Point> values(n);
    std::vector<WrittenEdge> edges(n);
    std::vector<PointText> texts(n);
    std::vector<JsonValue*> vertex_values(n);
    vertex_values[0] = start;
    for (std::size_t i = 0; i < n; ++i) {
      const Edge& e = reversed ? read.edges[n - 1 - i] : read.edges[i];
      values[i] = reversed ? e.target : e.source;
      edges[i].arc = e.is_arc();
      edges[i].ccw = reversed ? !e.ccw : e.ccw;
      edges[i].center = e.center;
      JsonValue& edge = edge_list->items[i];
      if (edges[i].arc) edges[i].center_text = point_text(*find_mutable(edge, "center"), what);
      if (i + 1 < n) vertex_values[i + 1] = find_mutable(edge, edges[i].arc ? "arc_to" : "line_to");
    }
    for (std::size_t i = 0; i < n; ++i) texts[i] = point_text(*vertex_values[i], what);
    JsonValue& last = edge_list->items[n - 1];
    point_text(*find_mutable(last, edges[n - 1].arc ? "arc_to" : "line_to"), what);
    // Arcs: rational nominal radius (so offset points are exact and stay on the offset circle).
    for (std::size_t i = 0; i < n; ++i)
      if (edges[i].arc && !is_rational_square(squared_distance(values[i], edges[i].center)))
        throw ModelError(edge_list->items[i].pointer,
                         "a profile tolerance (" + what +
                             ") needs arcs of rational radius: this arc's squared radius " +
                             decimal(squared_distance(values[i], edges[i].center)) + " is not a rational square");
    return WrittenLoop{n, sigma, std::move(values), std::move(edges), std::move(texts), start, edge_list};
  }

  // Writes vertex j of a written loop (vertex 0 is the start and the last edge's end).
  static void write_vertex(const WrittenLoop& w, std::size_t j, const PointText& text) {
    auto write = [](JsonValue& point, const PointText& t) {
      point.items[0] = string_value(t.x, point.items[0].pointer);
      point.items[1] = string_value(t.y, point.items[1].pointer);
    };
    std::size_t before = (j + w.n - 1) % w.n;   // the edge ending at vertex j
    if (j == 0) write(*w.start, text);
    JsonValue& edge = w.edge_list->items[before];
    write(*find_mutable(edge, w.edges[before].arc ? "arc_to" : "line_to"), text);
  }

  void offset_loop(JsonValue& target, const Loop& read, const std::string& delta, const std::string& what) {
    WrittenLoop w = written_loop(target, read, what);
    std::size_t n = w.n;
    int sigma = w.sigma;
    const std::vector<Point>& values = w.values;
    const std::vector<WrittenEdge>& edges = w.edges;
    const std::vector<PointText>& texts = w.texts;
    JsonValue* edge_list = w.edge_list;
    std::vector<PointText> moved(n);
    for (std::size_t j = 0; j < n; ++j) {
      std::size_t in = (j + n - 1) % n, out = j;
      const Point& v = values[j];
      Normal a = normal(texts, edges, in, j, sigma);
      Normal b = normal(texts, edges, out, j, sigma);
      std::string mx, my;
      if (!edges[in].arc && !edges[out].arc) {
        std::string denominator = paren("1+" + a.x + "*" + b.x + "+" + a.y + "*" + b.y);
        mx = paren(a.x + "+" + b.x) + "/" + denominator;
        my = paren(a.y + "+" + b.y) + "/" + denominator;
      } else {
        // Exact nominal tangency test: the two outward normals at v are the same direction.
        auto outward = [&](std::size_t i) -> Point {
          if (edges[i].arc) {
            int kappa = sigma * (edges[i].ccw ? 1 : -1);
            return Point{Rational(kappa * (v.x - edges[i].center.x)), Rational(kappa * (v.y - edges[i].center.y))};
          }
          const Point& p = values[i];
          const Point& q = values[(i + 1) % n];
          Rational dx = q.x - p.x, dy = q.y - p.y;
          return Point{Rational(sigma * dy), Rational(-sigma * dx)};
        };
        Point u = outward(in), w = outward(out);
        if (u.x * w.y - u.y * w.x != 0 || u.x * w.x + u.y * w.y <= 0)
          throw ModelError(edge_list->items[out].pointer,
                           "a profile tolerance (" + what +
                               ") needs the arcs of the loop to join their neighbours tangentially; the corner at (" +
                               decimal(v.x) + ", " + decimal(v.y) + ") is not smooth");
        const Normal& radial = edges[in].arc ? a : b;
        mx = radial.x;
        my = radial.y;
      }
      moved[j] = PointText{texts[j].x + " + " + delta + "*" + paren(mx), texts[j].y + " + " + delta + "*" + paren(my)};
    }
    for (std::size_t j = 0; j < n; ++j) write_vertex(w, j, moved[j]);
  }

  // One segment edge j of a written loop offset by δ (outward from the material): its two
  // vertices slide along the neighbouring segments' lines to the offset line,
  // v + δ D / (n·D) with n the edge's outward unit normal and D the neighbour's direction;
  // the rest of the loop stays. The neighbours must be segments not parallel to the edge
  // (decided exactly at nominal).
  void offset_edge(JsonValue& target, const Loop& read, const std::string& delta, const std::string& what,
                   std::size_t j, const JsonValue& index_value) {
    WrittenLoop w = written_loop(target, read, what);
    std::size_t n = w.n, prev = (j + n - 1) % n, next = (j + 1) % n;
    if (w.edges[j].arc)
      throw ModelError(index_value.pointer, "a profile tolerance on one edge needs a segment: edge " + std::to_string(j) +
                                                " is an arc (band the whole loop instead)");
    if (w.edges[prev].arc || w.edges[next].arc)
      throw ModelError(index_value.pointer, "a profile tolerance on edge " + std::to_string(j) +
                                                " needs segments on both sides of it (a neighbour is an arc)");
    const Point& a = w.values[j];
    const Point& b = w.values[next];
    const Point& before = w.values[prev];
    const Point& after = w.values[(j + 2) % n];
    auto cross = [](const Rational& ux, const Rational& uy, const Rational& vx, const Rational& vy) {
      return Rational(ux * vy - uy * vx);
    };
    Rational ex = b.x - a.x, ey = b.y - a.y;
    if (cross(ex, ey, a.x - before.x, a.y - before.y) == 0 || cross(ex, ey, after.x - b.x, after.y - b.y) == 0)
      throw ModelError(index_value.pointer, "a profile tolerance on edge " + std::to_string(j) +
                                                " needs neighbours that are not parallel to it");
    Normal normal_text = normal(w.texts, w.edges, j, j, w.sigma);
    auto slide = [&](const PointText& v, const PointText& from, const PointText& to) {
      std::string dx = paren(to.x + "-" + from.x), dy = paren(to.y + "-" + from.y);
      std::string dot = paren(normal_text.x + "*" + dx + "+" + normal_text.y + "*" + dy);
      return PointText{v.x + " + " + delta + "*" + dx + "/" + dot, v.y + " + " + delta + "*" + dy + "/" + dot};
    };
    PointText moved_a = slide(w.texts[j], w.texts[prev], w.texts[j]);
    PointText moved_b = slide(w.texts[next], w.texts[next], w.texts[(j + 2) % n]);
    write_vertex(w, j, moved_a);
    write_vertex(w, next, moved_b);
  }

  JsonValue& root_;
  const Model& nominal_;
  std::vector<ProfileTolerance> result_;
};

}  // namespace

std::vector<ProfileTolerance> translate_profile_tolerances(JsonValue& root, const Model& nominal) {
  return Translator(root, nominal).run();
}

}  // namespace hipair::model_detail
