#pragma once
// gmsh is a process-wide singleton; this guard initializes it quietly and finalizes it,
// and turns gmsh's own errors (thrown as std::string or exceptions) into our FormatError.
#include <gmsh.h>

#include <string>

namespace ffr::preproc::detail {

class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 2);
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The messages gmsh logged so far (errors and warnings first lines).
  static std::string log_text() {
    std::vector<std::string> log;
    try {
      gmsh::logger::get(log);
    } catch (...) {
    }
    std::string s;
    for (const auto& l : log) s += l + "\n";
    return s;
  }
  static std::string last_error() {
    std::string e;
    try {
      gmsh::logger::getLastError(e);
    } catch (...) {
    }
    return e;
  }
};

}  // namespace ffr::preproc::detail
