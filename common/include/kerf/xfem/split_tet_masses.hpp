/// @file split_tet_masses.hpp
/// @brief The split tets' piece masses, integrated once and kept from one model to the next of a growing cut (chapter 7).
#pragma once

#include "kerf/quadrature/piece_quadrature_rule.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <vector>

namespace kerf {

/// cut_xfem_piece_masses() (cut_xfem_mass.hpp) at unit density for every tet, with the split
/// tets' pieces integrated once. Chapter 7 rebuilds its mass at every change of topology, and
/// integrating every split tet's pieces anew by the scene's rule was most of that: a tet that
/// kept its pieces (MeshPieces::kept_from_previous) keeps their masses, as CutXfemModel keeps
/// their points. The other tets' masses (whole tets: the element's; tets with branch functions:
/// over the model's own points) are cheap and computed when asked.
class SplitTetMasses {
public:
  /// Integrates the pieces of every split tet of `model` without branch functions, by `rule`
  /// for degree 2 (Tet4) or 4 (Tet10), or copies them from `before` (the masses of the model
  /// the cut grew from) where the tet kept its pieces.
  /// @throws std::invalid_argument if `before` is given and is of another mesh, or the pieces
  ///         do not say which tets were kept (make them with recut_mesh_into_pieces)
  SplitTetMasses(const CutXfemModel& model, const PieceRuleFunction& rule, const SplitTetMasses* before = nullptr);
  /// Tet t's piece masses at unit density: cut_xfem_piece_masses(model, t, 1, rule), to the bit.
  /// @param model the model these masses were made for (its tets' pieces)
  /// @throws std::invalid_argument if `model` has another number of tets
  std::vector<Eigen::MatrixXd> operator()(const CutXfemModel& model, Eigen::Index t) const;
  /// How many split tets the constructor integrated (the others were copied from `before`).
  Eigen::Index num_integrated() const { return integrated_; }

private:
  PieceRuleFunction rule_;
  std::vector<std::vector<Eigen::MatrixXd>> split_; // per tet: its pieces' masses if split; empty otherwise
  Eigen::Index integrated_ = 0;
};

} // namespace kerf
