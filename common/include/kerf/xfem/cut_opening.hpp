/// @file cut_opening.hpp
/// @brief How far a cut has opened: the jump of the XFEM displacement across the cut surface, integrated over it.
///
/// An XFEM field is discontinuous across the cut where the enrichments let it be. Its jump at a
/// point X of the cut, with n the unit normal there,
///
///   [[u]](X) = u(X + eps n) - u(X - eps n)   (eps -> 0),
///
/// is how far the two lips have moved apart; its normal part [[u]] . n > 0 is an opening, < 0
/// the lips pressed through each other (no contact keeps them apart, Paulus section 6). Swapping
/// n swaps the two points, so [[u]] . n does not depend on how the cut's triangles are oriented.
/// Integrated over the cut, the normal jump is the volume of the wound's gap,
///
///   V_gap = int_cut [[u]] . n dA  ~  sum_s A_s [[u]](c_s) . n_s,
///
/// and V_gap / A_cut the mean opening. The sum is the midpoint rule on sub-triangles s: each cut
/// triangle split into m^2 similar ones, m = ceil(longest edge / spacing), so that the sample
/// points are about `spacing` apart however large the blade's quads are. Chapter 7's sinusoidal cut (Paulus section 5.3) charts
/// these against time; Paulus show the opened wound in pictures only (their Fig. 10).
///
/// Where the cut is not yet a discontinuity (a tet the blade has not crossed: its nodes are not
/// enriched, Koschier section 8) the field is continuous and the jump is eps times the strain,
/// so eps must be small against the tets: the caller gives it. A sub-triangle whose two points do
/// not both lie in the mesh (the part of a blade's sweep outside the organ) is left out, and its
/// area is not counted in A_cut: A_cut is the cut's area inside the body to within the area of
/// the sub-triangles its boundary crosses (about the boundary's length times spacing).
#pragma once

#include "kerf/mesh/point_locator.hpp"
#include "kerf/mesh/triangle_surface.hpp"
#include "kerf/xfem/cut_xfem_model.hpp"

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace kerf {

/// The opening of a cut, summed over its triangles inside the body.
struct CutOpening {
  double area = 0.0;               ///< A_cut: the area of the sub-triangles whose both points lie in the mesh (m^2)
  double gap_volume = 0.0;         ///< V_gap = sum_s A_s [[u]](c_s) . n_s (m^3)
  double max_normal_opening = 0.0; ///< the largest [[u]] . n at a sample point (m; 0 if none was measured)
  double max_jump = 0.0;           ///< the largest |[[u]]| at a sample point (m)
  int samples = 0;                 ///< sub-triangles measured

  /// V_gap / A_cut (m), 0 for an empty measure.
  double mean_opening() const { return area > 0.0 ? gap_volume / area : 0.0; }
};

/// Where the opening is sampled: the centroid c_s of every sub-triangle of every cut triangle,
/// moved eps along the triangle's normal to either side, and the tets that hold the two points.
/// This depends on the cuts and the reference mesh only, not on the model: a growing cut keeps
/// the triangles it had, so update() finds the points of the triangles it has not seen and
/// keeps the rest (chapter 7 would otherwise locate every point of the cut again at each change
/// of topology, which costs more than the change itself).
class CutSamplePoints {
public:
  /// A point and the tet that holds it (-1: outside the mesh).
  struct Located {
    Eigen::Vector3d X;
    Eigen::Index tet;
  };
  /// A sub-triangle: its area, unit normal and the points either side of its centroid.
  struct Sample {
    double area;
    Eigen::Vector3d n;
    Located above; // c + eps n
    Located below; // c - eps n
  };

  /// @param locator a point locator of the reference mesh (kept by reference)
  /// @param spacing the largest distance (m) between sample points along a cut triangle's edges; > 0
  /// @param eps     the distance (m) of the two points from the cut; > 0, small against the tets
  /// @throws std::invalid_argument for spacing or eps <= 0 or not finite
  CutSamplePoints(const PointLocator& locator, double spacing, double eps);

  /// Samples `cuts` (the file's comment): a triangle already sampled, the same cut's same
  /// triangle with the same corners, keeps its points; the others are located.
  void update(const std::vector<TriangleSurface>& cuts);

  /// Calls visit(sample) for every sub-triangle of every cut, in the cuts' and triangles' order.
  template <class Visit>
  void for_each_sample(Visit visit) const {
    for (const auto& cut : cuts_)
      for (const SampledTriangle& triangle : cut)
        for (const Sample& sample : triangle.samples) visit(sample);
  }

private:
  struct SampledTriangle {
    Eigen::Matrix3d corners = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN()); // rows a, b, c; none yet: NaN
    std::vector<Sample> samples;
  };
  SampledTriangle sample_triangle(const Eigen::Matrix3d& corners) const;

  const PointLocator& locator_;
  double spacing_;
  double eps_;
  std::vector<std::vector<SampledTriangle>> cuts_; // per cut, per triangle
};

/// The opening of a field across the cuts: each sample point's field as weights of the model's
/// DOF nodes, so that the opening of a field costs a few dot products per point. The weights
/// change with the model (chapter 7 makes a new sampler at each change of topology), the field
/// at every step.
class CutOpeningSampler {
public:
  /// Samples `cuts` (the file's comment).
  /// @param model   the cut XFEM model whose fields will be measured (kept by reference)
  /// @param locator a point locator of model.mesh()
  /// @param cuts    the cut surfaces, in the reference configuration (m)
  /// @param spacing the largest distance (m) between sample points along a cut triangle's edges; > 0
  /// @param eps     the distance (m) of the two points from the cut; > 0, small against the tets
  /// @throws std::invalid_argument for spacing or eps <= 0 or not finite
  CutOpeningSampler(const CutXfemModel& model, const PointLocator& locator, const std::vector<TriangleSurface>& cuts, double spacing,
                    double eps);

  /// The opening on `model` at points already located (a sub-triangle with a point outside the
  /// mesh or outside every piece of its tet is left out).
  /// @param model  the cut XFEM model whose fields will be measured (kept by reference)
  /// @param points sample points located in model.mesh()
  CutOpeningSampler(const CutXfemModel& model, const CutSamplePoints& points);

  /// The opening of the field u (3 model.num_dof_nodes() values).
  /// @throws std::invalid_argument for u of the wrong size
  CutOpening measure(const Eigen::VectorXd& u) const;

  /// The number of sample points inside the mesh.
  int num_samples() const { return static_cast<int>(samples_.size()); }

private:
  // The field at a point as sum_k weight_k u(node_k): the shape functions of the phantom element
  // of the piece that holds the point, and the branch functions acting there (CutXfemModel::
  // displacement_at, unrolled once). A sample's two points' terms lie one after the other in
  // terms_: [above, below) at c + eps n, [below, end) at c - eps n.
  struct Sample {
    double area;       // of the sub-triangle (m^2)
    Eigen::Vector3d n; // its unit normal
    std::size_t above, below, end;
  };
  Eigen::Vector3d value(const Eigen::VectorXd& u, std::size_t begin, std::size_t end) const;
  const CutXfemModel& model_;
  std::vector<std::pair<int, double>> terms_; // (DOF node, weight)
  std::vector<Sample> samples_;
};

/// The opening of u across `cuts` in one call: CutOpeningSampler(...).measure(u).
CutOpening measure_cut_opening(const CutXfemModel& model, const PointLocator& locator, const Eigen::VectorXd& u,
                               const std::vector<TriangleSurface>& cuts, double spacing, double eps);

} // namespace kerf
