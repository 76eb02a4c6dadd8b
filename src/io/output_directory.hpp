// Publishing the files of one run into a directory together: all or nothing.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace hipair::io {

/// One file of a run: its name inside the output directory and its bytes.
struct RunFile {
  std::string name;
  std::string content;
};

/// Writes `files` into `directory` as one unit. Every file is first written into a temporary
/// sibling directory (".NAME.tmp-RANDOM" beside `directory`); only when all of them are
/// complete are they moved in. If `directory` does not exist the temporary directory is renamed
/// to it (one atomic step); otherwise each file it already holds under one of the new names, and
/// each file for which `earlier_output(name)` is true (outputs of an earlier run that this run
/// does not write), is moved aside first and restored if any later step fails. On failure
/// `directory` is left exactly as it was (or absent, if it was) and IoError is thrown; no
/// temporary file or directory is left behind. Files in `protect` (the run's inputs) are never
/// moved or removed. Names must be plain file names (no '/').
void publish_directory(const std::filesystem::path& directory, const std::vector<RunFile>& files,
                       const std::function<bool(const std::string&)>& earlier_output = {},
                       const std::vector<std::filesystem::path>& protect = {});

}  // namespace hipair::io
