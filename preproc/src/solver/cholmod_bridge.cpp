#include "cholmod_bridge.hpp"

#include <sstream>
#include <utility>

namespace ffr::preproc::detail {

namespace {
// CHOLMOD's error hook carries no user pointer; the message goes to a per-thread slot that
// the wrapper reads right after the failing call (CHOLMOD calls are synchronous).
thread_local std::string g_last_error;

void capture_error(int status, const char* file, int line, const char* message) {
  std::ostringstream os;
  os << "CHOLMOD status " << status << ": " << (message ? message : "(no message)") << " ("
     << (file ? file : "?") << ":" << line << ")";
  g_last_error = os.str();
}
}  // namespace

CholmodCommon::CholmodCommon() {
  cholmod_l_start(&c_);
  c_.print = 0;  // library code never prints
  c_.error_handler = &capture_error;
  c_.supernodal = CHOLMOD_SUPERNODAL;
  c_.final_ll = 1;  // supernodal factors are LL^T anyway; keep it so if converted
  // Stop at the first non-positive pivot: the factor is useless then, and we report it.
  c_.quick_return_if_not_posdef = 1;
}

CholmodCommon::~CholmodCommon() { cholmod_l_finish(&c_); }

std::string CholmodCommon::take_last_error() { return std::exchange(g_last_error, {}); }

}  // namespace ffr::preproc::detail
