#include "io/output_paths.hpp"

#include <hipair/error.hpp>

#include <optional>

namespace hipair::io {
namespace {

std::string quoted(const std::filesystem::path& path) {
  std::string out = "'";   // (appended, not '+': GCC 12's -Wrestrict misfires on "'" + string)
  out += path.string();
  out += "'";
  return out;
}

}  // namespace

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  namespace fs = std::filesystem;
  std::error_code ec_a, ec_b;
  // Both exist: the device and inode decide (symbolic and hard links included).
  bool a_exists = fs::exists(a, ec_a), b_exists = fs::exists(b, ec_b);
  if (a_exists && b_exists) {
    std::error_code ec;
    bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  // Otherwise the resolved paths (a file that does not exist yet cannot be an input, but two
  // outputs that do not exist yet may still be the same path).
  std::error_code ec1, ec2;
  fs::path ra = fs::weakly_canonical(fs::absolute(a), ec1);
  fs::path rb = fs::weakly_canonical(fs::absolute(b), ec2);
  if (ec1 || ec2) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return ra == rb;
}

void refuse_overwriting_inputs(const std::vector<PlannedOutput>& outputs,
                               const std::vector<std::filesystem::path>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const PlannedOutput& output = outputs[i];
    if (output.path.empty()) continue;
    for (const std::filesystem::path& input : inputs)
      if (same_file(output.path, input))
        throw IoError(output.option + " " + quoted(output.path) + " is the input file " + quoted(input) +
                      ": refusing to overwrite it (nothing was written)");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same_file(output.path, outputs[j].path))
        throw IoError(output.option + " " + quoted(output.path) + " is also the output of " + outputs[j].option +
                      " " + quoted(outputs[j].path) + ": refusing to write one file twice (nothing was written)");
  }
}

namespace {

// The nearest existing ancestor-or-self of `path` (made absolute), when it is not a directory;
// none when that ancestor is a directory (or the path cannot be made absolute: left to the
// writer's own message).
std::optional<std::filesystem::path> existing_non_directory(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path target = fs::absolute(path, ec).lexically_normal();
  if (ec) return std::nullopt;
  if (target.filename().empty()) target = target.parent_path();
  for (fs::path at = target;; at = at.parent_path()) {
    fs::file_status status = fs::status(at, ec);   // through symbolic links, as the writers go
    if (fs::exists(status)) return fs::is_directory(status) ? std::nullopt : std::optional<fs::path>(at);
    if (at == at.parent_path()) return std::nullopt;
  }
}

}  // namespace

void refuse_unusable_output_directory(const std::filesystem::path& directory, const std::string& option) {
  if (directory.empty()) return;
  std::optional<std::filesystem::path> file = existing_non_directory(directory);
  if (!file) return;
  std::error_code ec;
  if (std::filesystem::exists(directory, ec))   // DIR itself is that file
    throw IoError(option + " " + quoted(directory) + ": it exists and is not a directory (nothing was run or written)");
  throw IoError(option + " " + quoted(directory) + ": " + quoted(*file) +
                " exists and is not a directory, so the output directory cannot be made (nothing was run or written)");
}

void refuse_unusable_output_files(const std::vector<PlannedOutput>& outputs) {
  for (const PlannedOutput& output : outputs) {
    if (output.path.empty()) continue;
    std::filesystem::path parent = std::filesystem::absolute(output.path).lexically_normal().parent_path();
    if (std::optional<std::filesystem::path> file = existing_non_directory(parent))
      throw IoError(output.option + " " + quoted(output.path) + ": " + quoted(*file) +
                    " exists and is not a directory, so the file cannot be written there (nothing was built or written)");
  }
}

void refuse_overwriting_input(const std::filesystem::path& output, const std::string& option,
                              const std::filesystem::path& input) {
  refuse_overwriting_inputs({PlannedOutput{output, option}}, {input});
}

}  // namespace hipair::io
