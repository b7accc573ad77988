/// @file tip_enrichment_radius.hpp
/// @brief The default radius of geometric crack-tip enrichment: the one number a
///        scene's "crack_tip" may leave out.
///
/// Geometric enrichment (Laborde et al. 2005, Bechet et al. 2005) gives the branch functions to
/// every node within r_e of the front. The optimal rate needs r_e fixed while h shrinks; too large
/// an r_e costs 12 unknowns per node and the expensive near-front quadrature in every tet it
/// reaches. The rule: twice the mean edge of the tets the front crosses (two rings of elements),
/// chosen by chapter 5's convergence study (examples/05_convergence_study.cpp,
/// figures/05_crack_tip/convergence.md), which measures error against cost over radii: the
/// .cpp gives the numbers. A radius fixed in metres (the scene's "radius") is what restores the
/// optimal rate under refinement and what K by the interaction integral needs.
#pragma once

#include "kerf/cut/crack_front.hpp"
#include "kerf/mesh/tet_mesh.hpp"

namespace kerf {

/// The default r_e (m) for the fronts `fronts` in `mesh`.
/// @param mesh   Tet4 or Tet10 mesh
/// @param fronts the fronts (find_crack_fronts); 0 is returned when there are none
double default_tip_enrichment_radius(const TetMesh& mesh, const CrackFronts& fronts);

} // namespace kerf
