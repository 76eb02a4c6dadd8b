// The exact bounding-box test in front of the overlap oracle for a translating polygon pair
// (Session 75, poly75; builder_model.cpp's chart-point classifier). Where neither part rotates
// and every edge is a segment, each part's exact bounding box (of its vertices, at its body
// frame) moves with the part; at a chart point where the two moved boxes are strictly apart on
// one coordinate (a positive gap), every point of one part is at a positive distance from every
// point of the other: the oracle's answer is `apart`, and the builder gives it without preparing
// the oracle. Exact rationals throughout; false says nothing (the oracle decides).
#pragma once

#include "curves/contact_curves.hpp"

#include <hipair/model.hpp>
#include <hipair/rational.hpp>

namespace hipair::cspace {

class TranslatedBoxes {
 public:
  TranslatedBoxes(const Model& model, const PairAxes& axes) : model_(model), axes_(axes) {
    const std::size_t part_index[2] = {axes.first, axes.second};
    const bool moves[2] = {axes.first_moves, axes.second_moves};
    applies_ = true;
    for (int p = 0; p < 2 && applies_; ++p) {
      const Part& part = model.parts.at(part_index[p]);
      if (moves[p] && part.motion.kind != Motion::Kind::translation) applies_ = false;
      bool first = true;
      for (const Loop& loop : part.loops)
        for (const Edge& edge : loop.edges) {
          if (edge.is_arc()) applies_ = false;
          for (const Point* q : {&edge.source, &edge.target}) {
            if (first || q->x < lo_[p][0]) lo_[p][0] = q->x;
            if (first || q->x > hi_[p][0]) hi_[p][0] = q->x;
            if (first || q->y < lo_[p][1]) lo_[p][1] = q->y;
            if (first || q->y > hi_[p][1]) hi_[p][1] = q->y;
            first = false;
          }
        }
      if (first) applies_ = false;   // (a part without edges)
    }
  }

  /// Both parts are polygons without rotation: apart() can answer.
  bool applies() const { return applies_; }

  /// The parts' moved boxes strictly apart at chart point q (q.y read when both parts move).
  bool apart(const ChartPoint& q) const {
    if (!applies_) return false;
    thread_local Rational offset[2][2], left, right;
    const Rational* value[2] = {axes_.first_moves ? &q.x : nullptr,
                                axes_.second_moves ? (axes_.first_moves ? &q.y : &q.x) : nullptr};
    const std::size_t part_index[2] = {axes_.first, axes_.second};
    for (int p = 0; p < 2; ++p)
      for (int c = 0; c < 2; ++c) {
        if (!value[p]) {
          offset[p][c] = 0;
          continue;
        }
        // (world_map of a translation: the offset value * direction)
        const Point& d = model_.parts[part_index[p]].motion.direction;
        mpq_mul(offset[p][c].get_mpq_t(), value[p]->get_mpq_t(), (c == 0 ? d.x : d.y).get_mpq_t());
      }
    for (int c = 0; c < 2; ++c)
      for (int p = 0; p < 2; ++p) {
        // part p's upper side below part (1 - p)'s lower side on coordinate c
        mpq_add(left.get_mpq_t(), hi_[p][c].get_mpq_t(), offset[p][c].get_mpq_t());
        mpq_add(right.get_mpq_t(), lo_[1 - p][c].get_mpq_t(), offset[1 - p][c].get_mpq_t());
        if (left < right) return true;
      }
    return false;
  }

 private:
  const Model& model_;
  PairAxes axes_;
  bool applies_ = false;
  Rational lo_[2][2], hi_[2][2];   // [part][x, y] at the parts' body frames
};

}  // namespace hipair::cspace
