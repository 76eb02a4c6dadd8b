// libFuzzer target: any byte string given to the certificate reader either yields a
// certificate or a hipair::Error; a certificate read is then checked by the verifier
// (check_certificate, what hipair-verify runs) against the example model it names (or the
// first one), which must answer valid or invalid with a reason. A sliced_connected certificate
// (<hipair/sliced_certificate.hpp>, a claim outside Certificate) goes to its own reader and check
// (check_sliced_connected), as hipair-verify dispatches it (verify_certificate_file). Anything else escaping
// (another exception, a crash, undefined behaviour, a leak, a hang) is a bug. Built from the
// verifier's own sources (certify/ and the model reader) by run_certificate_fuzz.sh.
#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced_apart.hpp>
#include <hipair/sliced_certificate.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace {

// The example models the seed certificates are about (read once), from the directory named by
// HIPAIR_EXAMPLES in the environment (run_fuzz.sh sets it; a path compiled in made the object
// differ from checkout to checkout, a ccache miss in every fresh clone).
const std::vector<hipair::Model>& models() {
  static const std::vector<hipair::Model> list = [] {
    const char* examples = std::getenv("HIPAIR_EXAMPLES");
    if (examples == nullptr || *examples == '\0') {
      std::fputs("certificate_verifier_fuzzer: set HIPAIR_EXAMPLES to examples/models (run_fuzz.sh does)\n", stderr);
      std::exit(2);
    }
    std::vector<hipair::Model> result;
    for (const char* name : {"lever-stop.json", "ratchet.json", "geneva.json", "cam-follower.json", "peg-in-hole.json"})
      result.push_back(hipair::read_model_file(std::filesystem::path(examples) / name));
    return result;
  }();
  return list;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto model_named = [](const std::string& name) {
    const hipair::Model* model = &models().front();
    for (const hipair::Model& candidate : models())
      if (candidate.name == name) model = &candidate;
    return model;
  };
  if (hipair::is_sliced_apart_certificate(text)) {   // (session 69: the tree's work is bounded by its own limits)
    hipair::SlicedApartCertificate apart;
    try {
      apart = hipair::read_sliced_apart_certificate(text);
    } catch (const hipair::Error&) {
      return 0;
    }
    hipair::VerificationResult result = hipair::check_sliced_apart(apart, *model_named(apart.envelope.model_name));
    if (result.valid ? result.summary.empty() : result.reason.empty()) __builtin_trap();
    return 0;
  }
  if (hipair::is_sliced_connected_certificate(text)) {
    hipair::SlicedConnectedCertificate connected;
    try {
      connected = hipair::read_sliced_connected_certificate(text);
    } catch (const hipair::Error&) {
      return 0;
    }
    hipair::VerificationResult result = hipair::check_sliced_connected(connected, *model_named(connected.envelope.model_name));
    if (result.valid ? result.summary.empty() : result.reason.empty()) __builtin_trap();
    return 0;
  }
  hipair::Certificate certificate;
  try {
    certificate = hipair::read_certificate(text);
  } catch (const hipair::Error&) {
    return 0;
  }
  hipair::VerificationResult result = hipair::check_certificate(certificate, *model_named(certificate.model_name));
  // Exactly one of: valid with a summary, invalid with a reason.
  if (result.valid ? result.summary.empty() : result.reason.empty()) __builtin_trap();
  return 0;
}
