#include "ffr/formats/h5.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/threads.hpp"
#include "pattern.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

namespace ffr::preproc {
namespace {

constexpr std::size_t kBatch = 512;

struct Computed {
  ElementRef ref;
  std::vector<Index> dofs;
  detail::Placement place;
  ElementMatrices em;
  double scaled_jacobian = 1.0;  ///< solids only
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
  const auto refs = all_elements(model);
  const auto kernel = opt.kernel ? opt.kernel : [](const FeModel& m, const ElementRef& r) { return element_matrices(m, r); };

  const detail::Pattern pattern = detail::build_pattern(model, refs);
  Assembled out;
  out.elements = static_cast<Index>(refs.size());
  out.K = pattern.make_matrix();
  if (!opt.stiffness_only) {
    out.M = pattern.make_matrix();
    out.Ms = pattern.make_node_matrix();
  }
  for (const auto& pb : model.blocks) out.has_structural = out.has_structural || pb.kind != ElementKind::Solid;
  out.has_structural = out.has_structural || !model.masses.empty();

  std::mutex scatter_mutex;
  std::atomic<std::size_t> next_batch{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::atomic<std::size_t> done{0};

  auto scatter = [&](std::vector<Computed>& batch) {
    std::lock_guard<std::mutex> lock(scatter_mutex);
    for (auto& c : batch) {
      pattern.add(out.K, c.place, c.em.K);
      if (opt.stiffness_only) continue;
      pattern.add(out.M, c.place, c.em.M);
      if (c.ref.block >= 0 && model.blocks[static_cast<std::size_t>(c.ref.block)].kind == ElementKind::Solid)
        pattern.add_node_scalar(out.Ms, c.place, c.em.M);
      if (c.scaled_jacobian < out.worst_scaled_jacobian) {
        out.worst_scaled_jacobian = c.scaled_jacobian;
        out.worst_element = describe(model, c.ref);
      }
      for (const auto& s : c.em.samples) {
        out.mass += s.w;
        out.rdm += s.w * s.c;
        out.rrdm += s.w * s.c * s.c.transpose();
      }
      if (c.em.M_rotary.size() > 0) {
        Eigen::Matrix<double, Eigen::Dynamic, 3> R(static_cast<Index>(c.dofs.size()), 3);
        for (std::size_t i = 0; i < c.dofs.size(); ++i) R.row(static_cast<Index>(i)) = model.rigid_motion(c.dofs[i]).tail<3>();
        out.rotary_I += R.transpose() * c.em.M_rotary * R;
      }
    }
    done += batch.size();
  };

  auto worker = [&] {
    std::vector<Computed> batch;
    while (!failed) {
      const std::size_t b = next_batch++;
      const std::size_t begin = b * kBatch;
      if (begin >= refs.size()) break;
      const std::size_t end = std::min(refs.size(), begin + kBatch);
      batch.clear();
      try {
        for (std::size_t i = begin; i < end; ++i) {
          Computed c{refs[i], element_dofs(model, refs[i]), {}, {}, 1.0};
          c.place = pattern.place(c.dofs, model);
          try {
            c.em = kernel(model, refs[i]);
            if (!opt.stiffness_only && refs[i].block >= 0 && model.blocks[static_cast<std::size_t>(refs[i].block)].kind == ElementKind::Solid) {
              const auto& blk = model.mesh->blocks[model.blocks[static_cast<std::size_t>(refs[i].block)].block];
              c.scaled_jacobian = solid_quality(blk.type, model.mesh->element_coords(blk, refs[i].index)).min_scaled_jacobian;
            }
          } catch (const ElementError& e) {
            throw formats::FormatError(model.part ? model.part->geometry.string() : "mesh", describe(model, refs[i]),
                                       e.what());
          }
          if (static_cast<std::size_t>(c.em.K.rows()) != c.dofs.size() || (!opt.stiffness_only && c.em.M.rows() != c.em.K.rows()))
            throw std::logic_error("kernel returned matrices of the wrong size for " + describe(model, refs[i]));
          batch.push_back(std::move(c));
        }
        scatter(batch);
      } catch (...) {
        std::lock_guard<std::mutex> lock(scatter_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };

  const unsigned nthreads = opt.threads > 0 ? static_cast<unsigned>(opt.threads) : max_threads();
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < nthreads; ++t) pool.emplace_back(worker);
  if (opt.progress) {
    // The calling thread reports progress while helping with the work.
    std::thread reporter_helper(worker);
    while (done < refs.size() && !failed) {
      opt.progress(refs.empty() ? 1.0 : static_cast<double>(done) / static_cast<double>(refs.size()));
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    reporter_helper.join();
  } else {
    worker();
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  // Rigid-body integrals of the solids from Ms, exactly (c is interpolated isoparametrically).
  if (out.Ms.nonZeros() > 0) {
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(out.Ms.rows());
    const Eigen::MatrixX3d X = model.mesh->x;
    const Eigen::MatrixX3d MX = out.Ms * X;
    out.mass += ones.dot(out.Ms * ones);
    out.rdm += MX.transpose() * ones;
    out.rrdm += X.transpose() * MX;
  }
  if (opt.progress) opt.progress(1.0);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace ffr::preproc
