/// @file visual_surface.hpp
/// @brief A fine visual surface embedded in the tet mesh and moved by the (XFEM) displacement of the piece each vertex lies in.
///
/// Gutierrez section 3.2 and Koschier section 7: the picture does not show the simulation mesh
/// but a finer surface (implicit_surface_mesh.hpp) whose vertices are tied, once, to the tets
/// of the reference configuration: vertex v lies in tet t_v at barycentric coordinates
/// lambda_v, x_v = sum_a lambda_v,a X_a. Each frame moves it by the displacement field there,
/// x_v + u(t_v, x_v); for XFEM the field of the piece of t_v that holds x_v, so a vertex on
/// either side of a cut follows its own side.
///
/// Vertices outside every tet. The fine surface is smoother than the tets' boundary, whose
/// triangles are chords of phi = 0: where the boundary is convex the fine surface pokes out
/// between the tets' corners: on the liver almost every visual vertex (1816 of 1900 at 3000
/// tets) lies a little outside, by about Mesh_3's facet distance of the tet mesh. Such a vertex
/// takes the tet of the closest boundary face and its barycentric coordinates in that tet, some
/// of them negative: the tet's linear field extrapolated a little, which moves it with its tet
/// exactly in a rigid or linear motion. We record the distance to that face; the tests and
/// figures/07_liver/visual_surface.md give the largest.
///
/// Triangles across a cut. Once a cut opens, a visual triangle whose corners lie on different
/// sides would stretch across the gap and hide it (and shade it as a wall). The minimal cure,
/// ours: drop every visual triangle with an edge that crosses the cut in the reference
/// configuration (untorn_triangles, keep_triangles). The gap then shows the background, or the far inside
/// of the surface, between ragged edges about one visual triangle wide; the cut faces
/// themselves are not drawn (Koschier section 7 builds them from the cut surface: an extension).
/// Chapter 8 splits the torn triangles along the cut instead (CutSkin).
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace kerf {

/// Where a visual vertex is tied to the tet mesh.
struct VisualVertexEmbedding {
  int tet = -1;                   ///< t_v, the tet that holds the vertex (or the nearest one)
  Eigen::Vector4d barycentric;    ///< lambda_v, summing to 1; all >= 0 (up to 1e-10) inside
  double distance = 0.0;          ///< 0 inside; outside, the distance to t_v's closest boundary face (m)
};

/// A displacement field the visual surface follows: u(t, X), the displacement (m) at the
/// reference point X of tet t. For XFEM, xfem_visual_displacement below.
using VisualDisplacement = std::function<Eigen::Vector3d(int tet, const Eigen::Vector3d& x_reference)>;

/// The fine surface and its embedding in a tet mesh (reference configuration).
class VisualSurface {
public:
  /// Embeds every vertex of `reference` in `mesh` (Tet4 or Tet10: the corners are used). Inside
  /// the mesh by PointLocator; outside it, the closest of the mesh's boundary faces, found among
  /// all of them (cost #outside vertices times #boundary faces: 0.2 s for 5124 outside vertices
  /// against the 1464 faces of the 10k-tet liver, 07_visual_surface_study).
  /// @param mesh      the tet mesh (kept by reference)
  /// @param reference the visual surface in the reference configuration
  VisualSurface(const TetMesh& mesh, TriangleSurface reference);

  /// The surface in the reference configuration.
  const TriangleSurface& reference() const { return reference_; }
  /// One embedding per vertex.
  const std::vector<VisualVertexEmbedding>& embedding() const { return embedding_; }
  /// sum_a lambda_v,a X_a: vertex v's position rebuilt from its tet's corners (m).
  Eigen::Vector3d embedded_position(Eigen::Index v) const;
  /// The number of vertices outside every tet.
  Eigen::Index num_outside() const;
  /// The largest distance of an outside vertex to its tet (m; 0 if none is outside).
  double largest_distance() const;

  /// The surface moved: vertex v at x_v + u(t_v, x_v), the triangles unchanged.
  TriangleSurface deform(const VisualDisplacement& u) const;

private:
  const TetMesh& mesh_;
  TriangleSurface reference_;
  std::vector<VisualVertexEmbedding> embedding_;
};

/// The triangles of `visual` (reference configuration) of which no edge crosses a triangle of
/// any of `cuts`: the triangles that would stretch across an opened cut are the others. Each
/// edge tests only the cut triangles near it (CutSurfaces::triangles_near_segment), so a rebuild
/// costs O(visual edges log(cut triangles)), not their product. A crossing is an
/// edge whose ends lie strictly on opposite sides of a cut triangle's plane and passes through it
/// (its edges included).
/// @return the indices of the triangles kept, increasing
std::vector<int> untorn_triangles(const TriangleSurface& visual, const CutSurfaces& cuts);

/// `surface` with only the triangles `keep` (same vertices): for a moved visual surface and
/// untorn_triangles of its reference.
TriangleSurface keep_triangles(const TriangleSurface& surface, const std::vector<int>& keep);

/// The skin of a cut organ, drawn without a gap at the wound's rim: the visual surface's untorn
/// triangles as they are, and each torn triangle that the cut crosses cleanly, through two of
/// its edges once each, split along the cut into a triangle on one side and a quad (two
/// triangles) on the other. The points where the cut crosses the two edges are doubled, one for
/// each side, and each moves with its own side's field, as do the split triangles' corners:
/// evaluated at a point of that side inside the body (the fine skin pokes out between the tets'
/// corners, and the field extrapolated from a cut tet's nearest point may be the other side's,
/// which is what makes the dropped triangles' edges ragged). The rim is then a line along the
/// cut instead of the saw teeth that dropping torn triangles leaves (untorn_triangles). A torn
/// triangle crossed otherwise (the cut ends inside it, or meets all three edges) is still dropped.
/// Each edge's first crossing is the one taken: an edge that two sheets cross, or one sheet twice,
/// is split as if crossed once.
class CutSkin {
public:
  /// @param visual  the visual surface (kept by reference)
  /// @param cuts    the cut surfaces (reference configuration, m)
  /// @param locator a point locator of the mesh the visual surface is embedded in
  CutSkin(const VisualSurface& visual, const CutSurfaces& cuts, const PointLocator& locator);

  /// The skin moved by u: the visual surface's vertices as VisualSurface::deform moves them but
  /// the split triangles' corners, which move with their side, then the rim's points (one for
  /// each crossed edge and side, shared by the two triangles of the edge); the untorn triangles,
  /// then the split ones.
  TriangleSurface deform(const VisualDisplacement& u) const;
  /// Torn triangles split along the cut, and torn triangles dropped.
  int num_split() const { return static_cast<int>(split_.size() / 3); }
  int num_dropped() const { return dropped_; }

private:
  // Where a point moves: as the field at `at`, a point of its side, in tet `tet`.
  struct Follower {
    int tet;
    Eigen::Vector3d at;
  };
  // A point X where the cut crosses a visual edge, for the side of the edge's vertex w: it
  // follows its follower, or, without one, moves as w does.
  struct RimPoint {
    Eigen::Vector3d X;
    std::optional<Follower> follower;
    int w;
  };
  const VisualSurface& visual_;
  std::vector<int> untorn_;
  std::vector<std::pair<int, Follower>> vertex_followers_; // the split triangles' vertices, moved with their side
  std::vector<RimPoint> rim_;
  std::vector<Eigen::Vector3i> split_; // corners: a visual vertex v, or rim point k as num_vertices + k
  int dropped_ = 0;
};

/// The XFEM field as the visual surface asks for it: model.displacement_at(u, t, X), the field of
/// the piece of t that holds X. A vertex just outside a cut tet lies in none of its pieces; it
/// takes the field at the nearest point of the tet in barycentric terms (the coordinates clamped
/// at 0 and rescaled to sum 1), on that point's piece. In a tet integrated whole the tet's field
/// is extrapolated, as VisualSurface does.
/// @param model the model (kept by reference)
/// @param u     its unknowns (kept by reference)
VisualDisplacement xfem_visual_displacement(const CutXfemModel& model, const Eigen::VectorXd& u);

} // namespace kerf
