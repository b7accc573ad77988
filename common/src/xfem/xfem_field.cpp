#include "kerf/xfem/xfem_field.hpp"

#include <Eigen/Dense>

#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/point_locator.hpp"

#include <limits>
#include <vector>

namespace kerf {

int side_of_point(const XfemModel& model, Eigen::Index t, const Eigen::Vector3d& x) {
  const Enrichment& e = model.enrichment();
  const TetSide tet_side = e.tet_side[static_cast<std::size_t>(t)];
  if (tet_side == TetSide::above) return +1;
  if (tet_side == TetSide::below) return -1;
  Eigen::Vector4d lambda;
  for (int a = 0; a < 4; ++a) lambda[a] = e.level_set.lambda[model.mesh().tets(t, a)];
  return model.shape_values(t, x).dot(lambda) >= 0.0 ? +1 : -1;
}

Eigen::Vector3d xfem_displacement_on_side(const XfemModel& model, const Eigen::VectorXd& u, Eigen::Index t,
                                          const Eigen::Vector3d& x, int side) {
  const Eigen::Vector4d phi = model.shape_values(t, x);
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int a = 0; a < 4; ++a) value += phi[a] * model.side_displacement(u, t, a, side);
  return value;
}

Eigen::Vector3d xfem_displacement(const XfemModel& model, const Eigen::VectorXd& u, Eigen::Index t, const Eigen::Vector3d& x) {
  return xfem_displacement_on_side(model, u, t, x, side_of_point(model, t, x));
}

Eigen::MatrixXd xfem_displacement_at(const XfemModel& model, const Eigen::VectorXd& u, const Eigen::MatrixXd& points,
                                     Eigen::Index& num_outside) {
  return evaluate_tet_field_at(
      model.mesh(), [&](Eigen::Index t, const Eigen::Vector3d& x) { return xfem_displacement(model, u, t, x); }, points, num_outside);
}

void sample_xfem_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out, const XfemModel& model,
                        const Eigen::VectorXd& u, std::ostream* warnings) {
  sample_tet_field_probes(
      probes_in, probes_out, model.mesh(), [&](Eigen::Index t, const Eigen::Vector3d& x) { return xfem_displacement(model, u, t, x); },
      warnings);
}

void write_xfem_vtu(const std::filesystem::path& file, const XfemModel& model, const Eigen::VectorXd& u) {
  const TetMesh& mesh = model.mesh();
  const Enrichment& e = model.enrichment();
  std::vector<Eigen::Vector3d> points, displacements;
  std::vector<std::array<int, 4>> tets;
  std::vector<double> side_of_tet, parent_of_tet;
  std::vector<int> shared_point(static_cast<std::size_t>(mesh.num_nodes()), -1);

  const auto add_piece = [&](Eigen::Index t, const Eigen::Matrix<double, 4, 3>& corners, int side) {
    std::array<int, 4> tet{};
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d x = corners.row(c).transpose();
      tet[static_cast<std::size_t>(c)] = static_cast<int>(points.size());
      points.push_back(x);
      displacements.push_back(xfem_displacement_on_side(model, u, t, x, side));
    }
    tets.push_back(tet);
    side_of_tet.push_back(side);
    parent_of_tet.push_back(static_cast<double>(t));
  };

  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const auto k = static_cast<std::size_t>(t);
    if (!model.has_enriched_corner(t)) {
      std::array<int, 4> tet{};
      for (int a = 0; a < 4; ++a) {
        const int v = mesh.tets(t, a);
        int& shared = shared_point[static_cast<std::size_t>(v)];
        if (shared < 0) {
          shared = static_cast<int>(points.size());
          points.push_back(mesh.nodes.row(v).transpose());
          displacements.push_back(u.segment<3>(3 * v));
        }
        tet[static_cast<std::size_t>(a)] = shared;
      }
      tets.push_back(tet);
      side_of_tet.push_back(0.0);
      parent_of_tet.push_back(static_cast<double>(t));
      continue;
    }
    if (e.tet_side[k] == TetSide::cut) {
      for (const auto& sub : e.pieces[k].above) add_piece(t, sub, +1);
      for (const auto& sub : e.pieces[k].below) add_piece(t, sub, -1);
    } else {
      add_piece(t, tet_corners(mesh, t), e.tet_side[k] == TetSide::below ? -1 : +1);
    }
  }

  TetMesh pieces;
  pieces.nodes.resize(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixXd displacement(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t p = 0; p < points.size(); ++p) {
    pieces.nodes.row(static_cast<Eigen::Index>(p)) = points[p].transpose();
    displacement.row(static_cast<Eigen::Index>(p)) = displacements[p].transpose();
  }
  pieces.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  Eigen::MatrixXd side(static_cast<Eigen::Index>(tets.size()), 1), parent(static_cast<Eigen::Index>(tets.size()), 1);
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (int c = 0; c < 4; ++c) pieces.tets(static_cast<Eigen::Index>(t), c) = tets[t][static_cast<std::size_t>(c)];
    side(static_cast<Eigen::Index>(t), 0) = side_of_tet[t];
    parent(static_cast<Eigen::Index>(t), 0) = parent_of_tet[t];
  }
  write_vtu(file, pieces, {{"displacement", displacement}}, {{"side", side}, {"parent_tet", parent}});
}

} // namespace kerf
