// The render area's pictures, asserted pixel by pixel on a hand-made cut body (two_pieces.hpp):
// a body drawn is not blank and has the proportions of what was drawn, a cut opened by its
// displacement shows the background through the gap, a closed one does not, the warp factor
// scales the gap, a clip plane cuts the body, and the colours follow |u| or the pieces.
#include "two_pieces.hpp"

#include "kerf/render/piece_mesh.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/warped_surface.hpp"
#include "support/run_program.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <optional>

namespace {

vtkSmartPointer<vtkImageData> draw_two_pieces(const char* name, double lift, double warp,
                                              const kerf::PictureSettings& settings = render_test::front_view(),
                                              const std::optional<kerf::ClipPlane>& clip = std::nullopt) {
  const auto file = kerf_test::fresh_dir(name) / "two_pieces.vtu";
  render_test::write_two_pieces(file, lift);
  const vtkSmartPointer<vtkUnstructuredGrid> body = kerf::read_piece_mesh(file);
  const vtkSmartPointer<vtkPolyData> surface = kerf::warped_surface(*body, warp, clip);
  return kerf::render_surface_image(*surface, settings);
}

} // namespace

TEST_CASE("a closed cut: the picture has the requested size, is not blank, and the body's proportions") {
  const vtkSmartPointer<vtkImageData> image = draw_two_pieces("closed", 0.0, 1.0);
  CHECK(image->GetDimensions()[0] == 300);
  CHECK(image->GetDimensions()[1] == 300);
  CHECK(image->GetNumberOfScalarComponents() == 3);
  // The body, fitted to the picture, covers a good part of it, but not all.
  const double drawn = render_test::drawn_fraction(*image);
  CHECK(drawn > 0.15);
  CHECK(drawn < 0.6);
  // Seen from the front, the slabs' face is 1 m wide (y, to the right) and 2 m high (z, up):
  // the camera stands where CameraView says, with z up.
  const render_test::ScanLine up = render_test::scan_column(*image, 150);
  const render_test::ScanLine across = render_test::scan_row(*image, (up.first + up.last) / 2);
  CHECK(static_cast<double>(up.extent()) / across.extent() == kerf_test::relative(2.0, 0.03));
  // The two pieces touch along z = 1: no background shows between them.
  CHECK(up.background_between == 0);
  CHECK(across.background_between == 0);
  // The colour bar is drawn in its strip at the right edge.
  int bar_pixels = 0;
  for (int j = 0; j < 300; ++j)
    for (int i = 264; i < 300; ++i) bar_pixels += render_test::is_background(*image, i, j) ? 0 : 1;
  CHECK(bar_pixels > 300);
}

TEST_CASE("a cut opened by the displacement shows the background in the gap, s * lift high") {
  // The upper piece moved up by 0.3 m: along the column through the middle, the body spans
  // 2.3 m, of which the gap is 0.3 m; its face is seen straight on, so the picture keeps the ratio.
  const vtkSmartPointer<vtkImageData> open = draw_two_pieces("open", 0.3, 1.0);
  const render_test::ScanLine up = render_test::scan_column(*open, 150);
  CHECK(up.background_between > 0);
  CHECK(static_cast<double>(up.background_between) / up.extent() == kerf_test::relative(0.3 / 2.3, 0.08));

  // Warped twice as much, the gap is 0.6 m of 2.6 m.
  const vtkSmartPointer<vtkImageData> twice = draw_two_pieces("open_twice", 0.3, 2.0);
  const render_test::ScanLine up_twice = render_test::scan_column(*twice, 150);
  CHECK(static_cast<double>(up_twice.background_between) / up_twice.extent() == kerf_test::relative(0.6 / 2.6, 0.05));

  // Not warped, the same file draws the cut closed.
  const vtkSmartPointer<vtkImageData> unmoved = draw_two_pieces("open_unwarped", 0.3, 0.0);
  CHECK(render_test::scan_column(*unmoved, 150).background_between == 0);
}

TEST_CASE("a clip plane draws the part of the body on the side its normal points to, cut along the plane") {
  // The plane y = 0.3 with its normal -y keeps the strip 0 <= y <= 0.3 of the slabs: 0.3 m wide
  // and 2 m high. Tets dropped whole instead of clipped would leave 0 or 0.5 m (the mesh's
  // cells end at y = 0, 0.5 and 1).
  const kerf::ClipPlane clip{{0, 0.3, 0}, {0, -1, 0}};
  const vtkSmartPointer<vtkImageData> image = draw_two_pieces("clipped", 0.0, 1.0, render_test::front_view(), clip);
  const render_test::ScanLine up = render_test::scan_column(*image, 150);
  const render_test::ScanLine across = render_test::scan_row(*image, (up.first + up.last) / 2);
  CHECK(static_cast<double>(up.extent()) / across.extent() == kerf_test::relative(2.0 / 0.3, 0.05));
}

TEST_CASE("the colours follow |u| (blue at rest, red where it is largest) or the piece, one colour per value") {
  const vtkSmartPointer<vtkImageData> by_u = draw_two_pieces("colour_u", 0.3, 1.0);
  const render_test::ScanLine up = render_test::scan_column(*by_u, 150);
  const int lower = up.first + up.extent() / 4, upper = up.last - up.extent() / 4;
  const render_test::Pixel at_rest = render_test::pixel(*by_u, 150, lower), moved = render_test::pixel(*by_u, 150, upper);
  CHECK(at_rest.b > at_rest.r + 100);
  CHECK(moved.r > moved.b + 100);

  // By piece: piece 0 blue, piece 1 orange (the value -1, absent here, would be grey).
  const vtkSmartPointer<vtkImageData> by_piece = draw_two_pieces("colour_piece", 0.3, 1.0, render_test::front_view("piece"));
  const render_test::Pixel piece_0 = render_test::pixel(*by_piece, 150, lower), piece_1 = render_test::pixel(*by_piece, 150, upper);
  CHECK(piece_0.b > piece_0.r + 80);
  CHECK(piece_1.r > piece_1.b + 80);

  // A value keeps its colour when the others are not in the picture: the upper piece alone
  // (clipped above z = 1.5) is still orange, not the first colour of the table.
  const kerf::ClipPlane above{{0, 0, 1.5}, {0, 0, 1}};
  const vtkSmartPointer<vtkImageData> alone = draw_two_pieces("colour_piece_alone", 0.3, 1.0, render_test::front_view("piece"), above);
  const render_test::ScanLine up_alone = render_test::scan_column(*alone, 150);
  const render_test::Pixel only_1 = render_test::pixel(*alone, 150, (up_alone.first + up_alone.last) / 2);
  CHECK(only_1.r > only_1.b + 80);
}
