#pragma once
// The whole offline reduction of one part: mesh -> FE model -> assembly -> reduction ->
// invariants -> SID (in memory). ffr-reduce is a thin command line around it.

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/part/part.hpp"

#include <filesystem>
#include <functional>
#include <string>

namespace ffr::preproc {

struct PipelineLog {
  std::function<void(const std::string&)> stage;     ///< one line per stage, with its time
  std::function<void(const std::string&)> progress;  ///< transient progress text
};

struct PipelineOptions {
  std::filesystem::path vtk;  ///< if set: write the mode shapes for ParaView here
};

/// Runs every stage. Throws formats::FormatError for bad input (exit 2), other exceptions
/// for internal failures (exit 1).
formats::Sid run_pipeline(const PartSpec& part, const PipelineOptions& options = {}, const PipelineLog& log = {});

}  // namespace ffr::preproc
