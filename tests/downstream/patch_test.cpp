// The patch test, from outside Kerf. Give the boundary nodes of a box the displacement of a
// uniform stretch, u = e (x, -nu y, -nu z); with no load, linear tets reproduce a linear field
// exactly, so every interior node must move by the same formula (to round-off). It prints the
// largest error and fails if it is not round-off. It solves with CHOLMOD and writes a .vtu, so
// that it links the parts of kerf that call CHOLMOD and VTK.
#include <kerf/fem/solve_linear_static.hpp>
#include <kerf/io/write_vtu.hpp>
#include <kerf/mesh/box_mesh.hpp>

#include <algorithm>
#include <cstdio>

int main() {
  const kerf::TetMesh mesh = kerf::make_box_mesh({0, 0, 0}, {2, 1, 1}, {4, 3, 3});
  const kerf::LinearMaterial material; // E = 300 kPa, nu = 0.35
  const double e = 0.01;
  const auto exact = [&](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(e * x.x(), -material.poisson * e * x.y(), -material.poisson * e * x.z());
  };
  std::vector<kerf::DirichletNodes> boundary;
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector3d x = mesh.nodes.row(v);
    if ((x.array() < 1e-9).any() || (x - Eigen::Vector3d(2, 1, 1)).array().abs().minCoeff() < 1e-9)
      boundary.push_back({{v}, exact(x)});
  }
  const kerf::DofMap dofs = kerf::make_dof_map(mesh.num_nodes(), boundary);
  const Eigen::VectorXd u = kerf::solve_linear_static(mesh, material, dofs, Eigen::VectorXd::Zero(3 * mesh.num_nodes()),
                                                      {"cholmod"});
  double error = 0;
  for (int v = 0; v < mesh.num_nodes(); ++v)
    error = std::max(error, (u.segment<3>(3 * v) - exact(mesh.nodes.row(v).transpose())).norm());
  kerf::write_vtu("patch_test.vtu", mesh, {{"displacement", u.reshaped(3, mesh.num_nodes()).transpose()}}, {});
  std::printf("patch test: %d interior nodes of %d, largest error %.3g m\n", dofs.num_free / 3,
              static_cast<int>(mesh.num_nodes()), error);
  return dofs.num_free == 3 * 3 * 2 * 2 && error < 1e-12 ? 0 : 1;
}
