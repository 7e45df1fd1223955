#include "ffr/formats/h5.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/threads.hpp"
#include "../run_parts.hpp"
#include "coloring.hpp"
#include "pattern.hpp"
#include "../stopwatch.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>

namespace ffr::preproc {
namespace {

// What each worker sums besides the matrices, merged after the last class.
struct Sums {
  double mass = 0;
  Eigen::Vector3d rdm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rrdm = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotary_I = Eigen::Matrix3d::Zero();
  double worst_scaled_jacobian = 1.0;
  std::size_t worst = static_cast<std::size_t>(-1);  ///< element index in refs

  /// Keeps element i if it is worse (the lower index on a tie, whatever thread met it first).
  void consider(double scaled_jacobian, std::size_t i) {
    if (scaled_jacobian < worst_scaled_jacobian || (scaled_jacobian == worst_scaled_jacobian && i < worst)) {
      worst_scaled_jacobian = scaled_jacobian;
      worst = i;
    }
  }
  void merge(const Sums& o) {
    mass += o.mass;
    rdm += o.rdm;
    rrdm += o.rrdm;
    rotary_I += o.rotary_I;
    consider(o.worst_scaled_jacobian, o.worst);
  }
};

std::string describe(const FeModel& model, const ElementRef& ref) {
  if (ref.block < 0) return "point mass '" + model.masses[static_cast<std::size_t>(ref.index)].name + "'";
  const auto& pb = model.blocks[static_cast<std::size_t>(ref.block)];
  const auto& blk = model.mesh->blocks[pb.block];
  return "element " + std::to_string(model.mesh->element_tag(blk, ref.index)) + " (" + name(blk.type) + ", group " +
         blk.group + ")";
}

}  // namespace

Assembled assemble(const FeModel& model, const AssemblyOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto refs = opt.elements ? *opt.elements : all_elements(model);
  const auto kernel = opt.kernel ? opt.kernel : [](const FeModel& m, const ElementRef& r) { return element_matrices(m, r); };

  const detail::Pattern pattern = detail::build_pattern(model, refs);
  const unsigned nthreads = std::max(1u, opt.threads > 0 ? static_cast<unsigned>(opt.threads) : max_threads());
  Assembled out;
  out.elements = static_cast<Index>(refs.size());
  const unsigned fill_threads = opt.fill_threads > 0 ? static_cast<unsigned>(opt.fill_threads) : nthreads;
  for (const auto& pb : model.blocks) out.has_structural = out.has_structural || pb.kind != ElementKind::Solid;
  out.has_structural = out.has_structural || !model.masses.empty();
  const bool with_M = !opt.stiffness_only && !(opt.node_mass_only && !out.has_structural);
  pattern.make_matrix(out.K, fill_threads);
  if (with_M) pattern.make_matrix(out.M, fill_threads);
  if (!opt.stiffness_only) pattern.make_node_matrix(out.Ms);

  // Each element's DOFs and the entities they belong to; colour classes of elements with no
  // entity in common, whose scatters touch disjoint entries (coloring.hpp).
  std::vector<std::vector<Index>> dofs(refs.size()), ents(refs.size());
  for (std::size_t i = 0; i < refs.size(); ++i) {
    dofs[i] = element_dofs(model, refs[i]);
    for (const Index d : dofs[i]) {
      const Index e = pattern.entity_of_dof(model, d);
      if (std::find(ents[i].begin(), ents[i].end(), e) == ents[i].end()) ents[i].push_back(e);
    }
  }
  const auto blocks = detail::color_blocks(ents, static_cast<Index>(pattern.ent_dof0.size()), opt.block_elements);
  ents = {};

  // Sums per block, merged in block order at the end: the same totals whatever thread did which
  // block, and however many took part (spare_core).
  std::vector<Sums> sums(blocks.block_ptr.size() - 1);
  std::atomic<bool> failed{false};
  std::size_t done = 0;

  // Computes element i and adds it to the matrices (no other thread writes its entries now).
  auto element = [&](std::size_t i, Sums& sum) {
    const ElementRef& ref = refs[i];
    const detail::Placement place = pattern.place(dofs[i], model);
    ElementMatrices em;
    double scaled_jacobian = 1.0;
    const bool solid = ref.block >= 0 && model.blocks[static_cast<std::size_t>(ref.block)].kind == ElementKind::Solid;
    try {
      em = kernel(model, ref);
      if (!opt.stiffness_only && solid) {
        const auto& blk = model.mesh->blocks[model.blocks[static_cast<std::size_t>(ref.block)].block];
        scaled_jacobian = solid_min_scaled_jacobian(blk.type, model.mesh->element_coords(blk, ref.index));
      }
    } catch (const ElementError& e) {
      throw formats::FormatError(model.part ? model.part->geometry.string() : "mesh", describe(model, ref), e.what());
    }
    if (static_cast<std::size_t>(em.K.rows()) != dofs[i].size() || (!opt.stiffness_only && em.M.rows() != em.K.rows()))
      throw std::logic_error("kernel returned matrices of the wrong size for " + describe(model, ref));
    pattern.add(out.K, place, em.K);
    if (opt.stiffness_only) return;
    if (with_M) pattern.add(out.M, place, em.M);
    if (solid) pattern.add_node_scalar(out.Ms, place, em.M);
    if (solid && scaled_jacobian < 1.0) sum.consider(scaled_jacobian, i);  // solids below the ideal 1
    for (const auto& smp : em.samples) {
      sum.mass += smp.w;
      sum.rdm += smp.w * smp.c;
      sum.rrdm += smp.w * smp.c * smp.c.transpose();
    }
    if (em.M_rotary.size() > 0) {
      Eigen::Matrix<double, Eigen::Dynamic, 3> R(static_cast<Index>(dofs[i].size()), 3);
      for (std::size_t k = 0; k < dofs[i].size(); ++k) R.row(static_cast<Index>(k)) = model.rigid_motion(dofs[i][k]).tail<3>();
      sum.rotary_I += R.transpose() * em.M_rotary * R;
    }
  };

  auto last_report = std::chrono::steady_clock::now();
  for (const auto& cls : blocks.classes) {
    std::atomic<std::size_t> next{0};
    const bool spare = opt.spare_core && nthreads < max_threads() && opt.spare_core();
    const unsigned nt = static_cast<unsigned>(std::min<std::size_t>(nthreads + (spare ? 1u : 0u), cls.size()));
    // Workers take whole blocks of the class (the elements of a block share entries); one that
    // throws stops the others at their next block, and run_parts rethrows its error once all
    // have finished.
    detail::run_parts(nt, [](unsigned p) { return p; }, [&](unsigned, unsigned, unsigned) {
      try {
        for (std::size_t k = 0; !failed && (k = next.fetch_add(1)) < cls.size();)
          for (std::size_t e = blocks.block_ptr[cls[k]]; e < blocks.block_ptr[cls[k] + 1]; ++e)
            element(blocks.order[e], sums[cls[k]]);
      } catch (...) {
        failed = true;
        throw;
      }
    });
    for (const std::size_t b : cls) done += blocks.block_ptr[b + 1] - blocks.block_ptr[b];
    if (opt.progress && std::chrono::steady_clock::now() - last_report > std::chrono::milliseconds(200)) {
      opt.progress(static_cast<double>(done) / static_cast<double>(refs.size()));
      last_report = std::chrono::steady_clock::now();
    }
  }
  Sums total;
  for (const Sums& sum : sums) total.merge(sum);
  out.mass += total.mass;
  out.rdm += total.rdm;
  out.rrdm += total.rrdm;
  out.rotary_I += total.rotary_I;
  out.worst_scaled_jacobian = total.worst_scaled_jacobian;
  if (total.worst < refs.size()) out.worst_element = describe(model, refs[total.worst]);
  // Rigid-body integrals of the solids from Ms, exactly (c is interpolated isoparametrically).
  if (out.Ms.nonZeros() > 0) {
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(out.Ms.rows());
    const Eigen::MatrixX3d X = model.mesh->x;
    const auto Ms = out.Ms.selfadjointView<Eigen::Upper>();
    const Eigen::MatrixX3d MX = Ms * X;
    out.mass += ones.dot(Ms * ones);
    out.rdm += MX.transpose() * ones;
    out.rrdm += X.transpose() * MX;
  }
  if (opt.progress) opt.progress(1.0);
  out.seconds = seconds_since(t0);
  return out;
}

SparseMatrix assembly_pattern(const FeModel& model, unsigned threads) {
  SparseMatrix A;
  detail::build_pattern(model, all_elements(model)).make_matrix(A, threads, 1.0);
  return A;
}

}  // namespace ffr::preproc
