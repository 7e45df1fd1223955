// ffr-reduce PART.json -o OUT.sid.h5: geometry or mesh -> FE -> modes -> invariants -> SID file.
#include "ffr/cli/cli.hpp"
#include "ffr/cli/output_files.hpp"
#include "ffr/cli/process_threads.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "ffr/preproc/solver/parallel_session.hpp"
#include "ffr/preproc/threads.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
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
                        spectra, arpack, or slepc (SLEPc over MPI, where built in: run
                        under mpirun -np N for N ranks) (overrides the part file)
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
  PETSC_OPTIONS         options of PETSc, SLEPc and MUMPS under the slepc backend (e.g.
                        "-st_mat_mumps_icntl_14 50" for more MUMPS workspace; docs/cluster.md)

under MPI (backend slepc): every rank runs the pipeline, rank 0 alone prints and writes the
file, after every rank has succeeded; a failing rank ends the job with its exit status.

exit status: 0 ok, 2 bad input (the message names the file and the field), 1 other failure.
)",
    "ffr-reduce PART.json -o OUT.sid.h5 [--vtk MODES.vtk] [--backend block|spectra|arpack|slepc] "
    "[--factorization supernodal|cholmod] [--threads N] "
    "[--max-memory GIB] [--quiet]"};

// Every file written must pass the identities of the format; a failure is a bug, not input.
void check_valid(const ffr::formats::Sid& sid) {
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
}

// The number of ranks the launcher started (mpirun, srun), from its environment; 1 without one.
int launcher_ranks() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* s = std::getenv(v)) {
      const long n = std::strtol(s, nullptr, 10);
      if (n > 0) return static_cast<int>(n);
    }
  return 1;
}

// Runs f on this rank. With several ranks a failure ends the whole job (the others may be
// waiting for this one in a collective operation) with run_main's exit status for it; nothing
// has been written then, since rank 0 writes only after every rank has passed the last barrier.
template <class F>
void on_this_rank(const ffr::preproc::ParallelSession* session, F&& f) {
  if (!session || session->size() == 1) return f();
  auto fail = [session](const char* what, int status) {
    std::cerr << "ffr-reduce: error: " << what << " (rank " << session->rank() << " of " << session->size() << ")\n";
    session->abort(status);
  };
  try {
    f();
  } catch (const ffr::formats::FormatError& e) {
    fail(e.what(), 2);
  } catch (const std::invalid_argument& e) {
    fail(e.what(), 2);
  } catch (const std::exception& e) {
    fail(e.what(), 1);
  } catch (...) {
    fail("unknown failure", 1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ffr::cli::run_main(argc, argv, kCommand, [](ffr::cli::Args& args) {
    bool quiet = args.flag("--quiet");
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
    // Before the reduction, which may take minutes: outputs that cannot be written or would
    // replace the part file, its geometry or each other.
    std::vector<ffr::cli::NamedPath> outputs{{"-o", *out}};
    if (vtk) outputs.push_back({"--vtk", *vtk});
    ffr::cli::check_outputs(outputs, {{"the part file", part.file}, {"the part's geometry", part.geometry}});
    if (backend) {
      if (*backend != "spectra" && *backend != "arpack" && *backend != "block" && *backend != "slepc")
        throw ffr::cli::UsageError("--backend must be block, spectra, arpack or slepc");
      if (*backend == "slepc" && !ffr::preproc::slepc_available())
        throw ffr::cli::UsageError("--backend slepc: not built into this program (configure with -DFFR_SLEPC=ON)");
      // The part's MUMPS keys would be ignored without a word by any other backend.
      const auto& given = part.reduction.mumps.keys_given;
      if (*backend != "slepc" && !given.empty())
        throw ffr::cli::UsageError("--backend " + *backend + ": " + pos[0] + " sets reduction." + given.front() +
                                   ", which only backend \"slepc\" (MUMPS's factorization) reads; remove it from the "
                                   "part file or run with --backend slepc");
      part.reduction.backend = *backend;
    }
    if (factorization) {
      if (*factorization != "supernodal" && *factorization != "cholmod")
        throw ffr::cli::UsageError("--factorization must be supernodal or cholmod");
      // As the part file's own check: the dense kernels are the supernodal factorization's.
      if (*factorization == "cholmod" && part.reduction.dense_kernels != "auto")
        throw ffr::cli::UsageError("--factorization cholmod: " + pos[0] + " sets reduction.dense_kernels, which only "
                                   "the supernodal factorization reads (CHOLMOD's calls the BLAS itself)");
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
    // Under mpirun every rank runs this program: only the slepc backend divides the work, and
    // the others would each write the same file.
    const int ranks = launcher_ranks();
    if (ranks > 1 && part.reduction.backend != "slepc")
      throw ffr::cli::UsageError("started as " + std::to_string(ranks) + " MPI ranks, but reduction.backend is \"" +
                                 part.reduction.backend + "\": only \"slepc\" runs on several ranks (run it without "
                                 "mpirun, or set reduction.backend to \"slepc\")");
    std::unique_ptr<ffr::preproc::ParallelSession> session;
    if (part.reduction.backend == "slepc") session = std::make_unique<ffr::preproc::ParallelSession>();
    const bool rank0 = !session || session->rank() == 0;
    quiet = quiet || !rank0;
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
    if (!rank0) opt.vtk.clear();
    ffr::formats::Sid sid;
    on_this_rank(session.get(), [&] {
      sid = ffr::preproc::run_pipeline(part, opt, log);
      check_valid(sid);
    });
    if (session) session->barrier();
    if (!rank0) return 0;
    ffr::formats::write_sid(sid, *out);
    if (!quiet) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "ffr-reduce: wrote " << *out << " (" << sid.nq() << " modes, " << sid.nodes.size() << " nodes) in "
                << s << " s";
      if (session) std::cerr << " on " << session->size() << " rank(s)";
      std::cerr << "\n";
    }
    return 0;
  });
}
