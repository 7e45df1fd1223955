#pragma once
// Global stiffness and mass of an FeModel over its full DOFs (see fe_model.hpp), assembled
// into a precomputed CSC pattern (no triplet list: at 1M DOF a triplet list would need
// several GB). Element matrices are computed by worker threads in batches; the scatter is
// serialized per batch.

#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/model/sparse.hpp"

#include <functional>
#include <string>
#include <vector>

namespace ffr::preproc {

/// Every element of the model: property elements then attached masses, as (kind, index).
struct ElementRef {
  int block = -1;   ///< index into FeModel::blocks, or -1 for an attached mass
  Index index = 0;  ///< element index in the block, or the mass index
};

/// The real element kernels for each ElementKind (and attached masses).
ElementMatrices element_matrices(const FeModel& model, const ElementRef& ref);
/// M, M_rotary and the mass samples as element_matrices() gives them; K may be zero (shells
/// skip their stiffness kernels). For the inertia integrals.
ElementMatrices element_mass(const FeModel& model, const ElementRef& ref);
/// Full DOFs of an element in the order of its matrices.
std::vector<Index> element_dofs(const FeModel& model, const ElementRef& ref);
std::vector<ElementRef> all_elements(const FeModel& model);

struct AssemblyOptions {
  int threads = 0;                                   ///< 0: hardware concurrency
  /// Threads that write K's and M's structure before the elements (0: as `threads`). That
  /// pass is the first touch of their memory, and where the kernel backs fresh pages slowly
  /// (a page fault costing microseconds) that touch bounds the pass, so it pays to run it on
  /// every core even where the element loop leaves one to another task (the pipeline's early
  /// analysis).
  int fill_threads = 0;
  /// Asked before each colour class: true once one more core than `threads` is free for the
  /// element loop (the pipeline's early analysis has finished), which then takes it. Empty:
  /// `threads` throughout. The matrices and sums do not depend on how many threads took part.
  std::function<bool()> spare_core;
  /// Elements per block of neighbours: the unit of work of a thread (the elements of a block
  /// share entries of K and M; blocks of one colour class share none). The 100k-DOF plate's
  /// 20662 elements make 323 blocks of 64; blocks of 32 to 256 assembled it equally fast at
  /// one thread (0.74-0.93 s, against 1.2 s with the elements coloured one by one).
  std::size_t block_elements = 64;
  std::function<void(double fraction)> progress;     ///< called from the calling thread
  /// Only K (no mass, no Ms, no quality): for geometric-stiffness assemblies.
  bool stiffness_only = false;
  /// M left out (0 x 0) where the part has solid elements alone and no attached masses, where
  /// it is Ms (x) I3 entry for entry and the caller forms what it needs of it from Ms
  /// (reduce/node_mass.hpp). Why: the pipeline's clamped and free reductions need M only on
  /// the eigen-solve's structure, and scattering it and extracting it from the whole assembled
  /// M took 0.1-0.15 s of the 100k-DOF plate's 4.8-5.5 s at one thread (tools/bench/reduce).
  bool node_mass_only = false;
  /// Only these elements (null: all_elements()): K, M, Ms and the sums are then this subset's
  /// contributions, as a rank of a distributed reduction assembles its share.
  const std::vector<ElementRef>* elements = nullptr;
  /// Substitute kernel (stiffening, tests); empty = element_matrices().
  std::function<ElementMatrices(const FeModel&, const ElementRef&)> kernel;
};

struct Assembled {
  SparseMatrix K, M;                 ///< num_dofs x num_dofs, full symmetric storage (M 0 x 0: node_mass_only)
  double mass = 0;                   ///< exact: solids through Ms, the rest through mass samples
  Eigen::Vector3d rdm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rrdm = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotary_I = Eigen::Matrix3d::Zero();  ///< sum of M_rotary under rigid rotation
  /// Scalar mass matrix of the solid elements on mesh nodes (num_nodes x num_nodes), its upper
  /// triangle (multiply through selfadjointView<Eigen::Upper>()): a solid's consistent mass is
  /// Ms_e (x) I3, so its inertia integrals follow from Ms exactly. Upper-only: it is kept
  /// through the eigen-solve, whose memory peaks it adds to (7 MB less on the 100k plate).
  SparseMatrix Ms;
  bool has_structural = false;       ///< any shell, beam or attached mass (needs the sample pass)
  Index elements = 0;
  double seconds = 0;
  /// Worst solid element by the scaled Jacobian (1 ideal, <= 0 inverted), for the mesh report.
  double worst_scaled_jacobian = 1.0;
  std::string worst_element;

  Assembled() = default;
  Assembled(const Assembled&) = default;
  Assembled& operator=(const Assembled&) = default;
  /// Moves that hand over the storage of K, M and Ms. Why not the implicit ones: Eigen 3.4's
  /// SparseMatrix declares its copy operations and no move ones, so a defaulted move of this
  /// struct copies the three matrices: the pipeline's `fe = assemble(...)` copied 108 MB on the
  /// 100k-DOF plate of tools/bench/reduce, with both copies resident meanwhile.
  Assembled(Assembled&& other) { *this = std::move(other); }
  Assembled& operator=(Assembled&& other) {
    SparseMatrix k, m, ms;  // other's matrices, taken out before the memberwise copy
    k.swap(other.K);
    m.swap(other.M);
    ms.swap(other.Ms);
    *this = static_cast<const Assembled&>(other);  // the rest: sums, counts and a name
    K.swap(k);
    M.swap(m);
    Ms.swap(ms);
    return *this;
  }
};

/// Assembles K and M. Element errors (inverted, degenerate, bad properties) become
/// formats::FormatError naming the mesh file and the element tag and group.
Assembled assemble(const FeModel& model, const AssemblyOptions& options = {});

/// The structure assemble() gives K and M (both have the same), every stored value 1, without
/// integrating a single element: all a symbolic factorization needs (EarlyAnalysis).
SparseMatrix assembly_pattern(const FeModel& model, unsigned threads = 1);

}  // namespace ffr::preproc
