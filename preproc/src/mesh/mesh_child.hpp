#pragma once
// gmsh in a child process. gmsh 4.8 crashes (SIGSEGV) on some damaged mesh files (an element
// node tag of 2^31, a flipped byte in a binary .msh) instead of reporting them; run in a child,
// such a crash becomes a clear error that names the file, and the run exits with status 2
// instead of dying. The mesh comes back through a pipe.
//
// The child never outlives the call: it dies with the parent (PR_SET_PDEATHSIG, also for a
// parent killed with SIGKILL), and the parent kills and reaps it on every way out, the wall-clock
// limit of meshing included (a .geo script that loops would otherwise run for ever).

#include "ffr/preproc/mesh/gmsh_import.hpp"

#include <functional>
#include <string>

namespace ffr::preproc::detail {

/// The wall-clock limit of the child: `seconds` (0 or infinite: none) and the setting that
/// raises it, named in the message.
struct ChildLimit {
  double seconds = 0;
  std::string setting;
};

/// Runs load(report) in a forked child and returns its mesh (and report). A FormatError thrown
/// in the child is rethrown here as it was; any other exception as std::runtime_error; a child
/// killed by a signal, or still running after the limit (then killed), gives a FormatError
/// naming `file`. Without fork, runs load here.
Mesh load_in_child(const std::string& file, const std::function<Mesh(MeshReport*)>& load, MeshReport* report,
                   const ChildLimit& limit = {});

}  // namespace ffr::preproc::detail
