#include "io/output_directory.hpp"

#include "io/output_paths.hpp"

#include <hipair/error.hpp>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <set>

namespace hipair::io {
namespace {

namespace fs = std::filesystem;

// Tests inject a failure of the N-th move into the directory (1-based) with the environment
// variable HIPAIR_TEST_PUBLISH_FAIL_AT=N, to check the roll-back; nothing else reads it.
long injected_failure() {
  const char* text = std::getenv("HIPAIR_TEST_PUBLISH_FAIL_AT");
  if (!text || !*text) return 0;
  char* end = nullptr;
  long n = std::strtol(text, &end, 10);
  return end && *end == '\0' && n > 0 ? n : 0;
}

void write_whole_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError("cannot write '" + path.string() + "': " + std::strerror(errno));
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  int error = errno;
  out.close();
  if (!out) throw IoError("cannot write '" + path.string() + "': " + (error ? std::strerror(error) : "write failed"));
}

// A move made into or out of the output directory, undone in reverse order on failure.
struct Move {
  fs::path from, to;
};

}  // namespace

void publish_directory(const fs::path& directory, const std::vector<RunFile>& files,
                       const std::function<bool(const std::string&)>& earlier_output,
                       const std::vector<fs::path>& protect) {
  std::set<std::string> names;
  for (const RunFile& file : files) {
    if (file.name.empty() || file.name.find('/') != std::string::npos || file.name == "." || file.name == ".." ||
        !names.insert(file.name).second)
      throw IoError("cannot write '" + (directory / file.name).string() + "': not a plain, unique file name");
  }
  std::error_code ec;
  fs::path target = fs::absolute(directory, ec).lexically_normal();
  if (ec) throw IoError("cannot write into '" + directory.string() + "': " + ec.message());
  if (target.filename().empty()) target = target.parent_path();
  fs::path parent = target.parent_path();
  bool exists = fs::exists(fs::symlink_status(target, ec));
  if (exists && !fs::is_directory(target, ec))
    throw IoError("cannot write into '" + directory.string() + "': it exists and is not a directory");
  if (exists) {
    for (const RunFile& file : files) {
      fs::path old = target / file.name;
      fs::file_status status = fs::symlink_status(old, ec);
      if (fs::exists(status) && fs::is_directory(status))
        throw IoError("cannot write '" + old.string() + "': a directory of that name is in the way (nothing was written)");
    }
  } else {
    fs::create_directories(parent, ec);
    if (ec) throw IoError("cannot create directory '" + parent.string() + "': " + ec.message());
  }

  // 1. Every file into a temporary sibling directory.
  std::random_device seed;
  fs::path staging = parent / ("." + target.filename().string() + ".tmp-" + std::to_string(seed()));
  if (!fs::create_directory(staging, ec) || ec)
    throw IoError("cannot create '" + staging.string() + "': " + (ec ? ec.message() : "it exists"));
  auto discard_staging = [&] {
    std::error_code ignore;
    fs::remove_all(staging, ignore);
  };
  try {
    for (const RunFile& file : files) write_whole_file(staging / file.name, file.content);
  } catch (...) {
    discard_staging();
    throw;
  }

  long fail_at = injected_failure();
  long moves = 0;
  auto move = [&](const fs::path& from, const fs::path& to) {
    ++moves;
    std::error_code error;
    if (fail_at == moves) error = std::make_error_code(std::errc::io_error);
    else fs::rename(from, to, error);
    if (error) throw IoError("cannot move '" + from.string() + "' to '" + to.string() + "': " + error.message());
  };

  // 2a. A new directory: one rename publishes everything.
  if (!exists) {
    try {
      move(staging, target);
    } catch (const IoError& error) {
      discard_staging();
      throw IoError(std::string(error.what()) + " (nothing was written)");
    }
    return;
  }

  // 2b. An existing directory: set the old files aside, move the new ones in; undo on failure.
  fs::path aside = staging / ".previous";
  std::vector<Move> done;
  try {
    fs::create_directory(aside);
    std::vector<std::string> stale;
    if (earlier_output)
      for (const fs::directory_entry& entry : fs::directory_iterator(target)) {
        std::string name = entry.path().filename().string();
        if (names.count(name) || !earlier_output(name) || entry.is_directory()) continue;
        bool input = false;
        for (const fs::path& p : protect) input = input || same_file(entry.path(), p);
        if (!input) stale.push_back(name);
      }
    for (const std::string& name : stale) {
      move(target / name, aside / name);
      done.push_back({target / name, aside / name});
    }
    for (const RunFile& file : files) {
      fs::path old = target / file.name;
      if (fs::exists(fs::symlink_status(old))) {
        move(old, aside / file.name);
        done.push_back({old, aside / file.name});
      }
      move(staging / file.name, old);
      done.push_back({staging / file.name, old});
    }
  } catch (const std::exception& error) {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      std::error_code ignore;
      fs::rename(it->to, it->from, ignore);
    }
    discard_staging();
    throw IoError(std::string(error.what()) + "; '" + directory.string() + "' was left as it was");
  }
  discard_staging();
}

}  // namespace hipair::io
