// Writes a synthetic SID, reads it back strictly, checks its identities, and calls into the
// runtime library: everything through the installed headers and libraries.
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/version.hpp"

#if __has_include("ffr/runtime/runtime.hpp")
#include "ffr/runtime/runtime.hpp"
#else
namespace ffr::runtime {
const char* version();
}
#endif

#include <cstring>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: ffr_consumer OUT.sid.h5\n";
    return 2;
  }
  ffr::formats::synthetic::ChainParams p;
  p.clamped = true;
  p.stiffening = true;
  ffr::formats::write_sid(ffr::formats::synthetic::spring_chain(p).sid, argv[1]);
  const ffr::formats::Sid sid = ffr::formats::read_sid(argv[1]);
  const auto report = ffr::formats::validate(sid);
  const bool versions_match = std::strcmp(ffr::runtime::version(), ffr::kVersion) == 0;
  std::cout << "read " << argv[1] << ": " << sid.nq() << " modes, mass " << sid.refmod.mass << ", "
            << report.failures() << " identity failures, runtime " << ffr::runtime::version() << "\n";
  if (sid.nq() != 4 || !report.ok() || !versions_match) return 1;
  std::cout << "consumer: ok\n";
  return 0;
}
