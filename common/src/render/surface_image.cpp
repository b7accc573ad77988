#include "kerf/render/surface_image.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/render/warped_surface.hpp"

#include <vtkActor.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>
#include <vtkVariant.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <string>

namespace kerf {
namespace {

/// The colours of the values -1, 0, 1, ..., 10 of a cell array such as the XFEM view's
/// `piece`: a light grey for -1 (there, the tets drawn whole), then colours that stay apart for
/// most colour-blind readers (Okabe and Ito's palette). A value keeps its colour whatever other
/// values a picture shows, so that pictures of one body, clipped or not, agree.
constexpr int first_category = -1;
constexpr double category_colours[12][3] = {
    {0.80, 0.80, 0.80}, {0.00, 0.45, 0.70}, {0.90, 0.62, 0.00}, {0.00, 0.62, 0.45},
    {0.80, 0.40, 0.00}, {0.34, 0.71, 0.91}, {0.80, 0.60, 0.70}, {0.94, 0.89, 0.26},
    {0.40, 0.40, 0.40}, {0.55, 0.00, 0.55}, {0.60, 0.30, 0.10}, {0.10, 0.10, 0.40}};

/// The distinct values of an array when all are whole numbers from -1 to 10, each of which
/// then gets its own colour; otherwise an empty set, and the array is drawn on a scale.
std::set<int> category_values(vtkDataArray& array) {
  std::set<int> values;
  for (vtkIdType i = 0; i < array.GetNumberOfTuples(); ++i) {
    const double value = array.GetTuple1(i);
    if (value != std::round(value) || value < first_category || value >= first_category + 12) return {};
    values.insert(static_cast<int>(value));
  }
  return values;
}

/// Colours the mapper by the array settings.colour_by names, and gives the colour bar its
/// title and table. One colour per value for a cell array of whole numbers from -1 to 10 (with
/// the values as the bar's labels); otherwise VTK's blue-to-red scale over the array's range.
void colour_mapper(vtkPolyDataMapper& mapper, vtkLookupTable& table, vtkScalarBarActor& bar, vtkPolyData& surface,
                   const std::string& colour_by) {
  const bool by_displacement = colour_by == "displacement";
  vtkDataArray* array = by_displacement ? surface.GetPointData()->GetArray(displacement_magnitude_name)
                                        : surface.GetCellData()->GetArray(colour_by.c_str());
  if (!array || array->GetNumberOfComponents() != 1)
    throw std::invalid_argument("render_surface_image: the surface has no one-component array for '" + colour_by + "'");
  mapper.SetScalarVisibility(true);
  if (by_displacement) {
    mapper.SetScalarModeToUsePointFieldData();
    mapper.SelectColorArray(displacement_magnitude_name);
  } else {
    mapper.SetScalarModeToUseCellFieldData();
    mapper.SelectColorArray(colour_by.c_str());
  }
  double range[2];
  array->GetRange(range);
  const std::set<int> values = by_displacement ? std::set<int>{} : category_values(*array);
  if (!values.empty()) {
    // Indexed lookup: the k-th annotated value gets the k-th colour of the table.
    table.IndexedLookupOn();
    table.SetNumberOfTableValues(static_cast<vtkIdType>(values.size()));
    vtkIdType k = 0;
    for (const int value : values) {
      const double* rgb = category_colours[value - first_category];
      table.SetTableValue(k++, rgb[0], rgb[1], rgb[2]);
      table.SetAnnotation(vtkVariant(static_cast<double>(value)), std::to_string(value));
    }
  } else {
    // A body that does not move has |u| = 0 everywhere: a range of zero width would leave the
    // table undefined, so it gets a width.
    if (range[1] <= range[0]) range[1] = range[0] + 1.0;
    table.SetHueRange(0.667, 0.0);
  }
  table.Build();
  mapper.SetLookupTable(&table);
  mapper.SetScalarRange(range);
  bar.SetLookupTable(&table);
  bar.SetTitle(by_displacement ? "|u| (m)" : colour_by.c_str());
}

/// The colour bar: a narrow strip at the right edge, black text on the white background. Its
/// text gets sizes in proportion to the picture's height (VTK would fit each text to its box,
/// which leaves a category's one-digit label tiny beside a long title).
void place_colour_bar(vtkScalarBarActor& bar, int picture_height) {
  bar.SetOrientationToVertical();
  bar.GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  bar.GetPositionCoordinate()->SetValue(0.86, 0.1);
  bar.SetWidth(0.12);
  bar.SetHeight(0.8);
  bar.SetNumberOfLabels(5);
  bar.SetLabelFormat("%.3g");
  bar.UnconstrainedFontSizeOn();
  for (vtkTextProperty* text : {bar.GetTitleTextProperty(), bar.GetLabelTextProperty(), bar.GetAnnotationTextProperty()}) {
    text->SetColor(0.0, 0.0, 0.0);
    text->ShadowOff();
    text->ItalicOff();
    text->BoldOff();
    text->SetFontSize(std::max(8, picture_height / 40));
  }
  bar.GetTitleTextProperty()->SetFontSize(std::max(10, picture_height / 30));
}

} // namespace

vtkSmartPointer<vtkImageData> render_surface_image(vtkPolyData& surface, const PictureSettings& settings) {
  if (settings.width < 1 || settings.height < 1) throw std::invalid_argument("render_surface_image: the size must be at least 1 by 1 pixels");
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw InputError("environment", "DISPLAY", "no X display to draw on (VTK 9.1 draws through X): run under xvfb-run -a");

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(&surface);
  vtkNew<vtkLookupTable> table;
  vtkNew<vtkScalarBarActor> bar;
  colour_mapper(*mapper, *table, *bar, surface, settings.colour_by);
  place_colour_bar(*bar, settings.height);

  vtkNew<vtkActor> body;
  body->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(body);
  renderer->AddActor2D(bar);
  const auto& [r, g, b] = picture_background;
  renderer->SetBackground(r / 255.0, g / 255.0, b / 255.0);
  // The camera is fitted to the body alone: the colour bar is a 2D actor, outside the bounds.
  place_camera(*renderer, settings.camera);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(settings.width, settings.height);
  window->AddRenderer(renderer);
  return window_picture(*window);
}

vtkSmartPointer<vtkImageData> window_picture(vtkRenderWindow& window) {
  window.Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(&window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkSmartPointer<vtkImageData> image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

} // namespace kerf
