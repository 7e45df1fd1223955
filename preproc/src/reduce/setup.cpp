#include "setup.hpp"

#include "sparse_ops.hpp"

namespace ffr::preproc::detail {

std::vector<InterfaceState> states_for(const FeModel& model, const ReductionSpec& spec) {
  std::vector<InterfaceState> st(model.interfaces.size(), InterfaceState::Free);
  if (spec.method == ReductionSpec::Method::Clamped) {
    st.at(static_cast<std::size_t>(model.find_interface(spec.interface))) = InterfaceState::Held;
  } else if (spec.method == ReductionSpec::Method::CraigBampton) {
    for (const auto& name : spec.interfaces)
      st.at(static_cast<std::size_t>(model.find_interface(name))) =
          name == spec.frame ? InterfaceState::Held : InterfaceState::Boundary;
  }
  return st;
}

SparseMatrix constrained(const DofTransform& t, const SparseMatrix& A, bool full) {
  if (!t.identity) return congruence(t.T, A, !full);
  if (full) return A;
  return A.triangularView<Eigen::Upper>();
}

FactorOptions eigen_factor_options(const ReductionSpec& spec) {
  FactorOptions f;
  f.memory_limit_bytes = spec.memory_limit_bytes;
  f.backend = spec.factorization == "cholmod" ? FactorizationBackend::Cholmod : FactorizationBackend::Supernodal;
  f.dense_kernels = dense_kernel_choice_from_string(spec.dense_kernels).value_or(DenseKernelChoice::Auto);
  // Free: definite by construction (negative shift); tiny pivots only in the deflated space.
  if (spec.method == ReductionSpec::Method::Free) f.min_pivot_ratio = 0;
  return f;
}

std::vector<Index> boundary_dofs(const FeModel& model, const DofTransform& t, const ReductionSpec& spec) {
  std::vector<Index> boundary;
  for (const auto& name : spec.interfaces) {
    if (name == spec.frame) continue;
    const Index d0 = model.interfaces[static_cast<std::size_t>(model.find_interface(name))].dof;
    for (int a = 0; a < 6; ++a) boundary.push_back(t.ind_of_full[static_cast<std::size_t>(d0 + a)]);
  }
  return boundary;
}

}  // namespace ffr::preproc::detail
