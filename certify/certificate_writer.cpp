// Writes certificates (docs/certify.md): JSON with exact rationals as strings. Used by the
// producer in the hipair library; the verifier only reads (certificate_reader.cpp).
#include <hipair/certificate.hpp>

#include "certify/certificate_json.hpp"
#include "certify/sliced_connected.hpp"

#include <cstdio>
#include <sstream>

namespace hipair {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (unsigned char ch : text) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += char(ch);
    } else if (ch < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", ch);
      out += escape;
    } else {
      out += char(ch);
    }
  }
  return out + "\"";
}
std::string number(const Rational& value) { return quoted(to_exact_string(value)); }
std::string interval(const RationalInterval& range) {
  return "[" + number(range.lo) + ", " + number(range.hi) + "]";
}
std::string edge_reference(const EdgeReference& edge) {
  return "{\"part\": " + quoted(edge.part) + ", \"loop\": " + std::to_string(edge.loop) +
         ", \"edge\": " + std::to_string(edge.edge) + ", \"label\": " + quoted(edge.label) + "}";
}
std::string crossing(const CrossingWitness& witness) {
  std::string out = "{\"edge\": " + edge_reference(witness.edge);
  if (witness.along) out += ", \"along\": " + interval(*witness.along);
  return out + ", \"across\": " + edge_reference(witness.across) + "}";
}
std::string pieces(const std::vector<BlockedPiece>& list, bool with_range, const std::string& indent) {
  std::string out = "[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    out += (i ? ",\n" : "\n") + indent + "  {";
    if (with_range) out += "\"range\": " + interval(list[i].range) + ", ";
    if (list[i].point)
      out += "\"point\": [" + number(list[i].point->x) + ", " + number(list[i].point->y) + "]}";
    else
      out += "\"crossing\": " + crossing(list[i].crossing) + "}";
  }
  return out + (list.empty() ? "]" : "\n" + indent + "]");
}
std::string configuration(const std::map<std::string, ExactPosition>& positions) {
  std::string out = "{";
  bool first = true;
  for (const auto& [part, position] : positions) {
    out += (first ? "\n      " : ",\n      ") + quoted(part) + ": {";
    first = false;
    out += (position.is_offset ? "\"offset\": " : "\"tangent\": ") + number(position.value);
    if (position.half_turn) out += ", \"centre\": \"pi\"";
    if (position.angle) out += ", \"angle\": " + number(*position.angle);
    if (position.angle_error) out += ", \"angle_error\": " + number(*position.angle_error);
    out += "}";
  }
  return out + (first ? "}" : "\n    }");
}

std::string feature(const FeatureReference& f) {
  std::string out = edge_reference(f.edge);
  if (f.vertex) out.insert(out.size() - 1, ", \"vertex\": true");
  return out;
}
std::string leaf_side(const LeafSide& side) {
  return "{\"pair\": " + std::to_string(side.pair) + ", \"bracket\": " + interval(side.bracket) +
         ", \"centre\": " + interval(side.centre) + "}";
}
std::string tolerance(const ToleranceClaim& t) {
  std::string out = "    \"property\": " + quoted(t.property) + ",\n    \"driver\": " + quoted(t.driver) +
                    ",\n    \"follower\": " + quoted(t.follower) + ",\n    \"range\": " + interval(t.range) +
                    (t.follower_range ? ",\n    \"follower_range\": " + interval(*t.follower_range) : std::string()) +
                    ",\n    \"scale\": " + number(t.scale) + ",\n    \"varied\": [";
  for (std::size_t i = 0; i < t.varied.size(); ++i) out += (i ? ", " : "") + quoted(t.varied[i]);
  out += "],\n    \"box\": [";
  for (std::size_t i = 0; i < t.box.size(); ++i) out += (i ? ", " : "") + interval(t.box[i]);
  out += "],\n    \"sides\": [";
  for (std::size_t i = 0; i < t.sides.size(); ++i)
    out += std::string(i ? "," : "") + "\n      {\"driver\": " + feature(t.sides[i].driver) + ", \"follower\": " +
           feature(t.sides[i].follower) + "}";
  out += t.sides.empty() ? "]" : "\n    ]";
  out += ",\n    \"leaves\": [";
  for (std::size_t i = 0; i < t.leaves.size(); ++i) {
    const ToleranceLeaf& leaf = t.leaves[i];
    out += std::string(i ? "," : "") + "\n      {\"parameters\": [";
    for (std::size_t j = 0; j < leaf.parameters.size(); ++j) out += (j ? ", " : "") + interval(leaf.parameters[j]);
    out += "], \"driver\": " + interval(leaf.driver);
    if (leaf.follower) {
      out += ", \"follower\": " + interval(*leaf.follower) + "}";
      continue;
    }
    out += ",\n       \"lower\": " + leaf_side(leaf.lower) + ", \"upper\": " + leaf_side(leaf.upper);
    if (leaf.witness) {
      out += ",\n       \"witness\": {\"value\": " + number(*leaf.witness) + ", \"slopes\": [";
      for (std::size_t j = 0; j < leaf.witness_slopes.size(); ++j) out += (j ? ", " : "") + number(leaf.witness_slopes[j]);
      out += "]";
      if (!leaf.witness_margins.empty()) {
        out += ", \"second_order_margins\": [";
        for (std::size_t j = 0; j < leaf.witness_margins.size(); ++j) out += (j ? ", " : "") + number(leaf.witness_margins[j]);
        out += "]";
      }
      out += "}";
    }
    out += "}";
  }
  out += t.leaves.empty() ? "]" : "\n    ]";
  out += ",\n    \"tree\": [";
  for (std::size_t i = 0; i < t.tree.size(); ++i) {
    const ToleranceTreeNode& n = t.tree[i];
    out += (i ? (i % 8 ? ", " : ",\n      ") : "");
    out += n.leaf ? std::to_string(n.index) : "[" + quoted(n.dimension) + ", " + number(n.value) + "]";
  }
  return out + "]";
}

}  // namespace

namespace certificate_json {

std::string quoted_text(const std::string& text) { return quoted(text); }

std::string position(const ExactPosition& p) {
  if (p.is_offset) return "{\"offset\": " + number(p.value) + "}";
  return "{\"tangent\": " + number(p.value) + (p.half_turn ? ", \"centre\": \"pi\"}" : std::string("}"));
}

std::string pose(const PlanarPose& p, bool with_part) {
  std::string out = "{";
  if (with_part) out += "\"part\": " + quoted(p.part) + ", ";
  if (p.slide)
    out += "\"slide\": " + number(*p.slide);
  else
    out += "\"x\": " + number(p.x) + ", \"y\": " + number(p.y);
  return out + ", \"tangent\": " + number(p.tangent) + (p.half_turn ? ", \"centre\": \"pi\"" : "") + "}";
}

std::string envelope(const Certificate& c, int version, const std::string& claim) {
  std::ostringstream out;
  out << "{\n  \"hipair_certificate\": " << version << ",\n  \"claim\": " << quoted(claim) << ",\n";
  out << "  \"statement\": " << quoted(c.statement) << ",\n";
  // no "file" for a model read from text (the reader refuses an empty file name)
  out << "  \"model\": {\n    \"name\": " << quoted(c.model_name) << ",\n";
  if (!c.model_file.empty()) out << "    \"file\": " << quoted(c.model_file) << ",\n";
  out << "    \"content_hash\": " << quoted(c.content_hash) << ",\n    \"parameters\": {";
  for (std::size_t i = 0; i < c.parameters.size(); ++i)
    out << (i ? ",\n      " : "\n      ") << quoted(c.parameters[i].name) << ": {\"value\": "
        << number(c.parameters[i].value) << ", \"overridden\": " << (c.parameters[i].overridden ? "true" : "false")
        << "}";
  out << (c.parameters.empty() ? "},\n" : "\n    },\n") << "    \"roundings\": [";
  for (std::size_t i = 0; i < c.roundings.size(); ++i)
    out << (i ? ",\n      " : "\n      ") << "{\"pointer\": " << quoted(c.roundings[i].pointer)
        << ", \"expression\": " << quoted(c.roundings[i].expression) << ", \"value\": " << number(c.roundings[i].value)
        << ", \"bound\": " << number(c.roundings[i].bound) << "}";
  out << (c.roundings.empty() ? "]\n  },\n" : "\n    ]\n  },\n");
  out << "  \"pair\": [" << quoted(c.first) << ", " << quoted(c.second) << "],\n";
  return out.str();
}

}  // namespace certificate_json

std::string write_certificate(const Certificate& c) {
  std::ostringstream out;
  // version 2 only when a jam piece has a point witness: every other certificate is written as
  // before (and reads with a version-1 verifier)
  bool point_pieces = false;
  for (const auto* list : {&c.cut, &c.lower_wall, &c.upper_wall})
    for (const BlockedPiece& piece : *list) point_pieces = point_pieces || bool(piece.point);
  out << certificate_json::envelope(c, point_pieces ? 2 : 1, to_string(c.claim));
  out << "  " << quoted(to_string(c.claim)) << ": {\n";
  switch (c.claim) {
    case ClaimKind::interference:
      out << "    \"configuration\": " << configuration(c.configuration);
      if (c.witness_point)
        out << ",\n    \"point\": [" << number(c.witness_point->x) << ", " << number(c.witness_point->y) << "]";
      if (c.witness_crossing) out << ",\n    \"crossing\": " << crossing(*c.witness_crossing);
      break;
    case ClaimKind::clearance:
      out << "    \"configuration\": " << configuration(c.configuration) << ",\n    \"distance\": "
          << number(c.distance);
      break;
    case ClaimKind::free_passage: {
      out << "    \"driver\": " << quoted(c.driver) << ",\n    \"follower\": " << quoted(c.follower)
          << ",\n    \"distance\": " << number(c.distance) << ",\n    \"range\": " << interval(c.range)
          << ",\n    \"path\": [";
      for (std::size_t i = 0; i < c.path.size(); ++i)
        out << (i ? ", " : "") << "[" << number(c.path[i].first) << ", " << number(c.path[i].second) << "]";
      out << "],\n    \"boxes\": [";
      for (std::size_t i = 0; i < c.boxes.size(); ++i) {
        out << (i ? ",\n      " : "\n      ") << "{\"driver\": " << interval(c.boxes[i].driver);
        if (c.boxes[i].follower) out << ", \"follower\": " << interval(*c.boxes[i].follower);
        out << "}";
      }
      out << (c.boxes.empty() ? "]" : "\n    ]");
      break;
    }
    case ClaimKind::tolerance:
      if (c.tolerance) out << tolerance(*c.tolerance);
      break;
    case ClaimKind::planar_interference:
    case ClaimKind::planar_clearance:
      if (c.pose) {
        out << "    \"pose\": " << certificate_json::pose(*c.pose, true);
      }
      if (!c.configuration.empty()) out << ",\n    \"configuration\": " << configuration(c.configuration);
      if (c.claim == ClaimKind::planar_clearance) out << ",\n    \"distance\": " << number(c.distance);
      if (c.witness_point)
        out << ",\n    \"point\": [" << number(c.witness_point->x) << ", " << number(c.witness_point->y) << "]";
      if (c.witness_crossing) out << ",\n    \"crossing\": " << crossing(*c.witness_crossing);
      break;
    case ClaimKind::jam:
      out << "    \"driver\": " << quoted(c.driver) << ",\n    \"follower\": " << quoted(c.follower)
          << ",\n    \"direction\": " << c.direction << ",\n    \"trap\": {\"driver\": " << interval(c.trap.driver);
      if (c.trap.follower) out << ", \"follower\": " << interval(*c.trap.follower);
      out << "},";
      if (c.start) {
        out << "\n    \"start\": {\"driver\": " << number(c.start->driver);
        if (c.start->follower) out << ", \"follower\": " << number(*c.start->follower);
        out << "},";
      }
      out << "\n    \"cut\": " << pieces(c.cut, bool(c.trap.follower), "    ");
      if (c.trap.follower)
        out << ",\n    \"lower_wall\": " << pieces(c.lower_wall, true, "    ") << ",\n    \"upper_wall\": "
            << pieces(c.upper_wall, true, "    ");
      break;
  }
  out << "\n  }\n}\n";
  return out.str();
}

// the sliced_connected claim (certify/sliced_connected.hpp), over the shared envelope
std::string write_sliced_connected_certificate(const SlicedConnectedCertificate& c) {
  std::string out = certificate_json::envelope(c.envelope, 1, "sliced_connected");
  out += "  \"sliced_connected\": {\n    \"from\": " + certificate_json::pose(c.from, true) +
         ",\n    \"to\": " + certificate_json::pose(c.to, true);
  if (c.pin_slot) {   // session 71: the other part's positions and the steps (q, s, u)
    if (c.from_other && c.to_other)
      out += ",\n    \"from_other\": " + certificate_json::position(*c.from_other) + ",\n    \"to_other\": " + certificate_json::position(*c.to_other);
    out += ",\n    \"steps\": [";
    for (std::size_t i = 0; i < c.steps.size(); ++i)
      out += std::string(i ? "," : "") + "\n      [" + number(c.steps[i][0]) + ", " + number(c.steps[i][1]) + ", " + number(c.steps[i][2]) + "]";
    out += c.steps.empty() ? "]" : "\n    ]";
    return out + "\n  }\n}\n";
  }
  out += ",\n    \"path\": [";
  for (std::size_t i = 0; i < c.path.size(); ++i) {
    const PlanarPose& p = c.path[i];
    out += std::string(i ? "," : "") + "\n      [" + certificate_json::quoted_text(to_exact_string(p.x)) + ", " +
           certificate_json::quoted_text(to_exact_string(p.y)) + ", " + certificate_json::quoted_text(to_exact_string(p.tangent)) +
           (p.half_turn ? ", \"pi\"]" : "]");
  }
  out += c.path.empty() ? "]" : "\n    ]";
  return out + "\n  }\n}\n";
}

}  // namespace hipair
