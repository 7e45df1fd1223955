#include "support.hpp"

#include <fstream>
#include <random>

namespace ffr::runtime::test {

TempDir::TempDir(const std::string& tag) {
  std::random_device rd;
  path = std::filesystem::temp_directory_path() / ("ffr_rt_" + tag + "_" + std::to_string(rd()));
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

Model model_from(const std::string& json, const std::filesystem::path& dir) {
  return parse_model(json, dir.empty() ? std::filesystem::current_path() : dir, "test-model.json");
}

}  // namespace ffr::runtime::test
