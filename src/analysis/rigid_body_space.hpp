// The rigid-body space of a pencil Â + s·Ê with a singular Â: its invariant subspaces for the
// pole s = 0, and the spectral projector that removes them from a shift-invert operator.
//
// A rigid-body motion u₀ (a free or sliding end, a pin) has Â·u₀ = 0. Where nothing damps it to
// ground (Wᵀ·Ê·u₀ = 0 for the left null vectors W), s = 0 is defective: the motion's velocity
// continues a Jordan chain, Â·u₁ = −Ê·u₀. The right basis V holds the null vectors and the
// chains' second vectors, the left basis W likewise for Âᵀ, Êᵀ. The null spaces come from
// rank-revealing sparse QR factorisations of Â and Âᵀ (SuiteSparseQR; its rank tolerance
// 20·(m + n)·ε·max‖column‖, on an equilibrated Â); a chain's next vector from the basic
// least-squares solution of the consistent system. Chains longer than two (a displacement and
// a velocity) are not handled: rigid_body_space() reports them as a failure.
//
// With the coupling K = Wᵀ·Ê·V (invertible for chains of length ≤ 2), Π = V·K⁻¹·Wᵀ·Ê projects
// onto the space along every other pole's vectors, and (I − Π) commutes with the shift-invert
// operator (Â + σÊ)⁻¹·Ê. `projector_left` is L = (K⁻¹·Wᵀ·Ê)ᵀ, so that Π = V·Lᵀ; for the
// transposed pencil the roles of V and W swap.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>

namespace emnet {

struct RigidBodySpace {
  Eigen::MatrixXd null_vectors;  // Â·z = 0: the rigid-body motions (right)
  Eigen::MatrixXd right, left;   // V, W: the invariant subspaces, chains included
  Eigen::MatrixXd projector_left, transposed_projector_left;  // L for Π = V·Lᵀ; and for Πᵀ
  std::string failure;  // non-empty when the space could not be formed; then nothing else is
};

RigidBodySpace rigid_body_space(const Eigen::SparseMatrix<double>& a,
                                const Eigen::SparseMatrix<double>& e);

}  // namespace emnet
