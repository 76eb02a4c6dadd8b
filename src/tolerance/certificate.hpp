// The producer of no-jam tolerance certificates (docs/certify.md "Tolerance"; the checked
// claim and its arithmetic are the verifier's, certify/tolerance_check.hpp). Internal to
// src/tolerance/: the analysis gives the nominal channel along the path, this searches the
// branch-and-bound leaves.
#pragma once

#include "model/parametric/parametric.hpp"

#include <hipair/cspace.hpp>
#include <hipair/tolerance.hpp>

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
};

/// Runs the branch-and-bound; a certificate it returns has been re-checked by the verifier's
/// code. \throws GeometryError when a produced certificate fails the re-check (a bug).
ToleranceCertification certify_no_jam(const CertifyRequest& request);

}  // namespace hipair::tolerance_detail
