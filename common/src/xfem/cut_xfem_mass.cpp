#include "kerf/xfem/cut_xfem_mass.hpp"

#include "kerf/fem/tet_mass.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace kerf {

void require_no_crack_tip_functions(const CutXfemModel& model, const char* who) {
  if (model.num_branch_nodes() > 0)
    throw std::invalid_argument(std::string(who) + ": eqs. 81-82 give the crack-tip functions no mass (use a per-piece lumping or the consistent mass)");
}

Eigen::MatrixXd cut_xfem_slot_mass(const CutXfemModel& model, Eigen::Index t, double density) {
  Eigen::MatrixXd m;
  model.for_each_slot_value(t, [&](int, double weight, const Eigen::VectorXd& g) {
    if (m.size() == 0) m = Eigen::MatrixXd::Zero(g.size(), g.size());
    m.noalias() += density * weight * g * g.transpose();
  });
  return m;
}

std::vector<Eigen::MatrixXd> cut_xfem_piece_masses(const CutXfemModel& model, Eigen::Index t, double density,
                                                   const PieceRuleFunction& rule) {
  const TetMesh& mesh = model.mesh();
  const MeshPieces& pieces = model.pieces();
  const int n = mesh.nodes_per_tet();
  if (model.has_branch_functions(t)) {
    // The phantom block of each piece, at the points of the tet's own rule: node a's value N_a
    // is slot a's (the first n of g).
    std::vector<Eigen::MatrixXd> masses;
    model.for_each_slot_value(t, [&](int p, double weight, const Eigen::VectorXd& g) {
      if (static_cast<std::size_t>(p) == masses.size()) masses.push_back(Eigen::MatrixXd::Zero(n, n));
      masses[static_cast<std::size_t>(p)].noalias() += density * weight * g.head(n) * g.head(n).transpose();
    });
    return masses;
  }
  if (!model.integrated_by_pieces(t) || pieces.num_pieces(t) == 1) {
    // The whole tet, possibly with enrichments that are 1 all over it.
    if (n == 4) return {tet4_mass(tet_corners(mesh, t), density)};
    Eigen::Matrix<double, 10, 3> X;
    for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
    return {tet10_mass(X, density)};
  }
  const TetPieces& tp = pieces.tets[static_cast<std::size_t>(pieces.entry[static_cast<std::size_t>(t)])];
  const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
  std::vector<Eigen::MatrixXd> masses;
  for (int p = 0; p < pieces.num_pieces(t); ++p) {
    // N_a N_b has degree 2 on a Tet4 piece and 4 on a Tet10 piece.
    const PieceQuadratureRule r = rule(X, tp, p, 2 * mesh.order());
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t q = 0; q < r.points.size(); ++q) {
      const Eigen::VectorXd N = model.shape_values(t, r.points[q]);
      m += density * r.weights[q] * N * N.transpose();
    }
    masses.push_back(m);
  }
  return masses;
}

namespace {

// assemble_cut_xfem_mass with tet t's piece masses at `density` from piece_masses(t).
template <typename PieceMasses>
Eigen::SparseMatrix<double> assemble_mass(const CutXfemModel& model, double density, const PieceMasses& piece_masses) {
  const TetMesh& mesh = model.mesh();
  const int n = mesh.nodes_per_tet();
  std::vector<Eigen::Triplet<double>> entries;
  // Adds T_p^T (m kron I_3) T_p for the scalar mass m (n x n) of piece p of tet t: node a's
  // value on the piece is u_a, plus a_k where enrichment k is 1 there, so its row of m goes to
  // the DOF node of u_a and to that of a_k.
  const auto add = [&](Eigen::Index t, int p, const Eigen::MatrixXd& m) {
    const auto dof_nodes = [&](int a) {
      std::vector<int> nodes{mesh.tets(t, a)};
      if (const int phantom = model.phantom_node(t, p, a); phantom != nodes.front()) nodes.push_back(phantom);
      return nodes;
    };
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (const int i : dof_nodes(a))
          for (const int j : dof_nodes(b))
            for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + c, 3 * j + c, m(a, b));
  };
  const TetMatrix& slots = model.assembly_slots();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (model.has_branch_functions(t)) {
      // The tet's slots carry the phantom element's unknowns and the branch functions' alike:
      // m_e scattered slot by slot is the sum over its pieces of T_p^T m_p T_p, plus the branch
      // rows and columns.
      const Eigen::MatrixXd m = cut_xfem_slot_mass(model, t, density);
      for (Eigen::Index r = 0; r < m.rows(); ++r)
        for (Eigen::Index s = 0; s < m.cols(); ++s)
          for (int c = 0; c < 3; ++c) entries.emplace_back(3 * slots(t, r) + c, 3 * slots(t, s) + c, m(r, s));
      continue;
    }
    const std::vector<Eigen::MatrixXd> masses = piece_masses(t);
    for (std::size_t p = 0; p < masses.size(); ++p) add(t, static_cast<int>(p), masses[p]);
  }
  const Eigen::Index size = 3 * model.num_dof_nodes();
  Eigen::SparseMatrix<double> M(size, size);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

} // namespace

Eigen::SparseMatrix<double> assemble_cut_xfem_mass(const CutXfemModel& model, double density, const PieceRuleFunction& rule) {
  return assemble_mass(model, density, [&](Eigen::Index t) { return cut_xfem_piece_masses(model, t, density, rule); });
}

Eigen::SparseMatrix<double> assemble_cut_xfem_mass(const CutXfemModel& model, double density, const SplitTetMasses& masses) {
  return assemble_mass(model, density, [&](Eigen::Index t) {
    std::vector<Eigen::MatrixXd> scaled = masses(model, t);
    for (Eigen::MatrixXd& m : scaled) m *= density;
    return scaled;
  });
}

double translation_mass(const Eigen::SparseMatrix<double>& M, Eigen::Index num_mesh_nodes) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(M.rows());
  for (Eigen::Index v = 0; v < num_mesh_nodes; ++v) e[3 * v] = 1.0;
  return e.dot(M * e);
}

} // namespace kerf
