#include "kerf/fem/assemble_stiffness.hpp"

#include "kerf/fem/positive_jacobian.hpp"
#include "kerf/fem/tet_stiffness.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"

namespace kerf {

void assemble_linear_stiffness(const TetMesh& mesh, const LinearMaterial& material, SparseAssembler& assembler,
                               Eigen::VectorXd& rhs_free) {
  // The element type is decided once, outside the loop, so that each loop body works on
  // fixed-size matrices (12x12 or 30x30) that live on the stack. The element functions
  // refuse a tet with det J <= 0 but cannot say which one it is; the loop checks the corner
  // volume first, so that the message names the element.
  if (mesh.order() == 1) {
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      require_positive_jacobian(6.0 * signed_tet_volume(mesh, t), "assemble_linear_stiffness", t);
      assembler.add_element<12>(t, tet4_stiffness(tet_corners(mesh, t), material), rhs_free);
    }
  } else {
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      require_positive_jacobian(6.0 * signed_tet_volume(mesh, t), "assemble_linear_stiffness", t);
      Eigen::Matrix<double, 10, 3> X;
      for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
      assembler.add_element<30>(t, tet10_stiffness(X, material), rhs_free);
    }
  }
}

} // namespace kerf
