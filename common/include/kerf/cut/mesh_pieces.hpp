/// @file mesh_pieces.hpp
/// @brief Every tet of a mesh cut into its pieces by the cut surfaces, and which pieces of neighbouring tets the material joins.
#pragma once

#include "kerf/cut/cut_surfaces.hpp"
#include "kerf/cut/tet_pieces.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "kerf/mesh/tet_neighbours.hpp"

#include <array>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

namespace kerf {

/// Two pieces of neighbouring tets that touch through their shared face where no cut lies.
struct PieceGlue {
  int piece_a = 0; ///< the piece of the tet itself
  int piece_b = 0; ///< the piece of the tet across the face
};

/// The pieces of the tets a cut meets, each held by a shared, immutable pointer: the pieces of a
/// grown cut share those of the tets it kept with the pieces before it, instead of copying their
/// cells and polygons (recut_mesh_into_pieces). Read as a vector of TetPieces.
class SharedTetPieces {
public:
  using Items = std::vector<std::shared_ptr<const TetPieces>>;
  /// Walks the pieces as const TetPieces&.
  class const_iterator {
  public:
    explicit const_iterator(Items::const_iterator at) : at_(at) {}
    const TetPieces& operator*() const { return **at_; }
    const TetPieces* operator->() const { return at_->get(); }
    const_iterator& operator++() {
      ++at_;
      return *this;
    }
    bool operator==(const const_iterator& other) const { return at_ == other.at_; }
    bool operator!=(const const_iterator& other) const { return at_ != other.at_; }

  private:
    Items::const_iterator at_;
  };
  const TetPieces& operator[](std::size_t e) const { return *items_[e]; }
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  const_iterator begin() const { return const_iterator(items_.begin()); }
  const_iterator end() const { return const_iterator(items_.end()); }
  /// Appends pieces of one's own.
  void push_back(TetPieces pieces) { items_.push_back(std::make_shared<const TetPieces>(std::move(pieces))); }
  /// Appends pieces shared with another SharedTetPieces (share(e) of it).
  void push_back(std::shared_ptr<const TetPieces> pieces) { items_.push_back(std::move(pieces)); }
  /// The pointer to entry e, to share it.
  const std::shared_ptr<const TetPieces>& share(std::size_t e) const { return items_[e]; }

private:
  Items items_;
};

/// The mesh cut into pieces.
///
/// A tet that no cut triangle meets is one whole piece (piece 0) and has no entry. Across a face
/// between two such tets the material is whole. Across a face of a tet with an entry, the
/// pieces on either side are joined where their polygons on the face overlap outside the cut:
/// so a cut lying exactly in a mesh face separates the two tets, although neither is cut.
struct MeshPieces {
  /// The mesh's face and node adjacency: a property of the mesh, not of the cut, so a caller that
  /// cuts one mesh again and again (a growing cut) computes it once and shares it.
  std::shared_ptr<const TetNeighbours> neighbours;
  std::vector<int> entry;               ///< #T: index into `tets`, -1 for a tet no cut triangle meets
  std::vector<int> entry_tet;           ///< the tet of each entry
  SharedTetPieces tets;                 ///< the pieces of each tet with an entry
  /// Per entry and face (opposite corner a): the glued pairs across it, piece_a of this tet,
  /// piece_b of the tet across (empty on the boundary). Between two entries, each holds the
  /// face's pairs from its own side.
  std::vector<std::array<std::vector<PieceGlue>, 4>> glues;
  std::array<int, 4> state_counts{};    ///< tets in each SurfaceCutState (uncut ones included)
  std::vector<int> tets_per_surface;    ///< how many tets each cut surface meets (0: it misses the mesh)
  /// #T: 1 where recut_mesh_into_pieces kept the previous pieces of the tet (or its having none)
  /// instead of cutting it again, 0 where it cut it; all 0 from cut_mesh_into_pieces. What a model
  /// of the grown cut may reuse (CutXfemModel's constructor from an earlier model).
  std::vector<unsigned char> kept_from_previous;

  /// The number of pieces of tet t (1 for a tet without an entry).
  int num_pieces(Eigen::Index t) const {
    const int e = entry[static_cast<std::size_t>(t)];
    return e < 0 ? 1 : tets[static_cast<std::size_t>(e)].num_pieces();
  }
  /// The cut state of tet t.
  SurfaceCutState state(Eigen::Index t) const {
    const int e = entry[static_cast<std::size_t>(t)];
    return e < 0 ? SurfaceCutState::uncut : tets[static_cast<std::size_t>(e)].state;
  }
  int count(SurfaceCutState s) const { return state_counts[static_cast<std::size_t>(s)]; }
  /// The glued piece pairs across face a of tet t: (piece of t, piece of the tet across).
  /// For a face with no entry on either side, the one pair (0, 0).
  std::vector<PieceGlue> glued_across(Eigen::Index t, int a) const;
};

/// Cuts every tet of `mesh` (its four corners; Tet10 edges are straight) by `cuts`, and joins
/// the pieces of neighbouring tets.
MeshPieces cut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts);

/// The same with the mesh's adjacency given: tet_neighbours(mesh), made once for the mesh.
MeshPieces cut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts, std::shared_ptr<const TetNeighbours> neighbours);

/// The same for a cut that has grown: `previous` holds the pieces of the same mesh by an earlier
/// state of the same cuts, whose triangles `cuts` keeps, in the same surfaces with the same
/// numbers, and adds to. A tet whose box misses `changed` (a box holding every triangle added
/// since) meets the same triangles as before, so its pieces are the previous ones and are
/// copied; so are those of a tet in the box that meets the same triangles as before and no other;
/// only the others are cut again. The glue is found anew for every tet with an entry
/// (it is cheap: faces of cut tets only). The result is that of cut_mesh_into_pieces, at the
/// cost of the changed region instead of the whole mesh: chapter 7 rebuilds after every tet
/// the blade crosses. Reuses previous.neighbours.
MeshPieces recut_mesh_into_pieces(const TetMesh& mesh, const CutSurfaces& cuts, const MeshPieces& previous,
                                  const Eigen::AlignedBox3d& changed);

} // namespace kerf
