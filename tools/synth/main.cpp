// ffr-synth: writes a synthetic SID file (formats/include/ffr/formats/synthetic.hpp).
#include "ffr/cli/cli.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <iostream>

namespace {

const ffr::cli::Command kCommand{
    "ffr-synth",
    R"(
Writes the SID file of a synthetic spring chain: lumped masses on Euler-Bernoulli beam
segments along +x (see synthetic.hpp for the model). Nodes "A" (first point) and "B" (last).

  --chain                 the body to write (the only kind so far)
  -o FILE                 output SID file (required)
  --points N              number of mass points (default 11)
  --length L              [m] (default 1)
  --mass M                total mass [kg] (default 1)
  --EA X                  axial stiffness [N] (default 1e6)
  --EI X                  bending stiffness about y and z [N m^2] (default 1)
  --EIy X, --EIz X        bending stiffness about y / z separately
  --start x,y,z           position of point A in the body frame (default 0,0,0)
  --clamped               clamp point A (default: free-free)
  --modes N               number of elastic modes kept (default 4)
  --damping Z             modal damping ratio (default 0)
  --stiffening            also write /stiffening
  --help, --version
)",
    "ffr-synth --chain [options] -o OUT.sid.h5"};

int run(ffr::cli::Args& a) {
  using ffr::cli::Args;
  using ffr::cli::UsageError;
  ffr::formats::synthetic::ChainParams p;
  const bool chain = a.flag("--chain");
  auto out = a.option("-o");
  if (auto v = a.option("--output")) out = v;
  auto integer = [&](const std::string& name, int& dst) {
    if (auto v = a.number(name)) {
      if (*v != static_cast<int>(*v)) throw UsageError(name + ": expected an integer");
      dst = static_cast<int>(*v);
    }
  };
  integer("--points", p.points);
  integer("--modes", p.modes);
  if (auto v = a.number("--length")) p.length = *v;
  if (auto v = a.number("--mass")) p.mass = *v;
  if (auto v = a.number("--EA")) p.EA = *v;
  if (auto v = a.number("--EI")) p.EIy = p.EIz = *v;
  if (auto v = a.number("--EIy")) p.EIy = *v;
  if (auto v = a.number("--EIz")) p.EIz = *v;
  if (auto v = a.number("--damping")) p.damping_ratio = *v;
  if (auto v = a.option("--start")) {
    const auto xyz = Args::parse_list(*v, "--start");
    if (xyz.size() != 3) throw UsageError("--start: expected x,y,z");
    p.start = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  }
  p.clamped = a.flag("--clamped");
  p.stiffening = a.flag("--stiffening");
  if (!a.positionals().empty()) throw UsageError("unexpected argument " + a.positionals().front());
  if (!chain) throw UsageError("say which body to write (--chain)");
  if (!out) throw UsageError("missing -o OUT.sid.h5");
  const auto c = ffr::formats::synthetic::spring_chain(p);
  ffr::formats::write_sid(c.sid, *out);
  std::cout << "wrote " << *out << ": " << c.sid.nq() << " modes, first " << c.sid.refmod.frequency_hz[0] << " Hz\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
