// Refusing outputs that would replace an input: every command that writes files checks its
// output paths against the files it read (and against each other) before it writes anything.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hipair::io {

/// One file a command is about to write: the path and the option that named it ("--svg").
struct PlannedOutput {
  std::filesystem::path path;
  std::string option;
};

/// True when `a` and `b` name the same file: the same path once symbolic links, "." and ".."
/// are resolved, or (both existing) the same device and inode, so hard links count too.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// Throws IoError, before anything is written, when an output would replace an input file
/// (the model read, a certificate read) or two outputs are the same file. `inputs` are the
/// files the command read. The message names the option and both paths.
void refuse_overwriting_inputs(const std::vector<PlannedOutput>& outputs,
                               const std::vector<std::filesystem::path>& inputs);

/// The one-output form: `refuse_overwriting_inputs({{output, option}}, {input})`.
void refuse_overwriting_input(const std::filesystem::path& output, const std::string& option,
                              const std::filesystem::path& input);

/// Throws IoError, before a command computes anything, when `directory` (an `--out DIR`) cannot
/// receive the run's files: it, or a directory it would lie in, exists and is not a directory (a
/// regular file, the model file itself, a device), or the place where the publication creates
/// entries (the nearest existing directory on DIR's way, and DIR itself when it exists) takes no
/// new entry (no write permission, a read-only mount, /proc, /sys: probed by creating and removing
/// an entry there). The message names `option` and the path.
/// Until session 52 (a file in the way) and session 63 (a place taking no entry) such a DIR was
/// refused only when the run's files were published, after the whole analysis or simulation
/// (hours for a long simulate, the results printed, then exit 3).
void refuse_unusable_output_directory(const std::filesystem::path& directory, const std::string& option);

/// Throws IoError, before a command computes anything, when an output file's directory cannot
/// hold it: the directory, or one it would lie in, exists and is not a directory (`--json
/// f.txt/x.json`), the directory does not exist, or it takes no new file (probed by creating and
/// removing one: the writer's temporary file is made there). Until session 52 (a file in the
/// way) and session 63 (a missing directory, one taking no file) `cspace` of a 3-DOF or pin-slot
/// pair and `certify` built everything first.
void refuse_unusable_output_files(const std::vector<PlannedOutput>& outputs);

}  // namespace hipair::io
