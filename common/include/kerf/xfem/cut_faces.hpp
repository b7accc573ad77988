/// @file cut_faces.hpp
/// @brief The faces of an opened cut, as triangles moved with the piece each lies on: what the picture shades inside the wound.
///
/// Every piece of a split tet has polygons on the cut (tet_pieces.hpp: PieceBoundaryPolygon with
/// on_cut). Moved by their own piece's field (the phantom element, plus the branch functions
/// where they act) the polygons of the two sides part as the cut opens, and together they are the
/// two walls of the wound: Koschier section 7 duplicates the cut surface once per side and maps
/// each copy with its side's field; the pieces' polygons are those copies, already clipped to the
/// body and split along the tets. Drawn in their own colour beside the visual surface
/// (visual_surface.hpp), they close the gap that dropping the torn visual triangles leaves.
///
/// Tets the front passes through are integrated whole (one piece), so the last stretch of a cut
/// before its front has no walls drawn: there the cut has not opened (chapter 4's enrichment), or
/// opens by the branch functions only, which the visual surface shows.
#pragma once

#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>

namespace kerf {

/// The cut's faces of every split tet's pieces, fanned into triangles, in the world: each
/// corner X at X + u_p(X) with u_p its piece's field. Counter-clockwise seen from the piece's
/// outside, so each wall faces into the gap.
/// @param model the model
/// @param u     its DOFs (3 model.num_dof_nodes())
TriangleSurface cut_face_surface(const CutXfemModel& model, const Eigen::VectorXd& u);

} // namespace kerf
