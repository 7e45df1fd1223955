// ffr-info: summary of a SID or ffr-sim results file (formats/SPEC.md), or the Campbell
// diagram of a SID. Exit status: 0 ok, 2 bad input, 1 other failure.
#include "export.hpp"
#include "summary.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/formats/modal_stress.hpp"
#include "ffr/formats/sid_io.hpp"

#include <iostream>

namespace {

const ffr::cli::Command kCommand{
    "ffr-info",
    R"(
Prints a summary of a SID file (mass, centre of mass, inertia about O and about the centre of
mass, modes, nodes, interfaces, provenance, and the identity checks of formats/SPEC.md) or of
an ffr-sim results file (time span, statistics, output channels with their final values).

  --json                  the same summary as JSON on stdout
  --campbell x|y|z        frequencies [Hz] of the body spinning about that axis through O,
  --speeds W1,W2,...      at these speeds [rad/s] (needs --campbell)
  --png OUT.png           with --campbell: also draw the diagram into OUT.png
  --plot CH1,CH2[i],...   of an ffr-sim results file: draw the time histories of these output
                          channels (all components, or component i from 0) into --png OUT.png;
                          legends name the components by the output's type (kinetic/potential/
                          total, x/y/z, Fx..Mz, mode k), else [i]; a channel's whole name is
                          matched first ("x[mm]"), and so is the longest list of
                          comma-separated pieces that names a channel ("a,b" for an output so named)
  --stress BODY           of an ffr-sim results file: von Mises and principal stresses over
                          time at the nodes of BODY's SID /stress group (sigma = sum_k q_k S_k,
                          q the run's modal_coordinates output of BODY): a table of each node's
                          peak, or with --json every sample ({"time", "nodes": [{"node",
                          "position", "layer", "von_mises": [nt], "principal": [nt][3]}]}),
                          stress in the SID's units (Pa), principal stresses descending; a
                          shell node has three entries, layer "top", "middle" and "bottom"
                          (a solid node's layer is "solid")
  --model MODEL.json      with --stress: the model file of the run (default: the one the run
                          names in its attribute `model`, as given or beside the run)
  --export-fbi -o OUT     write the SID as a SID_FEM text file (the standard input data of a
                          flexible body, the layout SIMPACK's flexible-body import reads)
  --export-mtx -o DIR     write the reduced matrices Me, Ke, De (and Ke.M1) as Matrix Market
                          files into DIR (formats/SPEC.md, "Exports")
  --help, --version

Exit status: 0 ok, 2 bad input (named on stderr), 1 other failure. Bad input includes a
damaged file (a content checksum that does not match) and a readable SID that fails any
validation check: its summary is printed with the failures listed, one line on stderr names
the file and the first failed check, and the status is 2. A file of format_version 1 (no
content checksums) is read with a warning on stderr. In --json output, bytes of a string that
are not valid UTF-8 are replaced by U+FFFD.
)",
    "ffr-info FILE.h5 [--json] | ffr-info FILE.sid.h5 --export-fbi|--export-mtx -o OUT | ffr-info FILE.sid.h5 --campbell x|y|z --speeds 0,50,100 [--json] [--png OUT.png] | ffr-info RESULTS.h5 --plot CH1,CH2 --png OUT.png | ffr-info RESULTS.h5 --stress BODY [--model MODEL.json] [--json]"};

int run(ffr::cli::Args& a) {
  using ffr::cli::UsageError;
  const bool json = a.flag("--json");
  const auto campbell = a.option("--campbell");
  const auto speeds = a.option("--speeds");
  const auto png = a.option("--png");
  const auto plot = a.option("--plot");
  const bool export_fbi = a.flag("--export-fbi"), export_mtx = a.flag("--export-mtx");
  const auto out = a.option("-o");
  const auto stress = a.option("--stress");
  const auto model = a.option("--model");
  const auto files = a.positionals();
  if (files.size() != 1) throw UsageError(files.empty() ? "missing FILE" : "expected one FILE, got " + std::to_string(files.size()));
  if (export_fbi || export_mtx || out) {
    if (export_fbi == export_mtx) throw UsageError(out ? "-o needs --export-fbi or --export-mtx" : "give one of --export-fbi and --export-mtx");
    if (!out) throw UsageError(export_fbi ? "--export-fbi needs -o OUT" : "--export-mtx needs -o DIR");
    if (json || plot || campbell || speeds || png || stress || model) throw UsageError("an export goes with no other option");
    return export_fbi ? ffr::info::run_export_fbi(files[0], *out) : ffr::info::run_export_mtx(files[0], *out);
  }
  if (stress) {
    if (plot || campbell || speeds || png) throw UsageError("--stress goes with --json and --model only");
    return ffr::info::run_stress(files[0], *stress, model.value_or(""), json);
  }
  if (model) throw UsageError("--model needs --stress BODY");
  if (plot) {
    if (campbell || speeds) throw UsageError("--plot and --campbell do not go together");
    return ffr::info::run_plot(files[0], *plot, png.value_or(""));
  }
  if (campbell || speeds || png) {
    if (!campbell) throw UsageError("--speeds and --png need --campbell x|y|z");
    if (!speeds) throw UsageError("--campbell needs --speeds W1,W2,...");
    return ffr::info::run_campbell(files[0], *campbell, *speeds, json, png.value_or(""));
  }

  nlohmann::json summary;
  std::vector<std::string> warnings;
  {
    const ffr::formats::h5::Reader r(files[0]);
    if (ffr::formats::is_results_file(r)) {
      summary = ffr::info::summarize_results(ffr::formats::read_results(files[0], &warnings), files[0]);
    } else {
      const auto version = r.has_attr("/", "format_version") ? r.attr_int("/", "format_version") : 0;
      summary = ffr::info::summarize_sid(ffr::formats::read_sid(files[0], &warnings), files[0], version);
      // The optional /stress group, which read_sid leaves out (formats/SPEC.md section 12.1).
      const auto stress = ffr::formats::read_modal_stress(files[0]);
      // "nodes": mesh nodes; "rows": stresses stored (a shell node has three layers).
      std::int64_t nodes = 0;
      for (Eigen::Index i = 0; stress && i < stress->size(); ++i)
        nodes += i == 0 || stress->node[static_cast<std::size_t>(i)] != stress->node[static_cast<std::size_t>(i - 1)];
      summary["stress"] = stress ? nlohmann::json{{"nodes", nodes}, {"rows", stress->size()}, {"selection", stress->selection}}
                                 : nlohmann::json(nullptr);
    }
  }
  summary["warnings"] = warnings;
  for (const auto& w : warnings) std::cerr << "ffr-info: warning: " << w << "\n";
  if (json)
    std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  else
    std::cout << ffr::info::render_text(summary);
  // A SID that fails validation is bad input (documented above), after its full summary.
  if (summary.contains("validation") && !summary["validation"]["ok"].get<bool>()) {
    const auto& first = summary["validation"]["failed"][0];
    std::cerr << "ffr-info: " << files[0] << ": fails " << summary["validation"]["failures"].get<int>()
              << " validation check(s), first " << first["name"].get<std::string>() << " ("
              << first["where"].get<std::string>() << ")\n";
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
