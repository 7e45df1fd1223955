#pragma once
// Stress over time from a run (formats/SPEC.md section 12.1): sigma(t) = sum_k q_k(t) S_k at the
// nodes of a body's SID /stress group, with q(t) the run's modal_coordinates output of that body,
// and its von Mises and principal stresses. One implementation for `ffr-info --stress` and the
// Python package's ffr.stress(), so the two agree bit for bit.

#include "ffr/formats/modal_stress.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ffr::formats {

struct StressHistory {
  std::string body;
  std::filesystem::path sid;          ///< the body's SID (relative paths as the model file gives them)
  std::string output;                 ///< the run's modal_coordinates output of the body
  std::string selection;              ///< the SID's /stress selection
  Eigen::VectorXd time;               ///< [nt] the run's output times
  std::vector<std::int64_t> node;     ///< [Ns] mesh node tags
  ModalStress::RowsX3 position;       ///< [Ns,3] undeformed node positions in K
  std::vector<std::int64_t> layer;    ///< [Ns] StressLayer of each row (all kSolid without shells)
  Eigen::MatrixXd von_mises;          ///< [nt,Ns]
  std::vector<Eigen::MatrixXd> principal;  ///< [Ns][nt,3], descending per row
};

/// Recovers the stresses of `body` from the results file `run`. The model file (to find the
/// body's SID and its modal-coordinates output) is `model` if not empty, else the one the run
/// names in its root attribute `model` (as given to ffr-sim, else relative to the run's folder).
/// Throws FormatError naming the file and field: no such body, no SID, no modal_coordinates
/// output, a SID without /stress, a mode count that differs from the run's.
StressHistory recover_stress(const std::filesystem::path& run, const std::string& body,
                             const std::filesystem::path& model = {});

}  // namespace ffr::formats
