// Default backend: Spectra's implicitly restarted Lanczos in the M inner product on the
// operator (K - sigma M)^{-1} M, built from our ShiftInvertOp / MassOp.

#include "eigen_backends.hpp"

#include <Spectra/SymGEigsShiftSolver.h>

#include <sstream>

namespace ffr::preproc::detail {

BackendOutcome run_spectra(ShiftInvertOp& op, MassOp& bop, const LanczosRequest& req) {
  using Solver = Spectra::SymGEigsShiftSolver<ShiftInvertOp, MassOp, Spectra::GEigsMode::ShiftInvert>;
  Solver solver(op, bop, req.nev, req.ncv, req.sigma);
  solver.init(req.v0->data());
  // Every lambda > sigma maps to nu = 1/(lambda - sigma) > 0, so the largest |nu| are the
  // eigenvalues nearest above sigma. Results are sorted by lambda ascending.
  solver.compute(Spectra::SortRule::LargestMagn, req.max_restarts, req.tol,
                 Spectra::SortRule::SmallestAlge);
  BackendOutcome out;
  out.iterations = static_cast<int>(solver.num_iterations());
  out.lambda = solver.eigenvalues();
  out.converged = static_cast<int>(out.lambda.size());
  out.success = solver.info() == Spectra::CompInfo::Successful;
  if (out.success) {
    out.X = solver.eigenvectors();
  } else {
    std::ostringstream os;
    os << "Spectra Lanczos did not converge: " << out.converged << " of " << req.nev
       << " eigenpairs after " << out.iterations << " restarts (ncv = " << req.ncv
       << ", tol = " << req.tol << "); raise max_restarts or ncv";
    out.message = os.str();
  }
  return out;
}

}  // namespace ffr::preproc::detail
