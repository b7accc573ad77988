#include "kerf/render/organ_view.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/render/surface_image.hpp"
#include "kerf/render/triangle_surface_polydata.hpp"
#include "kerf/render/write_png.hpp"

#include <vtkActor.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>

namespace kerf {

struct OrganView::Data {
  vtkNew<vtkPolyDataMapper> skin_mapper, wall_mapper, blade_mapper;
  vtkNew<vtkActor> skin, walls, blade;
  vtkNew<vtkTextActor> caption;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
};

namespace {

// Colours of liver tissue: the capsule's dark red-brown, and the paler parenchyma a cut exposes.
constexpr double skin_colour[3] = {0.55, 0.16, 0.12};
constexpr double wall_colour[3] = {0.86, 0.47, 0.42};
constexpr double steel_colour[3] = {0.72, 0.75, 0.8};

// A bar of square cross-section 2h around the segment from a to b: 8 corners, 12 triangles.
TriangleSurface bar_along(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double h) {
  const Eigen::Vector3d axis = (b - a).normalized();
  const Eigen::Vector3d any = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = axis.cross(any).normalized() * h, e2 = axis.cross(e1).normalized() * h;
  TriangleSurface bar;
  bar.vertices.resize(8, 3);
  const Eigen::Vector3d ends[2] = {a, b};
  const Eigen::Vector3d offsets[4] = {-e1 - e2, e1 - e2, e1 + e2, -e1 + e2};
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < 4; ++k) bar.vertices.row(4 * end + k) = (ends[end] + offsets[k]).transpose();
  bar.triangles.resize(12, 3);
  int row = 0;
  for (int k = 0; k < 4; ++k) { // the four sides
    const int k1 = (k + 1) % 4;
    bar.triangles.row(row++) << k, k1, 4 + k1;
    bar.triangles.row(row++) << k, 4 + k1, 4 + k;
  }
  bar.triangles.row(row++) << 0, 2, 1; // the two ends
  bar.triangles.row(row++) << 0, 3, 2;
  bar.triangles.row(row++) << 4, 5, 6;
  bar.triangles.row(row++) << 4, 6, 7;
  return bar;
}

void look(vtkActor& actor, const double colour[3]) {
  actor.GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  actor.GetProperty()->SetAmbient(0.15);
  actor.GetProperty()->SetDiffuse(0.8);
  actor.GetProperty()->SetSpecular(0.25);
  actor.GetProperty()->SetSpecularPower(30);
}

} // namespace

OrganViewSettings organ_view_settings(const RenderSpec& render, bool on_screen) {
  OrganViewSettings settings;
  settings.width = render.width;
  settings.height = render.height;
  settings.camera = {.azimuth = render.azimuth, .elevation = render.elevation, .zoom = render.zoom};
  settings.on_screen = on_screen;
  return settings;
}

OrganView::OrganView(const TriangleSurface& at_rest, const OrganViewSettings& settings) : data_(std::make_unique<Data>()) {
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw InputError("environment", "DISPLAY", "no X display to draw on (VTK 9.1 draws through X): run under xvfb-run -a");
  data_->skin_mapper->ScalarVisibilityOff();
  data_->wall_mapper->ScalarVisibilityOff();
  data_->skin->SetMapper(data_->skin_mapper);
  data_->walls->SetMapper(data_->wall_mapper);
  look(*data_->skin, skin_colour);
  look(*data_->walls, wall_colour);
  data_->blade_mapper->ScalarVisibilityOff();
  data_->blade->SetMapper(data_->blade_mapper);
  look(*data_->blade, steel_colour);
  data_->blade->GetProperty()->SetSpecular(0.6);
  data_->blade->SetVisibility(0);
  // The window picks the organ under the mouse; the blade drawn along the line of sight under it
  // would be picked first and pull the next edge out towards the camera.
  data_->blade->PickableOff();
  // The inside of the skin shows through the gap of an opened cut: the back faces get the
  // walls' colour, darker, so that a look into the wound reads as tissue.
  vtkNew<vtkProperty> inside;
  inside->SetColor(0.6 * wall_colour[0], 0.6 * wall_colour[1], 0.6 * wall_colour[2]);
  data_->skin->SetBackfaceProperty(inside);
  data_->renderer->AddActor(data_->skin);
  data_->renderer->AddActor(data_->walls);
  data_->renderer->AddActor(data_->blade);
  vtkTextProperty* text = data_->caption->GetTextProperty();
  text->SetFontSize(16);
  text->SetColor(0.1, 0.1, 0.1);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToTop();
  data_->caption->SetPosition(10, settings.height - 10);
  data_->caption->SetVisibility(0);
  data_->renderer->AddViewProp(data_->caption);
  const auto& [r, g, b] = picture_background;
  data_->renderer->SetBackground(r / 255.0, g / 255.0, b / 255.0);
  data_->window->SetOffScreenRendering(settings.on_screen ? 0 : 1);
  // A window redraws at every step: without multisampling. VTK's default, 8 samples a pixel, is
  // kept for the PNG frames the book shows; under Mesa's software OpenGL it makes a 960 x 720
  // frame cost 265 ms instead of 95 (chapter 7's results), for edges a little less jagged.
  if (settings.on_screen) data_->window->SetMultiSamples(0);
  data_->window->SetSize(settings.width, settings.height);
  data_->window->AddRenderer(data_->renderer);
  show(at_rest, TriangleSurface{});
  place_camera(*data_->renderer, settings.camera);
}

OrganView::~OrganView() = default;

void OrganView::show(const TriangleSurface& skin, const TriangleSurface& cut_walls, const std::optional<BladeEdge>& blade) {
  data_->skin_mapper->SetInputData(triangle_surface_polydata(skin, Shading::smooth));
  data_->wall_mapper->SetInputData(triangle_surface_polydata(cut_walls, Shading::faceted));
  data_->walls->SetVisibility(cut_walls.num_triangles() > 0);
  const bool drawn = blade && (blade->end - blade->start).norm() > 0.0;
  if (drawn) data_->blade_mapper->SetInputData(triangle_surface_polydata(bar_along(blade->start, blade->end, 0.00075), Shading::faceted));
  data_->blade->SetVisibility(drawn ? 1 : 0);
  data_->renderer->ResetCameraClippingRange();
}

void OrganView::caption(const std::string& text) {
  data_->caption->SetInput(text.c_str());
  data_->caption->SetVisibility(text.empty() ? 0 : 1);
}

vtkSmartPointer<vtkImageData> OrganView::picture() { return window_picture(*data_->window); }

void OrganView::write_png(const std::filesystem::path& file) { kerf::write_png(file, *picture()); }

vtkRenderWindow& OrganView::window() { return *data_->window; }
vtkRenderer& OrganView::renderer() { return *data_->renderer; }

} // namespace kerf
