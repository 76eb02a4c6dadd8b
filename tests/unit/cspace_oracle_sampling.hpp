// Exact point location against the exact overlap oracle at random rational configurations of a
// pair's C-space (the oracle and degenerate-corpus tests): the sample, the oracle's verdict there,
// and the one rule that relates a location to a verdict.
#pragma once

#include "curves/contact_curves.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace hipair::test {

// Where a chart sample lands: in a free or blocked cell, or on contact space (an edge or vertex,
// real or spurious, or a touching cell).
enum class SampleClass { free, blocked, on_contact };

// Draws rational configurations inside a C-space's chart boxes and asks the exact oracle there.
class OracleSampler {
 public:
  // A coordinate is a multiple of 1 / small_denominator of its chart side once in small_odds
  // draws (it hits edges and vertices now and then), otherwise k / prime of it.
  struct Draw {
    unsigned long small_odds;
    long small_denominator;
    unsigned long prime;
  };

  OracleSampler(const Model& model, const CSpace& space)
      : model_(model),
        space_(space),
        axes_(cspace::pair_axes(model, *model.find_part(space.first_part()), *model.find_part(space.second_part()))),
        layout_(cspace::chart_layout(model, axes_)),
        y_count_(space.dimension() == 2 ? layout_.y_charts.size() : 1) {}

  std::size_t oracle_charts() const { return layout_.x_charts.size() * y_count_; }

  struct Sample {
    ChartPoint q;
    Location location;
    cspace::Overlap overlap;
  };

  Sample next(std::mt19937_64& random, const Draw& draw) const {
    const std::size_t c = random() % space_.charts().size();
    const CSpaceChart& chart = space_.charts()[c];
    auto pick = [&](const Rational& lo, const Rational& hi) {
      Rational u = random() % draw.small_odds == 0
                       ? Rational(static_cast<long>(random() % static_cast<unsigned long>(draw.small_denominator + 1)),
                                  draw.small_denominator)
                       : Rational(mpz_class(static_cast<unsigned long>(random() % draw.prime)), draw.prime);
      u.canonicalize();
      return Rational(lo + u * (hi - lo));
    };
    // braced initialisation: x is drawn before y
    return at(ChartPoint{c, pick(chart.x_lo, chart.x_hi), space_.dimension() == 2 ? pick(chart.y_lo, chart.y_hi) : Rational(0)});
  }

  // The location of q and the oracle's verdict there.
  Sample at(const ChartPoint& q) const {
    Location location = space_.locate(q);
    const cspace::ChartAxis y_axis = space_.dimension() == 2 ? layout_.y_charts[q.chart % y_count_] : cspace::ChartAxis{};
    const cspace::Overlap overlap = cspace::classify_overlap(model_, axes_, layout_.x_charts[q.chart / y_count_], y_axis,
                                                             cspace::ChartPoint{q.x, q.y});
    return {q, location, overlap};
  }

  // Free <=> apart, blocked <=> overlapping; on a real edge or vertex (or in a touching cell)
  // touching; on a spurious edge or vertex the class of the cell around it, unless the curve
  // touches there. `where` names the sample in a failure.
  SampleClass expect_agrees(const Sample& s, const std::string& where) const {
    const Location& location = s.location;
    EXPECT_NE(location.kind, Location::Kind::outside) << where << ": a configuration inside a chart box is outside the C-space";
    if (location.kind == Location::Kind::touching ||
        (location.cell != no_index && space_.cells()[location.cell].kind == CellKind::touching)) {
      EXPECT_EQ(s.overlap, cspace::Overlap::touching) << where;
      return SampleClass::on_contact;
    }
    if (location.kind == Location::Kind::free) {
      EXPECT_EQ(s.overlap, cspace::Overlap::apart) << where;
      return SampleClass::free;
    }
    if (location.kind == Location::Kind::blocked) {
      EXPECT_EQ(s.overlap, cspace::Overlap::overlapping) << where;
      return SampleClass::blocked;
    }
    if (location.kind != Location::Kind::edge && location.kind != Location::Kind::vertex) return SampleClass::on_contact;
    bool real = false;
    if (location.kind == Location::Kind::edge) real = space_.edges()[location.edge].real;
    if (location.kind == Location::Kind::vertex) {
      if (space_.dimension() == 1) real = location.cell == no_index;
      real = real || space_.vertices()[location.vertex].touching;
      for (std::size_t e : space_.vertices()[location.vertex].edges) real = real || space_.edges()[e].real;
    }
    if (real) {
      EXPECT_EQ(s.overlap, cspace::Overlap::touching) << where;
    } else if (location.cell != no_index && s.overlap != cspace::Overlap::touching) {
      const bool free = space_.cells()[location.cell].kind == CellKind::free;
      EXPECT_EQ(s.overlap, free ? cspace::Overlap::apart : cspace::Overlap::overlapping) << where;
    }
    return SampleClass::on_contact;
  }

  std::string where(const Sample& s) const {
    return model_.name + " " + space_.first_part() + ":" + space_.second_part() + " chart " + std::to_string(s.q.chart) +
           " at " + s.q.x.get_str() + ", " + s.q.y.get_str();
  }

 private:
  const Model& model_;
  const CSpace& space_;
  cspace::PairAxes axes_;
  cspace::ChartLayout layout_;
  std::size_t y_count_;
};

}  // namespace hipair::test
