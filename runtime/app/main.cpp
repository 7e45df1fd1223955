// ffr-sim MODEL.json -o OUT.h5 [--csv OUT.csv]
// Exit status: 0 ok, 2 bad input (one line naming the file and the field), 1 other failure.
#include "ffr/runtime/runtime.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/version.hpp"

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

namespace {

constexpr const char* kUsage =
    "usage: ffr-sim MODEL.json -o OUT.h5 [--csv OUT.csv] [--quiet]\n"
    "\n"
    "Integrates the multibody model in MODEL.json (bodies, joints, forces, motions, outputs;\n"
    "flexible bodies from SID files) and writes the requested outputs to OUT.h5\n"
    "(/time, /outputs/<name>) and, with --csv, to a CSV file.\n"
    "\n"
    "  -o, --output FILE   results file (HDF5), required\n"
    "      --csv FILE      also write the outputs as CSV\n"
    "  -q, --quiet         no progress or notes on stderr\n"
    "  -h, --help          this text\n"
    "  -V, --version       the version\n"
    "\n"
    "Exit status: 0 ok, 2 bad input, 1 other failure (e.g. Newton divergence).\n";

struct Args {
  std::string model, out, csv;
  bool quiet = false;
};

int usage_error(const std::string& what) {
  std::fprintf(stderr, "ffr-sim: %s (see ffr-sim --help)\n", what.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ffr::runtime;
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* opt) -> const char* {
      if (i + 1 >= argc) return nullptr;
      (void)opt;
      return argv[++i];
    };
    if (s == "-h" || s == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (s == "-V" || s == "--version") {
      std::printf("ffr-sim %s\n", ffr::kVersion);
      return 0;
    } else if (s == "-o" || s == "--output") {
      const char* v = value("-o");
      if (!v) return usage_error("-o needs a file name");
      a.out = v;
    } else if (s == "--csv") {
      const char* v = value("--csv");
      if (!v) return usage_error("--csv needs a file name");
      a.csv = v;
    } else if (s == "-q" || s == "--quiet") {
      a.quiet = true;
    } else if (!s.empty() && s[0] == '-') {
      return usage_error("unknown option '" + s + "'");
    } else if (a.model.empty()) {
      a.model = s;
    } else {
      return usage_error("more than one model file given");
    }
  }
  if (a.model.empty()) return usage_error("no model file given");
  if (a.out.empty()) return usage_error("no results file given (-o OUT.h5)");

  try {
    const Model model = load_model(a.model);
    Data data(model);
    std::vector<std::string> notes = model.notes;
    for (auto& n : initialize(model, data)) notes.push_back(std::move(n));
    if (!a.quiet)
      for (const auto& n : notes) std::fprintf(stderr, "ffr-sim: note: %s\n", n.c_str());
    Recorder rec(model, step_count(model) / std::max(1, model.settings.output_every) + 2);
    RunOptions opt;
    bool reported = false;
    if (!a.quiet) {
      opt.progress_seconds = 2.0;
      opt.progress = [&](double t, double end) {
        std::fprintf(stderr, "\rffr-sim: t = %.6g / %.6g s (%.0f%%)", t, end, 100.0 * (t - model.settings.start) / (end - model.settings.start));
        std::fflush(stderr);
        reported = true;
      };
    }
    const RunInfo info = simulate(model, data, rec, opt);
    if (reported) std::fputc('\n', stderr);
    write_results_h5(a.out, model, rec, info);
    if (!a.csv.empty()) write_results_csv(a.csv, model, rec);
    if (!a.quiet)
      std::fprintf(stderr, "ffr-sim: %lld steps, %lld Newton iterations, %.3f s integration, %.2f us/step\n",
                   static_cast<long long>(info.steps), static_cast<long long>(info.newton_iterations),
                   info.integration_seconds, info.steps ? 1e6 * info.integration_seconds / static_cast<double>(info.steps) : 0.0);
    return 0;
  } catch (const ModelError& e) {
    std::fprintf(stderr, "ffr-sim: %s\n", e.what());
    return 2;
  } catch (const SolverError& e) {
    std::fprintf(stderr, "ffr-sim: %s (residual %.3g)\n", e.what(), e.residual());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ffr-sim: %s\n", e.what());
    return 1;
  }
}
