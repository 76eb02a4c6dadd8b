// Reads certificates (docs/certify.md): JSON with exact rationals as strings. Shared by the
// verifier hipair-verify and the hipair library. Reading is strict: unknown keys, missing keys
// and wrong types are errors with a JSON pointer.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>

#include "certify/certificate_json.hpp"
#include "core/exact_literal.hpp"
#include "model/json_document.hpp"


namespace hipair {

using model_detail::JsonValue;

std::string to_string(ClaimKind kind) {
  switch (kind) {
    case ClaimKind::interference: return "interference";
    case ClaimKind::clearance: return "clearance";
    case ClaimKind::jam: return "jam";
    case ClaimKind::free_passage: return "free_passage";
    case ClaimKind::tolerance: return "tolerance";
    case ClaimKind::planar_interference: return "planar_interference";
    case ClaimKind::planar_clearance: return "planar_clearance";
  }
  return "?";
}

namespace {

[[noreturn]] void fail(const JsonValue& at, const std::string& reason) { throw ModelError(at.pointer, reason); }

void check_keys(const JsonValue& object, std::initializer_list<const char*> allowed) {
  if (!object.is_object()) fail(object, "expected an object");
  for (const auto& member : object.members) {
    bool known = false;
    for (const char* key : allowed) known = known || member.key == key;
    if (!known) fail(member.value, "unknown key '" + member.key + "'");
  }
}
const JsonValue& require(const JsonValue& object, const char* key) {
  const JsonValue* value = object.find(key);
  if (!value) fail(object, std::string("missing key '") + key + "'");
  return *value;
}
std::string text(const JsonValue& value) {
  if (!value.is_string()) fail(value, "expected a string");
  return value.text;
}
Rational rational(const JsonValue& value) {
  if (!value.is_string()) fail(value, "expected an exact rational as a string (\"3/7\")");
  try {
    return parse_exact_literal(value.text);
  } catch (const Error& error) {
    fail(value, std::string("not an exact rational: ") + error.what());
  }
}
std::size_t index(const JsonValue& value) {
  if (!value.is_number() || value.text.empty() || value.text.size() > 9 ||
      value.text.find_first_not_of("0123456789") != std::string::npos)
    fail(value, "expected a non-negative integer");
  return std::stoul(value.text);
}
const JsonValue& array(const JsonValue& value, std::size_t size = 0) {
  if (!value.is_array()) fail(value, "expected an array");
  if (size && value.items.size() != size) fail(value, "expected " + std::to_string(size) + " elements");
  return value;
}
RationalInterval interval_of(const JsonValue& value) {
  array(value, 2);
  RationalInterval range{rational(value.items[0]), rational(value.items[1])};
  if (range.lo > range.hi) fail(value, "interval with lower end above upper end");
  return range;
}
EdgeReference edge_of(const JsonValue& value) {
  check_keys(value, {"part", "loop", "edge", "label"});
  return EdgeReference{text(require(value, "part")), index(require(value, "loop")), index(require(value, "edge")),
                       text(require(value, "label"))};
}
CrossingWitness crossing_of(const JsonValue& value) {
  check_keys(value, {"edge", "along", "across"});
  CrossingWitness witness{edge_of(require(value, "edge")), edge_of(require(value, "across")), std::nullopt};
  if (const JsonValue* along = value.find("along")) witness.along = interval_of(*along);
  return witness;
}
// A jam piece's witness: a crossing, or (version 2) a point inside both parts over the piece.
std::vector<BlockedPiece> pieces_of(const JsonValue& value, bool with_range, int version) {
  std::vector<BlockedPiece> list;
  for (const JsonValue& item : array(value).items) {
    check_keys(item, {"range", "crossing", "point"});
    BlockedPiece piece{{Rational(0), Rational(0)}, {}, std::nullopt};
    const JsonValue* crossing = item.find("crossing");
    const JsonValue* point = item.find("point");
    if (bool(crossing) == bool(point)) fail(item, "give exactly one witness of the piece: 'crossing' or 'point'");
    if (crossing) {
      piece.crossing = crossing_of(*crossing);
    } else {
      if (version < 2) fail(*point, "a piece's 'point' witness needs \"hipair_certificate\": 2");
      array(*point, 2);
      piece.point = Point{rational(point->items[0]), rational(point->items[1])};
    }
    if (with_range) piece.range = interval_of(require(item, "range"));
    else if (item.find("range")) fail(item, "a 1-D cut piece has no range");
    list.push_back(std::move(piece));
  }
  return list;
}
std::map<std::string, ExactPosition> configuration_of(const JsonValue& value) {
  if (!value.is_object()) fail(value, "expected an object: part -> position");
  std::map<std::string, ExactPosition> positions;
  for (const auto& member : value.members) {
    const JsonValue& entry = member.value;
    check_keys(entry, {"tangent", "offset", "centre", "angle", "angle_error"});
    ExactPosition position;
    position.is_offset = entry.find("offset") != nullptr;
    if (position.is_offset == (entry.find("tangent") != nullptr))
      fail(entry, "give exactly one of 'tangent' (rotation) and 'offset' (translation)");
    position.value = rational(require(entry, position.is_offset ? "offset" : "tangent"));
    if (position.is_offset && (entry.find("centre") || entry.find("angle")))
      fail(entry, "an offset has no centre or angle");
    if (const JsonValue* centre = entry.find("centre")) {
      std::string c = text(*centre);
      if (c != "pi" && c != "0") fail(*centre, "centre is \"0\" or \"pi\"");
      position.half_turn = c == "pi";
    }
    if (const JsonValue* angle = entry.find("angle")) position.angle = rational(*angle);
    if (const JsonValue* error = entry.find("angle_error")) position.angle_error = rational(*error);
    if (bool(position.angle) != bool(position.angle_error))
      fail(entry, "angle and angle_error go together");
    positions[member.key] = position;
  }
  return positions;
}
ConfigurationBox box_of(const JsonValue& value, bool follower_required) {
  check_keys(value, {"driver", "follower"});
  ConfigurationBox box{interval_of(require(value, "driver")), std::nullopt};
  if (const JsonValue* follower = value.find("follower")) box.follower = interval_of(*follower);
  if (follower_required != bool(box.follower))
    fail(value, follower_required ? "missing key 'follower'" : "no follower in a pair with a fixed part");
  return box;
}

FeatureReference feature_of(const JsonValue& value) {
  check_keys(value, {"part", "loop", "edge", "label", "vertex"});
  FeatureReference f;
  f.edge = EdgeReference{text(require(value, "part")), index(require(value, "loop")), index(require(value, "edge")),
                         text(require(value, "label"))};
  if (const JsonValue* vertex = value.find("vertex")) {
    if (!vertex->is_boolean()) fail(*vertex, "expected true or false");
    f.vertex = vertex->boolean;
  }
  return f;
}
LeafSide leaf_side_of(const JsonValue& value) {
  check_keys(value, {"pair", "bracket", "centre"});
  return LeafSide{index(require(value, "pair")), interval_of(require(value, "bracket")), interval_of(require(value, "centre"))};
}
ToleranceClaim tolerance_of(const JsonValue& body) {
  check_keys(body, {"property", "driver", "follower", "range", "follower_range", "scale", "varied", "box", "sides",
                    "leaves", "tree"});
  ToleranceClaim t;
  t.property = text(require(body, "property"));
  t.driver = text(require(body, "driver"));
  t.follower = text(require(body, "follower"));
  t.range = interval_of(require(body, "range"));
  if (const JsonValue* follower = body.find("follower_range")) t.follower_range = interval_of(*follower);
  t.scale = rational(require(body, "scale"));
  for (const JsonValue& name : array(require(body, "varied")).items) t.varied.push_back(text(name));
  for (const JsonValue& range : array(require(body, "box")).items) t.box.push_back(interval_of(range));
  for (const JsonValue& side : array(require(body, "sides")).items) {
    check_keys(side, {"driver", "follower"});
    t.sides.push_back(ContactSidePair{feature_of(require(side, "driver")), feature_of(require(side, "follower"))});
  }
  for (const JsonValue& item : array(require(body, "leaves")).items) {
    check_keys(item, {"parameters", "driver", "follower", "lower", "upper", "witness"});
    ToleranceLeaf leaf;
    for (const JsonValue& range : array(require(item, "parameters")).items) leaf.parameters.push_back(interval_of(range));
    leaf.driver = interval_of(require(item, "driver"));
    if (const JsonValue* follower = item.find("follower")) {
      // no_interference: a box of configurations, no sides.
      leaf.follower = interval_of(*follower);
      if (item.find("lower") || item.find("upper") || item.find("witness"))
        fail(item, "a leaf with a 'follower' interval (no_interference) has no sides or witness");
      t.leaves.push_back(std::move(leaf));
      continue;
    }
    leaf.lower = leaf_side_of(require(item, "lower"));
    leaf.upper = leaf_side_of(require(item, "upper"));
    if (const JsonValue* witness = item.find("witness")) {
      check_keys(*witness, {"value", "slopes", "second_order_margins"});
      leaf.witness = rational(require(*witness, "value"));
      for (const JsonValue& slope : array(require(*witness, "slopes")).items) leaf.witness_slopes.push_back(rational(slope));
      if (const JsonValue* margins = witness->find("second_order_margins")) {
        for (const JsonValue& m : array(*margins).items) leaf.witness_margins.push_back(rational(m));
        if (leaf.witness_margins.size() != 2) fail(*margins, "give two margins: the lower side's, then the upper side's");
      }
    }
    t.leaves.push_back(std::move(leaf));
  }
  for (const JsonValue& node : array(require(body, "tree")).items) {
    ToleranceTreeNode n;
    if (node.is_number()) {
      n.leaf = true;
      n.index = index(node);
    } else {
      array(node, 2);
      n.dimension = text(node.items[0]);
      n.value = rational(node.items[1]);
    }
    t.tree.push_back(std::move(n));
  }
  return t;
}

PlanarPose pose_of(const JsonValue& value) {
  check_keys(value, {"part", "x", "y", "slide", "tangent", "centre"});
  PlanarPose pose;
  pose.part = text(require(value, "part"));
  if (const JsonValue* slide = value.find("slide")) {
    if (value.find("x") || value.find("y")) fail(value, "a pose gives either \"slide\" (pin-slot) or \"x\" and \"y\"");
    pose.slide = rational(*slide);
  } else {
    pose.x = rational(require(value, "x"));
    pose.y = rational(require(value, "y"));
  }
  pose.tangent = rational(require(value, "tangent"));
  if (const JsonValue* centre = value.find("centre")) {
    std::string c = text(*centre);
    if (c != "pi" && c != "0") fail(*centre, "centre is \"0\" or \"pi\"");
    pose.half_turn = c == "pi";
  }
  return pose;
}

}  // namespace

namespace certificate_json {

void read_envelope(const JsonValue& root, Certificate& c) {
  if (const JsonValue* statement = root.find("statement")) c.statement = text(*statement);

  const JsonValue& model = require(root, "model");
  check_keys(model, {"name", "file", "content_hash", "parameters", "roundings"});
  c.model_name = text(require(model, "name"));
  if (const JsonValue* file = model.find("file")) {
    c.model_file = text(*file);
    // a label, but a file name: absent when there is none, never empty (docs/certify.md)
    if (c.model_file.empty()) fail(*file, "an empty file name (leave model.file out when there is none)");
  }
  c.content_hash = text(require(model, "content_hash"));
  const JsonValue& parameters = require(model, "parameters");
  if (!parameters.is_object()) fail(parameters, "expected an object: name -> {value, overridden}");
  for (const auto& member : parameters.members) {
    check_keys(member.value, {"value", "overridden"});
    const JsonValue& overridden = require(member.value, "overridden");
    if (!overridden.is_boolean()) fail(overridden, "expected true or false");
    c.parameters.push_back({member.key, rational(require(member.value, "value")), overridden.boolean});
  }
  for (const JsonValue& item : array(require(model, "roundings")).items) {
    check_keys(item, {"pointer", "expression", "value", "bound"});
    c.roundings.push_back(Rounding{text(require(item, "pointer")), text(require(item, "expression")),
                                   rational(require(item, "value")), rational(require(item, "bound"))});
  }
  const JsonValue& pair = array(require(root, "pair"), 2);
  c.first = text(pair.items[0]);
  c.second = text(pair.items[1]);
}

void keys(const JsonValue& object, std::initializer_list<const char*> allowed) { check_keys(object, allowed); }
const JsonValue& member(const JsonValue& object, const char* key) { return require(object, key); }
std::string read_text(const JsonValue& value) { return text(value); }
Rational read_rational(const JsonValue& value) { return rational(value); }
const JsonValue& read_array(const JsonValue& value) { return array(value); }
PlanarPose read_pose(const JsonValue& value) { return pose_of(value); }
[[noreturn]] void refuse(const JsonValue& at, const std::string& reason) { fail(at, reason); }

bool has_claim(std::string_view json_text, const char* claim) {
  try {
    JsonValue root = model_detail::parse_json(json_text);
    const JsonValue* found = root.is_object() ? root.find("claim") : nullptr;
    return found && found->is_string() && found->text == claim;
  } catch (const Error&) {
    return false;
  }
}

const JsonValue& read_claim(const JsonValue& root, const char* claim, Certificate& envelope) {
  check_keys(root, {"hipair_certificate", "claim", "statement", "model", "pair", claim});
  const JsonValue& version = require(root, "hipair_certificate");
  if (!version.is_number() || version.text != "1") fail(version, "unsupported certificate version (expected 1)");
  const JsonValue& named = require(root, "claim");
  if (text(named) != claim) fail(named, std::string("expected the claim '") + claim + "'");
  read_envelope(root, envelope);
  return require(root, claim);
}

}  // namespace certificate_json

Certificate read_certificate(std::string_view json_text) {
  JsonValue root = model_detail::parse_json(json_text);
  Certificate c;
  check_keys(root, {"hipair_certificate", "claim", "statement", "model", "pair", "interference", "clearance", "jam",
                    "free_passage", "tolerance", "planar_interference", "planar_clearance"});
  const JsonValue& version = require(root, "hipair_certificate");
  // version 2 (session 57): jam pieces may carry a 'point' witness; every version-1 certificate
  // reads the same as version 2
  if (!version.is_number() || (version.text != "1" && version.text != "2"))
    fail(version, "unsupported certificate version (expected 1 or 2)");
  int format = version.text == "2" ? 2 : 1;
  std::string claim = text(require(root, "claim"));
  if (claim == "interference") c.claim = ClaimKind::interference;
  else if (claim == "clearance") c.claim = ClaimKind::clearance;
  else if (claim == "jam") c.claim = ClaimKind::jam;
  else if (claim == "free_passage") c.claim = ClaimKind::free_passage;
  else if (claim == "tolerance") c.claim = ClaimKind::tolerance;
  else if (claim == "planar_interference") c.claim = ClaimKind::planar_interference;
  else if (claim == "planar_clearance") c.claim = ClaimKind::planar_clearance;
  else fail(require(root, "claim"), "unknown claim '" + claim + "'");
  certificate_json::read_envelope(root, c);

  for (const char* other : {"interference", "clearance", "jam", "free_passage", "tolerance", "planar_interference",
                            "planar_clearance"})
    if (other != claim && root.find(other)) fail(*root.find(other), "section '" + std::string(other) + "' does not belong to the claim '" + claim + "'");
  const JsonValue& body = require(root, claim.c_str());
  // The witness of an interference claim (fixed-axis or planar): exactly one of a point inside
  // both parts or a transversal crossing of their boundaries.
  auto read_overlap_witness = [&](const JsonValue& section) {
    if (const JsonValue* point = section.find("point")) {
      array(*point, 2);
      c.witness_point = Point{rational(point->items[0]), rational(point->items[1])};
    }
    if (const JsonValue* cross = section.find("crossing")) c.witness_crossing = crossing_of(*cross);
    if (bool(c.witness_point) == bool(c.witness_crossing)) fail(section, "give exactly one witness: 'point' or 'crossing'");
  };
  switch (c.claim) {
    case ClaimKind::interference: {
      check_keys(body, {"configuration", "point", "crossing"});
      c.configuration = configuration_of(require(body, "configuration"));
      read_overlap_witness(body);
      break;
    }
    case ClaimKind::clearance:
      check_keys(body, {"configuration", "distance"});
      c.configuration = configuration_of(require(body, "configuration"));
      c.distance = rational(require(body, "distance"));
      break;
    case ClaimKind::free_passage: {
      check_keys(body, {"driver", "follower", "distance", "range", "path", "boxes"});
      c.driver = text(require(body, "driver"));
      c.follower = text(require(body, "follower"));
      c.distance = rational(require(body, "distance"));
      c.range = interval_of(require(body, "range"));
      for (const JsonValue& vertex : array(require(body, "path")).items) {
        array(vertex, 2);
        c.path.emplace_back(rational(vertex.items[0]), rational(vertex.items[1]));
      }
      for (const JsonValue& box : array(require(body, "boxes")).items) c.boxes.push_back(box_of(box, !c.follower.empty()));
      break;
    }
    case ClaimKind::tolerance:
      c.tolerance = tolerance_of(body);
      break;
    case ClaimKind::planar_interference: {
      check_keys(body, {"pose", "configuration", "point", "crossing"});
      c.pose = pose_of(require(body, "pose"));
      if (const JsonValue* positions = body.find("configuration")) c.configuration = configuration_of(*positions);
      read_overlap_witness(body);
      break;
    }
    case ClaimKind::planar_clearance:
      check_keys(body, {"pose", "configuration", "distance"});
      c.pose = pose_of(require(body, "pose"));
      if (const JsonValue* positions = body.find("configuration")) c.configuration = configuration_of(*positions);
      c.distance = rational(require(body, "distance"));
      break;
    case ClaimKind::jam: {
      check_keys(body, {"driver", "follower", "direction", "trap", "start", "cut", "lower_wall", "upper_wall"});
      c.driver = text(require(body, "driver"));
      c.follower = text(require(body, "follower"));
      const JsonValue& direction = require(body, "direction");
      if (!direction.is_number() || (direction.text != "1" && direction.text != "-1"))
        fail(direction, "direction is 1 or -1");
      c.direction = direction.text == "1" ? 1 : -1;
      bool two = !c.follower.empty();
      c.trap = box_of(require(body, "trap"), two);
      {   // a free configuration in the trap (session 42)
        const JsonValue& start = require(body, "start");
        check_keys(start, {"driver", "follower"});
        c.start = JamStart{rational(require(start, "driver")), std::nullopt};
        if (two) c.start->follower = rational(require(start, "follower"));
        else if (start.find("follower")) fail(start, "no follower in a pair with a fixed part");
      }
      c.cut = pieces_of(require(body, "cut"), two, format);
      if (two) {
        c.lower_wall = pieces_of(require(body, "lower_wall"), true, format);
        c.upper_wall = pieces_of(require(body, "upper_wall"), true, format);
      } else if (body.find("lower_wall") || body.find("upper_wall")) {
        fail(body, "a jam against a fixed part has no walls");
      }
      break;
    }
  }
  return c;
}

}  // namespace hipair
