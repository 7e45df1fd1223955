#pragma once
// The part file's MUMPS choices (MumpsOptions) handed to PETSc's MUMPS interface, and what
// MUMPS reports of a factorization: its size, or, when it fails, which stage, MUMPS's INFOG(1)
// code and what to try. Shared by the slepc backend's solvers (slepc_backend.cpp,
// slepc_distributed.cpp).
#if FFR_HAVE_SLEPC
#include "ffr/preproc/solver/mumps_options.hpp"

#include <petscksp.h>

#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// The options prefixes of the factorizations: SLEPc's spectral transformation and the
/// constraint modes' solves (distributed_spd_solve).
inline constexpr const char* kEigenSolvePrefix = "st_";
inline constexpr const char* kSolvePrefix = "ffr_solve_";

/// MUMPS's controls for the factorizations under `prefix`, put into PETSc's options database
/// (MUMPS's controls are read from it when the factorization is set up, inside SLEPc's and
/// PETSc's own set-up) for as long as this object lives. A control that PETSC_OPTIONS already
/// sets is left as the user gave it.
class MumpsChoices {
 public:
  MumpsChoices(const MumpsOptions& o, const std::string& prefix);
  ~MumpsChoices();
  MumpsChoices(const MumpsChoices&) = delete;
  MumpsChoices& operator=(const MumpsChoices&) = delete;
  /// The ordering asked (ICNTL(7)), or -1 when PETSC_OPTIONS chose the ordering itself.
  int ordering() const { return ordering_; }

 private:
  std::vector<std::string> added_;
  int ordering_ = -1;
};

/// After `call` (its PETSc error code `ierr`) set up or used the MUMPS factor of `pc`: when it
/// failed, throws std::runtime_error naming the stage of MUMPS that failed, its INFOG(1) and
/// INFOG(2) and what to try (or PETSc's own message when MUMPS reports no failure); when MUMPS
/// ordered by another method than the one asked (one it is built without), throws too.
/// Otherwise returns one line on the factor: the ordering used, its entries and the memory
/// MUMPS allocated for it.
std::string mumps_outcome(PetscErrorCode ierr, const char* call, PC pc, const MumpsChoices& choices);

}  // namespace ffr::preproc::detail
#endif
