/// @file corotated_pieces.hpp
/// @brief The corotated strain energy of a Tet4 body, cut or not, as one flat list of linear
///        pieces: W(u), its gradient f_int(u), and products with the warped stiffness, all
///        without a matrix (chapter 8's step evaluates them a few times per time step).
#pragma once
#include "kerf/corotation/corotated_element.hpp"
#include "kerf/fem/linear_material.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace kerf {

class CutXfemModel;

/// On a piece of a Tet4 (a whole tet, or one piece of a cut tet) the field is linear: its
/// phantom element has the nodal values u_a + a_k (cut_xfem_model.hpp), so the deformation
/// gradient is one matrix,
///
///   F = I + sum_s q_s g_s^T,                                                    (8.1)
///
/// over the piece's slots s: its four nodes, and the enrichment each phantom node takes, every
/// slot with the gradient g_s = grad N_a of its node's shape function. With R the rotation of F
/// and the linear material's strain R^T F - I (symmetric for the polar R), the piece's energy is
/// V psi(F), the corotated element's 1/2 d^T K d (corotated_element.hpp), with
///
///   psi(F) = mu |R^T F - I|^2 + lambda/2 tr(R^T F - I)^2,                       (8.2)
///   P(F) = d psi / dF = 2 mu (F - R) + lambda tr(R^T F - I) R                   (8.3)
///
/// (the terms from dR/dF vanish for the polar rotation: McAdams et al. 2011), and the force on
/// slot s is V P g_s. The warped stiffness K_R = R K R^T (Schoch et al. 2013, eq. 38) applied to
/// d is the same loop with the linear stress of the strain sym(R^T D), D = sum_s d_s g_s^T.
///
/// A chapter 7 model with Tet4 and without branch functions is exactly this sum; its assembly
/// gives the same W and f_int (tests/chapter_08/test_corotated_pieces.cpp).
class CorotatedPieces {
public:
  /// Every integrated piece of `model` (kept by value: the model may go). Piece t < the mesh's
  /// number of tets is tet t whole; a tet the cut divides, or whose nodes carry an enrichment on
  /// it, is special: its whole piece has no volume here and its integrated pieces follow, from
  /// num_tets() on. `before`, the pieces of an earlier cut of the same mesh (or nullptr), lends its
  /// whole tets' data, shared and never changed, so that a cut costs what its special tets cost
  /// and a copy of one number a tet.
  /// @throws std::invalid_argument for a Tet10 model or one with branch functions, or a `before`
  ///         of another mesh (another number of tets or nodes)
  CorotatedPieces(const CutXfemModel& model, const LinearMaterial& material, RotationMethod rotation,
                  const CorotatedPieces* before = nullptr);

  Eigen::Index num_dof_nodes() const { return num_dof_nodes_; }
  /// The mesh's tets (whole pieces 0 ... num_tets() - 1) and the special tets' pieces after them.
  Eigen::Index num_pieces() const { return static_cast<Eigen::Index>(num_tets_ + volume_.size()); }
  Eigen::Index num_tets() const { return static_cast<Eigen::Index>(num_tets_); }
  /// The tets whose pieces are special (the constructor's comment), in increasing order.
  const std::vector<int>& special_tets() const { return special_tets_; }

  /// W(u) (J) and f_int(u) = dW/du (3 num_dof_nodes(), N); the rotation of every piece into
  /// `rotations`. If `rotations` holds one per piece already (the last evaluation's), each is
  /// found from there (a step moves them little); else from the identity.
  double energy(const Eigen::VectorXd& u, Eigen::VectorXd& f_int, std::vector<Eigen::Matrix3d>& rotations) const;
  /// Where to start the rotations of these pieces from those of another body of the same mesh
  /// (`rotations`, one per piece of that body, or at least one per tet; replaced in place, in the
  /// same memory where it fits): a whole tet keeps its own, a special piece takes its tet's whole
  /// piece's (which the pass turns in passing). After a cut the rotations are then a Newton
  /// iteration or two from the polar ones, not eight from the identity.
  void warm_rotations(std::vector<Eigen::Matrix3d>& rotations) const;
  /// K_R d with the warped stiffness at `rotations` (one per piece), and 1/2 d^T K_R d (J).
  double warped_product(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d, Eigen::VectorXd& K_d) const;
  /// sum_s q_s g_s^T of every piece: the pieces' displacement gradients for q.
  std::vector<Eigen::Matrix3d> gradient_sums(const Eigen::VectorXd& q) const;
  /// The same into `sums` (resized to one per piece), so that a step reuses its memory.
  void gradient_sums(const Eigen::VectorXd& q, std::vector<Eigen::Matrix3d>& sums) const;
  /// What chapter 8's step asks of the pieces at u, in one pass over them:
  ///   W(u) + c/2 d^T K_R d  and its gradient  f_int(u) + c K_R d,   d = u - u_ref,
  /// with the warped stiffness K_R at the rotations `turned` (one per piece) and u_ref given by its
  /// gradient sums (`reference_sums`, gradient_sums(u_ref)). The gradient into `force`; the
  /// rotations of u into `rotations` (warm, as energy()), each iterated until its last correction
  /// is below `turn_tolerance` (rad), which leaves it about the square of that from the polar
  /// rotation: 1e-7 is round-off; a step that stops after a few iterations anyway can take 1e-2
  /// (a correction of 1e-3 rad, typical within a step, then ends after one Newton iteration,
  /// within 1e-6 rad).
  struct StepTerms {
    double W = 0.0;        ///< W(u) (J)
    double half_dKd = 0.0; ///< 1/2 d^T K_R d (J)
  };
  StepTerms step_terms(const Eigen::VectorXd& u, const std::vector<Eigen::Matrix3d>& reference_sums, double c,
                       const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force,
                       std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance = 1e-7) const;
  /// The scalar Laplacian of the pieces on the DOF nodes (m), summed over the slots i, j of
  /// every piece p:
  ///
  ///   L_ij = sum_p V_p g_i . g_j,   so that   sum_ij L_ij q_i . q_j = int |grad u|^2,       (8.5)
  ///
  /// the same for x, y and z: one n x n matrix where the stiffness is 3n x 3n.
  Eigen::SparseMatrix<double> laplacian() const;
  /// The entries of laplacian() in the rows and columns of the enrichments (DOF nodes from the
  /// mesh's num_nodes() on), from the pieces that carry one: what a cut changes of it.
  Eigen::SparseMatrix<double> enrichment_laplacian() const;
  /// The largest |sum_p V_p - V_t| / V_t over the tets: the Laplacian's block of the mesh's nodes
  /// is the uncut mesh's exactly when this is round-off.
  double largest_volume_mismatch() const { return largest_volume_mismatch_; }

private:
  // The slots of piece p: their DOF nodes and gradients g_s (1/m).
  struct Slots {
    const int* node;
    const Eigen::Vector3d* gradient;
    int count;
  };
  Slots slots(std::size_t p) const;
  // V_p: a whole tet's volume, 0 where the tet is special; a special piece's.
  double volume(std::size_t p) const { return p < num_tets_ ? whole_volume_[p] : volume_[p - num_tets_]; }

  // sum_s q_s g_s^T over piece p's slots: (8.1) without the identity.
  Eigen::Matrix3d gradient_sum(const Eigen::VectorXd& q, std::size_t p) const;
  // The linear stress sigma = 2 mu strain + lambda tr(strain) I of a symmetric strain, and its
  // energy density psi = mu |strain|^2 + lambda/2 tr(strain)^2.
  Eigen::Matrix3d stress(const Eigen::Matrix3d& strain) const;
  double energy_density(const Eigen::Matrix3d& strain) const;
  // Adds V P g_s of piece p to its slots.
  void add_piece_force(std::size_t p, const Eigen::Matrix3d& VP, Eigen::VectorXd& force) const;
  // step_terms of one piece, the scalar way: the whole tets left over from the blocks, and a
  // block's lane whose rotation needs chapter 2's decomposition.
  StepTerms piece_step_terms(std::size_t p, const Eigen::VectorXd& u, const Eigen::Matrix3d& reference_sum, double c,
                             const Eigen::Matrix3d& turned, Eigen::VectorXd& force, Eigen::Matrix3d& rotation,
                             double turn_tolerance) const;
  // step_terms of the blocks, four pieces at a time (corotated_piece_blocks.cpp): the whole
  // tets', then the special pieces'.
  StepTerms block_step_terms(const Eigen::VectorXd& u, const std::vector<Eigen::Matrix3d>& reference_sums, double c,
                             const std::vector<Eigen::Matrix3d>& turned, Eigen::VectorXd& force, std::vector<Eigen::Matrix3d>& rotations,
                             double turn_tolerance) const;
  // ... of one kind of block (`slots` slots a lane), `volumes` four a block.
  template <int slots, class Block>
  StepTerms step_terms_of_blocks(const std::vector<Block>& blocks, const double* volumes, const Eigen::VectorXd& u,
                              const std::vector<Eigen::Matrix3d>& reference_sums, double c, const std::vector<Eigen::Matrix3d>& turned,
                              Eigen::VectorXd& force, std::vector<Eigen::Matrix3d>& rotations, double turn_tolerance) const;
  // warped_product of the blocks (corotated_piece_blocks.cpp), and of one kind of block.
  double block_warped_product(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& d, Eigen::VectorXd& K_d) const;
  template <int slots, class Block>
  double warped_product_of_blocks(const std::vector<Block>& blocks, const double* volumes, const std::vector<Eigen::Matrix3d>& rotations,
                               const Eigen::VectorXd& d, Eigen::VectorXd& K_d) const;
  // gradient_sums of the blocks (corotated_piece_blocks.cpp), and of one kind of block.
  void block_gradient_sums(const Eigen::VectorXd& q, std::vector<Eigen::Matrix3d>& sums) const;
  template <int slots, class Block>
  void gradient_sums_of_blocks(const std::vector<Block>& blocks, const Eigen::VectorXd& q, std::vector<Eigen::Matrix3d>& sums) const;
  // The Laplacian's entries of the given pieces (triplets summed).
  Eigen::SparseMatrix<double> laplacian_of(const std::vector<std::size_t>& pieces, bool enrichment_rows_only) const;

  Eigen::Index num_dof_nodes_ = 0;
  Eigen::Index num_mesh_nodes_ = 0;
  double largest_volume_mismatch_ = 0.0;
  double mu_ = 0.0, lambda_ = 0.0;
  RotationMethod rotation_;

  // Pieces four to a block and laid out lane by lane, so that step_terms evaluates four at once
  // with one vector instruction per operation (corotated_piece_blocks.cpp): the whole tets (tets
  // 4k ... 4k + 3 in block k, four slots) and the special pieces (up to eight slots, the missing
  // ones with a zero gradient; a lane without a piece repeats lane 0's with no volume).
  template <int slots>
  struct PieceBlockOf {
    std::size_t piece[4] = {};            // the four pieces, lane by lane
    int dof[slots][4] = {};               // [slot][lane]: the first DOF (3 node) of the slot
    double gradient[slots][3][4] = {};    // [slot][component][lane]: g_s
  };
  using PieceBlock = PieceBlockOf<4>;     // the volumes are each body's own (whole_volume_)
  using SpecialBlock = PieceBlockOf<8>;
  // What every cut of one mesh shares: each tet's four nodes and gradients, its volume, its block.
  struct WholeTets {
    std::vector<int> node;                 // 4 a tet
    std::vector<Eigen::Vector3d> gradient; // 4 a tet (1/m)
    std::vector<double> volume;            // |det J| / 6 (m^3)
    std::vector<PieceBlock> blocks;
  };
  std::size_t num_tets_ = 0;
  std::shared_ptr<const WholeTets> whole_;
  std::vector<double> whole_volume_;  // each tet's volume, 0 where it is special
  std::vector<int> special_tets_;
  // The special tets' pieces, piece num_tets_ + q for q = 0, 1, ...
  std::vector<double> volume_;              // V_p
  std::vector<int> piece_tet_;              // the tet of each
  std::vector<int> first_slot_;             // piece q's slots are [first_slot_[q], first_slot_[q + 1])
  std::vector<int> slot_node_;              // the DOF node of each slot
  std::vector<Eigen::Vector3d> slot_gradient_; // g_s (1/m)
  std::vector<std::size_t> enriched_pieces_; // the pieces with an enrichment slot
  std::vector<SpecialBlock> special_blocks_;
  std::vector<double> special_block_volume_; // 4 a special block, lane by lane (0: no piece)
  std::vector<std::size_t> unblocked_;       // the whole tets the blocks leave: the last num_tets_ % 4
};

} // namespace kerf
