#pragma once
// ffr-sim --vtk RUN.pvd: a ParaView collection of the run, one .vtu (VTK XML unstructured grid,
// ASCII) per output sample, holding every flexible body's deformed outer surface (the SID's
// /visual triangles) and every rigid body as its inertia box (the uniform box of the same mass
// and second moments about the centre of mass, on the principal axes), or by the STL surface
// its model-file key "visual" names (stl_reader.hpp). Point data:
// `displacement` (the elastic displacement A Phi q, global) and, when a body's SID has a /stress
// group, `von_mises` (sigma = sum_k q_k S_k at the surface vertices that are stress nodes, the
// largest over a shell node's top, middle and bottom layers; NaN at
// the others and on rigid bodies). Cell data `body`: the body's index in the model file.
//
// The frames go to the folder RUN_frames/ beside RUN.pvd: written into a temporary folder and
// renamed into place after the run, so a failed run leaves no frame and no .pvd. The temporary
// names are formats' (stale_temp.hpp: host and process id), so a run killed before its end
// leaves a folder the next run of the same collection removes.
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/outputs.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace ffr::vtk {

class Series {
 public:
  /// Checks everything that can be checked before the run: the folder of `pvd` exists, every
  /// flexible body's SID (resolved against `model_file`'s folder) has a /visual surface. Adds
  /// the hidden outputs it needs (each body's frame, flexible bodies' modal coordinates) at the
  /// end of model.outputs. Throws formats::FormatError (bad input) naming the file and the body.
  Series(const std::filesystem::path& pvd, const std::filesystem::path& model_file, runtime::Model& model);
  ~Series();
  Series(const Series&) = delete;
  Series& operator=(const Series&) = delete;

  /// The outputs of the model file (the hidden ones follow them).
  std::size_t user_outputs() const;
  /// Writes every recorded sample into the temporary folder.
  void write_frames(const runtime::Model& model, const runtime::Recorder& rec);
  /// Moves the frames into place and writes the .pvd (after the results file is written).
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffr::vtk
