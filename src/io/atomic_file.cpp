#include "io/atomic_file.hpp"

#include <hipair/error.hpp>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace hipair::io {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // A symbolic link is written through (its final target is replaced, the link stays); a target
  // that exists and is no regular file (a device such as /dev/full, a FIFO, a socket) is refused
  // before anything is written: the rename below would replace the node itself.
  fs::path target = path;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) throw IoError("cannot write '" + path.string() + "': too many levels of symbolic links");
    fs::path link = fs::read_symlink(target, ec);
    if (ec) throw IoError("cannot write '" + path.string() + "': " + ec.message());
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  fs::file_status status = fs::status(target, ec);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status))
    throw IoError("cannot write '" + path.string() + "': " +
                  (target == path ? std::string("it") : "its target '" + target.string() + "'") +
                  " is not a regular file (a device, FIFO or socket): nothing was written");
  fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec))
    throw IoError("cannot write '" + path.string() + "': directory '" + directory.string() +
                  "' does not exist");
  std::random_device seed;
  std::string temporary_name = ".";
  temporary_name += target.filename().string();
  temporary_name += ".tmp";
  temporary_name += std::to_string(seed());
  fs::path temporary = directory / temporary_name;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
      throw IoError("cannot write '" + path.string() + "': " + std::strerror(errno));
    try {
      write(out);
    } catch (...) {
      out.close();
      fs::remove(temporary, ec);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      fs::remove(temporary, ec);
      throw IoError("cannot write '" + path.string() + "': write failed");
    }
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignore;
    fs::remove(temporary, ignore);
    throw IoError("cannot write '" + path.string() + "': " + ec.message());
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw IoError("cannot read '" + path.string() + "': it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path.string() + "': " + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace hipair::io
