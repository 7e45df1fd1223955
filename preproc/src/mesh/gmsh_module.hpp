#pragma once
// gmsh in a shared module of its own (libexec/ffr/libffr-gmsh.so, source preproc/gmsh_module/),
// loaded the first time a part needs gmsh: a geometry to mesh, a .msh the own reader leaves to
// gmsh (msh41_reader.hpp), OpenCASCADE's mass properties.
//
// Why: gmsh 4.8 brings OpenCASCADE and some 130 shared libraries, and linking them at the start
// of every ffr-reduce run took 0.12-0.14 s (measured on a program linked to gmsh alone, doing
// nothing), also for a .msh the own reader reads, for --help, and for
// a part file refused at once. The module and the program are built from one source tree with
// one compiler, so the interface is plain C++ behind one C symbol.
#include "ffr/preproc/mesh/gmsh_import.hpp"

namespace ffr::preproc::detail {

inline constexpr int kGmshModuleAbi = 1;

/// What the module gives: load_mesh through gmsh (in the calling process: the caller runs it
/// in a child, mesh_child.hpp) and occ_mass_properties. Exceptions cross as they are.
struct GmshModule {
  int abi;
  Mesh (*load_mesh)(const PartSpec& part, MeshReport* report, const MeshLog& log);
  GeometryMass (*mass_properties)(const std::filesystem::path& geometry);
};

/// The module, loaded once: from $FFR_GMSH_MODULE if set, else next to the running program
/// (installed: libexec/ffr/), else in ../libexec/ffr/ from it (the build tree's bin/ and tests/),
/// else next to the shared object the preprocessor is linked into (the Python package).
/// Throws std::runtime_error naming the places tried (an incomplete installation).
const GmshModule& gmsh_module();

}  // namespace ffr::preproc::detail

extern "C" const ffr::preproc::detail::GmshModule* ffr_gmsh_module_v1();
