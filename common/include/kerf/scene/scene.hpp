/// @file scene.hpp
/// @brief The scene file (JSON): the user's description of a problem, read and validated.
#pragma once

#include "kerf/cut/blade_path.hpp"
#include "kerf/fem/linear_material.hpp"
#include "kerf/fracture/williams_field.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/node_region.hpp"
#include "kerf/scene/displacement_file.hpp"
#include "kerf/solve/linear_solver.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace kerf {

/// Where the mesh comes from: the box mesher, a file, or chapter 7's liver made by CGAL Mesh_3
/// (mesh/liver_mesh.hpp), and at which order.
struct MeshSpec {
  bool is_box = true;                  ///< true: "box"; false: "file" or "liver"
  bool is_liver = false;               ///< "liver": {"tets": n, "shape": s} (chapter 7)
  int liver_tets = 10000;              ///< the liver's target number of tets, in [1000, 1000000]
  LiverShape liver_shape = LiverShape::lobes; ///< "liver": {"shape": "lobes" | "wedge"}
  Eigen::Vector3d box_min{0, 0, 0};    ///< box lower corner (m)
  Eigen::Vector3d box_max{1, 1, 1};    ///< box upper corner (m)
  Eigen::Vector3i box_cells{1, 1, 1};  ///< hex cells along x, y, z (each split into 6 tets)
  std::filesystem::path file;          ///< mesh file, resolved against the scene's folder
  double scale = 1.0;                  ///< factor applied to the file's coordinates (to metres)
  int order = 1;                       ///< 1: Tet4, 2: Tet10 (mid-edge nodes added by Kerf)
};

/// u = displacement on the nodes of region, plus, if `has_rotation`, the rigid rotation by
/// `degrees` about `axis` through `center`: u(X) = (Q - I)(X - center) + displacement.
/// Or, if `from_file`, each node of the region takes its row of a displacement file.
/// Or, if `williams`, Williams's near-front field of the scene's one crack front, on every
/// side of the cut (scene_williams.hpp: the nodes' enrichments take it too, chapter 5).
struct DirichletSpec {
  NodeRegion region;
  Eigen::Vector3d displacement{0, 0, 0}; ///< m
  bool has_rotation = false;
  Eigen::Vector3d axis{0, 0, 1};         ///< rotation axis (normalised when read)
  double degrees = 0.0;                  ///< rotation angle, right-handed about axis
  Eigen::Vector3d center{0, 0, 0};       ///< a point on the axis (m)
  bool from_file = false;                ///< "displacement_file" given (read with the scene)
  DisplacementFile file;                 ///< its rows, when from_file
  bool williams = false;                 ///< "williams" given: the field of williams_K, plane strain
  StressIntensityFactors williams_K;     ///< Pa sqrt(m); K_I >= 0, each 0 when not given
  /// Dynamics (chapter 6): > 0 moves the nodes from rest to the displacement (and angle, or the
  /// file's values) along a smooth ramp over this many seconds (scene_prescribed_motion.hpp); 0
  /// holds them there from t = 0.
  double ramp_time = 0.0;

  /// The prescribed displacement of a node at reference position X, for an entry with a
  /// displacement and a rotation; an entry from a file gives each node its row instead
  /// (scene_dirichlet_nodes).
  Eigen::Vector3d displacement_at(const Eigen::Vector3d& X) const;
};

/// How the corotational chapters reach equilibrium (see quasi_static_solver.hpp).
struct QuasiStaticSpec {
  int load_steps = 10;
  int max_iterations = 40;
  double tolerance = 1e-9;
  std::string tangent = "consistent"; ///< "consistent" or "warped"
  std::string rotation = "automatic"; ///< "automatic", "higham" or "svd"
  std::string predictor = "previous"; ///< "previous" or "secant"
};

/// A total force spread uniformly by area over the boundary faces inside region.
struct TractionSpec {
  NodeRegion region;
  Eigen::Vector3d total_force{0, 0, 0}; ///< N
};

/// A cut: a rectangle (origin + two edges, chapter 3 on) or a triangle-mesh surface (chapter 4 on).
struct CutSpec {
  bool is_rectangle = true;
  Eigen::Vector3d origin{0, 0, 0}, edge1{0, 0, 0}, edge2{0, 0, 0}; ///< m
  std::filesystem::path surface;                                    ///< triangle mesh file (read_surface())
  double surface_scale = 1.0; ///< what the surface file's coordinates are multiplied by (0.001 for mm)
};

/// How the pieces of cut elements are integrated (chapter 4 on): `"quadrature": {"rule": ...}`.
struct QuadratureSpec {
  /// "subtets" (the default: Gauss rules on the sub-tetrahedra of each piece, exact for the
  /// polynomial integrands with positive weights inside the piece), "exact" (moment fitting on
  /// fixed points with the exact polyhedral moments: exact too, but with negative weights at
  /// points outside the piece, which the corotated Tet10 tangent does not survive),
  /// "moment_fitting", "volume_ratio" (Tet4 only), "lattice" or "regular".
  std::string rule = "subtets";
  bool given = false; ///< the scene has a "quadrature" field (chapters before 4 refuse it)
};

/// Crack-tip (branch) enrichment where a cut ends inside the body (chapter 5 on):
/// `"crack_tip": {"enrichment": "branch" | "none", "radius": r}`.
struct CrackTipSpec {
  /// "branch": the nodes near a cut's front get the four branch functions (Paulus section 3.4);
  /// "none": chapter 4's rule, the cut ends at the last row of enriched nodes.
  std::string enrichment = "branch";
  /// Geometric enrichment's radius (m): every node within it of a front is branch enriched,
  /// beside the nodes of the tets the front passes through (radius 0: those alone, the
  /// topological rule). Not given: the chapter's default (chapters/05_crack_tip says which).
  std::optional<double> radius;
  /// "none": Paulus's blending, the branch nodes' functions as they are; "corrected": Fries's
  /// ramp over the blending tets (branch_enrichment.hpp), linear model only.
  std::string blending = "none";
  /// Points per direction of each collapsed sub-tet in the tets a front crosses (n^3 per
  /// sub-tet, CrackTipFunctions::front_points); 0, not given: the model's default (4 on a Tet4,
  /// 6 on a Tet10). The rule is graded within a budget of 192 n^3 points per piece
  /// (front_quadrature.hpp), so fewer points make a cheaper, coarser rule: chapter 7's test of its
  /// rebuilds takes 2 (0.63 s a change at 1000 tets, 2.6 s with the default).
  int front_points = 0;
  /// How often at most the collapsed rule's grading may split one part (a collapsed sub-tet's
  /// face or edge near the front), CrackTipFunctions::front_grading, 0 to 12; default 12. The
  /// grading stops before that where the piece's estimated error meets its goal or its points
  /// reach the budget.
  int front_grading = 12;
  bool given = false; ///< the scene has a "crack_tip" field (chapters before 5 refuse it)
};

/// Time integration: "static", or "newmark" with its parameters (chapter 6 on).
struct TimeSpec {
  /// "static" (chapters 1-5), "newmark", "hht_alpha", "backward_euler" or "central_difference"
  std::string integrator = "static";
  double dt = 0.0;                          ///< s
  int steps = 0;
  double beta = 0.25, gamma = 0.5;          ///< Newmark parameters ("newmark" only)
  double alpha = -0.1;                      ///< HHT-alpha's alpha, in [-1/3, 0] ("hht_alpha" only)
  Eigen::Vector2d rayleigh{0.0, 0.0};       ///< damping C = alpha M + beta K
  /// "consistent" or a lumped scheme: "lumped" (the per-piece "bernstein", which gives every
  /// piece its own mass and centre of mass and lets a freed piece fall at g), "row_sum", "hrz",
  /// "virtual_tet" (the former "lumped": mass exact, weight at the element's centroid),
  /// "schoch_eq_81_82" (dynamics/lumped_mass.hpp). The default is "consistent", "lumped" for the
  /// central difference (which needs a diagonal mass).
  std::string mass = "consistent";
  /// The relative residual of each step's solve in the nonlinear Newmark step (corotational
  /// model, or moving clamps): the conjugate-gradient tolerance of its linear solves when the
  /// scene gives no "solver" (chapter 6 then steps with Jacobi-preconditioned CG), and where a
  /// "checked" or "newton" step stops iterating. 1e-3: on the cut soft block of
  /// figures/06_newmark/bench_newmark.md, within 1.3e-4 of a run solved exactly (1e-2 saves 14-23 %
  /// of the time but is only 5-13 times inside the 1 % bound).
  double tolerance = 1e-3;
  Eigen::Vector3d initial_velocity{0.0, 0.0, 0.0}; ///< m/s, the same at every node
  bool allow_unstable = false;              ///< run a Newmark pair outside 2 beta >= gamma >= 1/2, or an explicit step above its limit
  /// How a corotational Newmark step treats the rotations: "frozen" (rotations of the step's
  /// start, one linear solve, Mueller and Gross 2004), "checked" (the frozen step, solved again
  /// with the rotations of its iterate until its residual is within `tolerance`) or "newton"
  /// (Newton with the consistent tangent, to `tolerance`); RotationUpdate in
  /// nonlinear_newmark.hpp. Empty (not given): the chapter's default, "frozen" in chapter 6,
  /// "checked" in chapter 7, whose blade carves pieces that turn faster than a frozen step follows.
  std::string corotation;
  /// Chapter 8: the quasi-Newton iterations of a step (quasi_newton_newmark.hpp), >= 0; 0 iterates
  /// until the step's relative gradient is within `tolerance`. Not given: chapter 8's default (4).
  std::optional<int> iterations;
};

/// The "blade" field (chapter 7): the cutting edge's path in the world, and how finely its
/// sweep is recorded as the cut.
struct BladeSpec {
  bool given = false;
  std::vector<BladeKeyframe> path; ///< checked by BladePath: >= 2 keyframes, times increasing, edges of non-zero length
  /// The sheet grows by one quad when the edge has moved this far (m) since the sheet's last
  /// edge (Gutierrez's "collision quad" size; 0: the default, a quarter of the mesh's mean edge).
  double quad_length = 0.0;
  int samples = 9; ///< points along the edge pulled back into the reference configuration, >= 2
};

/// The "render" field (chapter 7): PNG frames of the visual surface, drawn off-screen.
struct RenderSpec {
  int every = 10;            ///< a frame every n steps (0: no frames)
  int width = 960, height = 720; ///< pixels
  double azimuth = -60, elevation = 35, zoom = 1.25; ///< the fixed camera (camera_view.hpp), degrees
  double visual_size = 0.003; ///< triangle size of the liver's visual surface (m)
  std::filesystem::path surface; ///< a visual surface file for a mesh read from a file (read_surface; empty: the mesh's boundary)
  double surface_scale = 1.0;    ///< what the surface file's coordinates are multiplied by
  bool animation = true;     ///< assemble the frames into an animated PNG
};

/// Everything a scene file says. Defaults are those of the book's scene reference page.
struct Scene {
  std::string name = "scene";            ///< used for output file names
  std::filesystem::path source;          ///< the file it was read from (for messages)
  MeshSpec mesh;
  LinearMaterial material;
  std::string model = "linear";          ///< "linear" or "corotational"
  std::vector<DirichletSpec> dirichlet;
  Eigen::Vector3d gravity{0, 0, 0};      ///< m/s^2
  std::vector<TractionSpec> traction;
  std::vector<CutSpec> cuts;
  QuadratureSpec quadrature;
  CrackTipSpec crack_tip;
  TimeSpec time;
  int output_every = 1;                  ///< write every n-th step
  SolverSettings solver;
  bool solver_given = false;             ///< the scene has a "solver" field (chapter 6's steps have their own default otherwise)
  QuasiStaticSpec quasi_static;
  BladeSpec blade;   ///< chapter 7
  RenderSpec render; ///< chapter 7
  bool render_given = false;
};

/// Reads and validates a scene file. Every problem (bad JSON, unknown field, wrong type, value
/// out of range, missing mesh file) is an InputError naming the file and the field path, e.g.
/// `beam.json: material.poisson: expected a number in (-1, 0.5 - 1e-6]: ...`.
Scene read_scene_file(const std::filesystem::path& file);

/// The same from JSON text; `source` names it in messages and relative paths are resolved
/// against `base_directory`.
Scene parse_scene(const std::string& json_text, const std::filesystem::path& source,
                  const std::filesystem::path& base_directory);

/// What a chapter has taught so far; a scene asking for more is rejected with a message that
/// says which chapter teaches it.
struct SceneFeatures {
  bool corotational = false;
  bool cuts = false;
  bool dynamics = false;
  bool cut_quadrature = false; ///< triangle-mesh cuts, several cuts, cut Tet10, the "quadrature" field (chapter 4)
  bool crack_tip = false;      ///< the "crack_tip" field (chapter 5)
  bool organ = false;          ///< the "liver" mesh, the "blade" and "render" fields (chapter 7)
  bool real_time = false;      ///< time.iterations (chapter 8)
  /// "williams" Dirichlet entries: chapter 5's static program prescribes them on the cut body's
  /// [u; a; b] (scene_williams.hpp); the dynamic chapters do not.
  bool williams = false;
};

/// Throws InputError if `scene` needs a method that is not in `taught`.
void require_features(const Scene& scene, const SceneFeatures& taught);

} // namespace kerf
