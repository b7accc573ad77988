/// @file cut_xfem_output.hpp
/// @brief What a run with triangle-mesh cuts writes: the pieces for ParaView, probe values, and the moments of every piece.
#pragma once

#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <ostream>

namespace kerf {

/// --probes IN --probes-out OUT for a cut body (DESIGN.md's contract): a warning counts the
/// points outside the mesh.
void sample_cut_xfem_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out,
                            const CutXfemModel& model, const Eigen::VectorXd& u, std::ostream* warnings);

/// The XFEM view of the cut body as a Tet4 .vtu: every tet that an enrichment splits is drawn
/// as the fan tets of its pieces' convex cells, each point displaced by its own piece's field,
/// so the cut opens in ParaView; every other tet as its four corners (for a Tet10 mesh its
/// field is drawn linear between corners). Cell data: `parent_tet` (0-based index in the mesh)
/// and `piece` (-1 for a tet drawn whole).
void write_cut_xfem_vtu(const std::filesystem::path& file, const CutXfemModel& model, const Eigen::VectorXd& u);

/// --moments-out FILE: one row per piece of every cut tet (completely cut: two or more pieces;
/// partially cut: one, the whole tet, which the cut enters without dividing it), header
/// `element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz`, the integrals over the piece of 1,
/// x, y, z, x^2, y^2, z^2, xy, yz, xz by `rule` (global coordinates, SI units), written with
/// 17 significant digits.
void write_piece_moments_csv(const std::filesystem::path& file, const TetMesh& mesh, const MeshPieces& pieces,
                             const PieceRuleFunction& rule);

} // namespace kerf
