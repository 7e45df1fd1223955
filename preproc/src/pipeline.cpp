#include "ffr/preproc/pipeline.hpp"

#include "ffr/formats/sha256.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/reduce/damping.hpp"
#include "ffr/preproc/reduce/invariants.hpp"
#include "ffr/preproc/reduce/modal_stress.hpp"
#include "ffr/preproc/reduce/node_data.hpp"
#include "ffr/preproc/reduce/reduction.hpp"
#include "ffr/preproc/reduce/stiffening.hpp"
#include "ffr/preproc/threads.hpp"
#include "ffr/preproc/visual/visual.hpp"
#include "ffr/version.hpp"
#include "matrix_input/matrix_input.hpp"
#include "reduce/distributed_reduction.hpp"
#include "reduce/pattern_analysis.hpp"
#include "reduce/setup.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

namespace ffr::preproc {
namespace {

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

std::string fmt(double v, int prec = 3) {
  std::ostringstream o;
  o.precision(prec);
  o << v;
  return o.str();
}

// Hash of what the mesh is: coordinates and connectivity, independent of the file format.
std::string mesh_hash(const Mesh& mesh) {
  formats::Sha256 h;
  h.update(mesh.x.data(), static_cast<std::size_t>(mesh.x.size()) * sizeof(double));
  for (const auto& b : mesh.blocks) {
    h.update(b.group.data(), b.group.size());
    const int t = to_gmsh(b.type);
    h.update(&t, sizeof t);
    // The full-integration HEX8 is another element on the same nodes (the default adds nothing,
    // so the hash of every other mesh stays as it was).
    if (b.type == ElementType::Hex8 && b.hex8 == Hex8Formulation::FullIntegration) h.update("C3D8", 4);
    h.update(b.conn.data(), b.conn.size() * sizeof(Index));
  }
  return h.hex();
}

std::string mass_model_text(const FeModel& model) {
  std::string s = "consistent";
  bool shells = false, beams = false;
  for (const auto& pb : model.blocks) {
    shells = shells || pb.kind == ElementKind::Shell;
    beams = beams || pb.kind == ElementKind::Beam;
  }
  if (shells) s += "; shells: thickness-integrated fibres (u + theta x z n), drilling inertia in the rotary part";
  if (beams) s += "; beams: section fibres with rotary inertia";
  if (!model.masses.empty()) s += "; attached rigid masses: offset and inertia (u + theta x e)";
  return s;
}

}  // namespace

formats::Sid run_pipeline(const PartSpec& part, const PipelineOptions& options, const PipelineLog& log) {
  auto stage = [&](const std::string& s) { if (log.stage) log.stage(s); };
  auto progress = [&](const std::string& s) { if (log.progress) log.progress(s); };
  Stopwatch sw;

  // 1. Mesh.
  MeshReport mrep;
  const Mesh mesh = load_mesh(part, &mrep, [&](const std::string& s) { progress(s); });
  {
    std::string counts;
    for (const auto& [t, n] : mrep.element_counts) counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + t;
    stage("mesh: " + std::to_string(mesh.num_nodes()) + " nodes, " + counts + (mrep.meshed ? " (meshed)" : " (read)") +
          " [" + fmt(sw.lap()) + " s]");
  }

  // 2. FE model.
  const FeModel model = build_model(mesh, part);
  stage("model: " + std::to_string(model.num_dofs) + " DOF, " + std::to_string(model.interfaces.size()) +
        " interface(s), " + std::to_string(model.masses.size()) + " attached mass(es) [" + fmt(sw.lap()) + " s]");
  // The stress request is checked against the mesh before the reduction's minutes are spent.
  const std::vector<Index> stress_at = part.stress ? stress_nodes(model) : std::vector<Index>{};

  // 3. Assembly, with the eigen-solve's symbolic analysis on another thread meanwhile; or
  // the part's own assembled matrices, without either.
  const bool from_files = part.matrices.given();
  std::string file_mass_type;
  // The slepc backend's distributed path: each rank assembles its share of the elements
  // (reduce/distributed_reduction.hpp).
  std::optional<detail::DistributedReduction> distributed;
  if (detail::distributed_reduction_applies(part)) distributed.emplace(model, part.reduction);
  EarlyAnalysis early = from_files || distributed ? EarlyAnalysis{} : EarlyAnalysis::start(model, part.reduction);
  Assembled fe;
  if (distributed) {
    fe = distributed->assemble([&](double f) { progress("assembly " + std::to_string(static_cast<int>(100 * f)) + " %"); });
    stage("assembly: " + std::to_string(fe.elements) + " elements, distributed, mass " + fmt(fe.mass, 6) + " " +
          part.units.mass + " [" + fmt(sw.lap()) + " s]");
    if (!fe.worst_element.empty())
      stage("  quality: worst scaled Jacobian " + fmt(fe.worst_scaled_jacobian) + " (" + fe.worst_element + ")");
  } else if (from_files) {
    detail::MatrixInput in = detail::read_matrix_input(model, part);
    fe = std::move(in.fe);
    file_mass_type = std::move(in.mass_type);
    stage("matrices: K and M from " + part.matrices.K.filename().string() + ", " + part.matrices.M.filename().string() +
          ", nnz(K) = " + std::to_string(fe.K.nonZeros()) + ", mass " + fmt(fe.mass, 6) + " " + part.units.mass + " (" +
          file_mass_type + ") [" + fmt(sw.lap()) + " s]");
  } else {
    AssemblyOptions aopt;
    // One core left to the analysis while it runs. Why: at two threads the analysis, not the
    // assembly, was what the factorization waited for on the 100k-DOF plate of tools/bench/reduce;
    // with the assembly on one thread the two took about a fifth less time together.
    if (early.started()) aopt.threads = static_cast<int>(std::max(1u, max_threads() - 1));
    // The structure of K and M on every core, though: it is the first touch of their 250 MB on
    // that plate, and where a page fault costs more than filling the page, threads share the
    // faults.
    aopt.fill_threads = static_cast<int>(max_threads());
    // And the core back to the element loop once the analysis is done.
    if (early.started()) aopt.spare_core = [&early] { return early.finished(); };
    aopt.progress = [&](double f) { progress("assembly " + std::to_string(static_cast<int>(100 * f)) + " %"); };
    // Only the stiffening's static solves use K and M after the reduction; otherwise they are
    // freed before the factorization, the memory peak of the run.
    const bool keep_matrices = part.stiffening || !part.preload.empty();
    // M itself is needed only by the stiffening and Craig-Bampton, and where the eigen-solve's
    // matrix is not a principal submatrix of the assembled one; otherwise a part of solids alone
    // has it from Ms (the assembly checks the solids).
    if (!keep_matrices && part.reduction.method != ReductionSpec::Method::CraigBampton) {
      try {
        const DofTransform t = build_transform(model, detail::states_for(model, part.reduction));
        aopt.node_mass_only = !detail::factorized_rows(model, t, part.reduction).empty();
      } catch (const std::exception&) {
        // Bad interfaces: M is assembled, and the reduction reports them as it always did.
      }
    }
    fe = assemble(model, aopt);
    stage("assembly: " + std::to_string(fe.elements) + " elements, nnz(K) = " + std::to_string(fe.K.nonZeros()) +
          ", mass " + fmt(fe.mass, 6) + " " + part.units.mass + " [" + fmt(sw.lap()) + " s]");
    if (!fe.worst_element.empty())
      stage("  quality: worst scaled Jacobian " + fmt(fe.worst_scaled_jacobian) + " (" + fe.worst_element + ")");
  }

  // 4. Modes.
  ReductionLog rlog;
  rlog.message = [&](const std::string& s) { stage("  " + s); };
  rlog.progress = progress;
  ReductionResult red = distributed ? distributed->reduce(fe, rlog)
                        : part.stiffening || !part.preload.empty()
                            ? reduce(model, fe, part.reduction, rlog, from_files ? nullptr : &early)
                            : reduce_consuming_matrices(model, fe, part.reduction, rlog, from_files ? nullptr : &early);
  {
    std::string f;
    for (Index i = 0; i < std::min<Index>(red.lambda.size(), 6); ++i)
      f += (i ? ", " : "") + fmt(std::sqrt(std::max(0.0, red.lambda(i))) / (2 * M_PI), 5);
    stage("modes: " + std::to_string(red.lambda.size()) + " (" + red.reference + "), first [Hz]: " + f +
          (red.lambda.size() > 6 ? ", ..." : "") + "; max residual " + fmt(red.max_residual, 2) + " [" + fmt(sw.lap()) + " s]");
  }
  if (distributed)
    for (const std::string& line : distributed->rank_lines()) stage("  " + line);

  // 5. Invariants.
  formats::Sid sid;
  sid.units_length = part.units.length;
  sid.units_mass = part.units.mass;
  sid.units_time = part.units.time;
  sid.resize(red.lambda.size());
  sid.nodes = node_data(model, red.Phi);
  const double t_unit = part.units.time == "ms" ? 1e-3 : 1.0;
  for (Index k = 0; k < red.lambda.size(); ++k)
    sid.refmod.frequency_hz(k) = std::sqrt(std::max(0.0, red.lambda(k))) / (2 * M_PI) / t_unit;
  sid.refmod.mode_type = red.types;
  sid.refmod.reference = red.reference;
  if (distributed) distributed->integrals(fe, red.Phi, sid);
  else compute_integrals(model, fe, red.Phi, sid);
  members_from_integrals(sid);
  sid.Ke = red.Ke;
  sid.De = damping_matrix(part.damping, sid.Me, sid.Ke);
  if (part.stiffening || !part.preload.empty()) {
    StiffeningResult st = compute_stiffening(model, fe, red.Phi, part.stiffening, [&](const std::string& s) { stage("  " + s); },
                                             progress);
    if (part.stiffening) sid.stiffening = std::move(st.stiffening);
    if (part.stiffening) sid.KeM1 = std::move(st.KeM1);
    if (!part.preload.empty()) sid.ksigma = st.ksigma;
    stage("stiffening: " + std::to_string(st.load_cases) + " unit load cases" +
          (part.preload.empty() ? std::string() : ", prestress from the preload") + " [" + fmt(sw.lap()) + " s]");
  }
  for (std::size_t i = 0; i < model.interfaces.size(); ++i)
    sid.interfaces.push_back({model.interfaces[i].name, static_cast<formats::Index>(i), model.interfaces[i].coupling,
                              model.interfaces[i].group});
  stage("invariants: m = " + fmt(sid.refmod.mass, 6) + ", centre of mass (" + fmt(sid.mdCM.M0.x() / sid.refmod.mass) +
        ", " + fmt(sid.mdCM.M0.y() / sid.refmod.mass) + ", " + fmt(sid.mdCM.M0.z() / sid.refmod.mass) + ") [" +
        fmt(sw.lap()) + " s]");

  if (part.stress) {
    sid.stress = recover_modal_stress(model, red.Phi, stress_at);
    stage("stress: " + std::to_string(stress_at.size()) + " nodes (" + sid.stress->selection + ") [" + fmt(sw.lap()) + " s]");
  }

  // 6. Visual data.
  if (part.visual || !options.vtk.empty()) {
    sid.visual = surface_with_modes(model, red.Phi);
    if (!options.vtk.empty()) write_vtk(options.vtk, model, red.Phi, sid.refmod.frequency_hz);
    stage("visual: " + std::to_string(sid.visual.vertices.rows()) + " vertices, " +
          std::to_string(sid.visual.triangles.rows()) + " triangles [" + fmt(sw.lap()) + " s]");
  }
  if (!part.visual) sid.visual = {};

  // Provenance.
  auto& p = sid.provenance;
  p.generator = kGenerator;
  p.part_sha256 = formats::sha256_file(part.file);
  p.mesh_sha256 = mesh_hash(mesh);
  p.reduction_method = red.reference.substr(0, red.reference.find(':'));
  p.reduction_parameters = red.parameters_json;
  p.damping_model = damping_text(part.damping);
  p.element_counts = mrep.element_counts;
  const std::string mm = from_files ? file_mass_type : mass_model_text(model);
  for (const char* g : {"/sid/mdCM", "/sid/J", "/sid/Ct", "/sid/Cr", "/sid/Me", "/sid/Gr", "/sid/Ge", "/sid/Oe", "/integrals"})
    p.mass_model[g] = mm;
  p.mass_model["/integrals/rotary"] = "point rotary inertia carried by no material point (shell drilling)";
  p.extra["geometry"] = part.geometry.filename().string();
  if (from_files) {
    using F = MatrixInputSpec::Format;
    const F f = part.matrices.format;
    const std::string format = f == F::Calculix ? "calculix" : f == F::Abaqus ? "abaqus"
                               : f == F::Dmig   ? "dmig " + part.matrices.K_name + ", " + part.matrices.M_name
                                                : "matrix_market";
    p.extra["matrices"] = format + ": K " + part.matrices.K.filename().string() + " (sha256 " + formats::sha256_file(part.matrices.K) +
                          "), M " + part.matrices.M.filename().string() + " (sha256 " + formats::sha256_file(part.matrices.M) + ")";
    p.element_counts.clear();
  }
  p.extra["eigen_backend"] = red.backend;
  p.extra["factorization"] = to_string(red.factor.backend);
  p.extra["max_relative_residual"] = fmt(red.max_residual, 3);
  p.extra["factor_nnz_L"] = fmt(red.factor.nnz_L, 6);
  for (const auto& o : model.outputs) p.extra["output_node." + o.name] = "mesh node " + std::to_string(mesh.node_tag(o.node)) +
                                                                          " at distance " + fmt(o.distance);
  return sid;
}

}  // namespace ffr::preproc
