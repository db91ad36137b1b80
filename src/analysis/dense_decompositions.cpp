// Eigen's dense decompositions, instantiated once: see dense_decompositions.hpp.
#include "dense_decompositions.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace emnet {

namespace {

// The singular values and the vectors `options` asked for of an Eigen SVD.
template <typename Result, typename Decomposition>
Result singular_value_decomposition(const Decomposition& svd, int options) {
  Result result;
  result.singular_values = svd.singularValues();
  if (options & (Eigen::ComputeThinU | Eigen::ComputeFullU)) result.u = svd.matrixU();
  if (options & (Eigen::ComputeThinV | Eigen::ComputeFullV)) result.v = svd.matrixV();
  return result;
}

}  // namespace

RealSingularValueDecomposition divide_and_conquer_svd(const Eigen::MatrixXd& m, int options) {
  return singular_value_decomposition<RealSingularValueDecomposition>(
      Eigen::BDCSVD<Eigen::MatrixXd>(m, static_cast<unsigned int>(options)), options);
}

RealSingularValueDecomposition jacobi_svd(const Eigen::MatrixXd& m, int options) {
  return singular_value_decomposition<RealSingularValueDecomposition>(
      Eigen::JacobiSVD<Eigen::MatrixXd>(m, static_cast<unsigned int>(options)), options);
}

ComplexSingularValueDecomposition complex_jacobi_svd(const Eigen::MatrixXcd& m, int options) {
  return singular_value_decomposition<ComplexSingularValueDecomposition>(
      Eigen::JacobiSVD<Eigen::MatrixXcd>(m, static_cast<unsigned int>(options)), options);
}

RealEigenDecomposition real_eigen_decomposition(const Eigen::MatrixXd& m) {
  RealEigenDecomposition result;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(m, true);
  result.converged = solver.info() == Eigen::Success;
  if (!result.converged) return result;
  result.values = solver.eigenvalues();
  result.vectors = solver.eigenvectors();
  return result;
}

}  // namespace emnet
