#include "io/atomic_file.hpp"

#include <hipair/error.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <array>
#include <new>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace hipair::io {

namespace {

// Writes `content` to an existing non-regular node (device, FIFO): opened without blocking (a FIFO
// without a reader fails with ENXIO instead of hanging), then written whole, every failure (e.g.
// ENOSPC from /dev/full) an IoError naming the path.
void write_to_node(const std::filesystem::path& path, const std::string& content, bool append = false) {
  int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC | (append ? O_APPEND : 0));
  if (fd < 0) {
    int error = errno;
    throw IoError("cannot write '" + path.string() + "': " +
                  (error == ENXIO ? std::string("it is a FIFO or socket with no reader") : std::strerror(error)) +
                  ": nothing was written");
  }
  int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  std::size_t done = 0;
  while (done < content.size()) {
    ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      int error = n < 0 ? errno : EIO;
      ::close(fd);
      throw IoError("cannot write '" + path.string() + "': " + std::strerror(error) +
                    (done == 0 ? ": nothing was written" : ": written only in part"));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && errno != EINTR)
    throw IoError("cannot write '" + path.string() + "': " + std::strerror(errno));
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // A path that leads (through links, /proc's included) to an existing node that is no regular
  // file and no directory (a device such as /dev/null or /dev/full, a FIFO, /dev/stdout) cannot
  // be replaced by a rename without destroying the node: the content is produced whole first (a
  // failing producer writes nothing) and then written to the node itself. A FIFO without a
  // reader is refused rather than waited for.
  fs::file_status followed = fs::status(path, ec);
  if (!ec && fs::exists(followed) && !fs::is_regular_file(followed) && !fs::is_directory(followed)) {
    std::ostringstream buffer;
    write(buffer);
    write_to_node(path, buffer.str());
    return;
  }
  // A symbolic link is written through (its final target is replaced, the link stays).
  fs::path target = path;
  bool descriptor = false;   // the chain passes through a process's open descriptor
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) throw IoError("cannot write '" + path.string() + "': too many levels of symbolic links");
    const std::string at = target.lexically_normal().string();
    descriptor = descriptor || at.rfind("/proc/", 0) == 0 || at.rfind("/dev/fd/", 0) == 0;
    fs::path link = fs::read_symlink(target, ec);
    if (ec) throw IoError("cannot write '" + path.string() + "': " + ec.message());
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  // /dev/stdout, /dev/fd/N or /proc/self/fd/N on a regular file (`> log`, `>> log`): the file
  // a descriptor has open is appended to through the descriptor's path, not replaced by a new
  // file of the same name (the shell's descriptor would keep the old, unlinked one).
  if (descriptor && fs::exists(fs::status(path, ec))) {
    std::ostringstream buffer;
    write(buffer);
    write_to_node(path, buffer.str(), true);
    return;
  }
  fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec))   // "does not exist" also for a parent that is a file until session 36
    throw IoError("cannot write '" + path.string() + "': directory '" + directory.string() + "' " +
                  (fs::exists(fs::status(directory, ec)) ? "is not a directory" : "does not exist"));
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

std::string read_file(const std::filesystem::path& path, std::size_t most_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw IoError("cannot read '" + path.string() + "': it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path.string() + "': " + std::strerror(errno));
  std::string text;
  std::array<char, 65536> chunk{};
  do {
    in.read(chunk.data(), chunk.size());
    try {
      text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    } catch (const std::bad_alloc&) {   // an endless input (a device) under a memory limit
      const std::size_t read = text.size();
      std::string().swap(text);
      throw IoError("cannot read '" + path.string() + "': out of memory after " + std::to_string(read) + " bytes");
    }
    if (text.size() > most_bytes)
      throw IoError("cannot read '" + path.string() + "': it is larger than " + std::to_string(most_bytes) + " bytes");
  } while (in);
  if (in.bad()) throw IoError("cannot read '" + path.string() + "': " + std::strerror(errno));
  return text;
}

}  // namespace hipair::io
