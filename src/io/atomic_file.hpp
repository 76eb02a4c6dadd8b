// Atomic output files: write to a temporary file beside the target, then rename.
#pragma once

#include <filesystem>
#include <string_view>

namespace hipair::io {

/// Writes `content` to `path` atomically: either the whole new file appears or the old state
/// is left untouched. \throws IoError.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Reads a whole file. \throws IoError naming the path.
std::string read_file(const std::filesystem::path& path);

}  // namespace hipair::io
