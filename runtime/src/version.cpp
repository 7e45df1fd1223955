#include "ffr/version.hpp"

namespace ffr::runtime {
const char* version() { return ffr::kVersion; }
}  // namespace ffr::runtime
