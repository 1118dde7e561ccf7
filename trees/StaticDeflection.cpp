#include "trees/StaticDeflection.hpp"

#include <Eigen/SparseCholesky>

#include <stdexcept>

namespace fw::trees {

Eigen::MatrixX3d static_deflection(const Skeleton& skeleton, const BeamModel& model,
                                   const WindBasisSettings& drag, const Eigen::Vector3d& wind) {
  // The same wind in every band: the load is the S = 1 operator's, split into bands that add up to it.
  const Eigen::MatrixXd G = WindBasis::load_operator(skeleton, drag);
  const Eigen::MatrixX3d bands =
      Eigen::MatrixX3d::Constant(G.cols() / 3, 3, 0.0).rowwise() + wind.transpose();
  const Eigen::VectorXd loads = G * WindBasis::squared_wind(bands);  // 6 n, node-major, the root included

  constexpr int kDofsPerNode = 6;
  Eigen::VectorXd free_loads = Eigen::VectorXd::Zero(model.dof_count());
  for (int node = 0; node < model.node_count(); ++node)
    for (int local = 0; local < kDofsPerNode; ++local)
      if (const int dof = model.free_dof_of(node, local); dof >= 0)
        free_loads(dof) = loads(kDofsPerNode * node + local);

  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(model.stiffness());
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("static_deflection: the stiffness could not be factorised");
  const Eigen::VectorXd u = solver.solve(free_loads);

  Eigen::MatrixX3d displacement = Eigen::MatrixX3d::Zero(model.node_count(), 3);
  for (int node = 0; node < model.node_count(); ++node)
    for (int axis = 0; axis < 3; ++axis)
      if (const int dof = model.free_dof_of(node, axis); dof >= 0) displacement(node, axis) = u(dof);
  return displacement;
}

}  // namespace fw::trees
