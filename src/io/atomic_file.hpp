// Atomic output files: write to a temporary file beside the target, then rename.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace hipair::io {

/// Writes `content` to `path` atomically: either the whole new file appears or the old state
/// is left untouched. \throws IoError.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);
/// The same, with the content written by `write` into the temporary file as it is produced (a
/// large document need not be held in memory whole). An exception from `write` removes the
/// temporary file and propagates. \throws IoError.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

/// Reads a whole file of at most `most_bytes` bytes (default 1 GiB: a device or pipe without end,
/// such as /dev/zero, is refused instead of read until memory runs out). \throws IoError naming
/// the path.
std::string read_file(const std::filesystem::path& path, std::size_t most_bytes = std::size_t{1} << 30);

}  // namespace hipair::io
