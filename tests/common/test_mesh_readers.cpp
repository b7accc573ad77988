// Tests of the mesh readers (Gmsh 1/2/4.1, VTK legacy and XML, Medit) and of the VTU/PVD writer.
//
// Every test writes its own small files into a fresh scratch folder: a unit cube split into
// six tets, two tets sharing a face, and their Tet10 versions. We check what comes back
// (counts, coordinates, connectivity, the Tet10 node order) and that every malformed variant
// is refused with a one-line InputError naming the file. Tet10 files with a curved edge are
// straightened with a warning; misnumbered or folded Tet10 are refused, naming the element.

#include "kerf/app/input_error.hpp"
#include "kerf/fem/tet_quadrature.hpp"
#include "kerf/fem/tet_shape_functions.hpp"
#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/read_gmsh.hpp"
#include "kerf/mesh/read_medit.hpp"
#include "kerf/mesh/read_mesh.hpp"
#include "kerf/mesh/read_vtk.hpp"
#include "kerf/mesh/tet_mesh.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// A fresh folder under the system's temporary folder, removed again at the end of the test.
struct ScratchFolder {
  fs::path path; ///< the folder, which exists and is empty at the start of the test
  /// Creates a folder with a random name, so that tests running in parallel do not collide.
  ScratchFolder()
      : path(fs::temp_directory_path() /
             ("kerf-test-mesh-readers-" + std::to_string(std::random_device{}()))) {
    fs::create_directories(path);
  }
  /// Removes the folder and everything the test wrote into it.
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
};

/// Writes `text` to `file`, replacing what was there.
void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  REQUIRE(out.good());
}

/// The whole content of `file`, bytes as they are.
std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The unit cube cut along its diagonal 0-7 into six positively oriented tets (node i sits at
/// x = i&1, y = (i>>1)&1, z = (i>>2)&1).
kerf::TetMesh unit_cube() {
  kerf::TetMesh mesh;
  mesh.nodes.resize(8, 3);
  for (int i = 0; i < 8; ++i) mesh.nodes.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  mesh.tets.resize(6, 4);
  mesh.tets << 0, 1, 3, 7, //
      0, 5, 1, 7,          //
      0, 3, 2, 7,          //
      0, 2, 6, 7,          //
      0, 4, 5, 7,          //
      0, 6, 4, 7;
  return mesh;
}

/// Two tets sharing the face 1-2-3, volumes 1/6 and 1/3.
kerf::TetMesh two_tets() {
  kerf::TetMesh mesh;
  mesh.nodes.resize(5, 3);
  mesh.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, 1, 2, 3, 4;
  return mesh;
}

/// The Tet10 version of a Tet4 mesh, one new node at the midpoint of every edge (shared
/// between the tets that share the edge), in Kerf's order kerf::tet_edge_corners.
kerf::TetMesh with_midpoints(const kerf::TetMesh& tet4) {
  std::map<std::pair<int, int>, int> node_of_edge;
  std::vector<Eigen::RowVector3d> extra;
  kerf::TetMesh mesh;
  mesh.tets.resize(tet4.num_tets(), 10);
  for (Eigen::Index t = 0; t < tet4.num_tets(); ++t) {
    for (int a = 0; a < 4; ++a) mesh.tets(t, a) = tet4.tets(t, a);
    for (int k = 0; k < 6; ++k) {
      const int i = tet4.tets(t, kerf::tet_edge_corners[k][0]);
      const int j = tet4.tets(t, kerf::tet_edge_corners[k][1]);
      const std::pair<int, int> key = std::minmax(i, j);
      auto found = node_of_edge.find(key);
      if (found == node_of_edge.end()) {
        found = node_of_edge.emplace(key, static_cast<int>(tet4.num_nodes() + extra.size())).first;
        extra.push_back(0.5 * (tet4.nodes.row(i) + tet4.nodes.row(j)));
      }
      mesh.tets(t, 4 + k) = found->second;
    }
  }
  mesh.nodes.resize(tet4.num_nodes() + static_cast<Eigen::Index>(extra.size()), 3);
  mesh.nodes.topRows(tet4.num_nodes()) = tet4.nodes;
  for (std::size_t e = 0; e < extra.size(); ++e)
    mesh.nodes.row(tet4.num_nodes() + static_cast<Eigen::Index>(e)) = extra[e];
  return mesh;
}

/// The node of `mesh` on the edge (i, j) of tet t, looked up by position, for writing Gmsh's
/// own edge order without relying on the reader's permutation table.
int midpoint_node(const kerf::TetMesh& mesh, Eigen::Index t, int i, int j) {
  const Eigen::RowVector3d middle =
      0.5 * (mesh.nodes.row(mesh.tets(t, i)) + mesh.nodes.row(mesh.tets(t, j)));
  for (int a = 4; a < 10; ++a)
    if ((mesh.nodes.row(mesh.tets(t, a)) - middle).norm() < 1e-14) return mesh.tets(t, a);
  FAIL("no mid-edge node on edge " << i << "-" << j);
  return -1;
}

/// The node list of tet t as Gmsh writes it: corners, then the mid-edge nodes of the edges
/// (0,1), (1,2), (2,0), (3,0), (3,2), (3,1) (Gmsh reference manual, "Node ordering").
std::vector<int> gmsh_tet_nodes(const kerf::TetMesh& mesh, Eigen::Index t) {
  std::vector<int> nodes = {mesh.tets(t, 0), mesh.tets(t, 1), mesh.tets(t, 2), mesh.tets(t, 3)};
  if (mesh.nodes_per_tet() == 10) {
    constexpr int gmsh_edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    for (const auto& edge : gmsh_edges) nodes.push_back(midpoint_node(mesh, t, edge[0], edge[1]));
  }
  return nodes;
}

/// Gmsh node tags with gaps, so that the reader has to renumber: node v gets tag 7 + 10 v.
long long tag_of(int v) { return 7 + 10LL * v; }

/// Gmsh format 1 ($NOD/$ELM, as SOFA's liver), with a point element the reader must skip.
std::string gmsh_v1(const kerf::TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "$NOD\n" << mesh.num_nodes() << "\n";
  for (int v = 0; v < mesh.num_nodes(); ++v)
    out << tag_of(v) << " " << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2)
        << "\n";
  out << "$ENDNOD\n$ELM\n" << mesh.num_tets() + 1 << "\n";
  out << "1 15 1 1 1 " << tag_of(0) << "\n"; // a point element, to be skipped
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const auto nodes = gmsh_tet_nodes(mesh, t);
    out << t + 2 << (nodes.size() == 10 ? " 11" : " 4") << " 1 1 " << nodes.size();
    for (const int v : nodes) out << " " << tag_of(v);
    out << "\n";
  }
  out << "$ENDELM\n";
  return out.str();
}

/// Gmsh format 2.2, with a $PhysicalNames section, a line and a triangle the reader must skip.
std::string gmsh_v2(const kerf::TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      << "$PhysicalNames\n1\n3 1 \"tissue\"\n$EndPhysicalNames\n"
      << "$Nodes\n" << mesh.num_nodes() << "\n";
  for (int v = 0; v < mesh.num_nodes(); ++v)
    out << tag_of(v) << " " << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2)
        << "\n";
  out << "$EndNodes\n$Elements\n" << mesh.num_tets() + 2 << "\n";
  out << "1 1 2 0 1 " << tag_of(0) << " " << tag_of(1) << "\n";                   // a line
  out << "2 2 2 0 1 " << tag_of(0) << " " << tag_of(1) << " " << tag_of(2) << "\n"; // a triangle
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const auto nodes = gmsh_tet_nodes(mesh, t);
    out << t + 3 << (nodes.size() == 10 ? " 11" : " 4") << " 2 1 1";
    for (const int v : nodes) out << " " << tag_of(v);
    out << "\n";
  }
  out << "$EndElements\n";
  return out.str();
}

/// Format 4.1, with the nodes in two blocks written in reverse order, so that the file order
/// differs from the tag order.
std::string gmsh_v4(const kerf::TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  const int n = static_cast<int>(mesh.num_nodes());
  const int first_block = n / 2;
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      << "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
      << "$Nodes\n2 " << n << " " << tag_of(0) << " " << tag_of(n - 1) << "\n";
  const std::pair<int, int> blocks[2] = {{n - 1, first_block}, {first_block - 1, 0}};
  for (const auto& [from, to] : blocks) {
    out << "3 1 0 " << from - to + 1 << "\n";
    for (int v = from; v >= to; --v) out << tag_of(v) << "\n";
    for (int v = from; v >= to; --v)
      out << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2) << "\n";
  }
  out << "$EndNodes\n$Elements\n2 " << mesh.num_tets() + 1 << " 1 " << mesh.num_tets() + 1 << "\n";
  out << "2 1 2 1\n1 " << tag_of(0) << " " << tag_of(1) << " " << tag_of(2) << "\n";
  out << "3 1 " << (mesh.nodes_per_tet() == 10 ? 11 : 4) << " " << mesh.num_tets() << "\n";
  for (int t = 0; t < mesh.num_tets(); ++t) {
    out << t + 2;
    for (const int v : gmsh_tet_nodes(mesh, t)) out << " " << tag_of(v);
    out << "\n";
  }
  out << "$EndElements\n";
  return out.str();
}

/// Legacy VTK, ASCII, with one extra triangle cell that the reader must skip.
std::string vtk_legacy(const kerf::TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "# vtk DataFile Version 3.0\nkerf test\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      << "POINTS " << mesh.num_nodes() << " double\n";
  for (int v = 0; v < mesh.num_nodes(); ++v)
    out << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2) << "\n";
  const int per_tet = mesh.nodes_per_tet();
  out << "CELLS " << mesh.num_tets() + 1 << " " << mesh.num_tets() * (per_tet + 1) + 4 << "\n";
  out << "3 0 1 2\n";
  for (int t = 0; t < mesh.num_tets(); ++t) {
    out << per_tet;
    for (int a = 0; a < per_tet; ++a) out << " " << mesh.tets(t, a);
    out << "\n";
  }
  out << "CELL_TYPES " << mesh.num_tets() + 1 << "\n5\n";
  for (int t = 0; t < mesh.num_tets(); ++t) out << (per_tet == 10 ? 24 : 10) << "\n";
  return out.str();
}

/// Medit ASCII, with a comment, a Triangles and a Corners section the reader must skip.
std::string medit(const kerf::TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "MeshVersionFormatted 2\n# written by the Kerf tests\nDimension\n3\n\nVertices\n"
      << mesh.num_nodes() << "\n";
  for (int v = 0; v < mesh.num_nodes(); ++v)
    out << mesh.nodes(v, 0) << " " << mesh.nodes(v, 1) << " " << mesh.nodes(v, 2) << " 0\n";
  out << "Triangles\n1\n1 2 3 5\nTetrahedra\n" << mesh.num_tets() << "\n";
  for (int t = 0; t < mesh.num_tets(); ++t)
    out << mesh.tets(t, 0) + 1 << " " << mesh.tets(t, 1) + 1 << " " << mesh.tets(t, 2) + 1 << " "
        << mesh.tets(t, 3) + 1 << " 1\n";
  out << "Corners\n2\n1 2\nEnd\n";
  return out.str();
}

/// The read mesh is the written one: same counts, and every tet has the same corner and
/// mid-edge positions (node numbers may differ when the file lists nodes in another order).
void check_same_mesh(const kerf::TetMesh& read, const kerf::TetMesh& expected) {
  REQUIRE(read.num_nodes() == expected.num_nodes());
  REQUIRE(read.num_tets() == expected.num_tets());
  REQUIRE(read.nodes_per_tet() == expected.nodes_per_tet());
  for (Eigen::Index t = 0; t < read.num_tets(); ++t)
    for (int a = 0; a < read.nodes_per_tet(); ++a)
      CHECK(read.nodes.row(read.tets(t, a)) == expected.nodes.row(expected.tets(t, a)));
}

/// After reading, node 4+k of every Tet10 must be the midpoint of the corners of edge k.
void check_tet10_order(const kerf::TetMesh& mesh) {
  REQUIRE(mesh.nodes_per_tet() == 10);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int k = 0; k < 6; ++k) {
      const Eigen::RowVector3d middle =
          0.5 * (mesh.nodes.row(mesh.tets(t, kerf::tet_edge_corners[k][0])) +
                 mesh.nodes.row(mesh.tets(t, kerf::tet_edge_corners[k][1])));
      CHECK((mesh.nodes.row(mesh.tets(t, 4 + k)) - middle).norm() < 1e-14);
    }
}

/// The message of the InputError `read` throws, or "" if it throws none.
std::string input_error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const kerf::InputError& error) {
    return error.what();
  }
  return "";
}

/// `file` is refused with a one-line InputError that names it and contains `expected`.
void check_refused(const fs::path& file, const std::string& expected) {
  CAPTURE(file);
  CHECK_THROWS_AS(kerf::read_mesh(file, nullptr), kerf::InputError);
  const std::string message = input_error_of([&] { kerf::read_mesh(file, nullptr); });
  CAPTURE(message);
  CHECK(message.find(file.string() + ": ") == 0);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find(expected) != std::string::npos);
}

/// Replaces the first occurrence of `from` in `text` by `to`, which must be there.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, "'" << from << "' is not in the test file");
  return text.replace(at, from.size(), to);
}

} // namespace

TEST_CASE("the test meshes are positively oriented") {
  for (const kerf::TetMesh& mesh : {unit_cube(), two_tets()}) {
    double volume = 0.0;
    for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
      CHECK(kerf::signed_tet_volume(mesh, t) > 0.0);
      volume += kerf::signed_tet_volume(mesh, t);
    }
    CHECK(volume == kerf_test::relative(mesh.num_tets() == 6 ? 1.0 : 0.5));
  }
}

TEST_CASE("read_mesh reads every format back: Tet4 and Tet10, counts, coordinates, connectivity") {
  ScratchFolder scratch;
  using Writer = std::function<std::string(const kerf::TetMesh&)>;
  const std::vector<std::pair<std::string, Writer>> formats = {
      {"v1.msh", gmsh_v1}, {"v2.msh", gmsh_v2}, {"v4.msh", gmsh_v4},
      {"legacy.vtk", vtk_legacy}, {"medit.mesh", medit}};
  for (const auto& [suffix, write] : formats) {
    for (const kerf::TetMesh& tet4 : {unit_cube(), two_tets()}) {
      for (const int order : {1, 2}) {
        if (order == 2 && suffix == "medit.mesh") continue; // Medit meshes are Tet4 only
        const kerf::TetMesh mesh = order == 1 ? tet4 : with_midpoints(tet4);
        const fs::path file = scratch.path / (std::to_string(mesh.num_tets()) + "tets-order" +
                                              std::to_string(order) + "-" + suffix);
        CAPTURE(file);
        write_text(file, write(mesh));
        std::ostringstream warnings;
        const kerf::TetMesh read = kerf::read_mesh(file, &warnings);
        CHECK(warnings.str().empty());
        check_same_mesh(read, mesh);
        if (order == 2) check_tet10_order(read);
      }
    }
  }
}

TEST_CASE("Gmsh readers renumber tags with gaps to 0-based indices in file order") {
  ScratchFolder scratch;
  const kerf::TetMesh mesh = two_tets();
  const fs::path v2 = scratch.path / "gaps.msh";
  write_text(v2, gmsh_v2(mesh));
  const kerf::TetMesh read = kerf::read_gmsh(v2, nullptr);
  CHECK(read.nodes == mesh.nodes);
  CHECK(read.tets == mesh.tets);

  // Format 4.1 file lists the nodes from the last to the first: the indices follow the file.
  const fs::path v4 = scratch.path / "reversed.msh";
  write_text(v4, gmsh_v4(mesh));
  const kerf::TetMesh reversed = kerf::read_gmsh(v4, nullptr);
  CHECK(reversed.nodes.row(0) == mesh.nodes.row(mesh.num_nodes() - 1));
  CHECK(reversed.tets(0, 0) == mesh.num_nodes() - 1);
}

TEST_CASE("write_vtu and read_vtk round-trip a Tet10 mesh with a point and a cell field") {
  ScratchFolder scratch;
  const kerf::TetMesh mesh = with_midpoints(unit_cube());
  const fs::path file = scratch.path / "new" / "folder" / "cube10.vtu"; // parents do not exist
  const kerf::PointField displacement{"displacement",
                                      Eigen::MatrixXd::Random(mesh.num_nodes(), 3)};
  const kerf::CellField material{"material", Eigen::MatrixXd::Constant(mesh.num_tets(), 1, 2.0)};
  kerf::write_vtu(file, mesh, {displacement}, {material});

  const std::string text = read_text(file);
  CHECK(text.find("Name=\"displacement\"") != std::string::npos);
  CHECK(text.find("Name=\"material\"") != std::string::npos);

  std::ostringstream warnings;
  const kerf::TetMesh read = kerf::read_vtk(file, &warnings);
  CHECK(warnings.str().empty());
  CHECK(read.nodes == mesh.nodes);
  CHECK(read.tets == mesh.tets);
  check_tet10_order(read);

  const fs::path tet4_file = scratch.path / "cube4.vtu";
  kerf::write_vtu(tet4_file, unit_cube(), {}, {});
  const kerf::TetMesh tet4 = kerf::read_mesh(tet4_file, nullptr);
  CHECK(tet4.nodes == unit_cube().nodes);
  CHECK(tet4.tets == unit_cube().tets);
}

TEST_CASE("write_vtu refuses fields of the wrong size and names a file it cannot write") {
  ScratchFolder scratch;
  const kerf::TetMesh mesh = two_tets();
  CHECK_THROWS_AS(kerf::write_vtu(scratch.path / "a.vtu", mesh,
                                  {{"u", Eigen::MatrixXd::Zero(mesh.num_nodes() + 1, 3)}}, {}),
                  std::invalid_argument);
  CHECK_THROWS_AS(kerf::write_vtu(scratch.path / "a.vtu", mesh, {},
                                  {{"m", Eigen::MatrixXd::Zero(mesh.num_tets() - 1, 1)}}),
                  std::invalid_argument);

  // A regular file where the parent folder should be: neither the folder nor the file can be made.
  write_text(scratch.path / "not-a-folder", "x");
  const fs::path file = scratch.path / "not-a-folder" / "out.vtu";
  CHECK_THROWS_AS(kerf::write_vtu(file, mesh, {}, {}), kerf::InputError);
  const std::string message = input_error_of([&] { kerf::write_vtu(file, mesh, {}, {}); });
  CHECK(message.find(file.string()) == 0);
  CHECK(message.find('\n') == std::string::npos);
}

TEST_CASE("write_pvd lists the frames with their times, relative to the .pvd's folder") {
  ScratchFolder scratch;
  const fs::path out = scratch.path / "run";
  const fs::path pvd = out / "series.pvd";
  kerf::write_pvd(pvd, {{0.0, out / "step_0000.vtu"}, {0.25, out / "frames" / "step_0001.vtu"}});
  const std::string text = read_text(pvd);
  CHECK(text.find("<VTKFile type=\"Collection\"") != std::string::npos);
  CHECK(text.find("timestep=\"0\" group=\"\" part=\"0\" file=\"step_0000.vtu\"") != std::string::npos);
  CHECK(text.find("timestep=\"0.25\" group=\"\" part=\"0\" file=\"frames/step_0001.vtu\"") !=
        std::string::npos);
  CHECK(text.find("</VTKFile>") != std::string::npos);
}

TEST_CASE("an inverted tet is reoriented with a warning") {
  ScratchFolder scratch;
  kerf::TetMesh inverted = two_tets();
  std::swap(inverted.tets(1, 1), inverted.tets(1, 2));
  REQUIRE(kerf::signed_tet_volume(inverted, 1) < 0.0);
  for (const auto& [name, text] : {std::pair{"inverted.msh", gmsh_v2(inverted)},
                                   std::pair{"inverted.mesh", medit(inverted)},
                                   std::pair{"inverted.vtk", vtk_legacy(inverted)}}) {
    const fs::path file = scratch.path / name;
    CAPTURE(file);
    write_text(file, text);
    std::ostringstream warnings;
    const kerf::TetMesh read = kerf::read_mesh(file, &warnings);
    CHECK(kerf::signed_tet_volume(read, 1) == kerf_test::relative(1.0 / 3.0));
    CHECK(warnings.str().find("1 inverted") != std::string::npos);
    CHECK(warnings.str().find(file.string()) != std::string::npos);
  }
}

TEST_CASE("malformed Gmsh files are refused with a one-line message naming the file") {
  ScratchFolder scratch;
  const std::string good = gmsh_v2(two_tets());
  const std::string good_v4 = gmsh_v4(two_tets());
  const std::string good_v1 = gmsh_v1(two_tets());
  const auto refused = [&](const std::string& name, const std::string& text,
                           const std::string& expected) {
    const fs::path file = scratch.path / name;
    write_text(file, text);
    check_refused(file, expected);
  };

  refused("truncated.msh", good.substr(0, good.find("$EndElements")), "truncated");
  refused("truncated-v4.msh", good_v4.substr(0, good_v4.find("$EndElements")), "truncated");
  refused("truncated-v1.msh", good_v1.substr(0, good_v1.find("$ENDELM")), "truncated");
  refused("empty.msh", "", "truncated");
  refused("too-few-nodes.msh", replaced(good, "$Nodes\n5\n", "$Nodes\n6\n"), "announces 6 nodes");
  refused("too-many-nodes.msh", replaced(good, "$Nodes\n5\n", "$Nodes\n4\n"), "$EndNodes");
  refused("too-few-elements.msh", replaced(good, "$Elements\n4\n", "$Elements\n5\n"),
          "announces 5 elements");
  refused("too-many-elements.msh", replaced(good, "$Elements\n4\n", "$Elements\n3\n"),
          "$EndElements");
  refused("wrong-count-v4.msh", replaced(good_v4, "$Nodes\n2 5 ", "$Nodes\n2 6 "), "6 nodes");
  refused("wrong-count-v1.msh", replaced(good_v1, "$ELM\n3\n", "$ELM\n2\n"), "$ENDELM");
  refused("hexahedron.msh", replaced(good, "\n3 4 2 1 1", "\n3 5 2 1 1 7 7 7 7"), "hexahedron");
  refused("prism-v4.msh", replaced(good_v4, "\n3 1 4 2\n", "\n3 1 6 2\n"), "prism");
  refused("unknown-type.msh", replaced(good, "\n3 4 2 1 1", "\n3 77 2 1 1"), "unknown Gmsh element type 77");
  refused("nan.msh", replaced(good, "\n17 1 0 0\n", "\n17 nan 0 0\n"), "node 1: coordinate is not a finite");
  refused("not-a-number.msh", replaced(good, "\n17 1 0 0\n", "\n17 one 0 0\n"), "line 11: expected a number for x");
  refused("unknown-node.msh", replaced(good, " 1 1 7 17 27 37\n", " 1 1 7 17 27 999\n"),
          "node tag 999 is not in the node section");
  refused("flat.msh", replaced(good, "\n47 1 1 1\n", "\n47 1 1 -1\n"), "element 1: tetrahedron has zero volume");
  refused("binary.msh", replaced(good, "2.2 0 8", "2.2 1 8"), "binary");
  refused("v40.msh", replaced(good_v4, "4.1 0 8", "4 0 8"), "format 4 is not supported");
  refused("mixed.msh",
          replaced(good, "\n4 4 2 1 1 17 27 37 47\n", "\n4 11 2 1 1 17 27 37 47 7 7 7 7 7 7\n"),
          "mixes 4-node and 10-node");
  refused("not-gmsh.msh", "solid cube\n", "$MeshFormat");
  refused("no-elements.msh", good.substr(0, good.find("$Elements")), "no element section");
}

TEST_CASE("malformed Medit files are refused with a one-line message naming the file") {
  ScratchFolder scratch;
  const std::string good = medit(two_tets());
  const auto refused = [&](const std::string& name, const std::string& text,
                           const std::string& expected) {
    const fs::path file = scratch.path / name;
    write_text(file, text);
    check_refused(file, expected);
  };
  refused("truncated.mesh", good.substr(0, good.find("Tetrahedra") + 14), "truncated");
  refused("no-end.mesh", replaced(good, "End\n", ""), "truncated");
  refused("too-few-vertices.mesh", replaced(good, "Vertices\n5\n", "Vertices\n6\n"), "vertex 6");
  refused("too-many-vertices.mesh", replaced(good, "Vertices\n5\n", "Vertices\n4\n"),
          "unknown keyword");
  refused("too-many-tets.mesh", replaced(good, "Tetrahedra\n2\n", "Tetrahedra\n3\n"),
          "tetrahedron 3");
  refused("index-zero.mesh", replaced(good, "\n1 2 3 4 1\n", "\n0 2 3 4 1\n"), "vertex index 0");
  refused("index-high.mesh", replaced(good, "\n1 2 3 4 1\n", "\n1 2 3 6 1\n"), "vertex index 6");
  refused("nan.mesh", replaced(good, "\n1 0 0 0\n", "\nnan 0 0 0\n"), "node 1: coordinate is not a finite");
  refused("flat.mesh", replaced(good, "\n1 1 1 0\n", "\n1 1 -1 0\n"), "element 1: tetrahedron has zero volume");
  refused("hexahedra.mesh", replaced(good, "End\n", "Hexahedra\n0\nEnd\n"), "Hexahedra");
  refused("dimension2.mesh", replaced(good, "Dimension\n3", "Dimension\n2"), "Dimension is 2");
  refused("not-medit.mesh", "solid cube\n", "MeshVersionFormatted");
}

TEST_CASE("malformed VTK files are refused with a one-line message naming the file") {
  ScratchFolder scratch;
  const std::string good = vtk_legacy(two_tets());
  const auto refused = [&](const std::string& name, const std::string& text,
                           const std::string& expected) {
    const fs::path file = scratch.path / name;
    write_text(file, text);
    check_refused(file, expected);
  };
  refused("truncated.vtk", good.substr(0, good.find("CELL_TYPES")), "");
  // VTK's legacy reader notices a POINTS count that is too small (the extra coordinates stand
  // where it expects a keyword); one that is too large it only reports through a warning that
  // is not sent to the reader's observers, and it fills the missing points with zeros.
  refused("too-many-points.vtk", replaced(good, "POINTS 5", "POINTS 4"), "");
  refused("too-many-cells.vtk", replaced(good, "CELL_TYPES 3", "CELL_TYPES 4"), "");
  refused("hexahedron.vtk",
          replaced(replaced(good, "CELLS 3 14\n", "CELLS 4 23\n"), "CELL_TYPES 3\n5\n10\n10\n",
                   "8 0 1 2 3 4 0 1 2\nCELL_TYPES 4\n5\n10\n10\n12\n"),
          "cell 3: cell type vtkHexahedron is not supported");
  refused("index-high.vtk", replaced(good, "\n4 0 1 2 3\n", "\n4 0 1 2 9\n"), "node index 9");
  refused("flat.vtk", replaced(good, "\n1 1 1\n", "\n1 1 -1\n"), "element 1: tetrahedron has zero volume");
  refused("polydata.vtk", replaced(good, "UNSTRUCTURED_GRID", "POLYDATA"), "");
  refused("no-cells.vtk", good.substr(0, good.find("CELLS")), "");

  // A .vtu file cut in the middle of its appended binary data.
  const fs::path whole = scratch.path / "whole.vtu";
  kerf::write_vtu(whole, two_tets(), {}, {});
  const std::string vtu = read_text(whole);
  refused("truncated.vtu", vtu.substr(0, vtu.size() / 2), "");
  refused("not-xml.vtu", "solid cube\n", "");
}

TEST_CASE("a missing file and an unknown extension are refused, naming the file") {
  ScratchFolder scratch;
  for (const char* name : {"missing.msh", "missing.vtu", "missing.vtk", "missing.mesh"})
    check_refused(scratch.path / name, "does not exist");
  const fs::path stl = scratch.path / "organ.stl";
  write_text(stl, "solid organ\nendsolid organ\n");
  check_refused(stl, ".msh");
  check_refused(stl, "'.stl' is not a mesh format");

  // The extension decides, whatever its case.
  const fs::path upper = scratch.path / "CUBE.MSH";
  write_text(upper, gmsh_v2(unit_cube()));
  CHECK(kerf::read_mesh(upper, nullptr).num_tets() == 6);
}

namespace {

/// The node tags of tet t as the Gmsh writers above list them, " 7 17 ... 97" (one leading
/// space per tag), optionally with two of the tet's local nodes swapped.
std::string gmsh_tag_list(const kerf::TetMesh& mesh, Eigen::Index t, int swap_a = 0, int swap_b = 0) {
  std::vector<int> nodes = gmsh_tet_nodes(mesh, t);
  std::swap(nodes[static_cast<std::size_t>(swap_a)], nodes[static_cast<std::size_t>(swap_b)]);
  std::ostringstream tags;
  for (const int v : nodes) tags << " " << tag_of(v);
  tags << "\n";
  return tags.str();
}

/// One tet with a thin side, corners (0,0,0), (1,0,0), (0,1,0), (0,0,0.1), and its mid-edge nodes.
kerf::TetMesh thin_tet10() {
  kerf::TetMesh tet4;
  tet4.nodes.resize(4, 3);
  tet4.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.1;
  tet4.tets.resize(1, 4);
  tet4.tets << 0, 1, 2, 3;
  return with_midpoints(tet4);
}

/// The smallest det J of tet t's own (possibly curved) Tet10 map at the points of the degree-2 rule.
double smallest_det_J(const kerf::TetMesh& mesh, Eigen::Index t) {
  Eigen::Matrix<double, 10, 3> X;
  for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(mesh.tets(t, a));
  double smallest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& xi : kerf::tet_quadrature_rule(2).points)
    smallest = std::min(smallest, (X.transpose() * kerf::tet10_shape_gradients(xi)).determinant());
  return smallest;
}

} // namespace

TEST_CASE("a Tet10 file with a slightly curved edge is straightened with one warning line") {
  // In two_tets() the edge between nodes 0 and 1 belongs to tet 0 alone; its mid-edge node
  // (0.5, 0, 0) is pulled 1e-3 of the edge length off the line, as a mesher curving the edge does.
  ScratchFolder scratch;
  const kerf::TetMesh straight = with_midpoints(two_tets());
  kerf::TetMesh curved = straight;
  Eigen::Index bent_node = -1;
  for (Eigen::Index v = 0; v < curved.num_nodes(); ++v)
    if (curved.nodes.row(v) == Eigen::RowVector3d(0.5, 0, 0)) bent_node = v;
  REQUIRE(bent_node >= 0);
  curved.nodes(bent_node, 1) = 1e-3;

  const fs::path vtu = scratch.path / "curved.vtu";
  kerf::write_vtu(vtu, curved, {}, {});
  const std::vector<std::pair<fs::path, std::string>> gmsh_files = {
      {scratch.path / "curved-v2.msh", replaced(gmsh_v2(straight), "0.5 0 0\n", "0.5 0.001 0\n")},
      {scratch.path / "curved-v4.msh", replaced(gmsh_v4(straight), "0.5 0 0\n", "0.5 0.001 0\n")}};
  for (const auto& [file, text] : gmsh_files) write_text(file, text);

  for (const fs::path& file : {vtu, gmsh_files[0].first, gmsh_files[1].first}) {
    CAPTURE(file);
    std::ostringstream warnings;
    const kerf::TetMesh read = kerf::read_mesh(file, &warnings);
    // Node for node the straight mesh, so that everything computed from it is the same.
    check_same_mesh(read, straight);
    const std::string warning = warnings.str();
    CAPTURE(warning);
    CHECK(warning.find("warning: " + file.string() + ": 1 Tet10 elements had curved edges") == 0);
    CHECK(warning.find("the first is element 0") != std::string::npos);
    CHECK(warning.find("up to 0.001 of the edge length") != std::string::npos);
    CHECK(warning.find('\n') == warning.size() - 1);
  }
}

TEST_CASE("a Tet10 file with two mid-edge nodes of one tet swapped is refused, naming the tet") {
  // Swapping the nodes of edges (0,1) and (1,2) of tet 1 puts each half an edge length off.
  ScratchFolder scratch;
  const kerf::TetMesh mesh = with_midpoints(two_tets());
  kerf::TetMesh swapped = mesh;
  std::swap(swapped.tets(1, 4), swapped.tets(1, 5));
  const fs::path vtu = scratch.path / "swapped.vtu";
  kerf::write_vtu(vtu, swapped, {}, {});
  check_refused(vtu, "element 1: mid-edge node");
  check_refused(vtu, "(local node 4, on the edge between corners 0 and 1) is 0.5 of the edge length");
  check_refused(vtu, "in the wrong order");
  // In Gmsh's order local nodes 4 and 5 are the same edges (0,1) and (1,2).
  for (const auto& [name, text] :
       {std::pair{"swapped-v2.msh", gmsh_v2(mesh)}, std::pair{"swapped-v4.msh", gmsh_v4(mesh)}}) {
    const fs::path file = scratch.path / name;
    write_text(file, replaced(text, gmsh_tag_list(mesh, 1), gmsh_tag_list(mesh, 1, 4, 5)));
    check_refused(file, "element 1: mid-edge node");
    check_refused(file, "is 0.5 of the edge length");
  }

  // Corner 0 of tet 1 (node 1, also a corner of tet 0) swapped with its mid-edge node on the
  // edge (0,3): the tet keeps half its volume, and the corner in a mid-edge slot is refused
  // before any distance is measured.
  kerf::TetMesh corner_as_mid_edge = mesh;
  std::swap(corner_as_mid_edge.tets(1, 0), corner_as_mid_edge.tets(1, 7));
  const fs::path corner_vtu = scratch.path / "corner.vtu";
  kerf::write_vtu(corner_vtu, corner_as_mid_edge, {}, {});
  check_refused(corner_vtu, "element 1: mid-edge node 1 (local node 7, on the edge between corners 0 and 3)");
  check_refused(corner_vtu, "is a corner of element 0");
}

TEST_CASE("a Tet10 file whose curved tet has det J < 0 at a quadrature point is refused") {
  // The node on edge (0,1) of the thin tet moved 0.2 edge lengths across it: within the
  // quarter-point limit, but the element folds (det J < 0 at a point of the degree-2 rule).
  ScratchFolder scratch;
  const kerf::TetMesh straight = thin_tet10();
  kerf::TetMesh folded = straight;
  REQUIRE(folded.nodes.row(folded.tets(0, 4)) == Eigen::RowVector3d(0.5, 0, 0));
  folded.nodes(folded.tets(0, 4), 2) = 0.2;
  REQUIRE(smallest_det_J(straight, 0) > 0.0);
  REQUIRE(smallest_det_J(folded, 0) < 0.0);

  const fs::path vtu = scratch.path / "folded.vtu";
  kerf::write_vtu(vtu, folded, {}, {});
  const fs::path v2 = scratch.path / "folded-v2.msh";
  write_text(v2, replaced(gmsh_v2(straight), "0.5 0 0\n", "0.5 0 0.2\n"));
  const fs::path v4 = scratch.path / "folded-v4.msh";
  write_text(v4, replaced(gmsh_v4(straight), "0.5 0 0\n", "0.5 0 0.2\n"));
  for (const fs::path& file : {vtu, v2, v4}) {
    check_refused(file, "element 0: det J = -");
    check_refused(file, "of the degree-2 quadrature rule: the curved tetrahedron folds over itself");
  }
}
