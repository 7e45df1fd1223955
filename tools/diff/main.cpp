// ffr-diff A.h5 B.h5 [--rtol R] [--atol A]: exit 0 equivalent, 1 different, 2 bad input.
#include "ffr/cli/cli.hpp"
#include "ffr/formats/diff.hpp"
#include "ffr/formats/sid_io.hpp"

#include <cstdio>
#include <iostream>

namespace {

const ffr::cli::Command kCommand{
    "ffr-diff",
    R"(
Compares two SID files member by member. A mode's sign, and a rotation of modes inside a
repeated eigenvalue, are not differences: B's modes are first aligned to A's and every
mode-dependent member of B transformed accordingly (see formats/include/ffr/formats/diff.hpp).
An entry differs when |a - b| > atol + rtol * scale, scale = the dataset's largest |entry|
(and at least its natural size from A's mass, size and mode amplitude).

  --rtol R       relative tolerance (default 1e-6)
  --atol A       absolute tolerance (default 0)
  --max N        number of worst entries listed (default 10)
  --no-align     compare the modes as they are
  --help, --version

Exit status: 0 equivalent, 1 different, 2 bad input (named on stderr), including a damaged
file (values that differ from its content checksums). A file of format_version 1 (no content
checksums) is compared with a warning on stderr.
)",
    "ffr-diff A.h5 B.h5 [--rtol R] [--atol A]"};

int run(ffr::cli::Args& args) {
  using ffr::cli::UsageError;
  ffr::formats::DiffOptions opt;
  if (auto v = args.number("--rtol")) opt.rtol = *v;
  if (auto v = args.number("--atol")) opt.atol = *v;
  if (auto v = args.number("--max")) opt.max_reported = static_cast<int>(*v);
  opt.align = !args.flag("--no-align");
  if (opt.rtol < 0 || opt.atol < 0) throw UsageError("--rtol and --atol must be >= 0");
  opt.group_rtol = std::max(opt.group_rtol, opt.rtol);
  const auto files = args.positionals();
  if (files.size() != 2) throw UsageError("expected two files A and B");
  std::vector<std::string> warnings;
  const auto a = ffr::formats::read_sid(files[0], &warnings);
  const auto b = ffr::formats::read_sid(files[1], &warnings);
  for (const auto& w : warnings) std::fprintf(stderr, "ffr-diff: warning: %s\n", w.c_str());
  const auto rep = ffr::formats::diff(a, b, opt);

  std::printf("%s vs %s: %s (%d datasets compared, %d differ; rtol %g, atol %g)\n", files[0].c_str(), files[1].c_str(),
              rep.equivalent ? "EQUIVALENT" : "DIFFERENT", rep.datasets_compared, rep.datasets_different, opt.rtol, opt.atol);
  const auto& al = rep.alignment;
  if (!al.flipped.empty() || !al.rotated_groups.empty()) {
    std::string s = "  modes aligned:";
    for (auto k : al.flipped) {
      s += " mode ";
      s += std::to_string(k + 1);
      s += " sign flipped;";
    }
    for (auto g : al.rotated_groups) {
      s += " modes";
      for (auto k : al.groups[static_cast<std::size_t>(g)]) {
        s += ' ';
        s += std::to_string(k + 1);
      }
      s += " rotated;";
    }
    std::printf("%s\n", s.c_str());
  }
  for (const auto& s : rep.structural) std::printf("  %s\n", s.c_str());
  for (const auto& d : rep.worst)
    std::printf("  %s%s: A %.10g, B %.10g (|diff| %.3g, rel %.3g, allowed %.3g)\n", d.dataset.c_str(), d.index.c_str(),
                d.a, d.b, d.abs, d.rel, d.allowed);
  return rep.equivalent ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
