#pragma once
// Checks of the files a command is asked to write, made before any work: a run or a reduction
// may take long, and an output that cannot be written, that replaces another output, or that
// replaces an input is a command-line mistake (ffr-sim m.json -o m.json replaced the model file
// by its results and exited with status 0; ffr-reduce did the same to a part file).

#include "ffr/cli/cli.hpp"

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace ffr::cli {

/// A file of the command line and what it is there, for messages: {"-o", "out.h5"},
/// {"the model file", "m.json"}.
struct NamedPath {
  std::string what;
  std::filesystem::path path;
};

/// Whether a and b name the same file: one existing file under two names (symbolic or hard
/// links included), or one path once ".", ".." and symbolic links are resolved (for a file not
/// written yet).
inline bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea), cb = fs::weakly_canonical(fs::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

/// Throws UsageError naming the option when an output's folder does not exist, when it is a
/// folder itself, when it names the same file as an earlier output, or when it names one of
/// the inputs (an empty input path is none).
inline void check_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  namespace fs = std::filesystem;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& o = outputs[i];
    const std::string named = o.what + " " + o.path.string();
    const fs::path dir = o.path.parent_path().empty() ? fs::path(".") : o.path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw UsageError(named + ": no directory " + dir.string() + " to write it in");
    if (fs::is_directory(o.path, ec)) throw UsageError(named + ": is a folder; give the name of the file to write");
    for (std::size_t j = 0; j < i; ++j)
      if (same_file(o.path, outputs[j].path))
        throw UsageError(named + " names the same file as " + outputs[j].what + " " + outputs[j].path.string());
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && same_file(o.path, in.path))
        throw UsageError(named + " would overwrite " + in.what + " " + in.path.string());
  }
}

}  // namespace ffr::cli
