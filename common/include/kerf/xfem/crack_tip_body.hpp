/// @file crack_tip_body.hpp
/// @brief A mesh cut by triangle surfaces that may end inside it, with its XFEM model: Heaviside-only (chapter 4) or with branch functions (chapter 5).
///
/// Chapter 5's studies, benchmark and tests compare the same cut body three ways: chapter 4's
/// enrichment alone (the cut ends at the last row of enriched nodes), and branch functions on
/// the nodes of the tets the front crosses (topological) or within a radius of the front
/// (geometric). The model keeps the mesh, the pieces, the enrichment and the fronts by
/// reference (cut_xfem_model.hpp), so one object owns them all and is built in place.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"
#include "kerf/xfem/tip_enrichment_radius.hpp"

#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace kerf {

/// What the nodes near a front carry.
enum class TipTreatment : signed char {
  heaviside_only, ///< chapter 4: nothing; the cut stops at the last row of sign-enriched nodes
  topological,    ///< branch functions on the nodes of the tets the front crosses (Paulus section 3.3)
  geometric,      ///< branch functions on every node within a radius of the front
};

inline const char* to_string(TipTreatment t) {
  return t == TipTreatment::heaviside_only ? "heaviside" : t == TipTreatment::topological ? "topological" : "geometric";
}

/// How the tets with branch nodes are integrated: CrackTipFunctions' settings, its defaults.
struct BranchRules {
  FrontRule front_rule = FrontRule::collapsed;
  int front_points = 0;
  int blending_degree = 6;
  int blending_depth = 3;
};

/// The cut body and its model. Not movable: the model points into it.
class CrackTipBody {
public:
  /// @param mesh      Tet4 or Tet10 mesh
  /// @param surfaces  the cuts
  /// @param material  the material
  /// @param treatment what the nodes near the fronts carry
  /// @param radius    the geometric rule's radius (m); 0 takes default_tip_enrichment_radius()
  /// @param rules     the branch tets' rules (CrackTipFunctions' fields after the enrichment and
  ///                  the fronts, which this object supplies); ignored for Heaviside-only
  CrackTipBody(TetMesh mesh, std::vector<TriangleSurface> surfaces, const LinearMaterial& material, TipTreatment treatment,
               double radius = 0.0, const BranchRules& rules = {})
      : mesh_(std::move(mesh)), cuts_(std::move(surfaces)), pieces_(cut_mesh_into_pieces(mesh_, cuts_)),
        fronts_(find_crack_fronts(mesh_, cuts_)), treatment_(treatment) {
    // Sub-tets with Gauss rules of the degree the model asks for: exact for the polynomial
    // integrands of the pieces (the branch tets have their own rules, CrackTipFunctions).
    const PieceRuleFunction rule = [](const Eigen::Matrix<double, 4, 3>&, const TetPieces& pieces, int piece, int degree) {
      return subtet_rule(pieces, piece, degree);
    };
    if (treatment == TipTreatment::heaviside_only || fronts_.empty()) {
      heaviside_ = make_surface_enrichment(mesh_, pieces_);
      model_ = std::make_unique<CutXfemModel>(mesh_, material, pieces_, *heaviside_, rule);
      return;
    }
    const bool geometric = treatment == TipTreatment::geometric;
    radius_ = geometric ? (radius > 0.0 ? radius : default_tip_enrichment_radius(mesh_, fronts_)) : 0.0;
    branch_.emplace(make_branch_enrichment(mesh_, pieces_, fronts_,
                                           geometric ? TipEnrichmentRule::geometric : TipEnrichmentRule::topological, radius_));
    functions_ = std::make_unique<CrackTipFunctions>(
        CrackTipFunctions{*branch_, fronts_, rules.front_rule, rules.front_points, rules.blending_degree, rules.blending_depth});
    model_ = std::make_unique<CutXfemModel>(mesh_, material, pieces_, branch_->sign, rule, functions_.get());
  }
  CrackTipBody(const CrackTipBody&) = delete;
  CrackTipBody& operator=(const CrackTipBody&) = delete;

  const TetMesh& mesh() const { return mesh_; }
  const CrackFronts& fronts() const { return fronts_; }
  const CutXfemModel& model() const { return *model_; }
  TipTreatment treatment() const { return treatment_; }
  /// The geometric rule's radius used (m), 0 for the other treatments.
  double radius() const { return radius_; }
  /// The branch enrichment, or nullptr for Heaviside-only.
  const BranchEnrichment* branch() const { return branch_ ? &*branch_ : nullptr; }

private:
  TetMesh mesh_;
  CutSurfaces cuts_;
  MeshPieces pieces_;
  CrackFronts fronts_;
  TipTreatment treatment_;
  double radius_ = 0.0;
  std::optional<SurfaceEnrichment> heaviside_;
  std::optional<BranchEnrichment> branch_;
  std::unique_ptr<CrackTipFunctions> functions_;
  std::unique_ptr<CutXfemModel> model_;
};

} // namespace kerf
