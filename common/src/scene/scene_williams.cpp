#include "kerf/scene/scene_williams.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/fracture/williams_branch_coefficients.hpp"

#include <sstream>
#include <stdexcept>

namespace kerf {

namespace {

/// The side of the cut piece p of tet t lies on: the cut_side of its first face on a cut (+1
/// above, -1 below), 0 for a piece that touches no cut (or a tet without pieces).
int piece_side(const MeshPieces& pieces, Eigen::Index t, int p) {
  const int entry = pieces.entry[static_cast<std::size_t>(t)];
  if (entry < 0) return 0;
  for (const PieceBoundaryPolygon& face :
       pieces.tets[static_cast<std::size_t>(entry)].pieces[static_cast<std::size_t>(p)].boundary)
    if (face.on_cut && face.cut_side != 0) return face.cut_side;
  return 0;
}

/// The sides of the parts of node v's support, a support the cut goes through: `home` for its
/// home part, enrichment[j] for the part of its j-th enrichment; 0 where no piece of the part
/// touches a cut.
struct PartSides {
  int home = 0;
  std::vector<int> enrichment;
};

PartSides part_sides(const CutXfemModel& model, int v) {
  const TetMesh& mesh = model.mesh();
  const MeshPieces& pieces = model.pieces();
  const SurfaceEnrichment& enrichment = model.enrichment();
  const int first = enrichment.first_enrichment[static_cast<std::size_t>(v)];
  if (!pieces.neighbours)
    throw std::logic_error(
        "williams_dirichlet_nodes: the pieces carry no node adjacency (cut_mesh_into_pieces makes it)");
  PartSides sides;
  sides.enrichment.assign(static_cast<std::size_t>(enrichment.enrichments_of(v)), 0);
  for (const int t : pieces.neighbours->node_tets[static_cast<std::size_t>(v)]) {
    if (enrichment.active[static_cast<std::size_t>(t)].empty()) continue; // no enrichment acts in t
    int a = 0;
    while (mesh.tets(t, a) != v) ++a;
    for (int p = 0; p < pieces.num_pieces(t); ++p) {
      const int side = piece_side(pieces, t, p);
      if (side == 0) continue;
      const int k = enrichment.active_enrichment(pieces, t, a, p);
      int& part = k < 0 ? sides.home : sides.enrichment[static_cast<std::size_t>(k - first)];
      if (part == 0) part = side;
    }
  }
  return sides;
}

} // namespace

StraightFrontFrame williams_front(const Scene& scene, const CrackFronts& fronts, const std::string& field) {
  const std::string file = scene.source.string();
  if (fronts.empty())
    throw InputError(file, field,
                     "no cut ends inside the mesh, so there is no crack front to measure Williams's field from");
  if (fronts.polylines.size() != 1)
    throw InputError(file, field,
                     "the cuts have " + std::to_string(fronts.polylines.size()) +
                         " fronts inside the mesh; Williams's field is that of one straight front");
  const FrontPolyline& line = fronts.polylines.front();
  if (line.closed)
    throw InputError(file, field, "the front is a closed loop; Williams's field is that of one straight front");
  const FrontSegment& first = line.segments.front();
  const Eigen::Vector3d origin = line.points.front(), along = (line.points.back() - origin).normalized();
  const double tolerance = 1e-9 * fronts.length();
  double off_line = 0.0, normal_turn = 0.0;
  for (const Eigen::Vector3d& x : line.points)
    off_line = std::max(off_line, ((x - origin) - (x - origin).dot(along) * along).norm());
  for (const FrontSegment& s : line.segments) normal_turn = std::max(normal_turn, (s.b - first.b).norm());
  if (off_line > tolerance || normal_turn > 1e-9) {
    std::ostringstream problem;
    problem << "the front is not straight (";
    if (off_line > tolerance)
      problem << "its points leave the line through its ends by up to " << off_line << " m";
    else
      problem << "the cut's normal along it turns by up to " << normal_turn;
    problem << "); Williams's field is that of a straight front";
    throw InputError(file, field, problem.str());
  }
  return make_straight_front_frame(origin, first.a, first.b);
}

Eigen::Vector3d williams_on_side(const StraightFrontFrame& front, const StressIntensityFactors& K,
                                 const LinearMaterial& material, const Eigen::Vector3d& x, int side) {
  const Eigen::Vector3d u = williams_displacement(front, K, material, x);
  if (side == 0 || front.local(x)[0] >= 0.0) return u; // ahead of the front: one value
  const int atan2_side = front_polar(front, x).theta > 0.0 ? 1 : -1;
  return side == atan2_side ? u : Eigen::Vector3d(-u); // theta continued by -+ 2 pi across the face
}

std::vector<DirichletNodes> williams_dirichlet_nodes(const CutXfemModel& model, const StraightFrontFrame& front,
                                                     const StressIntensityFactors& K, const LinearMaterial& material,
                                                     const std::vector<int>& nodes, double lambda) {
  const TetMesh& mesh = model.mesh();
  const SurfaceEnrichment& enrichment = model.enrichment();
  const CrackTipFunctions* tip = model.crack_tip();
  const auto num_nodes = static_cast<int>(mesh.num_nodes());
  const std::array<Eigen::Vector3d, 4> c = williams_branch_coefficients(front, K, material);
  std::vector<DirichletNodes> conditions;
  for (const int v : nodes) {
    const Eigen::Vector3d x = mesh.nodes.row(v).transpose();
    // The sides of the parts of a node with sign enrichments: its support is cut through, so
    // each part lies on one side. A support the front enters is one part that wraps around the
    // front, with pieces on both sides: its node takes atan2's side, except a branch node on
    // the cut, whose F_l(x_v) is taken above (BranchEnrichment::cut_side), and u_v must be the
    // field on that same side for the shifted functions to add up to the field.
    const int slot = tip ? tip->enrichment.branch_slot[static_cast<std::size_t>(v)] : -1;
    const PartSides sides = enrichment.enrichments_of(v) > 0 ? part_sides(model, v) : PartSides{};
    int home = sides.home;
    if (home == 0 && slot >= 0) home = tip->enrichment.cut_side[static_cast<std::size_t>(v)];
    const Eigen::Vector3d u_home = williams_on_side(front, K, material, x, home);
    conditions.push_back({{v}, lambda * u_home});
    const int first = enrichment.first_enrichment[static_cast<std::size_t>(v)];
    for (int j = 0; j < enrichment.enrichments_of(v); ++j) {
      const Eigen::Vector3d u_part =
          williams_on_side(front, K, material, x, sides.enrichment[static_cast<std::size_t>(j)]);
      conditions.push_back({{num_nodes + first + j}, lambda * (u_part - u_home)});
    }
    if (slot >= 0)
      for (int l = 0; l < 4; ++l)
        conditions.push_back(
            {{static_cast<int>(model.branch_dof_node(slot)) + l}, lambda * c[static_cast<std::size_t>(l)]});
  }
  return conditions;
}

std::optional<SceneWilliamsError> scene_williams_error(const Scene& scene, const CutXfemModel& model,
                                                       const CrackFronts& fronts, const Eigen::VectorXd& u) {
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i) {
    const DirichletSpec& spec = scene.dirichlet[i];
    if (!spec.williams) continue;
    const StraightFrontFrame front = williams_front(scene, fronts, "dirichlet[" + std::to_string(i) + "].williams");
    const auto exact = [&](const Eigen::Vector3d& x) {
      return williams_displacement(front, spec.williams_K, scene.material, x);
    };
    const auto exact_gradient = [&](const Eigen::Vector3d& x) {
      return williams_displacement_gradient(front, spec.williams_K, scene.material, x);
    };
    return SceneWilliamsError{i, cut_xfem_field_error(model, scene.material, u, fronts, exact, exact_gradient)};
  }
  return std::nullopt;
}

} // namespace kerf
