/// @file cut_xfem_model.hpp
/// @brief Tet4 and Tet10 XFEM with triangle-mesh cuts: every piece of a cut tet integrated as its own "phantom"
///        element, linear and corotational, with a rotation per quadrature point (Schoch et al. 2013, eqs. 31-40 on
///        the pieces).
///
/// The class is one model; its code is split by idea, one file each, so that a reader can stop
/// where the chapter they study ends:
///
/// - phantom_piece.hpp: a piece as the model integrates it, its phantom element's slots and its
///   rule's points (PhantomPiece);
/// - cut_xfem_model.cpp: the constructors and build(), the steps of building a model; the slots
///   of each tet (which DOF node each slot is, which slot each phantom node takes its enrichment
///   from); the DOF map and the linear solve;
/// - cut_xfem_model_rules.cpp: the points of every tet, whole tets by their own rule, cut tets by
///   the piece rule, pieces kept from the model before (chapter 7's rebuild); the volumes the
///   rules see;
/// - cut_xfem_model_assembly.cpp: forces, tangents and energies, linear and corotated, and the
///   gravity load;
/// - cut_xfem_model_field.cpp: the field at a point (displacement_at, functions_at, piece_at),
///   the slots' functions at the rules' points (for_each_slot_value: chapter 6's masses), the
///   phantom mesh;
/// - branch_tets.hpp, branch_tets.cpp: chapter 5, the tets with branch functions (BranchTets):
///   the functions, their rules, the stiffness and the rotation per piece.
///
/// A reader of chapter 4 can skip branch_tets.*: the model's files ask BranchTets::contains(t)
/// before they use it, and without crack-tip functions it is false in every tet.
#pragma once

#include "kerf/corotation/quasi_static_model.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/solve/linear_solver.hpp"
#include "kerf/xfem/branch_tets.hpp"
#include "kerf/xfem/enrichment_volumes.hpp"
#include "kerf/xfem/phantom_piece.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace kerf {

/// The degree a piece's rule needs for the stiffness and the body force together. On one piece
/// every enrichment is constant, so B^T C B has degree 0 on a Tet4 and 2 on a Tet10, and N b
/// (b constant) degree 1 and 2: one rule of the larger degree serves both, 1 for a Tet4 and 2
/// for a Tet10. (The mass N^T N needs 2 and 4: cut_xfem_mass.hpp asks for its own.)
inline int stiffness_and_load_degree(int order) { return order == 1 ? 1 : 2; }

/// A Tet4 or Tet10 mesh cut by triangle-mesh cuts, enriched on the one-ring.
///
/// The unknowns are [u_1 .. u_N, a_1 .. a_M]: three displacements per node, then three per
/// enrichment (surface_enrichment.hpp), numbered as DOF nodes 0 .. N + M - 1 as in chapter 3.
///
/// The one idea. On piece p of tet t every enrichment is constant, so the field there is an
/// ordinary Tet4 or Tet10 field with nodal values
///
///   u_p,a = u_a + a_k   where k = the enrichment of node a active on p (none: u_p,a = u_a),
///
/// the piece's "phantom" element. Written as u_p = T_p u_e with a 0/1 matrix T_p (chapter 3's
/// side operator, grown to several enrichments per node), everything the element does is the
/// ordinary element's on each piece, integrated over the piece only:
///
///   K^X_e = sum_p T_p^T (int_p B^T C B) T_p,   f_e = sum_p T_p^T (int_p N^T b),
///
/// and corotation takes the rotation of the phantom element's deformation gradient at every
/// quadrature point of the piece (eqs. 31-40 with u_p for u). A Tet4 piece has constant B and
/// one rotation (the weights' sum is all that matters); a Tet10 piece needs a rule of degree 2.
/// Tets that no enrichment reaches are chapter 1's and 2's elements, integrated with their own
/// rules (a tet that is cut, but whose nodes the rule of surface_enrichment.hpp leaves
/// unenriched, is continuous across the cut: the cut cannot open there, Koschier et al. 2017,
/// section 8).
///
/// Crack-tip functions (chapter 5). Given CrackTipFunctions, the unknowns grow by twelve per
/// branch node, [u; a; b] with b_{i,l} (l = 0..3) after the a's, DOF node N + M + 4 k + l for
/// the corner in branch slot k. Those functions are not constant on a piece: the tets that hold
/// a branch node add their gradients to the phantom element's at every point, are integrated
/// by a front or blending rule, and turn with one rotation per piece (branch_tets.hpp).
class CutXfemModel : public QuasiStaticModel {
public:
  /// @param mesh       Tet4 or Tet10 mesh, straight-edged (kept by reference)
  /// @param material   the material
  /// @param pieces     cut_mesh_into_pieces(mesh, cuts) (kept by reference)
  /// @param enrichment make_surface_enrichment(mesh, pieces) (kept by reference)
  /// @param rule       the quadrature rule of each piece of every tet that an enrichment splits
  /// @param tip        chapter 5's branch functions, or nullptr (kept by reference); `enrichment`
  ///                   must then be tip->enrichment.sign
  CutXfemModel(const TetMesh& mesh, const LinearMaterial& material, const MeshPieces& pieces,
               const SurfaceEnrichment& enrichment, const PieceRuleFunction& rule,
               const CrackTipFunctions* tip = nullptr);

  /// The model of the same mesh, material and rule after the cut has grown, integrated anew only
  /// where the cut changed (chapter 7 rebuilds it whenever the blade crosses a tet).
  ///
  /// `pieces` must be recut_mesh_into_pieces(mesh, cuts, before.pieces(), changed), with
  /// before.pieces() still alive. A tet whose pieces recut kept (MeshPieces::kept_from_previous)
  /// and that has no branch functions, before or now, keeps `before`'s quadrature points, which
  /// depend only on its pieces: the costly part, the rules of the cut tets (moment fitting, or
  /// sub-tets), is paid for the recut tets only. The tets integrated whole share one set of
  /// points with `before` (they depend on the mesh alone). What depends on the enrichments (the
  /// slots, and which slot each phantom node takes) is cheap and rebuilt for every tet, so the
  /// model equals the one the other constructor makes from the same arguments
  /// (tests/chapter_07/test_incremental_rebuild.cpp asserts it).
  /// @throws std::invalid_argument if `pieces` does not say which tets were kept
  CutXfemModel(const CutXfemModel& before, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
               const CrackTipFunctions* tip = nullptr);

  Eigen::Index num_dof_nodes() const override {
    return mesh_.num_nodes() + enrichment_.num_enrichments() + 4 * num_branch_nodes();
  }
  const TetMatrix& assembly_slots() const override { return slots_; }
  CorotationStatistics assemble(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                Eigen::VectorXd& f_int, SparseAssembler* assembler,
                                Eigen::VectorXd* rhs_free) const override;
  double position_force_norm() const override { return position_force_norm_; }

  /// The linear XFEM stiffness K^X added into `assembler`, lifting into rhs_free.
  void assemble_linear_stiffness(SparseAssembler& assembler, Eigen::VectorXd& rhs_free) const;
  /// The strain energy of the state u (J), summed over the points where assemble() evaluates the
  /// forces: 1/2 d^T K_q d with d = R^T x - X the corotated displacement of the point's phantom
  /// element (R = I when `corotated` is false, the linear XFEM energy 1/2 u^T K^X u). For the
  /// polar rotation of an isotropic material, assemble()'s f_int is its gradient
  /// (corotated_element.hpp), which is why chapter 6's energy account uses it.
  /// In a tet with branch functions the energy is 1/2 d^T K_p d per piece with the piece's one
  /// rotation (corotated_piece.hpp), of which assemble()'s force is the gradient only up to the
  /// strain's variation over the piece times its rotation (exactly when `corotated` is false).
  double energy(const Eigen::VectorXd& u, bool corotated, RotationMethod rotation = RotationMethod::automatic) const;
  /// assemble() (corotated) and energy(u, true) at once: each point's rotation, found once, gives
  /// its force, its tangent and its 1/2 d^T K_q d. A time step asks for W at its end state, where
  /// the next step assembles (chapter 7's step takes both from one pass). f_int and the tangent
  /// are assemble()'s to the bit; the energy is energy()'s to round-off (it is the same sum,
  /// 1/2 d^T K_q d instead of the strain density that energy() evaluates).
  /// @returns the strain energy W(u) (J)
  double assemble_with_energy(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                              Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                              CorotationStatistics* stats = nullptr) const;
  /// The body-force load sum_p T_p^T int_p N^T rho g (3 num_dof_nodes()).
  Eigen::VectorXd gravity_load(double density, const Eigen::Vector3d& g) const;
  /// The displacement at x (m) in tet t, on the piece that holds x (one above the cut, if x lies
  /// on the cut); NaN if t is integrated by pieces and none holds x. A tet integrated whole is
  /// not asked whether it holds x: its field is extended linearly beyond it (piece_at), which is
  /// what embedding a visual surface just outside the mesh wants; find the tet first
  /// (PointLocator) for a point anywhere in the body.
  Eigen::Vector3d displacement_at(const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) const;
  /// Its gradient du_i/dx_j (3x3) at x, on the same piece: the phantom element's, plus the
  /// branch functions' where they act (the interaction integral and the energy norm read it);
  /// NaN if x is not in tet t.
  Eigen::Matrix3d displacement_gradient_at(const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) const;
  /// The branch functions acting at x (m) on piece p of tet t: for each, its DOF node and its
  /// value N_a(x) (F_l(x) - F_l(x_a)); empty where no branch node acts.
  std::vector<std::pair<int, double>> branch_values_at(Eigen::Index t, int p, const Eigen::Vector3d& x) const;
  /// The same for a point known to lie on side `side` (+1 above, -1 below, 0 not known) of the
  /// cut, which may lie on the cut itself: F_1 then takes that side's value (theta = side pi).
  std::vector<std::pair<int, double>> branch_values_on_side(Eigen::Index t, const Eigen::Vector3d& x, int side) const;
  /// The functions the field is made of at x: their DOF nodes, values and gradients.
  struct FunctionsAt {
    std::vector<int> dof_node; ///< one entry per function (a DOF node may appear twice: u_a and a_k share N_a)
    Eigen::VectorXd value;     ///< its value at x
    Eigen::MatrixX3d gradient; ///< its gradient at x (m^-1), one row per function
  };
  /// Every function acting at x (m) in tet t, on the piece that holds x: N_a on node a and on the
  /// enrichment active there for the piece's phantom node, and the branch functions. The field
  /// at x is sum_j value_j q_(dof_node j) and its gradient sum_j q_(dof_node j) gradient_j^T:
  /// displacement_at and displacement_gradient_at one DOF node at a time, for a map that is
  /// linear in q (cut_state_transfer.hpp). Empty if x is not in tet t.
  FunctionsAt functions_at(Eigen::Index t, const Eigen::Vector3d& x) const;
  /// Every quadrature point tet t is integrated at, with the value there of each of its slots'
  /// functions: visit(p, w, g) for each point of each piece p that tet t integrates (one piece
  /// for a tet integrated whole), w its weight (m^3), g one value per slot (the slots of row t of
  /// assembly_slots()): N_a on node a's slot and on the slot of the sign enrichment active on p
  /// (the phantom element's), and the branch functions N_v (F_l - F_l(x_v)) on the branch slots.
  /// The field at the point is sum_s g_s q_s. In a tet with branch functions these are the
  /// points of its front or blending rule, the stiffness's; what chapter 6's mass integrates
  /// there (cut_xfem_mass.hpp: rho sum_q w_q g_q g_q^T).
  void for_each_slot_value(Eigen::Index t, const std::function<void(int, double, const Eigen::VectorXd&)>& visit) const;
  /// for_each_slot_value with each slot's gradient too: visit(p, w, g, G), G one row per slot
  /// (m^-1), from what the model stored for its rules (nothing is evaluated again).
  void for_each_slot_gradient(
      Eigen::Index t,
      const std::function<void(int, double, const Eigen::VectorXd&, const Eigen::MatrixX3d&)>& visit) const;
  /// Whether tet t holds a branch-enriched node (its field has the branch functions).
  bool has_branch_functions(Eigen::Index t) const { return branch_.contains(t); }
  /// The nodal values of the phantom element of piece p of tet t: row a is u_a + a_k.
  Eigen::MatrixX3d phantom_displacements(const Eigen::VectorXd& u, Eigen::Index t, int p) const;
  /// The piece of tet t that holds x (one above the cut if x lies on it), -1 if t is integrated
  /// by pieces and none holds x; 0 for a tet integrated whole, wherever x is (not checked).
  int piece_at(Eigen::Index t, const Eigen::Vector3d& x) const;
  /// The n shape functions of tet t at the point x (m).
  Eigen::VectorXd shape_values(Eigen::Index t, const Eigen::Vector3d& x) const;
  /// The DOF node that gives local node a of tet t its value on piece p: the node itself, or
  /// N + k for the enrichment k active there.
  int phantom_node(Eigen::Index t, int p, int a) const;
  /// The cut body as a Tet4 mesh of phantom elements, one tet per piece (Tet10: its corners),
  /// for asking which pieces the Dirichlet conditions hold (chapter 3's PhantomMesh).
  PhantomMesh phantom_mesh() const;

  const TetMesh& mesh() const { return mesh_; }
  const MeshPieces& pieces() const { return pieces_; }
  const SurfaceEnrichment& enrichment() const { return enrichment_; }
  /// Chapter 5's branch functions, or nullptr.
  const CrackTipFunctions* crack_tip() const { return tip_; }
  /// The number of branch-enriched nodes (0 without crack-tip functions).
  Eigen::Index num_branch_nodes() const { return tip_ ? tip_->enrichment.num_branch_nodes() : 0; }
  /// The first DOF node of branch slot k's four functions: N + M + 4 k.
  Eigen::Index branch_dof_node(int k) const { return mesh_.num_nodes() + enrichment_.num_enrichments() + 4 * k; }
  /// Whether tet t is integrated piece by piece, each of the cut's pieces (one if no cut splits
  /// it) as its own phantom element: an enrichment or a branch function acts in it. Not the same
  /// as being cut: a tet a cut splits, but on none of whose pieces an enrichment acts, is
  /// integrated whole (its field is continuous, the class comment).
  bool integrated_by_pieces(Eigen::Index t) const { return !piece_data_[static_cast<std::size_t>(t)].empty(); }
  /// How many pieces tet t is integrated as: pieces().num_pieces(t) where it is integrated by
  /// pieces, 1 where it is integrated whole (cut or not). Loop over these, not over the cut's
  /// pieces, wherever the model's pieces are asked for.
  int num_integrated_pieces(Eigen::Index t) const { return static_cast<int>(integrated_pieces(t).size()); }
  /// The volume of integrated piece p of tet t as its rule sees it, the sum of the weights
  /// (m^3); for a tet integrated whole (p = 0), the tet's volume.
  /// @throws std::out_of_range unless 0 <= p < num_integrated_pieces(t)
  double integrated_volume(Eigen::Index t, int p) const;
  /// The sum of every integrated piece's volume (m^3): the uncut mesh's, to round-off, when the
  /// pieces' rules integrate 1 exactly.
  double integrated_volume() const;
  /// V_enr and V_supp of every enrichment from the rules' weights (enrichment_volumes.hpp).
  EnrichmentVolumes enrichment_volumes() const;
  /// The total number of quadrature points on the pieces of split tets.
  Eigen::Index num_piece_points() const;
  /// How many of them have a negative weight (moment-fitted rules have some). A negative weight
  /// is harmless where the rule is exact for the integrand (the linear stiffness, the loads),
  /// but the corotated tangent at a point, R K_q R^T, is not a polynomial: with negative weights
  /// the sum over a piece need not be positive semi-definite, and Newton's matrix can lose
  /// definiteness.
  Eigen::Index num_negative_weights() const;

private:
  // Every tet integrated whole by its own rule, with the square of its position force |K_e X_e|:
  // a property of the mesh, shared by the models of a growing cut.
  struct WholeTets {
    std::vector<PhantomPiece> pieces;
    std::vector<double> position_force_squared;
  };

  // --- Building the model (cut_xfem_model.cpp) ---
  // The constructors' work: the slots, and the points of every tet, taken from `before` where
  // its pieces were kept (nullptr: none).
  void build(const CutXfemModel* before);
  // Per tet: the sign enrichments acting in it, sorted, once each (its slots n, n + 1, ...).
  std::vector<std::vector<int>> sign_enrichments_by_tet() const;
  // The rows of assembly_slots(): a tet's n nodes, then its sign enrichments, then four slots
  // per branch corner (branch_ must be made).
  TetMatrix make_slots(const std::vector<std::vector<int>>& sign_enrichments) const;
  // The number of tet t's slots: its row of assembly_slots() up to the first -1.
  int num_slots(Eigen::Index t) const;
  // How many of them are sign enrichments.
  int num_sign_slots(Eigen::Index t) const;
  // Which slot each node of the phantom element of piece p of tet t takes its enrichment from
  // (PhantomPiece::enrichment_slot): n entries, -1 for a node with no enrichment active on p.
  std::vector<int> phantom_slots(Eigen::Index t, int p) const;

  // --- The points of every tet (cut_xfem_model_rules.cpp) ---
  static std::shared_ptr<const WholeTets> integrate_whole_tets(const TetMesh& mesh, const LinearMaterial& material);
  // Tet t's pieces and their points (whole, kept from `before`, by the piece rule, or by
  // BranchTets), with the square of their position force.
  void integrate_tet(Eigen::Index t, const CutXfemModel* before);
  // Piece p of tet t on `points`, with its phantom slots; a Tet4 piece outside the branch tets
  // takes `tet4_stiffness` when the points are another piece's (shared with it), else its own.
  PhantomPiece phantom_piece(Eigen::Index t, int p, std::vector<PiecePoint> points,
                             std::shared_ptr<const Eigen::Matrix<double, 12, 12>> tet4_stiffness = nullptr) const;
  // What tet t integrates: its split pieces, or the whole tet as one piece.
  std::span<const PhantomPiece> integrated_pieces(Eigen::Index t) const;

  // --- Assembly (cut_xfem_model_assembly.cpp) ---
  // An element force and matrix big enough for any tet's slots, allocated once per assembly.
  struct ElementBuffers {
    explicit ElementBuffers(Eigen::Index max_slots) : f(3 * max_slots), K(3 * max_slots, 3 * max_slots) {}
    Eigen::VectorXd f;
    Eigen::MatrixXd K;
  };
  // One tet's forces (and tangent): linear (corotated false, R = I) or corotated, and with
  // `energy` (corotated only) its strain energy 1/2 d^T K_q d added.
  template <int n>
  void assemble_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                    bool corotated, Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                    CorotationStatistics& stats, ElementBuffers& buffers, double* energy = nullptr) const;
  // A tet with branch functions: its pieces' forces (BranchTets::add_forces), scattered.
  void assemble_branch_tet(Eigen::Index t, const Eigen::VectorXd& u, RotationMethod rotation,
                           CorotationalTangent tangent, bool corotated, Eigen::VectorXd& f_int,
                           SparseAssembler* assembler, Eigen::VectorXd* rhs_free, CorotationStatistics& stats) const;
  // The element's reference positions (node slots; 0 for the others) and unknowns (all slots)
  // of tet t, one row per slot.
  void slot_state(Eigen::Index t, const Eigen::VectorXd& u, Eigen::MatrixX3d& X, Eigen::MatrixX3d& q) const;
  // A tet with branch functions: its share of energy() (BranchTets::energy).
  double branch_tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const;
  // assemble() and assemble_with_energy(): every tet, its energy summed into `energy` if given.
  CorotationStatistics assemble_all(const Eigen::VectorXd& u, RotationMethod rotation, CorotationalTangent tangent,
                                    Eigen::VectorXd& f_int, SparseAssembler* assembler, Eigen::VectorXd* rhs_free,
                                    double* energy) const;
  // One tet's share of energy().
  template <int n>
  double tet_energy(Eigen::Index t, const Eigen::VectorXd& u, bool corotated, RotationMethod rotation) const;

  // --- The field (cut_xfem_model_field.cpp) ---
  // At point q of piece p of tet t: one value per slot, the phantom element's N_a on node a's
  // slot and on the slot of the sign enrichment active there, and each branch function's value
  // (for_each_slot_value's g).
  void slot_values(Eigen::Index t, int p, std::size_t q, Eigen::VectorXd& g) const;
  // The same for the gradients, one row per slot: G_a, and each branch function's own gradient.
  void slot_gradients(Eigen::Index t, int p, std::size_t q, Eigen::MatrixX3d& g) const;

  const TetMesh& mesh_;
  LinearMaterial material_;
  const MeshPieces& pieces_;
  const SurfaceEnrichment& enrichment_;
  const CrackTipFunctions* tip_ = nullptr;
  PieceRuleFunction rule_;
  TetMatrix slots_;
  BranchTets branch_;                                 // chapter 5: the tets with branch functions
  std::vector<std::vector<PhantomPiece>> piece_data_; // per tet; empty for tets integrated whole
  std::shared_ptr<const WholeTets> whole_;            // every tet's own rule, used where it is integrated whole
  std::vector<double> position_force_squared_;        // per tet: |K_p X_e|^2 summed over what it integrates
  double position_force_norm_ = 0.0;
};

/// The DofMap of [u; a]: the Dirichlet conditions on the mesh's nodes, a_i^k = 0 for every
/// enrichment of a gripped node (chapter 3's make_xfem_dof_map says why: the clamp holds the
/// tissue on every side of the cut at the node), and a_i^k = 0 for every sliver enrichment,
/// V_enr / V_supp < sliver_fraction (Koschier et al. 2017, eq. 22, enrichment_volumes.hpp; 0
/// keeps every sliver that has any volume).
DofMap make_cut_xfem_dof_map(const CutXfemModel& model, const std::vector<DirichletNodes>& conditions,
                             double sliver_fraction = default_sliver_fraction);

/// The pieces of the cut body that `dofs` leaves free to move rigidly: K^X_ff is singular
/// exactly when this is not empty (a phantom node is held when its u and its a are prescribed).
std::vector<UnheldPiece> cut_xfem_unheld_pieces(const CutXfemModel& model, const DofMap& dofs);

/// Linear XFEM in one call: assembles K^X, lifts, factorises and solves.
/// @param f_ext loads on all 3 num_dof_nodes() DOFs (e.g. gravity_load)
/// @return all DOFs [u; a]
/// @throws std::runtime_error naming the piece, before any factorisation, when a piece is held
///         by no Dirichlet condition (cut_xfem_unheld_pieces)
Eigen::VectorXd solve_linear_cut_xfem(const CutXfemModel& model, const DofMap& dofs, const Eigen::VectorXd& f_ext,
                                      const SolverSettings& solver_settings);

} // namespace kerf
