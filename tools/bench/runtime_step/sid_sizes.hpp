#pragma once
// Per-step time of one model with SID files reduced from meshes of different sizes.

#include <filesystem>
#include <string>
#include <vector>

namespace bench {

struct SidCase {
  std::filesystem::path path;
  long dof = 0;  ///< DOF of the mesh it was reduced from (for the report)
};

/// Runs the model at `model_path` once per SID, the string "`placeholder`" in the model file
/// replaced by the SID's path, `rounds` times interleaved; prints the best per-step time of
/// each, their ratio, Newton iterations, and the largest difference of the last body's x
/// coordinate from the run with the last SID.
int run_sid_sizes(const std::filesystem::path& model_path, const std::string& placeholder,
                  const std::vector<SidCase>& sids, int rounds);

}  // namespace bench
