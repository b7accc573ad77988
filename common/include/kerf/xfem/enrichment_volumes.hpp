/// @file enrichment_volumes.hpp
/// @brief How much material each enrichment acts on, V_enr against its node's support V_supp (Koschier et al. 2017, eqs. 22 and 27), and Koschier's eq. 22 test for the slivers to constrain.
#pragma once

#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace kerf {

/// Koschier et al.'s epsilon for eq. 22, "10^-9 for all of our results", and Kerf's default.
/// Why this value and not chapter 3's 1e-4, from the failure study (results.md, "Where it
/// fails"): both make the slivers that come loose solvable (with every rule but the lattice).
/// 1e-4 also keeps the Jacobi-scaled condition number of a Tet10 K_ff at the uncut mesh's order,
/// where 1e-9 lets it grow like (h / d)^2 (to 2e10 at d / h = 1e-4), but it pays for it: a
/// constrained sliver moves with its node's home part, across the cut, and glues the two sides
/// together with a spring of its own volume; for a cut through the body 0.006 of a cell above a
/// node layer the opening falls short by 1.8e-4 (Tet4) and 3.4e-3 (Tet10) of itself. With 1e-9
/// no such bridge shows, and CHOLMOD solves the ill-conditioned Tet10 systems to the accuracy of
/// the cut's position. A cut that does not separate is a wrong answer; a condition number is a
/// solver's problem (chapter 6's preconditioners).
inline constexpr double koschier_sliver_fraction = 1e-9;

/// The default epsilon of eq. 22: Koschier's.
inline constexpr double default_sliver_fraction = koschier_sliver_fraction;

/// Chapter 3's minimum volume fraction, carried to eq. 22 for comparison.
inline constexpr double chapter3_sliver_fraction = 1e-4;

/// Per enrichment k (numbered as in SurfaceEnrichment): the volume its function N_i psi_i^k
/// acts on, the volume its node's home part takes, and the volume of its node's support.
struct EnrichmentVolumes {
  /// V_{i,k,enr} = sum over the tets e of node i's support, over the pieces p of e on which
  /// psi_i^k = 1, of the piece's volume (Koschier eq. 22 with the volumes from the rule's
  /// weights: sum_q w_{e,p,q}) (m^3).
  std::vector<double> enriched;
  /// V_{i,supp}: the volume of the tets holding node i, the node of enrichment k (m^3).
  std::vector<double> support;
  /// The node i that enrichment k belongs to (SurfaceEnrichment::enrichment_node).
  std::vector<int> node;

  /// V_enr / V_supp of enrichment k, the ratio eq. 22 compares with epsilon.
  double fraction(Eigen::Index k) const {
    return enriched[static_cast<std::size_t>(k)] / support[static_cast<std::size_t>(k)];
  }
  /// V_home / V_supp of enrichment k's node: its home part, where no enrichment of the node acts,
  /// V_home = V_supp - sum over the node's enrichments l of V_{i,l,enr}.
  double home_fraction(Eigen::Index k) const;
};

/// The volumes of the pieces tet t is integrated as, as an integration rule sees them (m^3):
/// one per piece of the cut (num_pieces(t) of them) where the tet is integrated piece by piece,
/// a single one (the tet's) where it is integrated whole, cut or not. A tet that a cut splits
/// but on none of whose pieces an enrichment acts is integrated whole: its field is continuous
/// there (surface_enrichment.hpp), and its pieces have no volumes of their own to report.
using IntegratedPieceVolumes = std::function<std::vector<double>(Eigen::Index t)>;

/// Sums the pieces' volumes into V_enr and V_supp for every enrichment.
/// @param mesh          Tet4 or Tet10 mesh
/// @param pieces        cut_mesh_into_pieces(mesh, cuts)
/// @param enrichment    make_surface_enrichment(mesh, pieces)
/// @param piece_volumes the volumes tet t is integrated as; CutXfemModel gives its rules', so
///                      that a rule that puts no point on a sliver reports the sliver as empty
/// @throws std::invalid_argument if a tet reports neither one volume nor one per piece, or one
///         volume while an enrichment acts on one of its pieces
EnrichmentVolumes enrichment_volumes(const TetMesh& mesh, const MeshPieces& pieces, const SurfaceEnrichment& enrichment,
                                     const IntegratedPieceVolumes& piece_volumes);

/// The enrichments Koschier's eq. 22 constrains, in increasing order, the test applied to every
/// part of a node's support:
///
///   V_{i,k,enr} / V_{i,supp} < epsilon                                        (eq. 22)
///
/// holds a_i^k = 0: the sliver k then moves with its node's home part. Koschier et al. test the
/// parts where an enrichment acts, but the home part (where N_i alone acts) can be the sliver
/// too: a node on the skin with a cut close to and along the skin. Then N_i and N_i psi_i^k are
/// nearly the same function (they differ on the sliver only), the matrix of the step has an
/// eigenvalue of the sliver's relative volume against O(1) diagonals, and no diagonal scaling
/// lifts it. So where V_home / V_supp < epsilon the enrichment of the node's largest part is
/// held as well: u_i is then the value on that part, and the home sliver moves with it (the same
/// glue, a change of the field on at most epsilon of the support).
///
/// Constraining means a_i^k = 0 (make_cut_xfem_dof_map does it). Koschier et al. also move the
/// constrained DOF "with its according fragment" as rigidly as possible, which the paper does not
/// specify; Kerf does the baseline only. epsilon = 0 constrains nothing but enrichments whose
/// volume is zero or negative (a rule with no point on the piece).
std::vector<int> sliver_enrichments(const EnrichmentVolumes& volumes, double epsilon);

} // namespace kerf
