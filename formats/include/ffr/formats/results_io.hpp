#pragma once
// The results file of ffr-sim (formats/SPEC.md section 13): /time [nt], /outputs/<name>
// [nt,k], root attributes steps, newton_iterations, integration_seconds. Same strict HDF5
// layer and atomic writing as the SID.

#include "ffr/formats/h5.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ffr::formats {

inline constexpr const char* kResultsFormatName = "ffr-results";
/// 2: content checksums, as the SID's (SPEC.md section 4).
inline constexpr int kResultsFormatVersion = 2;

struct Results {
  struct Output {
    std::string name;
    std::string type;        ///< the model file's output type, "" if unknown
    Eigen::MatrixXd values;  ///< [nt, k]
  };
  Eigen::VectorXd time;  ///< [nt], non-decreasing
  std::vector<Output> outputs;
  std::int64_t steps = 0;
  std::int64_t newton_iterations = 0;
  double integration_seconds = 0.0;
  std::string generator;  ///< filled on write if empty
  /// A run that stopped before its end (ffr-sim --keep-partial): the time of the step that failed
  /// and the error, the file holding the samples before it; or the time an interrupted run
  /// reached, its last sample, and the signal. Empty for a complete run.
  std::optional<double> stopped_at;
  std::string stop_reason;

  const Output* find(const std::string& name) const;
};

/// Writes atomically. Throws std::invalid_argument if an output's row count differs from the
/// number of times, a name is empty or contains '/', or a value is not finite.
void write_results(const Results& r, const std::filesystem::path& path);

/// Reads strictly; outputs are returned sorted by name. Throws FormatError naming the file and
/// dataset. A file is accepted if `format` is "ffr-results", or if it has no `format` attribute
/// but has /time and /outputs.
/// Version 1 files (and files without `format`) have no content checksums: read with a warning
/// appended to `warnings`.
Results read_results(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);

/// True if the open file looks like a results file (see read_results).
bool is_results_file(const h5::Reader& r);

}  // namespace ffr::formats
