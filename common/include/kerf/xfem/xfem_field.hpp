/// @file xfem_field.hpp
/// @brief The enriched displacement field u(x) = sum Phi_i u_i + sum Phi_i Psi_i a_i (Schoch et al. eq. 42) at points,
///        for probes and errors, and the cut body written piece by piece so that ParaView shows the gap (Figs. 7-8).
#pragma once

#include "kerf/xfem/xfem_model.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <ostream>

namespace kerf {

/// The side of the cut (+1 above, -1 below) on which the point x of tet t lies: the tet's side
/// if it is not cut, otherwise the sign of the interpolated level set sum Phi_i(x) Lambda_i,
/// with a point on the cut counting as above (as a node on it does, eqs. 58-59).
int side_of_point(const XfemModel& model, Eigen::Index t, const Eigen::Vector3d& x);

/// u(x) of eq. 42 at the point x of tet t as the piece on side `side` sees it:
/// sum Phi_i(x) u_side,i, the linear field of that side's corner values (eq. 66).
Eigen::Vector3d xfem_displacement_on_side(const XfemModel& model, const Eigen::VectorXd& u, Eigen::Index t,
                                          const Eigen::Vector3d& x, int side);

/// u(x) of eq. 42 at the point x of tet t, on the side where x lies (side_of_point).
Eigen::Vector3d xfem_displacement(const XfemModel& model, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x);

/// u(x) at every row of `points` (#P by 3); rows outside the mesh get NaN and are counted.
Eigen::MatrixXd xfem_displacement_at(const XfemModel& model, const Eigen::VectorXd& u, const Eigen::MatrixXd& points,
                                     Eigen::Index& num_outside);

/// The probe contract for a cut body: as sample_probes, with each point's displacement taken on
/// the side of the cut where the point lies.
void sample_xfem_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out, const XfemModel& model,
                        const Eigen::VectorXd& u, std::ostream* warnings);

/// Writes the cut body as ParaView should see it (Schoch et al. section 5.2, "Postprocessing", and
/// Figs. 7-8): tets without enriched corners as they are, sharing their nodes; every tet with
/// an enriched corner as its pieces, the sub-tets above and below the cut, each with its own
/// points displaced by its side's field. The gap then opens where the enriched DOFs say it
/// does. Point field "displacement"; cell fields "side" (0 plain, +1 above, -1 below) and
/// "parent_tet".
void write_xfem_vtu(const std::filesystem::path& file, const XfemModel& model, const Eigen::VectorXd& u);

} // namespace kerf
