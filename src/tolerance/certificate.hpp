// The producer of no-jam tolerance certificates (docs/certify.md "Tolerance"; the checked
// claim and its arithmetic are the verifier's, certify/tolerance_check.hpp). Internal to
// src/tolerance/: the analysis gives the nominal channel along the path, this searches the
// branch-and-bound leaves.
#pragma once

#include "model/parametric/parametric.hpp"

#include <hipair/cspace.hpp>
#include <hipair/tolerance.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hipair::tolerance_detail {

/// The follower's channel at one driver position of the nominal path.
struct ChannelSample {
  double driver = 0;        ///< driver coordinate (rad or mm)
  bool bounded = false;     ///< both sides known
  FeatureIdentity lower_first, lower_second, upper_first, upper_second;   ///< the sides' feature pairs
  double lower = 0, upper = 0;   ///< the sides' follower coordinates (rad or mm, approximate)
  /// Not bounded: why, for the message (e.g. "'yoke' at 3.207 mm has no contact on its lower
  /// side"; the analysis's own words, approximate positions).
  std::string unbounded_why;
};

struct CertifyRequest {
  std::shared_ptr<const model_detail::ParametricModel> model;
  std::string model_text;
  std::string model_file;        ///< file name recorded in the certificate
  std::size_t driver = 0, follower = 0;   ///< part indices
  RationalInterval range;
  Rational scale = 1;
  std::vector<std::size_t> varied;        ///< parameter indices
  std::vector<ChannelSample> samples;     ///< along the range, increasing driver
  std::size_t max_leaves = 20000;
  /// Accept a leaf with a witness only when the verifier's check 7 also proves its witness path
  /// free over the leaf's box (at most `free_path_budget` bisections per leaf); else split it.
  bool free_path_leaves = false;
  std::size_t free_path_budget = 8;
  /// A leaf whose sides checks 1-6 prove apart from their slopes alone (no witness path: check 7
  /// cannot start there, so the certificate would be unproven) is split instead, up to this many
  /// times along a branch; beyond, it is accepted and the certificate's check names it (session 67).
  /// ToleranceOptions::certify_witness_splits (`--certify-witness-splits`; session 71).
  std::size_t witness_splits = 6;
  /// Progress of certify_no_jam (the corner search by driver position its first tenth, then the
  /// share of the region box x range the certified leaves cover, to 0.95) and of
  /// bracket_threshold (the bisection's width against the width asked for); empty: none.
  std::function<void(double)> progress;
};

/// The corner search of the jamming threshold at `request.scale`: at every driver position of
/// the nominal path the linearised worst corner of the box, and at the narrowest one the driver
/// refined between its neighbouring positions. `jams`: an exact witness (certain sign changes
/// of both sides at that rational corner and driver, in reverse order) in `witness`.
struct JamScan {
  bool jams = false;
  ToleranceCertification witness;   ///< outcome jams with its witness when `jams`
  double play = 0;                  ///< the narrowest corner channel met (approximate)
  double driver = 0;                ///< where (approximate)
};
JamScan corner_jam_scan(const CertifyRequest& request);

/// Bisection of the scale between `below` and `above` (grown by 3/2 up to four times until
/// the corner search jams) until (above - below) / above <= relative: at `above` an exact jam
/// witness; at `below` the corner search found none (not a proof: the no-jam certificate is).
struct ThresholdBracket {
  bool found = false;
  Rational below, above;
  ToleranceCertification witness;   ///< the jam at `above`
  double below_play = 0, below_driver = 0;   ///< the narrowest corner channel at `below`
  std::size_t steps = 0;            ///< corner searches run
};
ThresholdBracket bracket_threshold(const CertifyRequest& request, const Rational& below, const Rational& above,
                                   double relative, std::size_t max_steps = 80);

/// Seconds of the steady clock since `start` (the producers' and the analysis's timings).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A tolerance certificate and the verifier's re-check of its written text.
struct CheckedCertificate {
  Certificate certificate;
  VerificationResult check;
  double seconds_verify = 0;   ///< the re-check's time
};

/// The tolerance certificate of `claim` about the nominal model `model` (whose file is
/// `model_file` with text `model_text`), written, read back and checked by the verifier's code
/// (check_certificate_text): what both producers (certify_no_jam, the no-interference search)
/// hand back once their leaves cover the region. The caller judges the check.
CheckedCertificate checked_tolerance_certificate(const Model& model, const ToleranceClaim& claim,
                                                 const std::string& model_text, const std::string& model_file);

/// Runs the branch-and-bound; a certificate it returns has been re-checked by the verifier's
/// code. \throws GeometryError when a produced certificate fails the re-check (a bug).
ToleranceCertification certify_no_jam(const CertifyRequest& request);

}  // namespace hipair::tolerance_detail
