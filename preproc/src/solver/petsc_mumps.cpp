// MUMPS's controls and reports through PETSc (petsc_mumps.hpp). The INFOG codes and their
// meaning are those of the MUMPS 5 user's guide (section "Error diagnostics").
#include "petsc_mumps.hpp"

#if FFR_HAVE_SLEPC
#include "petsc_support.hpp"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace ffr::preproc::detail {

namespace {

const char* ordering_name(PetscInt code) {
  switch (code) {
    case 0: return "AMD";
    case 1: return "a given permutation";
    case 2: return "AMF";
    case 3: return "SCOTCH";
    case 4: return "PORD";
    case 5: return "METIS";
    case 6: return "QAMD";
    default: return "an ordering of its own";
  }
}

// A count MUMPS reports in an INFOG entry: negative means millions.
long long count_of(PetscInt v) { return v < 0 ? -1000000LL * v : static_cast<long long>(v); }

// What to try for an INFOG(1) code; `prefix` for the PETSC_OPTIONS the user may set.
std::string remedy(PetscInt code, const std::string& prefix) {
  const std::string icntl14 = "raise MUMPS's workspace relaxation ICNTL(14) (percent; e.g. PETSC_OPTIONS='-" + prefix +
                              "mat_mumps_icntl_14 80')";
  const std::string memory = "run on more ranks (each holds its share of the factor) or with \"out_of_core\": true in "
                             "the part file's reduction (the factors on disk)";
  switch (code) {
    case -5: case -7: case -13: case -22:
      return "MUMPS could not allocate memory: " + memory;
    case -8: case -9: case -11: case -14: case -15: case -17: case -20:
      return "MUMPS's workspace is too small: " + icntl14 + ", or " + memory;
    case -19:
      return "the memory per rank allowed by ICNTL(23) is too small: raise it (or leave it out of PETSC_OPTIONS), " + memory;
    case -6: case -10: case -40:
      return "the matrix is singular or not positive definite: the part has a mechanism or the shift lies above an "
             "eigenvalue (check the supports and the interfaces)";
    default:
      if (code <= -70 && code >= -90)
        return "MUMPS's out-of-core files could not be written or read: check that the out-of-core directory "
               "(reduction.out_of_core_dir, else TMPDIR) exists on every rank, is writable and has room";
      return "see INFOG(1) in the MUMPS user's guide";
  }
}

}  // namespace

MumpsChoices::MumpsChoices(const MumpsOptions& o, const std::string& prefix) {
  auto put = [&](const std::string& key, const std::string& value) {
    const std::string name = "-" + prefix + key;
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given), "PetscOptionsHasName");
    if (given) return false;
    check(PetscOptionsSetValue(nullptr, name.c_str(), value.c_str()), "PetscOptionsSetValue");
    added_.push_back(name);
    return true;
  };
  const int code = mumps_ordering_code(o.ordering);
  if (code >= 0 && put("mat_mumps_icntl_7", std::to_string(code))) ordering_ = code;
  if (o.out_of_core) {
    put("mat_mumps_icntl_22", "1");
    std::string dir = o.out_of_core_dir;
    if (dir.empty()) {
      const char* tmp = std::getenv("TMPDIR");
      dir = tmp && *tmp ? tmp : "/tmp";
    }
    put("mat_mumps_ooc_tmpdir", dir);
  }
}

MumpsChoices::~MumpsChoices() {
  for (const std::string& name : added_) PetscOptionsClearValue(nullptr, name.c_str());
}

std::string mumps_outcome(PetscErrorCode ierr, const char* call, PC pc, const MumpsChoices& choices) {
  const std::string petsc_text = ierr ? last_petsc_message() : std::string();
  Mat F = nullptr;
  PetscInt infog1 = 0, infog2 = 0;
  bool mumps = false;
  // The factor exists once the set-up reached MUMPS; another solver package (PETSC_OPTIONS)
  // has no INFOG: then PETSc's own error stands.
  if (PCFactorGetMatrix(pc, &F) == 0 && F && MatMumpsGetInfog(F, 1, &infog1) == 0 && MatMumpsGetInfog(F, 2, &infog2) == 0)
    mumps = true;
  if (mumps && infog1 < 0) {
    std::string prefix;
    {
      const char* p = nullptr;
      PCGetOptionsPrefix(pc, &p);
      prefix = p ? p : "";
    }
    const char* stage = petsc_text.find("analysis") != std::string::npos ? "analysis (ordering)"
                        : petsc_text.find("solve phase") != std::string::npos ? "solve"
                                                                               : "numerical factorization";
    std::ostringstream o;
    o << "slepc backend: MUMPS's " << stage << " failed in " << call << " (INFOG(1) = " << infog1
      << ", INFOG(2) = " << infog2 << "): " << remedy(infog1, prefix);
    throw std::runtime_error(o.str());
  }
  if (ierr) fail(ierr, call, petsc_text);
  PCFailedReason failed = PC_NOERROR;
  PCGetFailedReason(pc, &failed);
  if (failed != PC_NOERROR)
    throw std::runtime_error(std::string("slepc backend: the factorization failed in ") + call + " (" +
                             PCFailedReasons[failed] + ")");
  if (!mumps) return {};
  PetscInt used = -1, entries = 0, mem_max = 0, mem_sum = 0;
  MatMumpsGetInfog(F, 7, &used);
  if (choices.ordering() >= 0 && choices.ordering() != 7 && used >= 0 && used != choices.ordering())
    throw std::runtime_error(std::string("slepc backend: MUMPS ordered by ") + ordering_name(used) + ", not by the " +
                             ordering_name(choices.ordering()) +
                             " asked for (reduction.mumps_ordering): this MUMPS is built without it; choose one it "
                             "has (\"pord\", the default, is in every MUMPS; \"amd\", \"amf\", \"qamd\")");
  PetscInt est_max = 0, est_sum = 0;
  MatMumpsGetInfog(F, 29, &entries);
  MatMumpsGetInfog(F, 18, &mem_max);
  MatMumpsGetInfog(F, 19, &mem_sum);
  MatMumpsGetInfog(F, 16, &est_max);
  MatMumpsGetInfog(F, 17, &est_sum);
  PetscInt ooc = 0;
  MatMumpsGetIcntl(F, 22, &ooc);
  std::ostringstream o;
  o << "MUMPS: " << ordering_name(used) << " ordering, " << count_of(entries) << " entries in the factor (INFOG(29)), "
    << mem_max << " MB allocated on the largest rank, " << mem_sum << " MB on all (INFOG(18), INFOG(19)), "
    << "factors " << (ooc ? "out of core" : "in core") << "; in-core estimate " << est_max << " MB on the largest rank, "
    << est_sum << " MB on all (INFOG(16), INFOG(17))";
  return o.str();
}

}  // namespace ffr::preproc::detail
#endif
