// hipair-verify CERTIFICATE MODEL: re-checks a HIPAIR certificate against a model file with
// the verifier's own exact and interval predicates (see docs/certify.md).
#include <hipair/certificate.hpp>

#include "core/console_text.hpp"

#include <iostream>
#include <new>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3 || std::string(argv[1]) == "--help") {
    std::cerr << "usage: hipair-verify CERTIFICATE MODEL\n"
                 "Checks a HIPAIR certificate (interference, clearance, jam, free passage) against the model file.\n"
                 "Exit status 0: valid (the claim holds); 1: invalid (the reason is printed); 2: usage;\n"
                 "3: unproven (the evidence passes every check made, but the checks do not prove the claim:\n"
                 "   no-jam tolerance certificates; what was and was not checked is printed; docs/certify.md).\n";
    return argc == 2 && std::string(argv[1]) == "--help" ? 0 : 2;
  }
  try {
    hipair::VerificationResult result = hipair::verify_certificate_file(argv[1], argv[2]);
    if (result.valid) {
      std::cout << "valid: " << hipair::console::shortened_message(result.summary) << "\n";
      return 0;
    }
    if (result.unproven) {
      std::cout << "unproven: " << hipair::console::shortened_message(result.summary) << "\n";
      return 3;
    }
    std::cout << "invalid: " << hipair::console::shortened_message(result.reason) << "\n";
  } catch (const std::bad_alloc&) {
    std::cout << "invalid: out of memory\n";
  } catch (const std::exception& error) {
    std::cout << "invalid: " << hipair::console::shortened_message(error.what()) << "\n";
  }
  return 1;
}
