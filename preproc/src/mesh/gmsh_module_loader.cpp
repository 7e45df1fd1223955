#include "gmsh_module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::preproc::detail {
namespace {

constexpr const char* kModule = "libffr-gmsh.so";

const GmshModule* load() {
  std::vector<std::filesystem::path> places;
  if (const char* e = std::getenv("FFR_GMSH_MODULE"); e && *e) places.emplace_back(e);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    places.push_back(exe.parent_path() / kModule);
    places.push_back(exe.parent_path().parent_path() / "libexec" / "ffr" / kModule);
  }
  // A host that is not ffr's own program (python3 importing the ffr package): next to the
  // shared object this code is linked into.
  Dl_info self{};
  if (dladdr(reinterpret_cast<const void*>(&gmsh_module), &self) && self.dli_fname) {
    const std::filesystem::path object = std::filesystem::absolute(self.dli_fname, ec);
    if (!ec && object != exe) places.push_back(object.parent_path() / kModule);
  }
  std::string tried;
  for (const auto& p : places) {
    tried += (tried.empty() ? "" : ", ") + p.string();
    if (!std::filesystem::exists(p, ec)) continue;
    void* handle = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      throw std::runtime_error("cannot load gmsh's module " + p.string() + ": " + (why ? why : "dlopen failed"));
    }
    using Entry = const GmshModule* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "ffr_gmsh_module_v1"));
    const GmshModule* m = entry ? entry() : nullptr;
    if (!m || m->abi != kGmshModuleAbi)
      throw std::runtime_error(p.string() + " is not gmsh's module of this ffr (another version?)");
    return m;  // never unloaded: gmsh keeps process-wide state
  }
  throw std::runtime_error(std::string("gmsh's module ") + kModule + " was not found (looked at " + tried +
                           "): the installation is incomplete, or set FFR_GMSH_MODULE to its path");
}

}  // namespace

const GmshModule& gmsh_module() {
  // A failed load throws out of the initialization, which the next call tries again.
  static const GmshModule* const module = load();
  return *module;
}

}  // namespace ffr::preproc::detail
