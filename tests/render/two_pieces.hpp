// A hand-made cut body for the render tests: two pieces that touch, and the pictures' pixels.
#pragma once

#include "kerf/io/write_vtu.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/render/surface_image.hpp"

#include <vtkImageData.h>

#include <cstdlib>
#include <filesystem>

namespace render_test {

/// Two slabs [0, 0.1] x [0, 1] x [0, 1] (piece 0) and [0, 0.1] x [0, 1] x [1, 2] (piece 1), each
/// with points of its own, as the pieces of a cut tet have (write_cut_xfem_vtu): the cut is the
/// plane z = 1. Piece 1 is moved up by `lift` (m), piece 0 not at all, so that drawn with warp s
/// the gap between them is s * lift high. Written as Kerf's programs write their pieces.
inline void write_two_pieces(const std::filesystem::path& file, double lift) {
  const kerf::TetMesh lower = kerf::make_box_mesh({0, 0, 0}, {0.1, 1, 1}, {1, 2, 2});
  const kerf::TetMesh upper = kerf::make_box_mesh({0, 0, 1}, {0.1, 1, 2}, {1, 2, 2});
  kerf::TetMesh both;
  both.nodes.resize(lower.num_nodes() + upper.num_nodes(), 3);
  both.nodes << lower.nodes, upper.nodes;
  both.tets.resize(lower.num_tets() + upper.num_tets(), 4);
  both.tets << lower.tets, (upper.tets.array() + static_cast<int>(lower.num_nodes())).matrix();
  Eigen::MatrixXd displacement = Eigen::MatrixXd::Zero(both.num_nodes(), 3);
  displacement.bottomRows(upper.num_nodes()).col(2).setConstant(lift);
  Eigen::MatrixXd piece(both.num_tets(), 1);
  piece.topRows(lower.num_tets()).setZero();
  piece.bottomRows(upper.num_tets()).setOnes();
  kerf::write_vtu(file, both, {{"displacement", displacement}}, {{"piece", piece}});
}

/// The camera straight in front of the slabs' face x = 0.1, at their mid-height: y runs to the
/// right on the screen and z up, and the gap between the pieces is seen edge-on.
inline kerf::PictureSettings front_view(const char* colour_by = "displacement") {
  kerf::PictureSettings settings;
  settings.colour_by = colour_by;
  settings.camera = {.azimuth = 0, .elevation = 0, .zoom = 1};
  settings.width = 300;
  settings.height = 300;
  return settings;
}

/// The RGB colour of pixel (i, j), i from the left, j from the bottom.
struct Pixel {
  int r, g, b;
};
inline Pixel pixel(vtkImageData& image, int i, int j) {
  const auto* p = static_cast<const unsigned char*>(image.GetScalarPointer(i, j, 0));
  return {p[0], p[1], p[2]};
}

/// Whether pixel (i, j) shows the background (to within the blending of a smoothed edge).
inline bool is_background(vtkImageData& image, int i, int j) {
  const Pixel p = pixel(image, i, j);
  const auto& bg = kerf::picture_background;
  return std::abs(p.r - bg[0]) < 8 && std::abs(p.g - bg[1]) < 8 && std::abs(p.b - bg[2]) < 8;
}

/// What one scan line across the picture crosses: the first and the last pixel of the body on
/// it, and how many background pixels lie between the two (a gap in the body).
struct ScanLine {
  int first = -1, last = -1, background_between = 0;
  int extent() const { return last - first + 1; }
};

/// The scan line up the column i, from the bottom.
inline ScanLine scan_column(vtkImageData& image, int i) {
  ScanLine line;
  const int height = image.GetDimensions()[1];
  for (int j = 0; j < height; ++j)
    if (!is_background(image, i, j)) {
      if (line.first < 0) line.first = j;
      line.last = j;
    }
  for (int j = line.first + 1; j < line.last; ++j) line.background_between += is_background(image, i, j) ? 1 : 0;
  return line;
}

/// The scan line along the row j, from the left up to (not into) the colour bar's strip.
inline ScanLine scan_row(vtkImageData& image, int j) {
  ScanLine line;
  const int bar_start = static_cast<int>(0.85 * image.GetDimensions()[0]);
  for (int i = 0; i < bar_start; ++i)
    if (!is_background(image, i, j)) {
      if (line.first < 0) line.first = i;
      line.last = i;
    }
  for (int i = line.first + 1; i < line.last; ++i) line.background_between += is_background(image, i, j) ? 1 : 0;
  return line;
}

/// The share of the picture's pixels that are not background, in [0, 1].
inline double drawn_fraction(vtkImageData& image) {
  const int* size = image.GetDimensions();
  int drawn = 0;
  for (int j = 0; j < size[1]; ++j)
    for (int i = 0; i < size[0]; ++i) drawn += is_background(image, i, j) ? 0 : 1;
  return static_cast<double>(drawn) / (size[0] * size[1]);
}

} // namespace render_test
