#pragma once
// Helpers shared by the runtime tests.

#include "ffr/runtime/runtime.hpp"

#include <filesystem>
#include <string>

namespace ffr::runtime::test {

/// A fresh temporary directory for one test (removed by the destructor).
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag);
  ~TempDir();
  std::filesystem::path operator/(const std::string& f) const { return path / f; }
};

/// Writes text to a file.
void write_text(const std::filesystem::path& p, const std::string& text);

/// Parses a model from JSON text with relative paths resolved in `dir`.
Model model_from(const std::string& json, const std::filesystem::path& dir = {});

}  // namespace ffr::runtime::test
