// Tests of the cut-surface readers (OBJ, STL ASCII and binary, OFF, VTK legacy, VTP, VTU) and
// of the check every surface goes through (welding, degeneracy, manifoldness, orientation).
//
// Two small surfaces, written by the tests in every format: the unit square as two triangles
// (open: 4 boundary edges) and the closed surface of a tetrahedron (no boundary). Each file
// must read back to the same vertices and triangles; an STL file, which stores every corner of
// every triangle on its own, only after welding. Then we turn triangles over and count the
// ones the check turns back, and break each format in every way a user's file can be broken,
// checking that the one-line message names the file and the line, vertex, triangle or edge.

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/check_triangle_surface.hpp"
#include "kerf/mesh/read_surface.hpp"
#include "kerf/mesh/triangle_surface.hpp"

#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// The unit square in the plane z = 0 as two triangles, both with the normal +z.
kerf::TriangleSurface unit_square() {
  kerf::TriangleSurface square;
  square.vertices.resize(4, 3);
  square.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  square.triangles.resize(2, 3);
  square.triangles << 0, 1, 2, 0, 2, 3;
  return square;
}

/// The closed surface of the tetrahedron with corners 0, e_y, e_x, e_z, all normals outward.
/// Vertices are numbered in the order the triangles first use them, so that an STL file (which
/// welding numbers that way) reads back to the same numbering.
kerf::TriangleSurface tetrahedron_surface() {
  kerf::TriangleSurface tet;
  tet.vertices.resize(4, 3);
  tet.vertices << 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1;
  tet.triangles.resize(4, 3);
  tet.triangles << 0, 1, 2, 0, 3, 1, 1, 3, 2, 0, 2, 3;
  return tet;
}

/// The coordinates as the text formats write them: shortest round-trip form.
std::string number(double x) {
  std::ostringstream text;
  text.precision(17);
  text << x;
  return text.str();
}

std::string obj(const kerf::TriangleSurface& s) {
  std::string text = "# a test surface\no surface\n";
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    text += "v " + number(s.vertices(v, 0)) + " " + number(s.vertices(v, 1)) + " " + number(s.vertices(v, 2)) + "\n";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t)
    text += "f " + std::to_string(s.triangles(t, 0) + 1) + " " + std::to_string(s.triangles(t, 1) + 1) + " " +
            std::to_string(s.triangles(t, 2) + 1) + "\n";
  return text;
}

std::string off(const kerf::TriangleSurface& s) {
  std::string text = "OFF\n" + std::to_string(s.num_vertices()) + " " + std::to_string(s.num_triangles()) + " 0\n";
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    text += number(s.vertices(v, 0)) + " " + number(s.vertices(v, 1)) + " " + number(s.vertices(v, 2)) + "\n";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t)
    text += "3 " + std::to_string(s.triangles(t, 0)) + " " + std::to_string(s.triangles(t, 1)) + " " +
            std::to_string(s.triangles(t, 2)) + "\n";
  return text;
}

std::string ascii_stl(const kerf::TriangleSurface& s) {
  std::string text = "solid test\n";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index v = s.triangles(t, a);
      text += "      vertex " + number(s.vertices(v, 0)) + " " + number(s.vertices(v, 1)) + " " +
              number(s.vertices(v, 2)) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid test\n";
}

/// A binary STL file; its header starts with "solid", as many writers' do, to show that the
/// size decides, not the first word.
std::string binary_stl(const kerf::TriangleSurface& s) {
  std::string bytes(80, ' ');
  bytes.replace(0, 11, "solid kerf ");
  const auto append_uint32 = [&bytes](std::uint32_t value) {
    for (int b = 0; b < 4; ++b) bytes.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
  };
  const auto append_float = [&](float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    append_uint32(bits);
  };
  append_uint32(static_cast<std::uint32_t>(s.num_triangles()));
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t) {
    for (int c = 0; c < 3; ++c) append_float(0.0f);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) append_float(static_cast<float>(s.vertices(s.triangles(t, a), c)));
    bytes += std::string(2, '\0');
  }
  return bytes;
}

std::string points_block(const kerf::TriangleSurface& s) {
  std::string text = "POINTS " + std::to_string(s.num_vertices()) + " double\n";
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    text += number(s.vertices(v, 0)) + " " + number(s.vertices(v, 1)) + " " + number(s.vertices(v, 2)) + "\n";
  return text;
}

std::string triangle_lists(const kerf::TriangleSurface& s, const std::string& keyword) {
  std::string text = keyword + " " + std::to_string(s.num_triangles()) + " " + std::to_string(4 * s.num_triangles()) + "\n";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t)
    text += "3 " + std::to_string(s.triangles(t, 0)) + " " + std::to_string(s.triangles(t, 1)) + " " +
            std::to_string(s.triangles(t, 2)) + "\n";
  return text;
}

std::string vtk_polydata(const kerf::TriangleSurface& s) {
  return "# vtk DataFile Version 3.0\nkerf test\nASCII\nDATASET POLYDATA\n" + points_block(s) +
         triangle_lists(s, "POLYGONS") + "POINT_DATA " + std::to_string(s.num_vertices()) +
         "\nSCALARS s double 1\nLOOKUP_TABLE default\n" + std::string(static_cast<std::size_t>(2 * s.num_vertices()), ' ') + "\n";
}

std::string vtk_unstructured(const kerf::TriangleSurface& s) {
  std::string text = "# vtk DataFile Version 3.0\nkerf test\nASCII\nDATASET UNSTRUCTURED_GRID\n" + points_block(s) +
                     triangle_lists(s, "CELLS") + "CELL_TYPES " + std::to_string(s.num_triangles()) + "\n";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t) text += "5\n";
  return text;
}

/// The XML data arrays of the points and the triangles' connectivity and offsets.
std::string xml_arrays(const kerf::TriangleSurface& s, std::string& connectivity, std::string& offsets) {
  std::string points;
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v)
    points += number(s.vertices(v, 0)) + " " + number(s.vertices(v, 1)) + " " + number(s.vertices(v, 2)) + " ";
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t) {
    connectivity += std::to_string(s.triangles(t, 0)) + " " + std::to_string(s.triangles(t, 1)) + " " +
                    std::to_string(s.triangles(t, 2)) + " ";
    offsets += std::to_string(3 * (t + 1)) + " ";
  }
  return "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">" + points +
         "</DataArray></Points>\n";
}

std::string vtp(const kerf::TriangleSurface& s) {
  std::string connectivity, offsets;
  const std::string points = xml_arrays(s, connectivity, offsets);
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<PolyData><Piece NumberOfPoints=\"" + std::to_string(s.num_vertices()) +
         "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
         std::to_string(s.num_triangles()) + "\">\n" + points +
         "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity +
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray></Polys>\n</Piece></PolyData></VTKFile>\n";
}

std::string vtu(const kerf::TriangleSurface& s) {
  std::string connectivity, offsets;
  const std::string points = xml_arrays(s, connectivity, offsets);
  std::string types;
  for (Eigen::Index t = 0; t < s.num_triangles(); ++t) types += "5 ";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid><Piece NumberOfPoints=\"" + std::to_string(s.num_vertices()) + "\" NumberOfCells=\"" +
         std::to_string(s.num_triangles()) + "\">\n" + points +
         "<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity +
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types +
         "</DataArray></Cells>\n</Piece></UnstructuredGrid></VTKFile>\n";
}

/// Writes bytes as they are (binary STL holds zeros and no newlines to translate).
void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary);
  out << bytes;
  REQUIRE(out.good());
}

/// Every format Kerf reads a surface from, with a writer for it.
struct Format {
  const char* file_name;
  std::function<std::string(const kerf::TriangleSurface&)> write;
};

std::vector<Format> every_format() {
  return {{"surface.obj", obj},          {"surface.off", off},           {"ascii.stl", ascii_stl},
          {"binary.stl", binary_stl},    {"polydata.vtk", vtk_polydata}, {"grid.vtk", vtk_unstructured},
          {"surface.vtp", vtp},          {"surface.vtu", vtu}};
}

/// The message of the InputError that `read` throws, or "" if it throws none.
std::string input_error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const kerf::InputError& error) {
    return error.what();
  }
  return "";
}

/// Checks that reading `file` fails with a one-line InputError that starts with the file's
/// name and holds `expected` (the field and the problem).
void check_refused(const fs::path& file, const std::string& expected) {
  CAPTURE(file);
  const std::string message = input_error_of([&] { kerf::read_surface(file); });
  CAPTURE(message);
  REQUIRE_FALSE(message.empty());
  CHECK(message.rfind(file.string() + ": ", 0) == 0);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find(expected) != std::string::npos);
}

/// Replaces the first occurrence of `from` in `text` by `to`, which must be there.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, "'" << from << "' is not in the test file");
  return text.replace(at, from.size(), to);
}

/// Writes `text` to a file `name` in `folder` and checks that reading it is refused.
void check_refused_text(const fs::path& folder, const std::string& name, const std::string& text,
                        const std::string& expected) {
  write_bytes(folder / name, text);
  check_refused(folder / name, expected);
}

} // namespace

TEST_CASE("the test surfaces pass the check unchanged: counts of components and boundary edges") {
  kerf::TriangleSurface square = unit_square();
  const kerf::SurfaceCheck square_check = kerf::check_triangle_surface(square, "square");
  CHECK(square_check.merged_vertices == 0);
  CHECK(square_check.unused_vertices == 0);
  CHECK(square_check.flipped_triangles == 0);
  CHECK(square_check.components == 1);
  CHECK(square_check.boundary_edges == 4);
  CHECK(square.vertices == unit_square().vertices);
  CHECK(square.triangles == unit_square().triangles);

  kerf::TriangleSurface tet = tetrahedron_surface();
  const kerf::SurfaceCheck tet_check = kerf::check_triangle_surface(tet, "tet");
  CHECK(tet_check.flipped_triangles == 0);
  CHECK(tet_check.components == 1);
  CHECK(tet_check.boundary_edges == 0);
  CHECK(tet.triangles == tetrahedron_surface().triangles);
}

TEST_CASE("every format reads back the same vertices and triangles, STL after welding") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_round_trip");
  for (const auto& [name, surface] : {std::pair{"square", unit_square()}, std::pair{"tet", tetrahedron_surface()}}) {
    for (const Format& format : every_format()) {
      const fs::path file = folder / (std::string(name) + "_" + format.file_name);
      CAPTURE(file);
      write_bytes(file, format.write(surface));
      std::ostringstream warnings;
      const kerf::TriangleSurface read = kerf::read_surface(file, 1.0, &warnings);
      CHECK(read.vertices == surface.vertices);
      CHECK(read.triangles == surface.triangles);
      CHECK(warnings.str().empty());
    }
  }
}

TEST_CASE("binary and ASCII STL agree, and welding merges the 3 corners per triangle STL stores") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_stl");
  write_bytes(folder / "ascii.stl", ascii_stl(tetrahedron_surface()));
  write_bytes(folder / "binary.stl", binary_stl(tetrahedron_surface()));
  const kerf::TriangleSurface ascii = kerf::read_surface(folder / "ascii.stl");
  const kerf::TriangleSurface binary = kerf::read_surface(folder / "binary.stl");
  CHECK(ascii.vertices == binary.vertices);
  CHECK(ascii.triangles == binary.triangles);
  CHECK(binary.num_vertices() == 4);

  // The 12 corners of the file, before welding: 8 of them repeat an earlier position.
  kerf::TriangleSurface unwelded;
  unwelded.vertices.resize(12, 3);
  unwelded.triangles.resize(4, 3);
  const kerf::TriangleSurface tet = tetrahedron_surface();
  for (int t = 0; t < 4; ++t)
    for (int a = 0; a < 3; ++a) {
      unwelded.vertices.row(3 * t + a) = tet.vertices.row(tet.triangles(t, a));
      unwelded.triangles(t, a) = 3 * t + a;
    }
  const kerf::SurfaceCheck check = kerf::check_triangle_surface(unwelded, "unwelded");
  CHECK(check.merged_vertices == 8);
  CHECK(check.unused_vertices == 0);
  CHECK(unwelded.vertices == tet.vertices);
  CHECK(unwelded.triangles == tet.triangles);
}

TEST_CASE("scale multiplies the coordinates, and must be finite and positive") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_scale");
  for (const char* name : {"square.obj", "square.stl"}) {
    CAPTURE(name);
    const fs::path file = folder / name;
    write_bytes(file, std::string(name) == "square.obj" ? obj(unit_square()) : binary_stl(unit_square()));
    const kerf::TriangleSurface millimetres = kerf::read_surface(file, 0.001);
    CHECK(millimetres.vertices == 0.001 * unit_square().vertices);
    CHECK(millimetres.vertices(2, 0) == 0.001);
    for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
      const std::string message = input_error_of([&] { kerf::read_surface(file, bad); });
      CHECK(message.rfind(file.string() + ": scale: expected a finite number > 0", 0) == 0);
    }
  }
}

TEST_CASE("orientation: exactly the inverted triangles are flipped back, the first one leads") {
  // Triangles 1 and 3 of the closed tet surface turned over: the check turns back those two.
  kerf::TriangleSurface tet = tetrahedron_surface();
  for (const int t : {1, 3}) std::swap(tet.triangles(t, 1), tet.triangles(t, 2));
  const fs::path folder = kerf_test::fresh_dir("surface_readers_orientation");
  write_bytes(folder / "two_inverted.obj", obj(tet));
  std::ostringstream warnings;
  const kerf::TriangleSurface read = kerf::read_surface(folder / "two_inverted.obj", 1.0, &warnings);
  CHECK(read.triangles == tetrahedron_surface().triangles);
  CHECK(warnings.str() == "warning: " + (folder / "two_inverted.obj").string() +
                              ": 2 of 4 triangles flipped to agree in orientation with their neighbours "
                              "(the first triangle of each of the 1 connected components keeps its own)\n");
  kerf::TriangleSurface again = tet;
  CHECK(kerf::check_triangle_surface(again, "tet").flipped_triangles == 2);

  // Triangle 0 turned over: it keeps its orientation, so the other three are flipped, and the
  // whole surface comes out inward.
  kerf::TriangleSurface first_inverted = tetrahedron_surface();
  std::swap(first_inverted.triangles(0, 1), first_inverted.triangles(0, 2));
  CHECK(kerf::check_triangle_surface(first_inverted, "tet").flipped_triangles == 3);
  kerf::TriangleSurface inward = tetrahedron_surface();
  for (int t = 0; t < 4; ++t) std::swap(inward.triangles(t, 1), inward.triangles(t, 2));
  CHECK(first_inverted.triangles == inward.triangles);

  // Two squares apart, the second one upside down: two components, each keeps its first
  // triangle, so only the second square's second triangle (turned over alone) is flipped.
  kerf::TriangleSurface two;
  two.vertices.resize(8, 3);
  two.vertices << unit_square().vertices, unit_square().vertices.rowwise() + Eigen::RowVector3d(0, 0, 5);
  two.triangles.resize(4, 3);
  two.triangles << 0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 6, 7;
  const kerf::SurfaceCheck check = kerf::check_triangle_surface(two, "two squares");
  CHECK(check.components == 2);
  CHECK(check.boundary_edges == 8);
  CHECK(check.flipped_triangles == 1);
  CHECK(two.triangles.row(3) == Eigen::RowVector3i(4, 7, 6));
  CHECK(two.triangles.row(2) == Eigen::RowVector3i(4, 6, 5));
}

TEST_CASE("the check refuses what has no sides, naming the triangle, vertex or edge") {
  const auto refused = [](Eigen::MatrixX3d vertices, Eigen::MatrixX3i triangles, const std::string& expected) {
    kerf::TriangleSurface surface{std::move(vertices), std::move(triangles)};
    const std::string message = input_error_of([&] { kerf::check_triangle_surface(surface, "cut.obj"); });
    CAPTURE(message);
    CHECK(message.rfind("cut.obj: " + expected, 0) == 0);
  };
  const Eigen::MatrixX3d square = unit_square().vertices;
  const auto rows = [](std::initializer_list<std::initializer_list<int>> list) {
    Eigen::MatrixX3i m(static_cast<Eigen::Index>(list.size()), 3);
    Eigen::Index r = 0;
    for (const auto& row : list) {
      int c = 0;
      for (const int i : row) m(r, c++) = i;
      ++r;
    }
    return m;
  };
  refused(square, Eigen::MatrixX3i(0, 3), "triangles: the surface has no triangles");
  refused(square, rows({{0, 1, 4}}), "triangle 0: vertex index 4 is outside [0, 4)");
  refused(square, rows({{0, 1, -1}}), "triangle 0: vertex index -1 is outside [0, 4)");
  Eigen::MatrixX3d with_nan = square;
  with_nan(3, 1) = std::numeric_limits<double>::quiet_NaN();
  refused(with_nan, rows({{0, 1, 2}}), "vertex 3: coordinate is not a finite number");
  refused(square, rows({{0, 1, 2}, {2, 2, 3}}), "triangle 1: degenerate: corners 0 and 1 are at the same position (1, 1, 0)");
  // Two vertices at one position become one vertex, and the triangle that joined them is flat.
  Eigen::MatrixX3d repeated = square;
  repeated.row(3) = repeated.row(1);
  refused(repeated, rows({{0, 1, 2}, {1, 2, 3}}), "triangle 1: degenerate: corners 0 and 2 are at the same position (1, 0, 0)");
  Eigen::MatrixX3d collinear(3, 3);
  collinear << 0, 0, 0, 1, 1, 1, 3, 3, 3;
  refused(collinear, rows({{0, 1, 2}}), "triangle 0: degenerate: its three corners are collinear");
  refused(square, rows({{0, 1, 2}, {2, 1, 0}}), "triangle 1: has the same three corners as triangle 0");
  // Three triangles on the edge (0, 1): three sheets meet there.
  Eigen::MatrixX3d fan(5, 3);
  fan << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  refused(fan, rows({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), "edge (0, 1): non-manifold: shared by 3 triangles (0, 1, 2)");
  // The five-vertex Möbius strip: triangles (i, i+1, i+2) mod 5 around a twisted band.
  Eigen::MatrixX3d band(5, 3);
  band << 1, 0, 0, 0.3, 1, 0.2, -0.8, 0.6, -0.1, -0.8, -0.6, 0.3, 0.3, -1, -0.2;
  refused(band, rows({{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 0}, {4, 0, 1}}), "triangle ");
  kerf::TriangleSurface moebius{band, rows({{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 0}, {4, 0, 1}})};
  CHECK(input_error_of([&] { kerf::check_triangle_surface(moebius, "m"); }).find("not orientable") != std::string::npos);
}

TEST_CASE("collinearity is decided exactly: a sliver of area 1e-300 is a triangle") {
  kerf::TriangleSurface sliver;
  sliver.vertices.resize(3, 3);
  sliver.vertices << 0, 0, 0, 1, 0, 0, 2, 1e-300, 0;
  sliver.triangles.resize(1, 3);
  sliver.triangles << 0, 1, 2;
  CHECK_NOTHROW(kerf::check_triangle_surface(sliver, "sliver"));
  // The origin, (0.1, 0.2, 0.3) and (0.3, 0.6, 0.9) are collinear as written in decimal, but
  // the doubles nearest to them are not (0.3 is not three times the double nearest 0.1), and
  // the exact predicate judges the doubles: a triangle of area about 1e-17.
  kerf::TriangleSurface rounded;
  rounded.vertices.resize(3, 3);
  rounded.vertices << 0, 0, 0, 0.1, 0.2, 0.3, 0.3, 0.6, 0.9;
  rounded.triangles.resize(1, 3);
  rounded.triangles << 0, 1, 2;
  CHECK_NOTHROW(kerf::check_triangle_surface(rounded, "rounded"));
}

TEST_CASE("OBJ: polygons become fans, i/t/n and negative indices, unused vertices dropped") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_obj");
  const fs::path file = folder / "quad.OBJ"; // the extension decides whatever its case
  write_bytes(file,
              "mtllib cut.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 9 9 9 1.0\nvt 0 0\nvn 0 0 1\n"
              "g cut\nusemtl red\ns off\nf 1/1/1 2/1/1 3//1 4\r\nl 1 2\n");
  const kerf::TriangleSurface quad = kerf::read_surface(file);
  CHECK(quad.vertices == unit_square().vertices);
  CHECK(quad.triangles == unit_square().triangles);

  write_bytes(folder / "negative.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\n");
  const kerf::TriangleSurface negative = kerf::read_surface(folder / "negative.obj");
  CHECK(negative.triangles == unit_square().triangles);
}

TEST_CASE("malformed OBJ files are refused, naming the file and the line") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_bad_obj");
  const std::string good = obj(unit_square()); // 2 header lines, 4 vertices, then the faces on lines 7 and 8
  check_refused_text(folder, "index_high.obj", replaced(good, "f 1 3 4", "f 1 3 5"), "line 8: vertex index 5 is outside [1, 4]");
  check_refused_text(folder, "index_zero.obj", replaced(good, "f 1 3 4", "f 0 3 4"), "line 8: vertex index 0 is outside");
  check_refused_text(folder, "negative_far.obj", replaced(good, "f 1 3 4", "f -5 3 4"), "line 8: vertex index -5");
  check_refused_text(folder, "face_before_vertex.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "line 1: vertex index 1 is outside [1, 0]");
  check_refused_text(folder, "bad_number.obj", replaced(good, "v 1 0 0", "v 1 O 0"), "line 4: expected a number for y of vertex 2, found 'O'");
  check_refused_text(folder, "two_coordinates.obj", replaced(good, "v 1 0 0", "v 1 0"), "line 4: a vertex has 3 coordinates");
  check_refused_text(folder, "bad_index.obj", replaced(good, "f 1 3 4", "f 1 3 x4"), "line 8: expected a vertex index");
  check_refused_text(folder, "two_corners.obj", replaced(good, "f 1 3 4", "f 1 3"), "line 8: a face needs at least 3 vertices, found 2");
  check_refused_text(folder, "free_form.obj", good + "curv 0 1 1 2\n", "line 9: unknown statement 'curv'");
  check_refused_text(folder, "nan.obj", replaced(good, "v 1 0 0", "v nan 0 0"), "vertex 1: coordinate is not a finite number");
  check_refused_text(folder, "no_faces.obj", "v 0 0 0\nv 1 0 0\n", "triangles: the surface has no triangles");
  check_refused_text(folder, "empty.obj", "", "triangles: the surface has no triangles");
  check_refused_text(folder, "huge_index.obj", replaced(good, "f 1 3 4", "f 1 3 99999999999999999999"), "line 8: expected a vertex index");
}

TEST_CASE("malformed STL files are refused, naming the file and the line or field") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_bad_stl");
  const std::string binary = binary_stl(unit_square());
  REQUIRE(binary.size() == 84 + 2 * 50);
  check_refused_text(folder, "truncated_binary.stl", binary.substr(0, binary.size() - 10),
                     "triangle count: a binary STL file of 2 triangles has 84 + 50 * 2 = 184 bytes, this one has 174");
  const std::string huge = std::string(80, 'x') + "\xff\xff\xff\xff";
  check_refused_text(folder, "huge_count.stl", huge, "triangle count: a binary STL file of 4294967295 triangles");
  check_refused_text(folder, "short.stl", "hello", "header: neither ASCII STL");
  const std::string ascii = ascii_stl(unit_square());
  check_refused_text(folder, "truncated_ascii.stl", ascii.substr(0, ascii.find("endloop")), "the file is truncated");
  check_refused_text(folder, "no_endsolid.stl", replaced(ascii, "endsolid test\n", ""), "no 'endsolid'");
  check_refused_text(folder, "two_coordinates.stl", replaced(ascii, "vertex 1 0 0", "vertex 1 0"), "line 5: expected 'vertex' in facet 0");
  check_refused_text(folder, "bad_number.stl", replaced(ascii, "vertex 1 0 0", "vertex 1 zero 0"),
                     "line 5: expected a number for y of vertex 1 of facet 0, found 'zero'");
  check_refused_text(folder, "quad_facet.stl", replaced(ascii, "endloop", "vertex 0 0 1\nendloop"), "line 7: expected 'endloop'");
  check_refused_text(folder, "bad_normal.stl", replaced(ascii, "facet normal 0 0 0", "facet normal 0 0"), "line 2: expected 'facet normal nx ny nz'");
  check_refused_text(folder, "degenerate.stl", replaced(ascii, "vertex 1 0 0", "vertex 0 0 0"),
                     "triangle 0: degenerate: corners 0 and 1 are at the same position (0, 0, 0)");
  // A binary file cut short whose header says "solid": not taken for ASCII, its zero bytes tell.
  check_refused_text(folder, "solid_header_binary.stl", binary.substr(0, 150), "triangle count: a binary STL file of 2 triangles");
}

TEST_CASE("malformed OFF files are refused, naming the file and the line") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_bad_off");
  const std::string good = off(unit_square());
  check_refused_text(folder, "huge_count.off", replaced(good, "4 2 0", "400000000 2 0"),
                     "line 2: the number of vertices, 400000000, is more than the");
  check_refused_text(folder, "negative_count.off", replaced(good, "4 2 0", "4 -2 0"), "line 2: the number of faces must not be negative");
  check_refused_text(folder, "missing_count.off", replaced(good, "4 2 0", "4 2"), "line 2: expected the three counts");
  check_refused_text(folder, "index_high.off", replaced(good, "3 0 2 3", "3 0 2 4"), "line 8: face 1: vertex index 4 is outside [0, 4)");
  check_refused_text(folder, "truncated.off", good.substr(0, good.find("3 0 2 3")), "line 7: unexpected end of file while reading face 1 of 2");
  check_refused_text(folder, "extra_face.off", good + "3 0 1 3\n", "line 9: more lines after the 2 faces");
  check_refused_text(folder, "two_corners.off", replaced(good, "3 0 2 3", "2 0 2"), "line 8: face 1 announces 2 corners");
  check_refused_text(folder, "too_many_corners.off", replaced(good, "3 0 2 3", "5 0 2 3"), "line 8: face 1 announces 5 corners");
  check_refused_text(folder, "empty.off", "", "line 1: unexpected end of file while reading the OFF header");
  check_refused_text(folder, "colour_off.off", replaced(good, "OFF", "COFF"), "line 1: expected the header 'OFF'");
  check_refused_text(folder, "bad_number.off", replaced(good, "\n1 0 0\n", "\n1 0 0x\n"), "line 4: expected a number for z of vertex 1");

  // Counts on the header's line, a comment, and a face colour are read as OFF allows.
  write_bytes(folder / "compact.off", "OFF 4 1 0\n# the unit square as one quad\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n");
  const kerf::TriangleSurface compact = kerf::read_surface(folder / "compact.off");
  CHECK(compact.triangles == unit_square().triangles);
}

TEST_CASE("malformed VTK surface files are refused, naming the file and the cell") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_bad_vtk");
  const std::string polydata = vtk_polydata(unit_square());
  check_refused_text(folder, "index_high.vtk", replaced(polydata, "3 0 2 3", "3 0 2 9"), "polygon 1: node index 9 is outside [0, 4)");
  check_refused_text(folder, "no_polygons.vtk", polydata.substr(0, polydata.find("POLYGONS")), "POLYGONS: the file has no POLYGONS or TRIANGLE_STRIPS line");
  check_refused_text(folder, "huge_count.vtk", replaced(polydata, "POLYGONS 2 8", "POLYGONS 2 88888888888"), "line 10: POLYGONS: expected the count");
  const std::string grid = vtk_unstructured(unit_square());
  check_refused_text(folder, "tetra.vtk",
                     replaced(replaced(grid, "CELLS 2 8\n", "CELLS 2 9\n"), "3 0 2 3\nCELL_TYPES 2\n5\n5\n",
                              "4 0 1 2 3\nCELL_TYPES 2\n5\n10\n"),
                     "cell 1: cell type vtkTetra is not supported");
  check_refused_text(folder, "structured.vtk", replaced(polydata, "POLYDATA", "STRUCTURED_POINTS"), "line 4: expected 'DATASET UNSTRUCTURED_GRID' or 'DATASET POLYDATA'");
  const std::string xml = vtp(unit_square());
  check_refused_text(folder, "huge_polys.vtp", replaced(xml, "NumberOfPolys=\"2\"", "NumberOfPolys=\"99999999999\""), "NumberOfPolys");
  check_refused_text(folder, "truncated.vtp", xml.substr(0, xml.size() / 2), "");
}

TEST_CASE("a missing file, a folder and an unknown extension are refused, naming the file") {
  const fs::path folder = kerf_test::fresh_dir("surface_readers_files");
  for (const char* name : {"missing.obj", "missing.stl", "missing.off", "missing.vtk", "missing.vtp", "missing.vtu"})
    check_refused(folder / name, "file: does not exist");
  fs::create_directories(folder / "folder.obj");
  check_refused(folder / "folder.obj", "file: is a folder");
  write_bytes(folder / "cut.ply", "ply\n");
  check_refused(folder / "cut.ply", "extension: '.ply' is not a surface format Kerf reads; use .obj");
}
