#pragma once
// What the slepc backend asks of MUMPS, its distributed Cholesky factorization of K - sigma M
// (part file: reduction.mumps_ordering, reduction.out_of_core, reduction.out_of_core_dir).
// Options given in PETSC_OPTIONS for the same MUMPS control take precedence.

#include <string>
#include <vector>

namespace ffr::preproc {

struct MumpsOptions {
  /// The fill-reducing ordering of MUMPS's sequential analysis (ICNTL(7)): "pord" (4), "amd"
  /// (0), "amf" (2), "qamd" (6), "metis" (5), "scotch" (3), or "auto" (7: MUMPS chooses). METIS
  /// and SCOTCH exist only in a MUMPS built with them; asked of one without, MUMPS orders by
  /// another method and the factorization is refused (the ordering used is named).
  std::string ordering = "pord";
  /// The factors written to disk as they are computed (ICNTL(22) = 1): memory per rank falls
  /// to the active front and the buffers, each solve reads the factors back.
  bool out_of_core = false;
  /// Where the out-of-core files go (absolute); empty: the TMPDIR of the ranks, else /tmp.
  std::string out_of_core_dir;
  /// The MUMPS keys the part file gave (reduction.KEY; in the order above): a backend chosen on the
  /// command line other than slepc would ignore them, so ffr-reduce refuses it naming the first.
  std::vector<std::string> keys_given;
};

/// The ICNTL(7) value of an ordering name; -1 for a name that is not one.
int mumps_ordering_code(const std::string& name);
/// The names mumps_ordering_code knows, for messages: "pord", "amd", ...
const char* mumps_ordering_names();

}  // namespace ffr::preproc
