// A body cut by triangle-mesh cuts, with everything its XFEM model keeps alive (the model holds
// the mesh, the pieces and the enrichment by reference), as the tests of chapters 4-6 build it.
// The pieces are integrated with sub-tetrahedra of the degree the model asks for, exact for
// every polynomial integrand, unless a test passes another rule.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/mesh_pieces.hpp"
#include "kerf/fem/dof_map.hpp"
#include "kerf/fem/sparse_assembler.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/quadrature/gauss_piece_rules.hpp"
#include "kerf/xfem/branch_enrichment.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"
#include "kerf/xfem/surface_enrichment.hpp"

#include <utility>
#include <vector>

namespace support {

// Sub-tetrahedra with Gauss rules of the degree asked for.
inline kerf::PieceQuadratureRule subtets(const Eigen::Matrix<double, 4, 3>&, const kerf::TetPieces& pieces, int piece, int degree) {
  return kerf::subtet_rule(pieces, piece, degree);
}

// The full linear stiffness K^X of a model on all 3 num_dof_nodes() DOFs, every one free (row
// 3 d + c is component c of DOF node d).
inline Eigen::SparseMatrix<double> full_linear_stiffness(const kerf::CutXfemModel& model) {
  const kerf::DofMap all_free = kerf::make_dof_map(model.num_dof_nodes(), {});
  kerf::SparseAssembler assembler(model.assembly_slots(), all_free);
  Eigen::VectorXd no_lifting = Eigen::VectorXd::Zero(all_free.num_free);
  model.assemble_linear_stiffness(assembler, no_lifting);
  return assembler.matrix();
}

struct CutBody {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::SurfaceEnrichment enrichment;
  kerf::CutXfemModel model;
  CutBody(kerf::TetMesh m, std::vector<kerf::TriangleSurface> surfaces, const kerf::LinearMaterial& material,
          const kerf::PieceRuleFunction& rule = subtets)
      : mesh(std::move(m)), cuts(std::move(surfaces)), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        enrichment(kerf::make_surface_enrichment(mesh, pieces)), model(mesh, material, pieces, enrichment, rule) {}
};

// A cut body with chapter 5's branch functions where its cuts end inside it.
struct TipBody {
  kerf::TetMesh mesh;
  kerf::CutSurfaces cuts;
  kerf::MeshPieces pieces;
  kerf::CrackFronts fronts;
  kerf::BranchEnrichment branch;
  kerf::CrackTipFunctions functions;
  kerf::CutXfemModel model;
  TipBody(kerf::TetMesh m, std::vector<kerf::TriangleSurface> surfaces, const kerf::LinearMaterial& material,
          kerf::TipEnrichmentRule rule, double radius, kerf::FrontRule front_rule = kerf::FrontRule::collapsed, int front_points = 0,
          int blending_degree = 6, int blending_depth = 3, kerf::BlendingCorrection blending = kerf::BlendingCorrection::none)
      : mesh(std::move(m)), cuts(std::move(surfaces)), pieces(kerf::cut_mesh_into_pieces(mesh, cuts)),
        fronts(kerf::find_crack_fronts(mesh, cuts)), branch(kerf::make_branch_enrichment(mesh, pieces, fronts, rule, radius, blending)),
        functions{branch, fronts, front_rule, front_points, blending_degree, blending_depth},
        model(mesh, material, pieces, branch.sign, subtets, &functions) {}
};

} // namespace support
