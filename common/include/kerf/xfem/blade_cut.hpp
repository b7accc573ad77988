/// @file blade_cut.hpp
/// @brief The cut a moving blade grows while the body moves: its sheets in the reference configuration and the tets they have crossed.
///
/// One frame of the blade: its world edge is pulled back into the reference configuration
/// (blade_pull_back.hpp), offered to the sheet it is growing (cut/cut_sheet.hpp), and Gutierrez
/// and Ramos's semi-progressive test (cut/semi_progressive_cut.hpp) says which tets the new quads
/// have crossed. The model of the cut changes only when a tet becomes crossed. The blade's life
/// in the tissue, frame by frame:
/// - outside (no sample pulls back): its edge is remembered; if a sheet was growing, the blade has
///   left the body, and its edge closes the sheet, mapped by the last frame's anchor (a little
///   past the skin);
/// - entering: a new sheet starts with the edge of the frame before, mapped by this frame's
///   anchor, so that the sheet begins outside the skin and the cut is open there;
/// - inside: the edge is offered to the sheet;
/// - away (the hand lifted the blade): the sheet, if open, ends where it is, and the next contact
///   starts a new one at its own edge;
/// - put down in the tissue (no frame outside before it, as when the window's button is pressed
///   over the organ): a new sheet starts at this frame's pulled-back edge.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/cut/cut_sheet.hpp"
#include "kerf/cut/semi_progressive_cut.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/xfem/blade_pull_back.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace kerf {

/// The sheets a blade has left (one per pass through the body, the last perhaps still growing)
/// and the crossing state of every edge and tet of the mesh.
class BladeCut {
public:
  /// @param mesh        the reference mesh (kept by reference)
  /// @param quad_length how far the blade moves before the sheet keeps its edge (m); 0: a quarter
  ///        of the mesh's mean edge (Gutierrez and Ramos find "better responses if the size of
  ///        this quad is approximated to the average sizes of the elements"; a quarter keeps the
  ///        delay before a tet is cut below the tet)
  /// @param samples     points along the edge pulled back each frame, >= 2
  BladeCut(const TetMesh& mesh, double quad_length, int samples);

  /// One frame: the blade's world edge `world` (nullptr: away from the body) on the body `model`
  /// displaced by `u`; `last` forces the sheet to keep this edge (the path's end).
  /// @return whether a tet became crossed, so that the model must be rebuilt on surfaces()
  bool advance(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u, const BladeEdge* world, bool last);

  /// Every sheet with a triangle, as cut surfaces in the reference configuration.
  std::vector<TriangleSurface> surfaces() const;
  /// The box of the sheets' triangles added since the last call (only the tets it touches can
  /// have new pieces: recut_mesh_into_pieces), and empties it.
  Eigen::AlignedBox3d take_grown_box();

  const SemiProgressiveCut& crossing() const { return crossing_; }
  const std::vector<CutSheet>& sheets() const { return sheets_; }
  double quad_length() const { return quad_length_; }
  /// Whether the last sheet is growing: the blade is in the tissue.
  bool sheet_open() const { return sheet_open_; }

private:
  int samples_;
  SemiProgressiveCut crossing_;
  double quad_length_;
  std::vector<CutSheet> sheets_;
  bool sheet_open_ = false;
  std::optional<BladeEdge> outside_edge_; // the blade's last world edge before it entered
  ReferenceBlade last_blade_;
  Eigen::AlignedBox3d grown_;
};

/// Refuses a path whose first edge is already in the tissue (it would cut from nowhere): the cut
/// must open through the skin.
/// @throws InputError `file: blade.path: the blade's edge starts inside the body ...`
void require_blade_starts_outside(const CutXfemModel& model, const PointLocator& locator, const BladePath& path, int samples,
                                  const std::string& file);

} // namespace kerf
