#include "io/output_paths.hpp"

#include <hipair/error.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <random>

namespace hipair::io {
namespace {

std::string quoted(const std::filesystem::path& path) {
  std::string out = "'";   // (appended, not '+': GCC 12's -Wrestrict misfires on "'" + string)
  out += path.string();
  out += "'";
  return out;
}

// `path` with the symbolic links of its last component followed, even when the final target does
// not exist yet (a dangling link is written through to its target: `--svg link` with link -> the
// --json file is that file; hostile74 L1); at most 40 links, as the kernel follows.
std::filesystem::path through_links(std::filesystem::path path) {
  namespace fs = std::filesystem;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec)) || ec) break;
    fs::path target = fs::read_symlink(path, ec);
    if (ec) break;
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  return path;
}

}  // namespace

bool same_file(const std::filesystem::path& given_a, const std::filesystem::path& given_b) {
  const std::filesystem::path a = through_links(given_a), b = through_links(given_b);
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

// The nearest existing ancestor-or-self of `path` (absolute, lexically normal).
std::filesystem::path nearest_existing(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path at = path;
  while (!fs::exists(fs::status(at, ec)) && at != at.parent_path()) at = at.parent_path();
  return at;
}

// Why nothing can be created in the existing directory `directory` (none when something can): a
// uniquely named probe entry, a directory when `as_directory` (publish_directory's staging
// directory) or else a file (write_file_atomically's temporary file), is created there and removed
// at once, so the answer is the file system's own (permissions, a read-only mount, /proc and /sys,
// which take no new entries, even from root; access(2) says yes to root there).
std::optional<std::string> cannot_create_in(const std::filesystem::path& directory, bool as_directory) {
  std::random_device seed;
  for (int attempt = 0; attempt < 8; ++attempt) {
    const std::filesystem::path probe = directory / (".hipair-probe-" + std::to_string(seed()));
    int fd = -1;
    const int made = as_directory ? ::mkdir(probe.c_str(), 0700)
                                  : (fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600));
    if (made < 0) {
      if (errno == EEXIST) continue;
      return std::string(std::strerror(errno));
    }
    if (as_directory) {
      ::rmdir(probe.c_str());
    } else {
      ::close(fd);
      ::unlink(probe.c_str());
    }
    return std::nullopt;
  }
  return std::nullopt;   // names taken eight times: left to the writer
}

}  // namespace

void refuse_unusable_output_directory(const std::filesystem::path& directory, const std::string& option) {
  namespace fs = std::filesystem;
  if (directory.empty()) return;
  std::error_code ec;
  if (std::optional<fs::path> file = existing_non_directory(directory)) {
    if (fs::exists(directory, ec))   // DIR itself is that file
      throw IoError(option + " " + quoted(directory) + ": it exists and is not a directory (nothing was run or written)");
    throw IoError(option + " " + quoted(directory) + ": " + quoted(*file) +
                  " exists and is not a directory, so the output directory cannot be made (nothing was run or written)");
  }
  // Where io::publish_directory will create entries: its staging directory beside DIR (in the
  // nearest existing directory on DIR's way, the rest of the way made first), and, DIR existing,
  // the run's files moved into DIR. Until session 63 (hunt63) a place that takes no new entry
  // (a directory without write permission, a read-only mount, /proc, /sys) was found only there,
  // after the whole run: its results printed, then `cannot create '.../.DIR.tmp-N'`, exit 3.
  fs::path target = fs::absolute(directory, ec).lexically_normal();
  if (ec) return;   // left to the writer's own message
  if (target.filename().empty()) target = target.parent_path();
  std::vector<fs::path> places{nearest_existing(target.parent_path())};
  if (fs::is_directory(target, ec)) places.push_back(target);
  for (const fs::path& place : places)
    if (std::optional<std::string> why = cannot_create_in(place, true))
      throw IoError(option + " " + quoted(directory) + ": nothing can be created in " + quoted(place) + ": " + *why +
                    " (nothing was run or written)");
}

void refuse_unusable_output_files(const std::vector<PlannedOutput>& outputs) {
  namespace fs = std::filesystem;
  for (const PlannedOutput& output : outputs) {
    if (output.path.empty()) continue;
    std::error_code ec;
    fs::path parent = fs::absolute(output.path, ec).lexically_normal().parent_path();
    if (ec) continue;   // left to the writer's own message
    if (std::optional<fs::path> file = existing_non_directory(parent))
      throw IoError(output.option + " " + quoted(output.path) + ": " + quoted(*file) +
                    " exists and is not a directory, so the file cannot be written there (nothing was built or written)");
    // What io::write_file_atomically will meet once the build or search is done (session 63,
    // hunt63; until then each was found only after it, exit 3): a directory that does not exist
    // (the writer makes none), or one that takes no new file (its temporary file is created
    // there). A symbolic link (written through, also /dev/stdout and /proc/self/fd/N) or a
    // device, FIFO or socket (written to) is left to it, and so is a path that is a directory
    // (`cspace` of several pairs writes PATH-A-B beside it).
    const fs::file_status own = fs::symlink_status(output.path, ec);
    if (fs::is_symlink(own) || (fs::exists(own) && !fs::is_regular_file(own))) continue;
    if (!fs::is_directory(parent, ec))
      throw IoError(output.option + " " + quoted(output.path) + ": directory " + quoted(parent) +
                    " does not exist (nothing was built or written)");
    if (std::optional<std::string> why = cannot_create_in(parent, false))
      throw IoError(output.option + " " + quoted(output.path) + ": nothing can be created in " + quoted(parent) + ": " +
                    *why + " (nothing was built or written)");
  }
}

void refuse_overwriting_input(const std::filesystem::path& output, const std::string& option,
                              const std::filesystem::path& input) {
  refuse_overwriting_inputs({PlannedOutput{output, option}}, {input});
}

}  // namespace hipair::io
