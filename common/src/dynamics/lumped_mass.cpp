#include "kerf/dynamics/lumped_mass.hpp"

#include "kerf/fem/tet_mass.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

#include <stdexcept>
#include <vector>

namespace kerf {

namespace {

// The Bernstein row sums rho int_p B_i from the Lagrange ones r_i = rho int_p N_i. On a Tet4 the
// two bases are one. On a Tet10 B_a = N_a + (N_ab + N_ac + N_ad) / 4 and B_ab = N_ab / 2
// (lumped_mass.hpp): each edge node keeps half its row sum and gives a quarter to each end.
template <class Diagonal> Diagonal bernstein_row_sums(const Diagonal& r) {
  if constexpr (Diagonal::SizeAtCompileTime == 4) {
    return r;
  } else {
    if (r.size() == 4) return r;
    Diagonal D = r;
    for (int e = 0; e < 6; ++e) {
      D[4 + e] = r[4 + e] / 2;
      for (const int a : tet_edge_corners[e]) D[a] += r[4 + e] / 4;
    }
    return D;
  }
}

// The diagonal D_p (n entries, kg) that `scheme` gives the piece with unit-density mass m.
template <class Mass>
Eigen::Matrix<double, Mass::RowsAtCompileTime, 1> piece_diagonal(const Eigen::MatrixBase<Mass>& m, double density, LumpingScheme scheme) {
  using Diagonal = Eigen::Matrix<double, Mass::RowsAtCompileTime, 1>;
  const double volume = m.sum();
  const auto n = static_cast<double>(m.rows());
  switch (scheme) {
  case LumpingScheme::bernstein: return bernstein_row_sums<Diagonal>(density * m.rowwise().sum());
  case LumpingScheme::row_sum: return density * m.rowwise().sum();
  case LumpingScheme::hrz: return density * volume / m.diagonal().sum() * m.diagonal();
  case LumpingScheme::virtual_tet: return Diagonal::Constant(m.rows(), density * volume / n);
  case LumpingScheme::schoch_eq_81_82: break;
  }
  throw std::logic_error("piece_diagonal: eqs. 81-82 are not lumped piece by piece");
}

// Tet t's consistent slot mass (cut_xfem_slot_mass), scattered whole through add(i, j, value)
// on DOF nodes: a tet with branch functions is not lumped (lumped_mass.hpp says why).
template <typename Add>
void add_consistent_tet(const CutXfemModel& model, Eigen::Index t, double density, const Add& add) {
  const Eigen::MatrixXd m = cut_xfem_slot_mass(model, t, density);
  const TetMatrix& slots = model.assembly_slots();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index s = 0; s < m.cols(); ++s) add(slots(t, r), slots(t, s), m(r, s));
}

// lump_cut_xfem_mass with tet t's piece masses at unit density from piece_masses(t).
template <typename PieceMasses>
Eigen::SparseMatrix<double> lump_mass(const CutXfemModel& model, double density, LumpingScheme scheme, const PieceMasses& piece_masses) {
  const TetMesh& mesh = model.mesh();
  const int n = mesh.nodes_per_tet();
  // A DOF node's own mass (i, i) is summed in a vector, the couplings (i, k) of the enrichments
  // and the branch tets' blocks as triplets: a few thousand triplets to sort, not 12 per node of
  // every tet.
  Eigen::VectorXd own = Eigen::VectorXd::Zero(model.num_dof_nodes());
  std::vector<Eigen::Triplet<double>> entries;
  const auto add = [&](int i, int j, double value) {
    if (i == j) {
      own[i] += value;
      return;
    }
    for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + c, 3 * j + c, value);
  };
  if (scheme == LumpingScheme::schoch_eq_81_82) require_no_crack_tip_functions(model, "lump_cut_xfem_mass");
  const TetMatrix& slots = model.assembly_slots();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    // A Tet4 that no enrichment reaches (most of them) is one whole piece whose phantom nodes
    // are its own nodes (cut_xfem_piece_masses gives it tet4_mass): its diagonal straight onto
    // its nodes, without the general path's per-tet matrices. Eqs. 81-82 give it the same m / n.
    if (n == 4 && (slots.cols() == 4 || slots(t, 4) < 0) && scheme != LumpingScheme::schoch_eq_81_82) {
      const Eigen::Vector4d D = piece_diagonal(tet4_mass(tet_corners(mesh, t), 1.0), density, scheme);
      for (int a = 0; a < 4; ++a) own[mesh.tets(t, a)] += D[a];
      continue;
    }
    if (model.has_branch_functions(t)) {
      add_consistent_tet(model, t, density, add);
      continue;
    }
    const std::vector<Eigen::MatrixXd> masses = piece_masses(t);
    if (scheme == LumpingScheme::schoch_eq_81_82) {
      double element_volume = 0.0;
      for (const Eigen::MatrixXd& m : masses) element_volume += m.sum();
      const double share = density * element_volume / n; // m / n, eq. 81
      for (int a = 0; a < n; ++a) {
        add(mesh.tets(t, a), mesh.tets(t, a), share);
        // Eq. 82 with Psi in {0, 1} on each piece: the pieces where this node's enrichment is
        // active give (V_p / V) m / n each.
        for (std::size_t p = 0; p < masses.size(); ++p)
          if (const int k = model.phantom_node(t, static_cast<int>(p), a); k != mesh.tets(t, a))
            add(k, k, share * masses[p].sum() / element_volume);
      }
      continue;
    }
    for (std::size_t p = 0; p < masses.size(); ++p) {
      const Eigen::VectorXd D = piece_diagonal(masses[p], density, scheme);
      // T_p^T D T_p: node a's phantom value is u_i (+ a_k where enrichment k is active), so its
      // mass lands on (i, i) and, with an enrichment, on (i, k), (k, i) and (k, k).
      for (int a = 0; a < n; ++a) {
        const int i = mesh.tets(t, a);
        const int k = model.phantom_node(t, static_cast<int>(p), a);
        add(i, i, D[a]);
        if (k == i) continue;
        add(i, k, D[a]);
        add(k, i, D[a]);
        add(k, k, D[a]);
      }
    }
  }
  for (Eigen::Index i = 0; i < own.size(); ++i)
    for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + c, 3 * i + c, own[i]);
  const Eigen::Index size = 3 * model.num_dof_nodes();
  Eigen::SparseMatrix<double> M(size, size);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

} // namespace

Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const PieceRuleFunction& rule) {
  return lump_mass(model, density, scheme, [&](Eigen::Index t) { return cut_xfem_piece_masses(model, t, 1.0, rule); });
}

Eigen::SparseMatrix<double> lump_cut_xfem_mass(const CutXfemModel& model, double density, LumpingScheme scheme,
                                               const SplitTetMasses& masses) {
  return lump_mass(model, density, scheme, [&](Eigen::Index t) { return masses(model, t); });
}

Eigen::VectorXd lumped_gravity_load(const CutXfemModel& model, double density, const Eigen::Vector3d& g,
                                    LumpingScheme scheme, const PieceRuleFunction& rule) {
  if (scheme == LumpingScheme::schoch_eq_81_82) {
    require_no_crack_tip_functions(model, "lumped_gravity_load");
    return model.gravity_load(density, g);
  }
  const TetMesh& mesh = model.mesh();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * model.num_dof_nodes());
  const int n = mesh.nodes_per_tet();
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (model.has_branch_functions(t)) {
      // Its consistent mass times "every phantom node at g": slot s gets sum_a m_sa g over the
      // node slots (the sign and branch slots' accelerations are 0), which is rho int g_s g,
      // the tet's share of CutXfemModel::gravity_load, branch rows included.
      const Eigen::MatrixXd m = cut_xfem_slot_mass(model, t, density);
      for (Eigen::Index s = 0; s < m.rows(); ++s)
        f.segment<3>(3 * model.assembly_slots()(t, s)) += m.row(s).head(n).sum() * g;
      continue;
    }
    const std::vector<Eigen::MatrixXd> masses = cut_xfem_piece_masses(model, t, 1.0, rule);
    for (std::size_t p = 0; p < masses.size(); ++p) {
      const Eigen::VectorXd D = piece_diagonal(masses[p], density, scheme);
      // T_p^T (D 1 kron g): the phantom node's weight D_a g goes to u_i and to a_k.
      for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
        const int i = mesh.tets(t, a);
        const int k = model.phantom_node(t, static_cast<int>(p), a);
        f.segment<3>(3 * i) += D[a] * g;
        if (k != i) f.segment<3>(3 * k) += D[a] * g;
      }
    }
  }
  return f;
}

} // namespace kerf
