/// @file interaction_integral.hpp
/// @brief Stress intensity factors of a displacement field by the interaction integral in domain form, along a straight front.
///
/// The interaction integral of Moës, Dolbow and Belytschko (1999; after Shih and Asaro 1988)
/// superposes the field to measure (sigma, grad u) and an auxiliary Williams field (sigma2,
/// grad u2) of one mode with unit K (williams_field.hpp). In the front frame (a ahead,
/// b the cut normal, c along the front) and in its domain form with a weight q,
///     I = int_V ( sigma_ij du2_i/dx_a + sigma2_ij du_i/dx_a - W12 delta_aj ) dq/dx_j dV,
///     W12 = sigma_ij eps2_ij,
/// which for a q that vanishes on the domain's boundary equals the pointwise interaction
/// integral averaged along the front, int_front I(s) q(s) ds: the integrand's divergence is zero
/// because both fields are in equilibrium in a homogeneous material, and the traction-free flat
/// cut faces add nothing (sigma n = 0 there and delta_aj n_j = 0). For a straight front the
/// plane-strain auxiliary fields are exact 3D solutions, so this holds in 3D as it stands. Then
///     K_I = E' / 2 I_I / L_q,   K_II = E' / 2 I_II / L_q,   K_III = mu I_III / L_q,
/// with E' = E / (1 - nu^2) (plane strain) and L_q = int_front q ds.
///
/// The weight is q(x) = q_r(r) w(x_c): q_r = 1 for r <= inner_radius, falling as the smooth step
/// 1 - 10 s^3 + 15 s^4 - 6 s^5 (s from 0 to 1 across the ring; C2, so a Gauss rule across the
/// ring's edges errs only by what the third derivative's jump leaves) to 0 at outer_radius; w = 1 along the front
/// segment but for a ramp of length `end_ramp` at each end, where it falls to 0 by the same
/// step. Between the front and inner_radius q is flat across the front, so the integrand there
/// is zero (but for w's ramps): the elements next to the front, where a discrete field is worst,
/// do not enter, and no quadrature point meets the singularity. In w's ramps the term
/// (sigma_ic du2_i/dx_a + sigma2_ic du_i/dx_a) dq/dx_c does reach the front, where it grows like
/// 1/r for a field with shear content: the cells that may hold the front there are refined
/// towards it (`front_refinement_levels`), and every tet is cut by the planes x_c = const where
/// w changes its formula, so that no Gauss rule straddles a jump of w's curvature.
///
/// The field comes in through a callback that gives du_i/dx_j at a point of a tet, so any field
/// works: the FE field of a mesh, an XFEM field (the callback decides the side of the cut from
/// the point), or, in the tests, Williams's exact gradient. Each tet where q varies is
/// integrated by a Gauss rule on convex cells: a tet that the cut's plane (through the front,
/// normal b) crosses is first split along it, so that no rule straddles the cut, where the field
/// jumps, and no quadrature point lies on the plane.
#pragma once

#include "kerf/fem/linear_material.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <functional>

namespace kerf {

/// The domain of the integral: the front segment and the weight q = q_r(r) w(x_c).
struct InteractionDomain {
  StraightFrontFrame front;  ///< the front, its frame, and the origin from which x_c is measured
  double front_begin = 0.0;  ///< x_c of the segment's first end (m)
  double front_end = 1.0;    ///< x_c of its other end (m), > front_begin
  double end_ramp = 0.25;    ///< length of w's fall at each end (m), in (0, (front_end - front_begin) / 2]
  double inner_radius = 0.1; ///< q_r = 1 within this distance of the front (m), >= 0
  double outer_radius = 0.2; ///< q_r = 0 beyond it (m), > inner_radius
  int quadrature_degree = 4; ///< of the Gauss rule on each tet or cell (tet_quadrature_rule)
  /// How many times a cell that may hold the front within w's ramps is split into its 8
  /// children (towards the front only) before the Gauss rule: the integrand grows like 1/r there.
  int front_refinement_levels = 2;

  /// Throws std::invalid_argument naming the first field out of range.
  void check() const;
  /// q(x), and its gradient in global coordinates in `gradient`.
  double weight(const Eigen::Vector3d& x, Eigen::Vector3d& gradient) const;
  /// L_q = int_front q ds = int w dx_c = (front_end - front_begin) - end_ramp (each smooth step
  /// covers half its ramp).
  double weighted_front_length() const;
};

/// du_i/dx_j (3x3) of the field to measure at point x of tet t.
using DisplacementGradientAt = std::function<Eigen::Matrix3d(Eigen::Index t, const Eigen::Vector3d& x)>;

/// The integrand of I for the three auxiliary modes at one point: (I_I, I_II, I_III) densities,
/// to be multiplied by the quadrature weight and summed. For a caller with a quadrature of its
/// own (e.g. the pieces of cut tets); interaction_integral_sifs does the summing over a mesh.
Eigen::Vector3d interaction_integrand(const InteractionDomain& domain, const LinearMaterial& material, const Eigen::Vector3d& x,
                                      const Eigen::Matrix3d& grad_u);

/// K_I, K_II, K_III from the three integrals (I_I, I_II, I_III) summed over the domain.
StressIntensityFactors sifs_from_interaction_integrals(const Eigen::Vector3d& integrals, const LinearMaterial& material,
                                                       const InteractionDomain& domain);

/// The stress intensity factors, averaged along the segment with the weight w, of the field
/// whose gradient `grad_u` gives, on `mesh` (Tet4 or Tet10: only the corner nodes are used, so a
/// Tet10 must have straight edges). Throws std::invalid_argument for a bad domain, and when the
/// domain reaches outside the mesh: some tet on the mesh's boundary has a point where q > 0,
/// so the boundary term the domain form drops is not zero.
StressIntensityFactors interaction_integral_sifs(const TetMesh& mesh, const DisplacementGradientAt& grad_u, const LinearMaterial& material,
                                                 const InteractionDomain& domain);

} // namespace kerf
