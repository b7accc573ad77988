#include "kerf/fem/assemble_stiffness.hpp"

#include "kerf/fem/tet_stiffness.hpp"

namespace kerf {

void assemble_linear_stiffness(const TetMesh& mesh, const LinearMaterial& material, SparseAssembler& assembler,
                               Eigen::VectorXd& rhs_free) {
  // The element type is decided once, outside the loop, so that each loop body works on
  // fixed-size matrices (12x12 or 30x30) that live on the stack.
  if (mesh.order() == 1) {
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      assembler.add_element<12>(t, tet4_stiffness(tet_corners(mesh, t), material), rhs_free);
    }
  } else {
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      Eigen::Matrix<double, 10, 3> X;
      for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      assembler.add_element<30>(t, tet10_stiffness(X, material), rhs_free);
    }
  }
}

} // namespace kerf
