#include "cspace/half_turn_symmetry.hpp"

#include <map>
#include <tuple>

namespace hipair::cspace {
namespace {

Point reflected(const Point& q, const Point& pivot) {
  Point r{Rational(2 * pivot.x - q.x), Rational(2 * pivot.y - q.y)};
  r.x.canonicalize();
  r.y.canonicalize();
  return r;
}

// An exact key of an edge's geometry (what the contact kernels read of it).
using Key = std::tuple<int, Rational, Rational, Rational, Rational, Rational, Rational, bool, Rational>;

Key key_of(const Edge& e) {
  const bool arc = e.is_arc();
  return Key{arc ? 1 : 0,
             e.source.x,
             e.source.y,
             e.target.x,
             e.target.y,
             arc ? e.center.x : Rational(0),
             arc ? e.center.y : Rational(0),
             arc ? e.ccw : false,
             arc ? e.radius_squared : Rational(0)};
}

}  // namespace

Edge half_turned(const Edge& edge, const Point& pivot) {
  Edge image = edge;
  image.source = reflected(edge.source, pivot);
  image.target = reflected(edge.target, pivot);
  if (edge.is_arc()) image.center = reflected(edge.center, pivot);
  return image;
}

std::optional<std::vector<std::vector<HalfTurnImage>>> half_turn_symmetry(const Part& part, std::string* why) {
  auto refuse = [&](const std::string& reason) -> std::optional<std::vector<std::vector<HalfTurnImage>>> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (part.motion.kind != Motion::Kind::rotation) return refuse("the part does not turn about a fixed pivot");
  if (part.motion.angle_limits) return refuse("the part turns within angle limits");
  std::map<Key, HalfTurnImage> edges;
  for (std::size_t l = 0; l < part.loops.size(); ++l)
    for (std::size_t e = 0; e < part.loops[l].edges.size(); ++e)
      if (!edges.emplace(key_of(part.loops[l].edges[e]), HalfTurnImage{l, e}).second)
        return refuse("loop " + std::to_string(l) + " edge " + std::to_string(e) + " repeats an edge");
  std::vector<std::vector<HalfTurnImage>> image(part.loops.size());
  std::vector<std::vector<bool>> taken(part.loops.size());
  for (std::size_t l = 0; l < part.loops.size(); ++l) taken[l].assign(part.loops[l].edges.size(), false);
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const Loop& loop = part.loops[l];
    for (std::size_t e = 0; e < loop.edges.size(); ++e) {
      const auto found = edges.find(key_of(half_turned(loop.edges[e], part.motion.pivot)));
      if (found == edges.end())
        return refuse("loop " + std::to_string(l) + " edge " + std::to_string(e) +
                      ": its half turn is no edge of the part");
      const HalfTurnImage to = found->second;
      if (part.loops[to.loop].is_hole != loop.is_hole)
        return refuse("loop " + std::to_string(l) + " edge " + std::to_string(e) + ": image on a loop of another kind");
      if (taken[to.loop][to.edge])
        return refuse("loop " + std::to_string(l) + " edge " + std::to_string(e) + ": image taken twice");
      taken[to.loop][to.edge] = true;
      image[l].push_back(to);
    }
    // successive edges go to successive edges of one loop (the vertices map with their edges)
    for (std::size_t e = 0; e < loop.edges.size(); ++e) {
      const HalfTurnImage a = image[l][e], b = image[l][(e + 1) % loop.edges.size()];
      if (a.loop != b.loop || (a.edge + 1) % part.loops[a.loop].edges.size() != b.edge)
        return refuse("loop " + std::to_string(l) + " edge " + std::to_string(e) + ": successive edges not kept");
    }
  }
  if (why) why->clear();
  return image;
}

}  // namespace hipair::cspace
