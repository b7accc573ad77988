#include "kerf/cut/split_box_along_height_field.hpp"

#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/tet10_from_tet4.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace kerf {

HeightFieldSplitMesh split_box_along_height_field(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Eigen::Vector3i& cells,
                                                  double z_c, const HeightField& h, int order) {
  if (order != 1 && order != 2)
    throw std::invalid_argument("split_box_along_height_field: the order must be 1 or 2, not " + std::to_string(order));
  if ((cells.array() < 1).any() || cells[2] < 2)
    throw std::invalid_argument("split_box_along_height_field: cells must be at least 1 in x and y and 2 in z");
  if (!((max - min).minCoeff() > 0.0)) throw std::invalid_argument("split_box_along_height_field: max must exceed min in x, y and z");
  if (!(z_c > min[2] && z_c < max[2]))
    throw std::invalid_argument("split_box_along_height_field: z_c must lie strictly between min z and max z");
  if (!h) throw std::invalid_argument("split_box_along_height_field: the height function is empty");
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  const Eigen::Index per_layer = static_cast<Eigen::Index>(nx + 1) * (ny + 1);
  const double below = z_c - min[2], above = max[2] - z_c;

  HeightFieldSplitMesh result;
  result.layer = std::clamp(static_cast<int>(std::lround((z_c - min[2]) / (max[2] - min[2]) * nz)), 1, nz - 1);
  const int layer = result.layer;

  // Step 1 and 2: the surface's vertices give the layer its positions and every column its x, y.
  const TriangleSurface surface = height_field_surface(h, z_c, min.head<2>(), max.head<2>(), cells.head<2>());
  std::vector<double> heights(static_cast<std::size_t>(per_layer));
  for (Eigen::Index s = 0; s < per_layer; ++s) {
    const double height = h(surface.vertices(s, 0), surface.vertices(s, 1));
    if (!(height > -below && height < above)) {
      std::ostringstream message;
      message << "split_box_along_height_field: h = " << height << " m at grid node " << s << " (x = " << surface.vertices(s, 0)
              << ", y = " << surface.vertices(s, 1) << ") is not strictly between -(z_c - min z) = " << -below
              << " and max z - z_c = " << above << ": the tets next to it would flip";
      throw std::invalid_argument(message.str());
    }
    heights[static_cast<std::size_t>(s)] = height;
  }

  TetMesh tet4 = make_box_mesh(min, max, cells);
  for (Eigen::Index v = 0; v < tet4.num_nodes(); ++v) {
    const Eigen::Index s = v % per_layer;
    const int k = static_cast<int>(v / per_layer);
    const double height = heights[static_cast<std::size_t>(s)];
    double z = 0.0;
    if (k == layer) z = surface.vertices(s, 2);
    else if (k == 0) z = min[2];
    else if (k == nz) z = max[2];
    else if (k < layer) z = min[2] + (below + height) * (double(k) / layer);
    else z = z_c + height + (above - height) * (double(k - layer) / (nz - layer));
    tet4.nodes.row(v) << surface.vertices(s, 0), surface.vertices(s, 1), z;
  }

  // Step 3: mid-edge nodes from the mapped corners, so the edges stay straight.
  const TetMesh mesh = order == 2 ? tet10_from_tet4(tet4) : tet4;

  // Step 4: the layer's nodes, the tets below, and the duplicates.
  const auto index = [](int v) { return static_cast<std::size_t>(v); };
  const auto corner_layer = [&](int v) { return static_cast<int>(v / per_layer); }; // v < #V of the Tet4 mesh
  std::vector<char> on_layer(index(static_cast<int>(mesh.num_nodes())), 0);
  for (Eigen::Index v = 0; v < tet4.num_nodes(); ++v) on_layer[index(static_cast<int>(v))] = corner_layer(static_cast<int>(v)) == layer;
  std::vector<char> tet_below(static_cast<std::size_t>(mesh.num_tets()), 0);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    // A Kuhn tet spans one cell layer: it is below the node layer iff a corner is.
    for (int c = 0; c < 4; ++c) tet_below[static_cast<std::size_t>(t)] |= corner_layer(mesh.tets(t, c)) < layer;
    if (order == 2)
      for (int e = 0; e < 6; ++e)
        if (on_layer[index(mesh.tets(t, tet_edge_corners[e][0]))] && on_layer[index(mesh.tets(t, tet_edge_corners[e][1]))])
          on_layer[index(mesh.tets(t, 4 + e))] = 1;
  }

  const Eigen::Index num_nodes = mesh.num_nodes();
  SplitMesh& split = result.split;
  std::vector<int> duplicate(index(static_cast<int>(num_nodes)), -1);
  for (Eigen::Index v = 0; v < num_nodes; ++v)
    if (on_layer[index(static_cast<int>(v))]) {
      duplicate[index(static_cast<int>(v))] = static_cast<int>(num_nodes) + split.duplicated_nodes++;
      split.duplicate_of.push_back(static_cast<int>(v));
    }
  split.mesh.nodes.resize(num_nodes + split.duplicated_nodes, 3);
  split.mesh.nodes.topRows(num_nodes) = mesh.nodes;
  for (int k = 0; k < split.duplicated_nodes; ++k)
    split.mesh.nodes.row(num_nodes + k) = mesh.nodes.row(split.duplicate_of[static_cast<std::size_t>(k)]);
  split.mesh.tets = mesh.tets;

  // The layer's faces, read off the tets below: their outward normals point up, into the part
  // above. Each triangle is rotated to start at its smallest vertex and the list sorted, which
  // is height_field_surface()'s order (cell after cell, the triangle through (i+1, j) first).
  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    if (!tet_below[static_cast<std::size_t>(t)]) continue;
    for (int a = 0; a < 4; ++a) {
      std::array<int, 3> face;
      bool in_layer = true;
      for (int c = 0; c < 3; ++c) {
        const int v = mesh.tets(t, tet_outward_face_corners[a][c]);
        in_layer = in_layer && corner_layer(v) == layer;
        face[static_cast<std::size_t>(c)] = static_cast<int>(v - layer * per_layer);
      }
      if (!in_layer) continue;
      std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
      faces.push_back(face);
    }
    for (int a = 0; a < mesh.nodes_per_tet(); ++a) {
      const int copy = duplicate[index(mesh.tets(t, a))];
      if (copy >= 0) split.mesh.tets(t, a) = copy;
    }
  }
  std::sort(faces.begin(), faces.end());
  result.cut_surface.vertices = tet4.nodes.middleRows(layer * per_layer, per_layer);
  result.cut_surface.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    result.cut_surface.triangles.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return result;
}

} // namespace kerf
