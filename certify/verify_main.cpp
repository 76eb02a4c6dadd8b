// hipair-verify CERTIFICATE MODEL: re-checks a HIPAIR certificate against a model file with
// the verifier's own exact and interval predicates (see docs/certify.md).
// Batch mode (session 75, verify75): `--list FILE` (lines CERTIFICATE<TAB>MODEL) or `--model MODEL
// CERTIFICATE...` checks each certificate as a run of its own would (verify_certificate_file reads
// both files afresh and builds every object of the check anew; nothing is carried from one
// certificate to the next) and prints one line per certificate, "CERTIFICATE: <its verdict line>".
#include <hipair/certificate.hpp>

#include "core/console_text.hpp"

#include <fstream>
#include <iostream>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr int valid_status = 0, invalid_status = 1, usage_status = 2, unproven_status = 3;

struct Verdict {
  int status;
  std::string line;   // "valid: ...", "invalid: ..." or "unproven: ..."
};

// One certificate checked against its model: the verdict line and exit status of a single run.
Verdict check_one(const std::string& certificate, const std::string& model) {
  try {
    hipair::VerificationResult result = hipair::verify_certificate_file(certificate, model);
    if (result.valid) return {valid_status, "valid: " + hipair::console::shortened_message(result.summary)};
    if (result.unproven) return {unproven_status, "unproven: " + hipair::console::shortened_message(result.summary)};
    return {invalid_status, "invalid: " + hipair::console::shortened_message(result.reason)};
  } catch (const std::bad_alloc&) {
    return {invalid_status, "invalid: out of memory"};
  } catch (const std::exception& error) {
    return {invalid_status, "invalid: " + hipair::console::shortened_message(error.what())};
  }
}

int usage(int status) {
  std::cerr << "usage: hipair-verify CERTIFICATE MODEL\n"
         "       hipair-verify --list FILE          (each line CERTIFICATE<TAB>MODEL; FILE - is standard input)\n"
         "       hipair-verify --model MODEL CERTIFICATE...\n"
         "Checks a HIPAIR certificate (interference, clearance, jam, free passage) against the model file.\n"
         "Exit status 0: valid (the claim holds); 1: invalid (the reason is printed); 2: usage;\n"
         "3: unproven (the evidence passes every check made, but the checks do not prove the claim:\n"
         "   no-jam tolerance certificates; what was and was not checked is printed; docs/certify.md).\n"
         "Several certificates (--list, --model): each is checked on its own, one line each,\n"
         "\"CERTIFICATE: <verdict>\", in the given order; exit 1 if any is invalid, else 3 if any is\n"
         "unproven, else 0; 2 (nothing checked) for a list that cannot be read or has a malformed line.\n";
  return status;
}

// Reads the (certificate, model) pairs of a --list file into `jobs`; false (the message printed,
// naming the list and the line) when it cannot be read, has a malformed line or names nothing.
bool read_list(const std::string& name, std::vector<std::pair<std::string, std::string>>& jobs) {
  std::ifstream file;
  if (name != "-") {
    file.open(name);
    if (!file) {
      std::cerr << "hipair-verify: cannot read the list " << name << "\n";
      return false;
    }
  }
  std::istream& in = name == "-" ? std::cin : file;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::size_t tab = line.find('\t');
    if (tab == 0 || tab == std::string::npos || tab + 1 == line.size() || line.find('\t', tab + 1) != std::string::npos) {
      std::cerr << "hipair-verify: " << name << ":" << number
                << ": expected CERTIFICATE<TAB>MODEL (one tab, both paths non-empty)\n";
      return false;
    }
    jobs.emplace_back(line.substr(0, tab), line.substr(tab + 1));
  }
  if (in.bad()) {
    std::cerr << "hipair-verify: cannot read the list " << name << "\n";
    return false;
  }
  if (jobs.empty()) {
    std::cerr << "hipair-verify: the list " << name << " names no certificate\n";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 1 && args[0] == "--help") return usage(valid_status);
  std::vector<std::pair<std::string, std::string>> jobs;
  if (!args.empty() && args[0] == "--list") {
    if (args.size() != 2) return usage(usage_status);
    if (!read_list(args[1], jobs)) return usage_status;
  } else if (!args.empty() && args[0] == "--model") {
    if (args.size() < 3) return usage(usage_status);
    for (std::size_t i = 2; i < args.size(); ++i) jobs.emplace_back(args[i], args[1]);
  } else {
    if (args.size() != 2 || args[0] == "--help") return usage(usage_status);
    const Verdict verdict = check_one(args[0], args[1]);
    std::cout << verdict.line << "\n";
    return verdict.status;
  }
  bool any_invalid = false, any_unproven = false;
  for (const auto& [certificate, model] : jobs) {
    const Verdict verdict = check_one(certificate, model);
    std::cout << certificate << ": " << verdict.line << std::endl;   // a line per check, as it ends
    any_invalid = any_invalid || verdict.status == invalid_status;
    any_unproven = any_unproven || verdict.status == unproven_status;
  }
  return any_invalid ? invalid_status : any_unproven ? unproven_status : valid_status;
}
