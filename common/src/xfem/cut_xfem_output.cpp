#include "kerf/xfem/cut_xfem_output.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/io/probes_csv.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/quadrature/piece_quadrature_rule.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <vector>

namespace kerf {

void sample_cut_xfem_probes(const std::filesystem::path& probes_in, const std::filesystem::path& probes_out,
                            const CutXfemModel& model, const Eigen::VectorXd& u, std::ostream* warnings) {
  sample_tet_field_probes(
      probes_in, probes_out, model.mesh(), [&](Eigen::Index t, const Eigen::Vector3d& x) { return model.displacement_at(u, t, x); },
      warnings);
}

void write_cut_xfem_vtu(const std::filesystem::path& file, const CutXfemModel& model, const Eigen::VectorXd& u) {
  const TetMesh& mesh = model.mesh();
  const MeshPieces& pieces = model.pieces();
  std::vector<Eigen::Vector3d> points, displacements;
  std::vector<std::array<int, 4>> tets;
  std::vector<double> parent, piece_of_tet;
  std::vector<int> shared_point(static_cast<std::size_t>(mesh.num_nodes()), -1);

  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const int e = pieces.entry[static_cast<std::size_t>(t)];
    // A tet with branch functions is drawn cell by cell even as one piece: the partial cut
    // inside a tet the front crosses opens there (chapter 5).
    const bool branch = model.has_branch_functions(t);
    if (!model.integrated_by_pieces(t) || e < 0 || (pieces.num_pieces(t) == 1 && !branch)) {
      // Drawn whole: corners shared with the neighbours, displaced by the tet's one field
      // (at a corner that is the node's own u_i, or u_i + a_k where an enrichment is 1).
      const Eigen::MatrixX3d u_p = model.phantom_displacements(u, t, 0);
      std::array<int, 4> tet{};
      for (int a = 0; a < 4; ++a) {
        const int v = mesh.tets(t, a);
        const bool own = model.phantom_node(t, 0, a) == v;
        int& shared = shared_point[static_cast<std::size_t>(v)];
        if (!own || shared < 0) {
          const int index = static_cast<int>(points.size());
          points.push_back(mesh.nodes.row(v).transpose());
          displacements.push_back(u_p.row(a).transpose());
          if (own) shared = index;
          tet[static_cast<std::size_t>(a)] = index;
        } else {
          tet[static_cast<std::size_t>(a)] = shared;
        }
      }
      tets.push_back(tet);
      parent.push_back(static_cast<double>(t));
      piece_of_tet.push_back(-1.0);
      continue;
    }
    const TetPieces& tp = pieces.tets[static_cast<std::size_t>(e)];
    for (int p = 0; p < tp.num_pieces(); ++p) {
      const Eigen::MatrixX3d u_p = model.phantom_displacements(u, t, p);
      for (const int c : tp.pieces[static_cast<std::size_t>(p)].cells) {
        // The side of the cut the cell lies on, for the branch function F_1 at its vertices on
        // the cut (two-valued there): from its centre, behind the front; none ahead of it.
        int side = 0;
        if (branch) {
          const FrontPolar polar = model.crack_tip()->fronts.polar(convex_cell_inner_point(tp.cells[static_cast<std::size_t>(c)]));
          if (polar.x_a < 0.0) side = polar.x_b > 0.0 ? 1 : -1;
        }
        for (const Eigen::Matrix<double, 4, 3>& sub : convex_cell_tetrahedra(tp.cells[static_cast<std::size_t>(c)])) {
          std::array<int, 4> tet{};
          for (int k = 0; k < 4; ++k) {
            const Eigen::Vector3d x = sub.row(k).transpose();
            tet[static_cast<std::size_t>(k)] = static_cast<int>(points.size());
            points.push_back(x);
            Eigen::Vector3d value = (model.shape_values(t, x).transpose() * u_p).transpose();
            for (const auto& [node, phi] : model.branch_values_on_side(t, x, side)) value += phi * u.segment<3>(3 * node);
            displacements.push_back(value);
          }
          tets.push_back(tet);
          parent.push_back(static_cast<double>(t));
          piece_of_tet.push_back(static_cast<double>(p));
        }
      }
    }
  }

  TetMesh drawn;
  drawn.nodes.resize(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixXd displacement(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    drawn.nodes.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    displacement.row(static_cast<Eigen::Index>(i)) = displacements[i].transpose();
  }
  drawn.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  Eigen::MatrixXd parent_field(static_cast<Eigen::Index>(tets.size()), 1), piece_field(static_cast<Eigen::Index>(tets.size()), 1);
  for (std::size_t i = 0; i < tets.size(); ++i) {
    for (int k = 0; k < 4; ++k) drawn.tets(static_cast<Eigen::Index>(i), k) = tets[i][static_cast<std::size_t>(k)];
    parent_field(static_cast<Eigen::Index>(i), 0) = parent[i];
    piece_field(static_cast<Eigen::Index>(i), 0) = piece_of_tet[i];
  }
  write_vtu(file, drawn, {{"displacement", displacement}}, {{"parent_tet", parent_field}, {"piece", piece_field}});
}

void write_piece_moments_csv(const std::filesystem::path& file, const TetMesh& mesh, const MeshPieces& pieces,
                             const PieceRuleFunction& rule) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!out) throw InputError(file.string(), "write", "cannot open the file for writing");
  out << "element,piece,volume,mx,my,mz,mxx,myy,mzz,mxy,myz,mxz\n";
  const int degree = stiffness_and_load_degree(mesh.order());
  char line[512];
  for (std::size_t e = 0; e < pieces.tets.size(); ++e) {
    const TetPieces& tp = pieces.tets[e];
    if (tp.state != SurfaceCutState::completely_cut && tp.state != SurfaceCutState::partially_cut) continue;
    const int t = pieces.entry_tet[e];
    const Eigen::Matrix<double, 4, 3> X = tet_corners(mesh, t);
    for (int p = 0; p < tp.num_pieces(); ++p) {
      // The moments are of degree <= 2: a rule of the model's degree is exact for them if it
      // is exact at all (Tet4's degree 1 is raised to 2 here).
      const PieceQuadratureRule r = rule(X, tp, p, std::max(degree, 2));
      const Eigen::Matrix<double, 10, 1> m = piece_moments(r);
      std::snprintf(line, sizeof line, "%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, p, m[0], m[1], m[2],
                    m[3], m[4], m[5], m[6], m[7], m[8], m[9]);
      out << line;
    }
  }
  if (!out) throw InputError(file.string(), "write", "writing failed (disk full?)");
}

} // namespace kerf
