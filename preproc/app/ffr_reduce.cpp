// ffr-reduce PART.json -o OUT.sid.h5: geometry or mesh -> FE -> modes -> invariants -> SID file.
#include "ffr/cli/cli.hpp"
#include "ffr/cli/process_threads.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "ffr/preproc/threads.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <unistd.h>

namespace {

const ffr::cli::Command kCommand{
    "ffr-reduce",
    R"(
Reduces a flexible part to a SID file: meshes the geometry (or reads a .msh as it is),
assembles the finite-element stiffness and consistent mass, computes the modes of the
part file's reduction (free, clamped or craig-bampton), the shape-integral invariants and
writes them to one HDF5 file. The output is written under a temporary name and renamed
at the end, so a failed run leaves no file.

options:
  -o, --output FILE     the SID file to write (required)
  --vtk FILE            also write the mesh with every mode shape for ParaView (.vtk)
  --backend NAME        eigen-solver: block (default; block Lanczos, falls back to spectra),
                        spectra or arpack (overrides the part file)
  --factorization NAME  sparse Cholesky: supernodal (default) or cholmod (overrides the part file)
  --threads N           threads of assembly, factorization, substitutions and invariants
                        (default: all cores); the BLAS runs on one thread under the
                        supernodal factorization's own threads, on N under cholmod
  --max-memory GIB      refuse (before computing it) a factorization that needs more than this
                        many GiB; default: the memory available on the machine
  --quiet               no progress output (errors are still printed)
  --help, --version

environment:
  GLIBC_TUNABLES=glibc.malloc.hugetlb=1   transparent 2 MiB pages for the heap (glibc 2.35+):
                        fewer page faults where the kernel hands out huge pages cheaply
  OPENBLAS_CORETYPE     OpenBLAS's kernels, when the log says the CPU suits newer ones

exit status: 0 ok, 2 bad input (the message names the file and the field), 1 other failure.
)",
    "ffr-reduce PART.json -o OUT.sid.h5 [--vtk MODES.vtk] [--backend block|spectra|arpack] "
    "[--factorization supernodal|cholmod] [--threads N] "
    "[--max-memory GIB] [--quiet]"};

}  // namespace

int main(int argc, char** argv) {
  return ffr::cli::run_main(argc, argv, kCommand, [](ffr::cli::Args& args) {
    const bool quiet = args.flag("--quiet");
    auto out = args.option("--output");
    if (auto o = args.option("-o")) out = o;
    const auto vtk = args.option("--vtk");
    const auto backend = args.option("--backend");
    const auto factorization = args.option("--factorization");
    if (const auto threads = args.option("--threads")) {
      char* end = nullptr;
      const long n = std::strtol(threads->c_str(), &end, 10);
      if (threads->empty() || *end || n < 1 || n > 1024) throw ffr::cli::UsageError("--threads must be a count >= 1");
      ffr::preproc::set_max_threads(static_cast<unsigned>(n));
    }
    const auto max_memory = args.number("--max-memory");
    const auto pos = args.positionals();
    if (pos.size() != 1) throw ffr::cli::UsageError("expected one part file");
    if (!out) throw ffr::cli::UsageError("missing -o OUT.sid.h5");

    ffr::preproc::PartSpec part = ffr::preproc::load_part(pos[0]);
    if (backend) {
      if (*backend != "spectra" && *backend != "arpack" && *backend != "block")
        throw ffr::cli::UsageError("--backend must be block, spectra or arpack");
      part.reduction.backend = *backend;
    }
    if (factorization) {
      if (*factorization != "supernodal" && *factorization != "cholmod")
        throw ffr::cli::UsageError("--factorization must be supernodal or cholmod");
      part.reduction.factorization = *factorization;
    }
    // The BLAS's threads by the factorization that will call it (process_threads.hpp says why);
    // without --threads as many as the reducer's own (all cores).
    ffr::cli::set_numerical_library_threads(
        ffr::cli::blas_threads_for(part.reduction.factorization, ffr::preproc::max_threads()));
    if (max_memory) {
      if (!(*max_memory > 0)) throw ffr::cli::UsageError("--max-memory must be a positive number of GiB");
      part.reduction.memory_limit_bytes = static_cast<std::uint64_t>(*max_memory * 1024.0 * 1024.0 * 1024.0);
    }
    const bool tty = ::isatty(STDERR_FILENO);
    const auto t0 = std::chrono::steady_clock::now();
    ffr::preproc::PipelineLog log;
    if (!quiet) {
      log.stage = [tty](const std::string& s) {
        if (tty) std::cerr << "\r\033[K";
        std::cerr << "ffr-reduce: " << s << "\n";
      };
      if (tty) log.progress = [](const std::string& s) { std::cerr << "\r\033[K  " << s << std::flush; };
    }
    ffr::preproc::PipelineOptions opt;
    if (vtk) opt.vtk = *vtk;
    const ffr::formats::Sid sid = ffr::preproc::run_pipeline(part, opt, log);

    // Every file written must pass the identities of the format; a failure is a bug, not input.
    const auto report = ffr::formats::validate(sid);
    if (!report.ok()) {
      std::string text;
      for (const auto& c : report.checks)
        if (c.applicable && !c.pass) {
          char nums[96];  // %g: a relative violation of 1e300 is one short number, not 300 digits
          std::snprintf(nums, sizeof nums, ": violation %.3g (tolerance %.3g) ", c.rel, c.tol);
          text += "\n  " + c.name + nums + c.note;
        }
      throw std::runtime_error("the reduced body fails validation (nothing written):" + text);
    }
    ffr::formats::write_sid(sid, *out);
    if (!quiet) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "ffr-reduce: wrote " << *out << " (" << sid.nq() << " modes, " << sid.nodes.size() << " nodes) in "
                << s << " s\n";
    }
    return 0;
  });
}
