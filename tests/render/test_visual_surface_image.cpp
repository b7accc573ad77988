// The visual surface drawn (render/triangle_surface_polydata.hpp): a sphere's fine surface, written
// as a PNG of the requested size that is not blank, lit smoothly with vertex normals, where
// the same triangles drawn faceted show jumps of brightness at their edges; and a visual sphere
// moved by an opened XFEM cut, which shows the background through the gap.
#include "two_pieces.hpp"

#include "support/cut_body.hpp"
#include "kerf/mesh/box_mesh.hpp"
#include "kerf/mesh/implicit_surface_mesh.hpp"
#include "kerf/render/cutting_window.hpp"
#include "kerf/render/organ_view.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/triangle_surface_polydata.hpp"
#include "kerf/render/write_png.hpp"
#include "kerf/xfem/visual_surface.hpp"
#include "support/run_program.hpp"

#include <doctest/doctest.h>

#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkRenderWindow.h>

#include <algorithm>
#include <cstdlib>

namespace {

const kerf::TriangleSurface& sphere() {
  static const kerf::TriangleSurface surface = kerf::implicit_surface_mesh(
      [](const Eigen::Vector3d& x) { return x.norm() - 1.0; }, Eigen::Vector3d::Zero(), 1.2, kerf::implicit_surface_sizing(0.15));
  return surface;
}

// The largest change of brightness (r + g + b) between neighbours along row j, inside the body
// (from the first drawn pixel to the first background one after it, 10 pixels in from both:
// the colour bar further right is not the body).
int largest_step(vtkImageData& image, int j) {
  int first = 0;
  while (first < 300 && render_test::is_background(image, first, j)) ++first;
  int last = first;
  while (last + 1 < 300 && !render_test::is_background(image, last + 1, j)) ++last;
  int largest = 0;
  for (int i = first + 10; i < last - 10; ++i) {
    const render_test::Pixel a = render_test::pixel(image, i, j), b = render_test::pixel(image, i + 1, j);
    largest = std::max(largest, std::abs((a.r + a.g + a.b) - (b.r + b.g + b.b)));
  }
  return largest;
}

} // namespace

TEST_CASE("a visual surface is written as a PNG of the requested size, not blank") {
  const auto png = kerf_test::fresh_dir("visual_surface") / "sphere.png";
  const auto surface = kerf::triangle_surface_polydata(sphere(), kerf::Shading::smooth);
  const vtkSmartPointer<vtkImageData> image = kerf::render_surface_image(*surface, render_test::front_view(kerf::surface_label_name));
  kerf::write_png(png, *image);
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.string().c_str());
  reader->Update();
  CHECK(reader->GetOutput()->GetDimensions()[0] == 300);
  CHECK(reader->GetOutput()->GetDimensions()[1] == 300);
  // Not blank: the grey levels vary (the pixels' variance is positive), and the sphere covers a
  // disc of a fitted size.
  double sum = 0.0, sum2 = 0.0;
  for (int j = 0; j < 300; ++j)
    for (int i = 0; i < 300; ++i) {
      const render_test::Pixel p = render_test::pixel(*reader->GetOutput(), i, j);
      sum += p.g, sum2 += p.g * p.g;
    }
  const double mean = sum / 90000.0;
  CHECK(sum2 / 90000.0 - mean * mean > 100.0);
  CHECK(render_test::drawn_fraction(*image) > 0.2);
}

TEST_CASE("vertex normals light the surface smoothly; face normals show the facets") {
  const auto smooth = kerf::triangle_surface_polydata(sphere(), kerf::Shading::smooth);
  const auto faceted = kerf::triangle_surface_polydata(sphere(), kerf::Shading::faceted);
  const kerf::PictureSettings settings = render_test::front_view(kerf::surface_label_name);
  const vtkSmartPointer<vtkImageData> a = kerf::render_surface_image(*smooth, settings);
  const vtkSmartPointer<vtkImageData> b = kerf::render_surface_image(*faceted, settings);
  int step_smooth = 0, step_faceted = 0;
  for (const int j : {120, 150, 180}) {
    step_smooth = std::max(step_smooth, largest_step(*a, j));
    step_faceted = std::max(step_faceted, largest_step(*b, j));
  }
  const auto dir = kerf_test::fresh_dir("visual_surface_shading"); // to look at
  kerf::write_png(dir / "smooth.png", *a);
  kerf::write_png(dir / "faceted.png", *b);
  MESSAGE("largest brightness step: smooth ", step_smooth, ", faceted ", step_faceted);
  // Measured 15 against 66 (of 765) on a sphere of 0.15-radius triangles.
  CHECK(step_faceted > 3 * step_smooth);
}

TEST_CASE("a visual sphere in a box opened by an XFEM cut shows the background through the gap") {
  // The unit box cut through by z = 0.43, its upper side lifted by 0.15 m (tests/chapter_07's
  // field: u_i the home side's value, a_k the other side's minus it), a sphere of radius 0.4 in it.
  kerf::TriangleSurface cut;
  cut.vertices = Eigen::MatrixX3d{{-1, -1, 0.43}, {2, -1, 0.43}, {2, 2, 0.43}, {-1, 2, 0.43}};
  cut.triangles = Eigen::MatrixX3i{{0, 1, 2}, {0, 2, 3}};
  const support::CutBody body(kerf::make_box_mesh({0, 0, 0}, {1, 1, 1}, {3, 3, 4}), {cut}, kerf::LinearMaterial{1000.0, 0.3, 1.0});
  const Eigen::Vector3d lift(0, 0, 0.15);
  const auto side_value = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return x.z() > 0.43 ? lift : Eigen::Vector3d::Zero(); };
  const Eigen::Index N = body.mesh.num_nodes();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * body.model.num_dof_nodes());
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Vector3d x = body.mesh.nodes.row(i).transpose();
    u.segment<3>(3 * i) = side_value(x);
    for (int k = body.enrichment.first_enrichment[static_cast<std::size_t>(i)]; k < body.enrichment.first_enrichment[static_cast<std::size_t>(i) + 1]; ++k)
      u.segment<3>(3 * (N + k)) = (x.z() > 0.43 ? Eigen::Vector3d::Zero() : lift) - side_value(x);
  }
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  const kerf::TriangleSurface sphere = kerf::implicit_surface_mesh(
      [&](const Eigen::Vector3d& x) { return (x - centre).norm() - 0.4; }, centre, 0.49, kerf::implicit_surface_sizing(0.03));
  const kerf::VisualSurface visual(body.mesh, sphere);
  const kerf::TriangleSurface moved = kerf::keep_triangles(visual.deform(kerf::xfem_visual_displacement(body.model, u)),
                                                           kerf::untorn_triangles(sphere, kerf::CutSurfaces({cut})));
  const auto surface = kerf::triangle_surface_polydata(moved, kerf::Shading::smooth);
  const vtkSmartPointer<vtkImageData> image = kerf::render_surface_image(*surface, render_test::front_view(kerf::surface_label_name));
  kerf::write_png(kerf_test::fresh_dir("visual_surface_opened") / "opened.png", *image);
  // Along the column through the middle the body spans 0.8 + 0.15 m, of which the gap is the
  // lift, plus at most the strip of dropped triangles, about one triangle (3 cm) high; measured
  // 0.15 m: there, the inside of the far half of the sphere, seen through the ragged rim, fills the strip.
  const render_test::ScanLine up = render_test::scan_column(*image, 150);
  const double gap = static_cast<double>(up.background_between) / up.extent();
  MESSAGE("gap ", gap, " of the column, ", gap * 0.95, " m");
  CHECK(gap > 0.13 / 0.95);
  CHECK(gap < 0.22 / 0.95);
}

TEST_CASE("the organ view draws the blade in steel where it is given, and nothing of it otherwise") {
  // An organ of 5 cm radius (the sphere scaled) seen by OrganView (chapters 7 and 8's picture)
  // three times: without a blade, with one, without again. The blade is an edge standing beside
  // the organ, from (0.06, 0, -0.05) to (0.06, 0, 0.05) m, so that the skin hides none of it. The
  // pixels that change are the blade's, and steel is grey: r, g and b within 40 of each other.
  kerf::TriangleSurface organ = sphere();
  organ.vertices *= 0.05;
  kerf::OrganViewSettings settings;
  settings.width = 240;
  settings.height = 180;
  kerf::OrganView view(organ, settings);
  const auto draw = [&](const std::optional<kerf::BladeEdge>& blade) {
    view.show(organ, kerf::TriangleSurface{}, blade);
    vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
    copy->DeepCopy(view.picture());
    return copy;
  };
  const vtkSmartPointer<vtkImageData> before = draw(std::nullopt);
  const vtkSmartPointer<vtkImageData> with = draw(kerf::BladeEdge{{0.06, 0.0, -0.05}, {0.06, 0.0, 0.05}});
  const vtkSmartPointer<vtkImageData> after = draw(std::nullopt);
  int changed = 0, grey = 0, changed_after = 0;
  for (int j = 0; j < settings.height; ++j)
    for (int i = 0; i < settings.width; ++i) {
      const render_test::Pixel a = render_test::pixel(*before, i, j), b = render_test::pixel(*with, i, j),
                               c = render_test::pixel(*after, i, j);
      if (a.r != c.r || a.g != c.g || a.b != c.b) ++changed_after;
      if (a.r == b.r && a.g == b.g && a.b == b.b) continue;
      ++changed;
      if (std::max({b.r, b.g, b.b}) - std::min({b.r, b.g, b.b}) < 40) ++grey;
    }
  MESSAGE("pixels the blade changed: " << changed << ", grey among them: " << grey);
  CHECK(changed > 20);
  CHECK(grey >= 0.8 * changed);
  CHECK(changed_after == 0);
}

TEST_CASE("the window's blade: put down where the stroke starts over the skin, then held by the hand, not by the tissue") {
  // A sphere of 5 cm radius in a 240 x 180 window. Shift + a press left of the centre, then a move
  // to the centre: the blade's edge runs along the line of sight from 3 cm in front of the skin
  // under the cursor, 6 cm deep behind it.
  kerf::TriangleSurface organ = sphere();
  organ.vertices *= 0.05;
  kerf::OrganViewSettings settings;
  settings.width = 240;
  settings.height = 180;
  settings.on_screen = true;
  kerf::OrganView view(organ, settings);
  kerf::CuttingWindow window(view, 0.06);
  view.show(organ, kerf::TriangleSurface{});
  view.window().Render();
  window.deliver({0.0, kerf::WindowEvent::press, 110, 90, true});
  // A press alone does not put the blade down: the stroke starts when the cursor moves.
  CHECK_FALSE(window.blade());
  window.deliver({0.0, kerf::WindowEvent::move, 120, 90, true});
  const std::optional<kerf::BladeEdge> first = window.blade();
  REQUIRE(first);
  const Eigen::Vector3d skin = first->start + 0.03 * (first->end - first->start).normalized();
  MESSAGE("edge start " << first->start.transpose() << ", skin under the cursor at radius " << skin.norm());
  CHECK(std::abs(skin.norm() - 0.05) < 0.0025); // the sphere's facets: within 5 % of its radius
  CHECK(std::abs((first->end - first->start).norm() - 0.09) < 1e-12);
  // The tissue moves under the held blade (the sphere drawn 2 cm nearer the camera): the blade
  // stays where the hand holds it.
  kerf::TriangleSurface nearer = organ;
  const Eigen::Vector3d towards = -(first->end - first->start).normalized();
  for (Eigen::Index v = 0; v < nearer.vertices.rows(); ++v) nearer.vertices.row(v) += 0.02 * towards.transpose();
  view.show(nearer, kerf::TriangleSurface{}, first);
  view.window().Render();
  const std::optional<kerf::BladeEdge> held = window.blade();
  REQUIRE(held);
  CHECK((held->start - first->start).norm() < 1e-9);
  // A new stroke at the same place, the blade still drawn under the cursor: the pick finds the
  // skin (the blade is not pickable), 2 cm nearer now, not the bar's near end in front of it.
  window.deliver({0.0, kerf::WindowEvent::release, 120, 90, true});
  CHECK_FALSE(window.blade());
  window.deliver({0.0, kerf::WindowEvent::press, 110, 90, true});
  window.deliver({0.0, kerf::WindowEvent::move, 120, 90, true});
  const std::optional<kerf::BladeEdge> again = window.blade();
  REQUIRE(again);
  const double nearer_by = (again->start - first->start).dot(towards);
  MESSAGE("the new stroke's edge is " << nearer_by << " m nearer the eye");
  CHECK(std::abs(nearer_by - 0.02) < 0.002); // the pick's facet: within a tenth
}
