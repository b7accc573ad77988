/// @file branch_tets.hpp
/// @brief Chapter 5 inside the cut XFEM model: the tets with crack-tip (branch) functions, their rules, their
///        stiffness per piece and their one rotation per piece.
///
/// CutXfemModel (cut_xfem_model.hpp) is chapter 4's phantom-element model; this class holds all
/// that chapter 5 adds to it, so that a reader of chapter 4 can skip it. Given CrackTipFunctions,
/// every corner in branch slot k carries four more unknowns b_{k,l} (l = 0..3), and the field of
/// every tet that holds such a corner gains
///
///   sum_{v branch} sum_l (lambda_v F_l - I_h(lambda_v F_l)) b_{v,l}   (Paulus et al., eq. 3, shifted)
///
/// with lambda_v the corner's linear hat and I_h the element's nodal interpolant: on a Tet4
/// N_v (F_l - F_l(x_v)), Paulus et al.'s functions shifted; on a Tet10 the same space, still zero at
/// every node (branch_enrichment.hpp: why linear hats, not the Tet10's own functions). With
/// Fries's blending correction F_l is R F_l throughout, R the ramp of branch_enrichment.hpp, and
/// every corner of a blending tet has the four functions; the ramp nodes among them keep their
/// sign enrichments. The branch nodes have no sign enrichments (BranchEnrichment::sign): a node
/// is never both (Paulus et al., section 3.3).
///
/// Those functions are not constant on a piece, so the phantom element alone no longer describes
/// such a tet. In its slots, after the n nodes and the sign enrichments, come four branch slots
/// per branch corner. At each quadrature point the branch functions' gradients join the phantom
/// element's, and the tet is integrated by its front or blending rule (FrontRule): the functions
/// are no polynomials, and their gradients grow like 1 / sqrt(r) at the front. What the rules
/// give is kept here per piece: the functions' values and gradients at every point (the masses
/// and the gravity load read them), the piece's linear stiffness on the tet's slots, and each
/// slot's gradient averaged over the piece.
///
/// Corotation of such a tet: one rotation per piece, that of the piece's mean deformation
/// gradient, with the branch coefficients turned like the sign ones (corotated_piece.hpp says
/// why not one per point: the branch gradients are singular at the front). The same on Tet4 and
/// Tet10 meshes; every other tet keeps its rotation per point.
#pragma once

#include "kerf/corotation/corotated_element.hpp"
#include "kerf/corotation/corotation_statistics.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/quadrature/front_quadrature.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/phantom_piece.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace kerf {

/// How the tets with branch-enriched nodes are integrated: the branch functions are no
/// polynomials, and their gradients grow like 1 / sqrt(r) at the front.
enum class FrontRule : signed char {
  collapsed,       ///< sub-tets collapsed onto the front, exact in r (front_quadrature.hpp)
  refined_subtets, ///< Gauss rules on the sub-tets, each refined once into 8 (gauss_piece_rules.hpp)
};

/// Chapter 5's crack-tip enrichment, as the model takes it: which nodes carry the four branch
/// functions (branch_enrichment.hpp; its `sign` is the SurfaceEnrichment the model is given),
/// the fronts they are measured from, and the rules of the tets they act in.
struct CrackTipFunctions {
  const BranchEnrichment& enrichment; ///< kept by reference
  const CrackFronts& fronts;          ///< kept by reference
  FrontRule front_rule = FrontRule::collapsed;
  /// Points per direction of each collapsed sub-tet of a tet the front crosses (n^3 per
  /// sub-tet); with refined_subtets, the Gauss degree 2 n - 1 on sub-tets refined once. 0: the
  /// default, 4 on a Tet4 and 6 on a Tet10, whose integrands have two degrees more (measured in
  /// tests/chapter_05/test_crack_tip_model.cpp: a Tet10's exact quadratic field to 3e-5 with 4,
  /// 6e-9 with 6).
  int front_points = 0;
  /// The Gauss degree on the other tets with branch nodes (the sub-tets of their pieces, or of
  /// the whole tet, graded towards the front: near_front_graded_rule): the functions are smooth
  /// there, but no polynomials, and steep close to the front.
  int blending_degree = 6;
  int blending_depth = 3; ///< how often a sub-tet nearer the front than its size may be refined
  /// How often the collapsed rule halves a face near the front's line at most
  /// (front_collapsed_rule's grading, 0 to 12).
  int front_grading = default_front_grading;
  /// The blending rules' goal, a fraction of V / h (near_front_graded_rule's tolerance); 0: the
  /// strict default, front_rule_tolerance of the blending degree's points.
  double blending_tolerance = 0.0;
};

/// The tets of a mesh that hold a branch-enriched corner, with what the model needs of them.
class BranchTets {
public:
  /// What a piece of a tet with branch functions adds to its PhantomPiece.
  struct Piece {
    /// +1 / -1 if the piece lies above / below the cut, for theta's sign behind the front
    /// (functions_at); 0 where it is not known (a tet the front crosses is one piece).
    int side = 0;
    /// Per point (rows), the values of the tet's branch functions (columns, in the order of its
    /// branch slots), and their gradients (3 columns each, m^-1).
    Eigen::MatrixXd value, gradient;
    /// The piece's linear stiffness on the tet's slots (eq. 30 over the piece), 3S x 3S.
    Eigen::MatrixXd stiffness;
    /// Each slot's gradient averaged over the piece (corotated_piece.hpp), S x 3.
    Eigen::MatrixX3d mean_gradient;
    double volume = 0.0; ///< the sum of the weights (m^3)
  };

  BranchTets() = default;
  /// Which tets of `mesh` hold a branch corner of `tip` (none if `tip` is null), their ramps and
  /// the values R F_l at their nodes that the shift takes; no points yet (integrate).
  /// @param first_slot per tet: where its branch slots would begin, after its n nodes and its sign
  ///                   enrichments (kept for the tets with branch corners, -1 for the others)
  BranchTets(const TetMesh& mesh, const MeshPieces& pieces, const CrackTipFunctions* tip, std::vector<int> first_slot);

  /// Whether tet t holds a branch-enriched corner (its field has the branch functions).
  bool contains(Eigen::Index t) const { return first_slot_[static_cast<std::size_t>(t)] >= 0; }
  /// The slot of tet t's first branch function (-1 where there is none); function l of its j-th
  /// branch corner takes slot first_slot(t) + 4 j + l.
  int first_slot(Eigen::Index t) const { return first_slot_[static_cast<std::size_t>(t)]; }
  /// The local nodes (corners) of tet t that are branch enriched, in the order of its slots.
  const std::vector<int>& local_nodes(Eigen::Index t) const { return local_nodes_[static_cast<std::size_t>(t)]; }
  /// The number of tet t's slots: its nodes, sign enrichments and branch functions.
  int num_slots(Eigen::Index t) const { return first_slot(t) + 4 * static_cast<int>(local_nodes(t).size()); }

  /// The branch functions of tet t at x (m), for a point of a piece on side `side` of the cut
  /// (0: not known): one column per branch slot of the tet, the value in row 0 and the gradient
  /// (m^-1) in rows 1-3.
  Eigen::Matrix<double, 4, Eigen::Dynamic> functions_at(Eigen::Index t, const Eigen::Vector3d& x, int side) const;

  /// Integrates tet t: each of its pieces (the whole tet, if no cut splits it) by its front or
  /// blending rule, the branch functions at every point, and each piece's stiffness and mean
  /// slot gradients, once (a front tet's rule has thousands of points, and Newton or a time
  /// step assembles the tet again and again).
  /// @param enrichment_slots per piece: its phantom element's PhantomPiece::enrichment_slot
  /// @returns the pieces with their phantom slots and points
  std::vector<PhantomPiece> integrate(Eigen::Index t, const std::vector<std::vector<int>>& enrichment_slots,
                                      const LinearMaterial& material);
  /// What integrate() kept for piece p of tet t.
  const Piece& piece(Eigen::Index t, int p) const {
    return pieces_[static_cast<std::size_t>(t)][static_cast<std::size_t>(p)];
  }
  /// Sets the rows of the branch slots of g (one row per slot of tet t) to the branch
  /// functions' gradients at point q of piece p.
  void set_slot_gradients(Eigen::Index t, int p, std::size_t q, Eigen::MatrixX3d& g) const;

  /// Adds the forces of tet t (and its tangent, if K_e is given) on its slots: sum over the
  /// pieces of K_p q, or, corotated, each piece turned by its own rotation (corotated_piece.hpp).
  /// @param X  one row per slot: the nodes' reference positions, 0 for the other slots
  /// @param q  one row per slot: its unknowns
  /// @param f_e 3 num_slots(t), added to
  /// @param K_e 3 num_slots(t) square, added to; or null
  void add_forces(Eigen::Index t, const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q, RotationMethod rotation,
                  CorotationalTangent tangent, bool corotated, Eigen::VectorXd& f_e, Eigen::MatrixXd* K_e,
                  CorotationStatistics& stats) const;
  /// Tet t's strain energy, 1/2 d^T K_p d per piece with the piece's one rotation (R = I when
  /// `corotated` is false); X and q as for add_forces.
  double energy(Eigen::Index t, const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& q, bool corotated,
                RotationMethod rotation) const;

private:
  // The points of each piece of tet t by its front or blending rule, and the side of the cut
  // each piece lies on.
  std::vector<std::vector<PiecePoint>> piece_rules(Eigen::Index t, std::vector<int>& sides) const;

  const TetMesh* mesh_ = nullptr;
  const MeshPieces* mesh_pieces_ = nullptr;
  const CrackTipFunctions* tip_ = nullptr;
  std::vector<int> first_slot_;               // per tet; -1 without branch corners
  std::vector<std::vector<int>> local_nodes_; // per tet: its branch corners
  // Per tet with branch corners: R F_l at its n nodes (4 x n), what the shift interpolates.
  std::vector<Eigen::Matrix<double, 4, Eigen::Dynamic>> nodal_values_;
  std::vector<Eigen::Vector4d> ramp_corners_; // per tet: 1 for the corners in I* (all four without Fries's correction)
  std::vector<std::vector<Piece>> pieces_;    // per tet with branch corners, one per piece
};

} // namespace kerf
