#include "ffr/preproc/solver/mumps_options.hpp"

namespace ffr::preproc {

int mumps_ordering_code(const std::string& name) {
  // MUMPS's ICNTL(7) codes (MUMPS 5 user's guide).
  if (name == "amd") return 0;
  if (name == "amf") return 2;
  if (name == "scotch") return 3;
  if (name == "pord") return 4;
  if (name == "metis") return 5;
  if (name == "qamd") return 6;
  if (name == "auto") return 7;
  return -1;
}

const char* mumps_ordering_names() { return "\"pord\", \"amd\", \"amf\", \"qamd\", \"metis\", \"scotch\" or \"auto\""; }

}  // namespace ffr::preproc
