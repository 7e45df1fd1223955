#pragma once
// Viewer data: the outer surface of the model (boundary faces of solids, shell faces, as
// triangles on corner nodes) with the mode shapes on it, stored in the SID under /visual;
// and a legacy-VTK file of the whole mesh with every mode as point data, for ParaView.
#include "ffr/formats/sid.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <filesystem>

namespace ffr::preproc {

/// `vertex_nodes`, if given, receives the mesh node index of each vertex.
formats::Visual surface_with_modes(const FeModel& model, const Eigen::MatrixXd& Phi,
                                   std::vector<Index>* vertex_nodes = nullptr);

/// Writes `path` (.vtk, legacy ASCII unstructured grid) atomically: corner-node cells of every
/// element with properties, and one vector field "mode_<k>_<f>Hz" per mode.
void write_vtk(const std::filesystem::path& path, const FeModel& model, const Eigen::MatrixXd& Phi,
               const Eigen::VectorXd& frequency_hz);

}  // namespace ffr::preproc
