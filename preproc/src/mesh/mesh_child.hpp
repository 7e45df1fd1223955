#pragma once
// gmsh in a child process. gmsh 4.8 crashes (SIGSEGV) on some damaged mesh files (an element
// node tag of 2^31, a flipped byte in a binary .msh) instead of reporting them; run in a child,
// such a crash becomes a clear error that names the file, and the run exits with status 2
// instead of dying. The mesh comes back through a pipe.

#include "ffr/preproc/mesh/gmsh_import.hpp"

#include <functional>
#include <string>

namespace ffr::preproc::detail {

/// Runs load(report) in a forked child and returns its mesh (and report). A FormatError thrown
/// in the child is rethrown here as it was; any other exception as std::runtime_error; a child
/// killed by a signal gives a FormatError naming `file`. Without fork, runs load here.
Mesh load_in_child(const std::string& file, const std::function<Mesh(MeshReport*)>& load, MeshReport* report);

}  // namespace ffr::preproc::detail
