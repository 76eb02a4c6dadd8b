// The producer of no-jam tolerance certificates (certificate.hpp; docs/certify.md
// "Tolerance"). It chooses — it does not decide: the brackets, the split dimensions and the
// Newton iterates are approximate; whether a leaf holds is decided by the verifier's own check
// (certify/tolerance_check.hpp), and the finished certificate is re-checked from its JSON text.
#include "tolerance/certificate.hpp"

#include "certify/tolerance_check.hpp"
#include "core/model_scale.hpp"
#include "model/parametric/dimensions.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace hipair::tolerance_detail {
namespace {

using verify::Interval;
using verify::Jet;

double approx(const Interval& x) { return x.is_bounded() ? x.middle().get_d() : std::nan(""); }

// x rounded down (or up) to a multiple of 10^-14: short exact rationals in the certificate.
Rational grid(double x, bool up) {
  constexpr double scale = 1e14;
  double k = up ? std::ceil(x * scale) : std::floor(x * scale);
  Rational q(mpz_class(k), mpz_class("100000000000000"));
  q.canonicalize();
  return q;
}

FeatureReference reference(const Model& model, const FeatureIdentity& f) {
  const Part& part = model.parts.at(f.part);
  FeatureReference r;
  r.edge = EdgeReference{part.name, f.loop, f.edge, part.loops.at(f.loop).edges.at(f.edge).label};
  r.vertex = f.kind == FeatureKind::vertex;
  return r;
}

class Producer {
 public:
  explicit Producer(const CertifyRequest& request) : request_(request) {}

  // The claim, the pieces of constant sides along the range and the verifier's evaluator;
  // false with result.reason set when the request cannot be certified.
  bool prepare(ToleranceCertification& result) {
    result.scale = request_.scale;
    const Model& m = request_.model->nominal();
    claim_.driver = m.parts[request_.driver].name;
    claim_.follower = m.parts[request_.follower].name;
    claim_.range = request_.range;
    claim_.scale = request_.scale;
    for (std::size_t i : request_.varied) {
      const Parameter& p = m.parameters[i];
      claim_.varied.push_back(p.name);
      claim_.box.push_back({request_.scale * (p.range.lo - p.nominal), request_.scale * (p.range.hi - p.nominal)});
    }
    // The channel's sides along the range, and the pieces of constant sides.
    std::vector<Piece>& pieces = pieces_;
    for (const ChannelSample& s : request_.samples) {
      if (!s.bounded) {
        // The driver's coordinate in rad (mm when it translates), as `--range` takes it, and for a
        // rotating driver in degrees too, as the report's tables give it (session 51).
        std::ostringstream at;
        at << std::setprecision(6) << s.driver;
        if (m.parts[request_.driver].motion.kind == Motion::Kind::rotation)
          at << " rad (" << s.driver * 180 / 3.14159265358979323846 << " deg)";
        else
          at << " mm";
        result.reason = "the follower's channel is not bounded on both sides at driver " + at.str() + " (nominal geometry" +
                        (s.unbounded_why.empty() ? std::string() : ": " + s.unbounded_why) +
                        "): a no-jam certificate needs a contact on both sides. The analysis starts '" + claim_.follower +
                        "' at its initial position at the range's start (at the nearest touching position if the parts "
                        "overlap there) and follows it; start the range where the pair is engaged, or give '" +
                        claim_.follower + "' an initial position inside its channel there";
        return false;
      }
      std::size_t lower = side_index(m, s.lower_first, s.lower_second);
      std::size_t upper = side_index(m, s.upper_first, s.upper_second);
      if (pieces.empty() || pieces.back().lower != lower || pieces.back().upper != upper)
        pieces.push_back(Piece{lower, upper, {}});
      pieces.back().samples.push_back(&s);
    }
    if (pieces.empty()) {
      result.reason = "no driver position of the nominal path lies in the range";
      return false;
    }
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      if (k > 0) pieces[k].previous = &pieces[k - 1];
      if (k + 1 < pieces.size()) pieces[k].next = &pieces[k + 1];
      if (k + 1 < pieces.size() && drop_between(pieces[k], pieces[k + 1])) drops_ = true;
    }
    try {
      evaluator_ = std::make_unique<verify::ToleranceEvaluator>(request_.model, claim_);
    } catch (const verify::Rejection& rejection) {
      result.reason = rejection.reason;
      return false;
    }
    return true;
  }

  // The corner search alone (corner_jam_scan): at `scale`, is there an exact jam witness at the
  // linearised worst corner, the driver refined between the nominal path's positions?
  JamScan scan() {
    JamScan out;
    out.witness.scale = request_.scale;
    if (!prepare(out.witness)) return out;
    refine_ = true;
    out.jams = corner_jams(pieces_, out.witness);
    if (out.jams) {
      out.witness.outcome = ToleranceCertification::Outcome::jams;
      out.witness.reason = jam_reason_;
    }
    out.play = best_play_;
    out.driver = best_driver_;
    return out;
  }

  ToleranceCertification run() {
    auto start = std::chrono::steady_clock::now();
    ToleranceCertification result;
    if (!prepare(result)) return result;
    std::vector<Piece>& pieces = pieces_;
    // First the linearised worst corner of the box at each driver position of the nominal path:
    // above the jamming threshold the channel closes there, and a corner is an exact rational
    // vector of the box — the witness. The driver is refined between the positions at the
    // narrowest corner channel: the closing can lie between two positions (Geneva: at the
    // switch of the lower side from the lock arc to the pin, 2.2542 rad), where a leaf may
    // take a neighbouring piece's sides and the verifier would accept it (docs/tolerance.md
    // "The threshold, bracketed").
    refine_ = true;
    report_ = static_cast<bool>(request_.progress);
    if (corner_jams(pieces, result)) {
      result.outcome = ToleranceCertification::Outcome::jams;
      result.reason = jam_reason_;
      result.attempts = attempts_;
      result.seconds_produce = seconds_since(start);
      return result;
    }
    std::vector<RationalInterval> region = claim_.box;
    region.push_back(claim_.range);
    Status status = Status::ok;
    for (std::size_t k = 0; k < pieces.size() && status == Status::ok; ++k) {
      RationalInterval driver = region.back();
      if (k + 1 < pieces.size()) {
        double boundary = 0.5 * (pieces[k].samples.back()->driver + pieces[k + 1].samples.front()->driver);
        Rational cut = grid(boundary, false);
        if (cut > driver.lo && cut < driver.hi) {
          claim_.tree.push_back(split("driver", cut));
          std::vector<RationalInterval> low = region;
          low.back().hi = cut;
          region.back().lo = cut;
          status = solve(low, pieces[k], 0);
          continue;
        }
        // A piece too short to separate: its sides are tried over the next piece's region.
        continue;
      }
      status = solve(region, pieces[k], 0);
    }
    result.leaves = claim_.leaves.size();
    result.second_order_leaves = second_order_leaves_;
    result.attempts = attempts_;
    result.seconds_produce = seconds_since(start);
    if (status == Status::jams) {
      result.outcome = ToleranceCertification::Outcome::jams;
      result.reason = jam_reason_;
      result.witness_parameters = jam_witness_;
      result.witness_coordinate = jam_coordinate_;
      result.witness_lower = jam_lower_;
      result.witness_upper = jam_upper_;
      return result;
    }
    if (status != Status::ok) {
      result.reason = undecided_reason_;
      return result;
    }
    const Model& m = request_.model->nominal();
    ToleranceClaim claim = claim_;
    file_scale_margins(m, claim);
    // a copy whose parameters are rescaled by their length dimensions (session 67): the claim's
    // deviations and the parameters' values at the file's scale
    const std::vector<long> exponents = model_detail::parameter_scale_exponents(*request_.model);
    const bool rescaled = std::any_of(exponents.begin(), exponents.end(), [](long k) { return k != 0; });
    std::optional<Model> at_file_scale;
    if (rescaled) {
      file_scale_deviations(m, exponents, claim);
      at_file_scale = m;
      std::vector<long> back(exponents.size());
      for (std::size_t i = 0; i < back.size(); ++i) back[i] = -exponents[i];
      model_detail::scale_parameter_values(at_file_scale->parameters, back);
    }
    CheckedCertificate checked = checked_tolerance_certificate(at_file_scale ? *at_file_scale : m, claim,
                                                               request_.model_text, request_.model_file);
    const VerificationResult& check = checked.check;
    result.seconds_verify = checked.seconds_verify;
    // A no_jam certificate whose evidence passes checks 1-6 is "valid" when the verifier's check 7
    // proves a free follower path across the range, otherwise "unproven" (docs/certify.md).
    if (!check.valid && !check.unproven)
      throw GeometryError("tolerance certificate failed its own check (a producer bug): " + check.reason);
    result.outcome = ToleranceCertification::Outcome::certified;
    result.unproven = check.unproven;
    if (check.unproven) {
      std::size_t at = check.summary.find("; not proved: ");
      result.reason = at == std::string::npos ? check.summary : check.summary.substr(at + 2);
    }
    result.certificate = std::move(checked.certificate);
    return result;
  }

 private:
  // A mechanism drawn at an extreme scale is analysed on the model divided exactly by 10^E
  // (analysed_form; both parts rotate, so every other number of the claim is an angle or a
  // parameter's deviation, which the copy keeps): the second-order margins are values of contact
  // functions there (certify/tolerance_check.cpp contact_of), homogeneous in lengths of degree 2
  // (a vertex on a segment or an arc, two arcs) or 4 (an arc against a segment), so at the model
  // file's scale they are those times 10^(2E) or 10^(4E), exactly (session 56, scale56: before,
  // --certify was refused at every such scale).
  void file_scale_margins(const Model& m, ToleranceClaim& claim) const {
    const long exponent = request_.model->length_exponent();
    if (exponent == 0) return;
    auto arc = [&](const FeatureReference& f) {
      const Part& part = m.parts.at(*m.find_part(f.edge.part));
      return part.loops.at(f.edge.loop).edges.at(f.edge.edge).is_arc();
    };
    for (ToleranceLeaf& leaf : claim.leaves)
      for (std::size_t s = 0; s < leaf.witness_margins.size() && s < 2; ++s) {
        const ContactSidePair& side = claim.sides.at((s == 0 ? leaf.lower : leaf.upper).pair);
        const bool fourth = !side.driver.vertex && !side.follower.vertex && arc(side.driver) != arc(side.follower);
        leaf.witness_margins[s] *= power_of_ten_rational((fourth ? 4 : 2) * exponent);
      }
  }

  // Session 67 (scale67): on a copy whose parameters are rescaled by their length dimensions
  // (ParametricModel::rescaled of a model whose parameters lie beyond the doubles), a varied
  // parameter's deviations are the file's times 10^-k (model_detail::parameter_scale_exponents):
  // the box, the leaves' parameter intervals and the tree's splits along it are multiplied by
  // 10^k exactly, the witnesses' slopes per unit of it by 10^-k; the margins (contact functions,
  // homogeneous in lengths) are file_scale_margins'.
  static void file_scale_deviations(const Model& m, const std::vector<long>& exponents, ToleranceClaim& claim) {
    for (std::size_t j = 0; j < claim.varied.size(); ++j) {
      const Parameter* p = m.find_parameter(claim.varied[j]);
      if (!p) continue;
      const long k = exponents.at(static_cast<std::size_t>(p - m.parameters.data()));
      if (k == 0) continue;
      const Rational up = power_of_ten_rational(k), down = power_of_ten_rational(-k);
      if (j < claim.box.size()) {
        claim.box[j].lo *= up;
        claim.box[j].hi *= up;
      }
      for (ToleranceLeaf& leaf : claim.leaves) {
        if (j < leaf.parameters.size()) {
          leaf.parameters[j].lo *= up;
          leaf.parameters[j].hi *= up;
        }
        if (leaf.witness && j < leaf.witness_slopes.size()) leaf.witness_slopes[j] *= down;
      }
      for (ToleranceTreeNode& node : claim.tree)
        if (!node.leaf && node.dimension == claim.varied[j]) node.value *= up;
    }
  }

  enum class Status { ok, jams, undecided };
  struct Piece {
    std::size_t lower = 0, upper = 0;
    std::vector<const ChannelSample*> samples;
    const Piece* previous = nullptr;
    const Piece* next = nullptr;
  };

  // Whether a side of the channel jumps between the last sample of `a` and the first of the
  // next piece `b` (a *drop*: the escapement's tooth leaves the impulse face and the anchor's
  // lower side falls to the wheel's root circle), rather than passing continuously from one
  // feature pair to another (Geneva's lock/drive switch, a kink): the nominal side value moves
  // across the boundary by more than the channel is wide there (the smaller play of the two
  // samples) and by more than 4 times what the side's own slopes next to it (from each piece's
  // two samples nearest the boundary) would move it over that step. Approximate: it only
  // chooses where the producer spends check 7's work (Producer::solve), never a verdict.
  static bool drop_between(const Piece& a, const Piece& b) {
    const ChannelSample& last = *a.samples.back();
    const ChannelSample& first = *b.samples.front();
    const double step = first.driver - last.driver;
    if (!(step > 0)) return false;
    for (bool upper : {false, true}) {
      auto value = [&](const ChannelSample& s) { return upper ? s.upper : s.lower; };
      double slope = 0;
      bool known = false;
      if (a.samples.size() >= 2) {
        const ChannelSample& before = *a.samples[a.samples.size() - 2];
        if (last.driver > before.driver) {
          slope = std::max(slope, std::fabs(value(last) - value(before)) / (last.driver - before.driver));
          known = true;
        }
      }
      if (b.samples.size() >= 2) {
        const ChannelSample& after = *b.samples[1];
        if (after.driver > first.driver) {
          slope = std::max(slope, std::fabs(value(after) - value(first)) / (after.driver - first.driver));
          known = true;
        }
      }
      const double jump = std::fabs(value(first) - value(last));
      const double play = std::min(last.upper - last.lower, first.upper - first.lower);
      if (known && jump > 4 * slope * step && jump > play) return true;
    }
    return false;
  }

  // Progress: a certified leaf's share of the whole region (box x range) added to the share
  // covered (the leaves do not overlap: they are the tree's), shown as 0.1 ... 0.95.
  void covered(const std::vector<RationalInterval>& region) {
    double share = 1;
    for (std::size_t i = 0; i < region.size(); ++i) {
      const RationalInterval& whole = i < claim_.box.size() ? claim_.box[i] : claim_.range;
      Rational full = whole.hi - whole.lo;
      if (full > 0) share *= Rational((region[i].hi - region[i].lo) / full).get_d();
    }
    covered_ += share;
    request_.progress(0.1 + 0.85 * std::min(1.0, covered_));
  }

  static ToleranceTreeNode split(const std::string& name, const Rational& value) {
    ToleranceTreeNode n;
    n.dimension = name;
    n.value = value;
    return n;
  }

  std::size_t side_index(const Model& m, const FeatureIdentity& a, const FeatureIdentity& b) {
    const FeatureIdentity& d = a.part == request_.driver ? a : b;
    const FeatureIdentity& f = a.part == request_.driver ? b : a;
    ContactSidePair pair{reference(m, d), reference(m, f)};
    for (std::size_t i = 0; i < claim_.sides.size(); ++i) {
      const ContactSidePair& s = claim_.sides[i];
      if (s.driver.edge.loop == pair.driver.edge.loop && s.driver.edge.edge == pair.driver.edge.edge &&
          s.driver.vertex == pair.driver.vertex && s.follower.edge.loop == pair.follower.edge.loop &&
          s.follower.edge.edge == pair.follower.edge.edge && s.follower.vertex == pair.follower.vertex)
        return i;
    }
    claim_.sides.push_back(pair);
    return claim_.sides.size() - 1;
  }

  // The nominal side value at driver d (linear interpolation between the piece's samples).
  static double guess(const Piece& piece, bool upper, double d) {
    const auto& s = piece.samples;
    auto value = [&](std::size_t i) { return upper ? s[i]->upper : s[i]->lower; };
    if (s.size() == 1 || d <= s.front()->driver) return value(0);
    for (std::size_t i = 1; i < s.size(); ++i)
      if (d <= s[i]->driver) {
        double t = (d - s[i - 1]->driver) / (s[i]->driver - s[i - 1]->driver);
        return value(i - 1) + t * (value(i) - value(i - 1));
      }
    return value(s.size() - 1);
  }

  struct SideGuess {
    bool ok = false;             // certain opposite signs at the bracket's ends over the leaf
    double root = 0;
    RationalInterval centre, bracket;
    std::vector<double> slope;   // varied parameters, then the driver
    bool centre_certain = false; // the centre interval's sign change holds
    bool monotone = false;       // ok, and the follower derivative has one sign over the bracket
  };

  // A side that check 7 found undecided over a candidate leaf (a vertex of one part on an edge
  // of the other): kept as a candidate for the envelope witness of later leaves.
  void learn(const ContactSidePair& pair) {
    for (std::size_t i = 0; i < claim_.sides.size(); ++i) {
      const ContactSidePair& s = claim_.sides[i];
      if (s.driver.edge.loop == pair.driver.edge.loop && s.driver.edge.edge == pair.driver.edge.edge &&
          s.driver.vertex == pair.driver.vertex && s.follower.edge.loop == pair.follower.edge.loop &&
          s.follower.edge.edge == pair.follower.edge.edge && s.follower.vertex == pair.follower.vertex) {
        if (std::find(learned_.begin(), learned_.end(), i) == learned_.end() && learned_.size() < 16) learned_.push_back(i);
        return;
      }
    }
    if (learned_.size() >= 16) return;
    claim_.sides.push_back(pair);
    learned_.push_back(claim_.sides.size() - 1);
  }

  // Side `pair`'s root (follower coordinate) at driver d with the geometry `point`, by Newton
  // from `start` (approximate: it only chooses); NaN when it fails or wanders to another branch.
  double newton(verify::ToleranceGeometry& point, std::size_t pair, const Rational& d, double start) {
    Jet driver(verify::enclose(d));
    double y = start;
    for (int iteration = 0; iteration < 40; ++iteration) {
      Jet f = evaluator_->contact(point, pair, driver, Jet::variable(verify::enclose(Rational(y)), 0, 1));
      double value = approx(f.value), slope = approx(f.partial(0));
      if (!std::isfinite(value) || !std::isfinite(slope) || slope == 0) break;
      double step = value / slope;
      y -= step;
      if (!std::isfinite(y)) break;
      if (std::fabs(step) <= 1e-15 * (1 + std::fabs(y)))
        return std::fabs(y - start) > 0.5 ? std::nan("") : y;   // wandered to another branch
    }
    return std::nan("");
  }

  // Newton at the leaf's centre from the nominal side value, a certified centre interval, the
  // root's gradient (middle of its enclosure over the box), then bracket ends widened until the
  // contact function's sign over the whole leaf is certain at both.
  SideGuess side_guess(std::size_t pair, double start, const ToleranceLeaf& leaf, verify::ToleranceGeometry& over,
                       verify::ToleranceGeometry& point, const std::vector<double>& half, double half_driver) {
    SideGuess g;
    Rational d0 = (leaf.driver.lo + leaf.driver.hi) / 2;
    Jet driver(verify::enclose(d0));
    double y = newton(point, pair, d0, start);
    if (!std::isfinite(y)) return g;
    g.root = y;
    double eps = 1e-12 * (1 + std::fabs(y));
    g.centre = {grid(y - eps, false), grid(y + eps, true)};
    int s0 = evaluator_->contact(point, pair, driver, Jet(verify::enclose(g.centre.lo))).value.sign();
    int s1 = evaluator_->contact(point, pair, driver, Jet(verify::enclose(g.centre.hi))).value.sign();
    g.centre_certain = s0 != 0 && s1 != 0 && s0 != s1;
    std::size_t m = evaluator_->variables();
    Jet f = evaluator_->contact(over, pair, Jet::variable(verify::enclose(leaf.driver), evaluator_->driver_variable(), m),
                                Jet::variable(verify::enclose(Rational(y)), evaluator_->follower_variable(), m));
    double fy = approx(f.partial(evaluator_->follower_variable()));
    if (!std::isfinite(fy) || fy == 0) return g;
    double spread = 0;
    for (std::size_t i = 0; i <= evaluator_->varied_count(); ++i) {
      double s = -approx(f.partial(i)) / fy;
      if (!std::isfinite(s)) return g;
      g.slope.push_back(s);
      spread += std::fabs(s) * (i < half.size() ? half[i] : half_driver);
    }
    if (!g.centre_certain) return g;
    int sign_lo = 0, sign_hi = 0;
    double w = 1.1 * spread + 4 * eps;
    for (int attempt = 0; attempt < 10 && sign_lo == 0; ++attempt, w *= 1.3) {
      g.bracket.lo = grid(y - w, false);
      sign_lo = evaluator_->sign_over_leaf(leaf, pair, g.bracket.lo, over, point);
    }
    w = 1.1 * spread + 4 * eps;
    for (int attempt = 0; attempt < 10 && sign_hi == 0; ++attempt, w *= 1.3) {
      g.bracket.hi = grid(y + w, true);
      sign_hi = evaluator_->sign_over_leaf(leaf, pair, g.bracket.hi, over, point);
    }
    g.ok = sign_lo != 0 && sign_hi != 0 && sign_lo != sign_hi;
    if (g.ok) {   // without it, only a leaf with a witness can use this side (check_witness)
      Jet over_bracket = evaluator_->contact(
          over, pair, Jet::variable(verify::enclose(leaf.driver), evaluator_->driver_variable(), m),
          Jet::variable(verify::enclose(g.bracket), evaluator_->follower_variable(), m));
      g.monotone = over_bracket.partial(evaluator_->follower_variable()).sign() != 0;
    }
    return g;
  }

  // At every sample of the nominal path: the sides' sensitivities over the box (middles of their
  // enclosures), the corner of the box that narrows the channel most by them, and at that exact
  // corner and driver position both sides isolated by certain sign changes. The upper side
  // certainly below the lower one is a jam with an exact witness.
  bool corner_jams(const std::vector<Piece>& pieces, ToleranceCertification& result) {
    std::size_t k = claim_.varied.size();
    std::vector<Interval> box;
    std::vector<double> half;
    for (std::size_t i = 0; i < k; ++i) {
      box.push_back(verify::enclose(claim_.box[i]));
      half.push_back(Rational((claim_.box[i].hi - claim_.box[i].lo) / 2).get_d());
    }
    verify::ToleranceGeometry over = evaluator_->geometry(box, true);
    std::size_t positions = 0, done = 0;
    for (const Piece& piece : pieces) positions += piece.samples.size();
    for (const Piece& piece : pieces)
      for (const ChannelSample* s : piece.samples) {
        if (report_) request_.progress(0.1 * static_cast<double>(done++) / static_cast<double>(positions));
        ++attempts_;
        Rational d(s->driver);
        if (d < claim_.range.lo || d > claim_.range.hi) continue;
        ToleranceLeaf leaf;
        leaf.parameters = claim_.box;
        leaf.driver = {d, d};
        std::vector<Interval> middle;
        for (std::size_t i = 0; i < k; ++i) middle.push_back(verify::enclose((claim_.box[i].lo + claim_.box[i].hi) / 2));
        verify::ToleranceGeometry point = evaluator_->geometry(middle, false);
        SideGuess gl = side_guess(piece.lower, s->lower, leaf, over, point, half, 0);
        SideGuess gu = side_guess(piece.upper, s->upper, leaf, over, point, half, 0);
        if (gl.slope.size() != k + 1 || gu.slope.size() != k + 1) continue;
        ToleranceLeaf corner;
        corner.driver = {d, d};
        std::vector<Interval> at;
        for (std::size_t i = 0; i < k; ++i) {
          // the play U - L decreases with p_i when its slope is positive: take the low end
          const Rational& end = gu.slope[i] - gl.slope[i] > 0 ? claim_.box[i].lo : claim_.box[i].hi;
          corner.parameters.push_back({end, end});
          at.push_back(verify::enclose(end));
        }
        verify::ToleranceGeometry corner_point = evaluator_->geometry(at, false);
        verify::ToleranceGeometry corner_over = evaluator_->geometry(at, true);
        SideGuess cl = side_guess(piece.lower, s->lower, corner, corner_over, corner_point, std::vector<double>(k, 0), 0);
        SideGuess cu = side_guess(piece.upper, s->upper, corner, corner_over, corner_point, std::vector<double>(k, 0), 0);
        if (cl.centre_certain && cu.centre_certain && cu.root - cl.root < best_play_) {
          best_play_ = cu.root - cl.root;
          best_driver_ = s->driver;
          best_ = Best{&piece, s, corner.parameters, at, cl.root, cu.root};
        }
        if (!(cl.centre_certain && cu.centre_certain && cu.centre.hi < cl.centre.lo)) continue;
        record_jam(d, corner, cl, cu, result);
        return true;
      }
    return refine_ && refined_corner_jams(result);
  }

  void record_jam(const Rational& d, const ToleranceLeaf& corner, const SideGuess& cl, const SideGuess& cu,
                  ToleranceCertification& result) {
    std::size_t k = claim_.varied.size();
    jam_reason_ = "the channel's sides cross at driver " + to_exact_string(d) + " (" + std::to_string(d.get_d()) +
                  "): the upper side's root lies in [" + to_exact_string(cu.centre.lo) + ", " +
                  to_exact_string(cu.centre.hi) + "], below the lower side's [" + to_exact_string(cl.centre.lo) +
                  ", " + to_exact_string(cl.centre.hi) + "] (certain sign changes), at the corner of the box";
    result.witness_parameters.clear();
    for (std::size_t i = 0; i < k; ++i) {
      result.witness_parameters.emplace_back(claim_.varied[i], corner.parameters[i].lo);
      jam_reason_ += " " + claim_.varied[i] + "=" + to_exact_string(corner.parameters[i].lo);
    }
    result.witness_coordinate = d;
    result.witness_lower = cl.centre;
    result.witness_upper = cu.centre;
  }

  // The corner of the position with the narrowest corner channel (corner_jams), the driver
  // moved to the smallest play between its neighbouring positions (golden section on the two
  // sides' Newton roots: approximate, it only chooses), and there the same exact test.
  bool refined_corner_jams(ToleranceCertification& result) {
    if (!best_.piece) return false;
    // Between the neighbouring positions, but not past the midpoint to a position of another
    // piece (there the sides are other feature pairs: the certificate's pieces split there).
    const auto& all = request_.samples;
    std::size_t at = static_cast<std::size_t>(best_.sample - all.data());
    const auto& own = best_.piece->samples;
    auto end = [&](std::size_t j) {
      bool same = std::find(own.begin(), own.end(), &all[j]) != own.end();
      return same ? all[j].driver : 0.5 * (all[j].driver + best_.sample->driver);
    };
    double a = at > 0 ? end(at - 1) : best_.sample->driver;
    double b = at + 1 < all.size() ? end(at + 1) : best_.sample->driver;
    a = std::max(a, claim_.range.lo.get_d());
    b = std::min(b, claim_.range.hi.get_d());
    verify::ToleranceGeometry point = evaluator_->geometry(best_.at, false);
    verify::ToleranceGeometry over = evaluator_->geometry(best_.at, true);
    auto play = [&](double d) {
      Rational q(d);
      double l = newton(point, best_.piece->lower, q, best_.lower);
      double u = newton(point, best_.piece->upper, q, best_.upper);
      return std::isfinite(l) && std::isfinite(u) ? u - l : std::numeric_limits<double>::infinity();
    };
    const double golden = 0.5 * (std::sqrt(5.0) - 1);
    double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
    double f1 = play(x1), f2 = play(x2);
    for (int iteration = 0; iteration < 100 && b - a > 1e-15 * (1 + std::fabs(a)); ++iteration) {
      if (f1 <= f2) {
        b = x2;
        x2 = x1;
        f2 = f1;
        x1 = b - golden * (b - a);
        f1 = play(x1);
      } else {
        a = x1;
        x1 = x2;
        f1 = f2;
        x2 = a + golden * (b - a);
        f2 = play(x2);
      }
    }
    double dm = f1 <= f2 ? x1 : x2;
    double fm = std::min(f1, f2);
    if (fm < best_play_) {
      best_play_ = fm;
      best_driver_ = dm;
    }
    Rational d = grid(dm, false);
    ToleranceLeaf corner;
    corner.driver = {d, d};
    corner.parameters = best_.parameters;
    std::size_t k = claim_.varied.size();
    SideGuess cl = side_guess(best_.piece->lower, best_.lower, corner, over, point, std::vector<double>(k, 0), 0);
    SideGuess cu = side_guess(best_.piece->upper, best_.upper, corner, over, point, std::vector<double>(k, 0), 0);
    if (!(cl.centre_certain && cu.centre_certain && cu.centre.hi < cl.centre.lo)) return false;
    record_jam(d, corner, cl, cu, result);
    return true;
  }

  // x > 0 rounded down to 10 significant digits (a short exact rational); 0 when x <= 0.
  static Rational short_below(const Rational& x) {
    if (!(x > 0)) return Rational(0);
    double v = x.get_d() * (1 - 1e-9);
    if (!(v > 0) || !std::isfinite(v)) return Rational(0);
    int exponent = static_cast<int>(std::floor(std::log10(v))) - 9;
    mpz_class ten = 1;
    mpz_ui_pow_ui(ten.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(exponent)));
    Rational unit = exponent >= 0 ? Rational(ten) : Rational(mpz_class(1), ten);
    Rational q = Rational(mpz_class(std::floor(v / unit.get_d()))) * unit;
    q.canonicalize();
    while (q > 0 && q > x) q -= unit;   // never above x (the double's rounding)
    return q;
  }

  // Fills w's second-order margins from the verifier's second-order enclosure of each side's
  // contact function at the witness; false when one of them contains 0.
  bool second_order_margins(ToleranceLeaf& w) {
    w.witness_margins.clear();
    for (bool upper : {false, true}) {
      Interval e = evaluator_->second_order(w, upper);
      if (e.sign() == 0) return false;
      Rational margin = short_below(e.sign() > 0 ? e.lower() : -e.upper());
      if (!(margin > 0)) return false;
      w.witness_margins.push_back(margin);
    }
    return true;
  }

  // Per dimension (varied parameters, then the driver): the mean-value remainder that the
  // witness test of `w` adds for it (|partial| x half-width of each side's contact function at
  // the witness path, where the partial's sign is not certain), relative to the function's size
  // at the leaf's centre. Only guides the split.
  std::vector<double> witness_error(const ToleranceLeaf& w, verify::ToleranceGeometry& over,
                                    verify::ToleranceGeometry& point, const std::vector<double>& half,
                                    double half_driver) {
    std::size_t k = claim_.varied.size(), m = evaluator_->variables();
    auto offset = [](const RationalInterval& r) {
      Rational c = (r.lo + r.hi) / 2;
      return verify::enclose(RationalInterval{r.lo - c, r.hi - c});
    };
    Interval value = verify::enclose(*w.witness);
    std::vector<Interval> slopes;
    for (std::size_t i = 0; i <= k; ++i) {
      slopes.push_back(verify::enclose(w.witness_slopes[i]));
      value = value + slopes.back() * (i < k ? offset(w.parameters[i]) : offset(w.driver));
    }
    slopes.push_back(Interval(Rational(0)));
    Jet witness(value, slopes);
    Jet driver = Jet::variable(verify::enclose(w.driver), evaluator_->driver_variable(), m);
    Jet driver_centre(verify::enclose((w.driver.lo + w.driver.hi) / 2));
    std::vector<double> score(k + 1, 0.0);
    for (const LeafSide* side : {&w.lower, &w.upper}) {
      Jet h = evaluator_->contact(over, side->pair, driver, witness);
      double size = std::fabs(approx(evaluator_->contact(point, side->pair, driver_centre, Jet(verify::enclose(*w.witness))).value));
      if (!(size > 0)) size = 1;
      for (std::size_t i = 0; i <= k; ++i) {
        const Interval& d = h.partial(i);
        if (d.sign() != 0 || !d.is_bounded()) continue;
        double magnitude = std::max(std::fabs(d.lower().get_d()), std::fabs(d.upper().get_d()));
        score[i] += magnitude * (i < k ? half[i] : half_driver) / size;
      }
    }
    return score;
  }

  // A linear witness y* = w + sum a_i (x_i - c_i) for the channel between the envelopes of
  // all candidate sides over the leaf (session 20): by each candidate's linearisation about the
  // centre (root R_j, slopes s_j), y* stays above a lower candidate over the leaf when
  // w - R_j - sum |a_i - s_ji| h_i > 0 and below an upper one when R_j - w - sum |a_i - s_ji| h_i
  // > 0. The smallest of these margins is concave and piecewise linear in each a_i with its
  // breakpoints at the candidates' slopes: a few rounds of coordinate ascent over those, then w
  // in the middle. Nullopt when there are no more than the two sides of the piece or the
  // linearised channel closes. Approximate (doubles): it only chooses; the verifier decides.
  template <class Candidates>
  std::optional<std::pair<double, std::vector<double>>> envelope_witness(const Candidates& lowers,
                                                                         const Candidates& uppers,
                                                                         const std::vector<double>& half,
                                                                         double half_driver) const {
    std::size_t k = half.size();
    std::vector<const SideGuess*> lo, up;
    for (const auto& c : lowers)
      if (std::isfinite(c.second.root) && c.second.slope.size() == k + 1) lo.push_back(&c.second);
    for (const auto& c : uppers)
      if (std::isfinite(c.second.root) && c.second.slope.size() == k + 1) up.push_back(&c.second);
    if (lo.empty() || up.empty() || lo.size() + up.size() <= 2) return std::nullopt;
    auto width = [&](std::size_t i) { return i < k ? half[i] : half_driver; };
    std::vector<double> a(k + 1, 0.0);
    double lo_best = -1e300, up_best = 1e300;
    for (const SideGuess* g : lo) lo_best = std::max(lo_best, g->root);
    for (const SideGuess* g : up) up_best = std::min(up_best, g->root);
    for (std::size_t i = 0; i <= k; ++i) {   // start: the middle of the binding pair's slopes
      const SideGuess* gl = lo.front();
      const SideGuess* gu = up.front();
      for (const SideGuess* g : lo) if (g->root == lo_best) gl = g;
      for (const SideGuess* g : up) if (g->root == up_best) gu = g;
      a[i] = 0.5 * (gl->slope[i] + gu->slope[i]);
    }
    // penalty sums per candidate, kept up to date
    std::vector<double> pl(lo.size(), 0.0), pu(up.size(), 0.0);
    for (std::size_t i = 0; i <= k; ++i) {
      for (std::size_t j = 0; j < lo.size(); ++j) pl[j] += std::fabs(a[i] - lo[j]->slope[i]) * width(i);
      for (std::size_t j = 0; j < up.size(); ++j) pu[j] += std::fabs(a[i] - up[j]->slope[i]) * width(i);
    }
    auto margin = [&](const std::vector<double>& ql, const std::vector<double>& qu) {
      double top = -1e300, bottom = 1e300;
      for (std::size_t j = 0; j < lo.size(); ++j) top = std::max(top, lo[j]->root + ql[j]);
      for (std::size_t j = 0; j < up.size(); ++j) bottom = std::min(bottom, up[j]->root - qu[j]);
      return std::make_pair(bottom - top, 0.5 * (top + bottom));
    };
    for (int round = 0; round < 4; ++round) {
      bool moved = false;
      for (std::size_t i = 0; i <= k; ++i) {
        double h = width(i);
        if (!(h > 0)) continue;
        std::vector<double> breaks;
        for (const SideGuess* g : lo) breaks.push_back(g->slope[i]);
        for (const SideGuess* g : up) breaks.push_back(g->slope[i]);
        double best_value = margin(pl, pu).first, best_a = a[i];
        for (double b : breaks) {
          std::vector<double> ql = pl, qu = pu;
          for (std::size_t j = 0; j < lo.size(); ++j) ql[j] += (std::fabs(b - lo[j]->slope[i]) - std::fabs(a[i] - lo[j]->slope[i])) * h;
          for (std::size_t j = 0; j < up.size(); ++j) qu[j] += (std::fabs(b - up[j]->slope[i]) - std::fabs(a[i] - up[j]->slope[i])) * h;
          double v = margin(ql, qu).first;
          if (v > best_value + 1e-12 * std::fabs(best_value)) {   // a strict gain only
            best_value = v;
            best_a = b;
          }
        }
        if (best_a != a[i]) {
          for (std::size_t j = 0; j < lo.size(); ++j) pl[j] += (std::fabs(best_a - lo[j]->slope[i]) - std::fabs(a[i] - lo[j]->slope[i])) * h;
          for (std::size_t j = 0; j < up.size(); ++j) pu[j] += (std::fabs(best_a - up[j]->slope[i]) - std::fabs(a[i] - up[j]->slope[i])) * h;
          a[i] = best_a;
          moved = true;
        }
      }
      if (!moved) break;
    }
    auto [value, middle] = margin(pl, pu);
    if (!(value > 0)) return std::nullopt;
    return std::make_pair(middle, a);
  }

  // `refused`: how many leaves on the branch above held without a witness path and were split.
  Status solve(const std::vector<RationalInterval>& region, const Piece& piece, int depth, std::size_t refused = 0) {
    if (attempts_ >= 4 * request_.max_leaves || claim_.leaves.size() >= request_.max_leaves) {
      undecided_reason_ = "the branch-and-bound gave up after " + std::to_string(attempts_) + " boxes (" +
                          std::to_string(claim_.leaves.size()) + " leaves certified)";
      return Status::undecided;
    }
    ++attempts_;
    std::size_t k = claim_.varied.size();
    std::vector<Interval> centre;
    std::vector<double> half;
    for (std::size_t i = 0; i < k; ++i) {
      centre.push_back(verify::enclose((region[i].lo + region[i].hi) / 2));
      half.push_back(Rational((region[i].hi - region[i].lo) / 2).get_d());
    }
    Rational d0 = (region[k].lo + region[k].hi) / 2;
    double half_driver = Rational((region[k].hi - region[k].lo) / 2).get_d();
    double dd = d0.get_d();
    ToleranceLeaf leaf;
    leaf.parameters.assign(region.begin(), region.begin() + static_cast<std::ptrdiff_t>(k));
    leaf.driver = region[k];
    std::vector<Interval> box;
    for (std::size_t i = 0; i < k; ++i) box.push_back(verify::enclose(region[i]));
    verify::ToleranceGeometry over = evaluator_->geometry(box, true);
    verify::ToleranceGeometry point = evaluator_->geometry(centre, false);
    // Each side: the piece's own contact pair, and near a switch of sides (where the nominal
    // side's curve may turn back within the box) the neighbouring pieces'.
    auto candidates = [&](bool is_upper) {
      std::vector<std::pair<std::size_t, SideGuess>> out;
      std::vector<const Piece*> pieces{&piece};
      if (piece.previous) pieces.push_back(piece.previous);
      if (piece.next) pieces.push_back(piece.next);
      for (const Piece* candidate : pieces) {
        std::size_t p = is_upper ? candidate->upper : candidate->lower;
        bool seen = false;
        for (const auto& o : out) seen = seen || o.first == p;
        if (seen) continue;
        out.emplace_back(p, side_guess(p, guess(*candidate, is_upper, dd), leaf, over, point, half, half_driver));
      }
      return out;
    };
    auto lowers = candidates(false), uppers = candidates(true);
    std::size_t own_lowers = lowers.size(), own_uppers = uppers.size();
    // The sides check 7 found undecided on earlier leaves (learn): candidates too, lower or upper
    // by where their root nearest the channel's middle lies.
    std::size_t learned_seen = 0;
    auto add_learned = [&]() {
      double middle = 0.5 * (lowers.front().second.root + uppers.front().second.root);
      if (!std::isfinite(middle)) middle = 0.5 * (guess(piece, false, dd) + guess(piece, true, dd));
      for (; learned_seen < learned_.size(); ++learned_seen) {
        std::size_t p = learned_[learned_seen];
        bool seen = false;
        for (const auto& o : lowers) seen = seen || o.first == p;
        for (const auto& o : uppers) seen = seen || o.first == p;
        if (seen) continue;
        double y = newton(point, p, d0, middle);
        if (!std::isfinite(y)) continue;
        SideGuess g = side_guess(p, y, leaf, over, point, half, half_driver);
        if (!std::isfinite(g.root) || g.slope.size() != k + 1) continue;
        (g.root < middle ? lowers : uppers).emplace_back(p, std::move(g));
      }
    };
    add_learned();
    std::size_t lower_pair = lowers.front().first, upper_pair = uppers.front().first;
    SideGuess lower = lowers.front().second, upper = uppers.front().second;
    if (lower.centre_certain && upper.centre_certain && upper.centre.hi < lower.centre.lo) {
      // Both sides isolated at the centre (certain sign changes) and in reverse order: the
      // channel is closed at this parameter vector and driver position.
      jam_reason_ = "the channel's sides cross at driver " + std::to_string(dd) + ": upper side at " +
                    std::to_string(upper.root) + ", lower side at " + std::to_string(lower.root) +
                    " (follower), at the parameter deviations";
      jam_witness_.clear();
      for (std::size_t i = 0; i < k; ++i) {
        Rational c = (region[i].lo + region[i].hi) / 2;
        jam_witness_.emplace_back(claim_.varied[i], c);
        jam_reason_ += " " + claim_.varied[i] + "=" + to_exact_string(c);
      }
      jam_coordinate_ = d0;
      jam_lower_ = lower.centre;
      jam_upper_ = upper.centre;
      return Status::jams;
    }
    // A leaf with these two sides: first with a witness follower path between them (a linear
    // function of the parameters and the driver, so that what moves both sides alike cancels),
    // then with the play enclosed from the sides' slopes.
    bool free_path_failed = false;   // the last candidate passed checks 1-6, check 7 did not prove it
    bool held_without_witness = false;   // a pair of sides passed checks 1-6 here without a witness
    // Check 7 over a candidate leaf before it is accepted: always with free_path_leaves, and in
    // the plain search on a channel with a drop somewhere along the range (session 68). There the
    // sides that pass checks 1-6 need not be the ones binding over the whole leaf: on the
    // escapement the plain search named, over a leaf before the drop, the next piece's sides
    // (the wheel's root circle below) with a witness midway between the root circle and the
    // upper side, which runs through the tooth, and check 7 then left the whole certificate
    // unproven; gating only the leaves next to a drop was not enough (at the whole turn's end the
    // root circle's own side took a witness that check 7 could not prove past the rising tooth
    // back). So every candidate leaf is accepted only when check 7 proves its witness path over
    // the leaf, else it is split where check 7 would, as free_path_leaves does (its envelope
    // witnesses included). Without a drop (Geneva's continuous lock/drive switch, the spur
    // gears) the plain search is unchanged: near Geneva's threshold check 7 on every leaf
    // multiplies its leaves, and its certificates there stay unproven rightly (docs/certify.md,
    // session 17).
    const bool free_path = request_.free_path_leaves || drops_;
    auto accept = [&](ToleranceLeaf candidate) {
      free_path_failed = false;
      try {
        evaluator_->check_leaf(candidate, claim_.leaves.size(), over, point);
      } catch (const verify::Rejection&) {
        return false;
      }
      if (free_path && candidate.witness) {
        // Check 7 over the leaf's box, with the candidate in place (the evaluator reads claim_).
        claim_.leaves.push_back(candidate);
        std::optional<std::size_t> split;
        std::optional<ContactSidePair> event;
        std::string failure =
            evaluator_->free_leaf_failure(claim_.leaves.size() - 1, request_.free_path_budget, &split, &event);
        claim_.leaves.pop_back();
        if (!failure.empty()) {
          free_path_failed = true;
          if (event) learn(*event);
          if (split && !free_path_split_) free_path_split_ = split;   // where check 7 would split
          return false;
        }
      }
      ToleranceTreeNode node;
      node.leaf = true;
      node.index = claim_.leaves.size();
      claim_.tree.push_back(node);
      claim_.leaves.push_back(std::move(candidate));
      if (report_) covered(region);
      return true;
    };
    // `path`: a witness (value at the centre, slopes) chosen for the channel between all the
    // candidate sides (envelope_witness); without it, the middle of the two named sides.
    auto attempt = [&](std::size_t lp, const SideGuess& gl, std::size_t up, const SideGuess& gu,
                       const std::pair<double, std::vector<double>>* path = nullptr) {
      if (!gl.ok || !gu.ok || !(gu.root > gl.root)) return false;
      double mid = path ? path->first : 0.5 * (gl.root + gu.root), spread = 0, predicted = gu.root - gl.root;
      std::vector<Rational> a;
      for (std::size_t i = 0; i <= k; ++i) {
        double h = i < k ? half[i] : half_driver;
        double slope = path ? path->second[i] : 0.5 * (gl.slope[i] + gu.slope[i]);
        a.push_back(grid(slope, false));
        spread += std::fabs(slope) * h;
        predicted -= std::fabs(gu.slope[i] - gl.slope[i]) * h;
      }
      if (predicted <= 0) return false;
      if (path && !(mid > gl.root && mid < gu.root)) return false;
      Rational top = grid(mid + 1.05 * spread + 1e-12, true), bottom = grid(mid - 1.05 * spread - 1e-12, false);
      RationalInterval bl = gl.bracket, bu = gu.bracket;
      if (bl.hi < top) bl.hi = top;
      if (bu.lo > bottom) bu.lo = bottom;
      if (bottom > bl.lo && top < bu.hi) {
        ToleranceLeaf w = leaf;
        w.lower = LeafSide{lp, bl, gl.centre};
        w.upper = LeafSide{up, bu, gu.centre};
        w.witness = grid(mid, false);
        w.witness_slopes = a;
        if (accept(w)) return true;
        // The same witness with the second-order Taylor form (check 6): the margins are the
        // verifier's own enclosures at this leaf, rounded down to short rationals. (Not when
        // only check 7 failed: the margins do not change the path.)
        if (!free_path_failed && second_order_margins(w) && accept(w)) {
          ++second_order_leaves_;
          return true;
        }
        w.witness_margins.clear();
        // The most promising pair of sides so far (largest linearised margin relative to the
        // play at the centre) guides the split.
        double ratio = predicted / (gu.root - gl.root);
        if (witness_score_.empty() || ratio > witness_ratio_) {
          witness_ratio_ = ratio;
          witness_score_ = witness_error(w, over, point, half, half_driver);
        }
      }
      if (!gl.monotone || !gu.monotone) return false;
      ToleranceLeaf p = leaf;
      p.lower = LeafSide{lp, gl.bracket, gl.centre};
      p.upper = LeafSide{up, gu.bracket, gu.centre};
      if (refused < request_.witness_splits) {
        // Without a witness path check 7 cannot start (the certificate would be unproven at this
        // leaf): split it instead, at most witness_splits times along a branch (session 67).
        if (!held_without_witness) {
          try {
            evaluator_->check_leaf(p, claim_.leaves.size(), over, point);
            held_without_witness = true;
          } catch (const verify::Rejection&) {
          }
        }
        return false;
      }
      return accept(std::move(p));
    };
    std::vector<double> score(k + 1, 1.0);
    witness_score_.clear();
    free_path_split_.reset();
    bool slopes = lower.slope.size() == k + 1 && upper.slope.size() == k + 1;
    if (slopes && (!lower.ok || !upper.ok)) {
      // A side not isolated over the leaf: split where that side varies most.
      for (std::size_t i = 0; i <= k; ++i) {
        double h = i < k ? half[i] : half_driver;
        score[i] = (lower.ok ? 0 : std::fabs(lower.slope[i]) * h) + (upper.ok ? 0 : std::fabs(upper.slope[i]) * h);
      }
    } else if (lower.ok && upper.ok) {
      double predicted = upper.root - lower.root;
      for (std::size_t i = 0; i <= k; ++i) {
        score[i] = std::fabs(upper.slope[i] - lower.slope[i]) * (i < k ? half[i] : half_driver);
        predicted -= score[i];
      }
      if (attempt(lower_pair, lower, upper_pair, upper)) return Status::ok;
    } else {
      // Sides not found at the centre: split the widest dimension relative to the box.
      for (std::size_t i = 0; i < k; ++i) {
        Rational full = claim_.box[i].hi - claim_.box[i].lo;
        score[i] = Rational((region[i].hi - region[i].lo) / full).get_d();
      }
      score[k] = Rational((region[k].hi - region[k].lo) / (claim_.range.hi - claim_.range.lo)).get_d();
    }
    // Near a switch of sides (session 20): the witness between the envelopes of all the
    // candidates — above every lower one and below every upper one by their linearisations over
    // the leaf — so that the path stays in the channel whichever side binds at a corner of the
    // box; the leaf then names the pair of sides nearest to it at the centre (checks 3-6 prove
    // them, check 7 the others).
    bool envelope_feasible = false;
    for (int round = 0; round < 3 && free_path && lower.slope.size() == k + 1 &&
                        upper.slope.size() == k + 1;
         ++round) {
      std::size_t known = learned_.size();
      if (auto path = envelope_witness(lowers, uppers, half, half_driver)) {
        std::vector<std::size_t> lo_order, up_order;
        for (std::size_t a = 0; a < lowers.size(); ++a) lo_order.push_back(a);
        for (std::size_t b = 0; b < uppers.size(); ++b) up_order.push_back(b);
        auto nearest = [&](bool is_upper, std::size_t x, std::size_t y) {
          const SideGuess& gx = (is_upper ? uppers : lowers)[x].second;
          const SideGuess& gy = (is_upper ? uppers : lowers)[y].second;
          double dx = std::isfinite(gx.root) ? std::fabs(gx.root - path->first) : 1e300;
          double dy = std::isfinite(gy.root) ? std::fabs(gy.root - path->first) : 1e300;
          return dx < dy;
        };
        std::sort(lo_order.begin(), lo_order.end(), [&](std::size_t x, std::size_t y) { return nearest(false, x, y); });
        std::sort(up_order.begin(), up_order.end(), [&](std::size_t x, std::size_t y) { return nearest(true, x, y); });
        // The nearest pair whose checks 1-6 pass decides: another pair would give check 7 the
        // same path.
        bool tried = false;
        for (std::size_t a : lo_order) {
          for (std::size_t b : up_order) {
            if (attempt(lowers[a].first, lowers[a].second, uppers[b].first, uppers[b].second, &*path)) {
              return Status::ok;
            }
            if ((tried = free_path_failed)) break;
          }
          if (tried) break;
        }
        envelope_feasible = true;
      }
      if (learned_.size() == known) break;
      add_learned();   // check 7 named a new side: try again with it
    }
    // The neighbouring sides (near a switch of sides).
    for (std::size_t a = 0; a < own_lowers && !envelope_feasible; ++a)
      for (std::size_t b = 0; b < own_uppers; ++b)
        if ((a || b) && attempt(lowers[a].first, lowers[a].second, uppers[b].first, uppers[b].second)) return Status::ok;
    // A pair of sides whose linearised play stays positive but whose witness test failed: split
    // where the test's mean-value remainder is largest (a dimension moving both sides alike adds
    // nothing to the play, yet its width widens every gradient enclosure).
    if (witness_score_.size() == k + 1 && *std::max_element(witness_score_.begin(), witness_score_.end()) > 0)
      score = witness_score_;
    // A leaf that passed checks 1-6 but whose witness path check 7 did not prove (free_path_leaves):
    // split where check 7's undecided event would have been split.
    if (free_path_split_ && *free_path_split_ <= k) {
      score.assign(k + 1, 0.0);
      score[*free_path_split_] = 1.0;
    }
    // A leaf that held without a witness path (refused above): split the driver, unless check 7
    // chose a dimension. Where no witness passes, the binding side usually switches along the
    // driver inside the leaf (the escapement's drop: the tooth leaves the impulse face and the
    // lower side falls from it to the wheel's root circle), which no parameter split removes.
    if (held_without_witness && !free_path_split_) {
      score.assign(k + 1, 0.0);
      score[k] = 1.0;
    }
    if (depth > 400) {
      undecided_reason_ = "the branch-and-bound reached depth 400 without certifying a box near driver " + std::to_string(dd);
      return Status::undecided;
    }
    std::size_t best = static_cast<std::size_t>(std::max_element(score.begin(), score.end()) - score.begin());
    Rational cut = (region[best].lo + region[best].hi) / 2;
    if (best == k) {
      Rational snapped = grid(cut.get_d(), false);
      if (snapped > region[k].lo && snapped < region[k].hi) cut = snapped;
    }
    claim_.tree.push_back(split(best == k ? "driver" : claim_.varied[best], cut));
    std::vector<RationalInterval> low = region, high = region;
    low[best].hi = cut;
    high[best].lo = cut;
    if (held_without_witness) ++refused;
    Status s = solve(low, piece, depth + 1, refused);
    if (s != Status::ok) return s;
    return solve(high, piece, depth + 1, refused);
  }

  struct Best {   // the narrowest corner channel met by corner_jams
    const Piece* piece = nullptr;
    const ChannelSample* sample = nullptr;
    std::vector<RationalInterval> parameters;
    std::vector<Interval> at;
    double lower = 0, upper = 0;   // the sides' roots there
  };

  const CertifyRequest& request_;
  std::vector<Piece> pieces_;
  bool refine_ = false;
  Best best_;
  double best_play_ = std::numeric_limits<double>::infinity();
  double best_driver_ = 0;
  ToleranceClaim claim_;
  std::unique_ptr<verify::ToleranceEvaluator> evaluator_;
  std::size_t attempts_ = 0;
  std::size_t second_order_leaves_ = 0;
  bool drops_ = false;   ///< a side drops somewhere along the range (drop_between): check 7 gates every leaf
  std::vector<std::size_t> learned_;   ///< sides named by check 7's undecided events (learn)   ///< leaves whose witness lies between all candidates' envelopes
  std::optional<std::size_t> free_path_split_;   ///< check 7's split choice for the current region
  std::vector<double> witness_score_;
  double witness_ratio_ = 0;
  bool report_ = false;      ///< progress asked for (run(), not the corner search alone)
  double covered_ = 0;       ///< share of the region the certified leaves cover (progress)
  std::string jam_reason_, undecided_reason_;
  std::vector<std::pair<std::string, Rational>> jam_witness_;
  Rational jam_coordinate_;
  RationalInterval jam_lower_, jam_upper_;
};

}  // namespace

CheckedCertificate checked_tolerance_certificate(const Model& model, const ToleranceClaim& claim,
                                                 const std::string& model_text, const std::string& model_file) {
  CheckedCertificate out;
  Certificate& c = out.certificate;
  c.claim = ClaimKind::tolerance;
  c.model_name = model.name;
  c.model_file = model_file;
  c.content_hash = model.content_hash;
  for (const Parameter& p : model.parameters) c.parameters.push_back({p.name, p.nominal, false});
  c.roundings = model.roundings;
  c.first = claim.driver;
  c.second = claim.follower;
  c.tolerance = claim;
  c.statement = certificate_statement(c, model);
  auto verify_start = std::chrono::steady_clock::now();
  out.check = check_certificate_text(read_certificate(write_certificate(c)), model_text, model_file);
  out.seconds_verify = seconds_since(verify_start);
  return out;
}

ToleranceCertification certify_no_jam(const CertifyRequest& request) { return Producer(request).run(); }

JamScan corner_jam_scan(const CertifyRequest& request) { return Producer(request).scan(); }

ThresholdBracket bracket_threshold(const CertifyRequest& base, const Rational& below, const Rational& above,
                                   double relative, std::size_t max_steps) {
  ThresholdBracket out;
  CertifyRequest request = base;
  request.progress = nullptr;   // (the scans report nothing: the bisection's width does)
  auto jams = [&](const Rational& scale, JamScan& scan) {
    request.scale = scale;
    scan = corner_jam_scan(request);
    ++out.steps;
    return scan.jams;
  };
  JamScan low, high;
  Rational lo = below, hi = above;
  if (jams(lo, low)) return out;   // no bracket: a corner jams already below
  for (int grow = 0; !jams(hi, high); ++grow) {
    if (grow >= 4) {
      out.witness = high.witness;   // (its reason when the search could not start)
      return out;
    }
    lo = hi;
    hi = hi * Rational(3, 2);
  }
  out.witness = high.witness;
  // Bisection on short rationals (12 significant digits of the midpoint, strictly inside).
  // Progress: log(first width / width) against log(first width / the width asked for).
  const double first = Rational((hi - lo) / hi).get_d();
  auto report = [&] {
    double now = Rational((hi - lo) / hi).get_d();
    if (base.progress && first > relative && now > 0) base.progress(std::log(first / now) / std::log(first / relative));
  };
  while (out.steps < max_steps && Rational((hi - lo) / hi).get_d() > relative) {
    report();
    double mid = Rational((lo + hi) / 2).get_d();
    int digits = 12 - static_cast<int>(std::floor(std::log10(mid)));
    mpz_class ten;
    mpz_ui_pow_ui(ten.get_mpz_t(), 10, static_cast<unsigned long>(std::max(digits, 0)));
    Rational q(mpz_class(std::floor(mid * ten.get_d())), ten);
    q.canonicalize();
    if (!(q > lo && q < hi)) q = (lo + hi) / 2;
    JamScan scan;
    if (jams(q, scan)) {
      hi = q;
      out.witness = scan.witness;
    } else {
      lo = q;
      low = scan;
    }
  }
  out.found = true;
  out.below = lo;
  out.above = hi;
  out.below_play = low.play;
  out.below_driver = low.driver;
  return out;
}

}  // namespace hipair::tolerance_detail
