#include "kerf/render/cutting_window.hpp"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <Eigen/Core>

#include <cmath>
#include <optional>

namespace kerf {

namespace {
// How far the cursor moves after the press before the blade is put down (the stroke_pixels of
// cutting_window.hpp).
constexpr double stroke_pixels = 8.0;
} // namespace

struct CuttingWindow::Data {
  OrganView& view;
  double depth;
  vtkRenderWindowInteractor* interactor = nullptr;
  vtkNew<vtkCellPicker> picker;
  vtkNew<vtkCallbackCommand> events, timer;
  bool cutting = false, turning = false, closed = false;
  bool stroke = false;         // the cursor has moved stroke_pixels since the press that cuts
  std::optional<double> hand_distance; // the blade's distance from the eye in this stroke (m)
  int x = 0, y = 0;
  int press_x = 0, press_y = 0;
  std::function<void()> tick;

  Data(OrganView& v, double d) : view(v), depth(d) {}

  // The mouse: the left button with Shift held cuts; without Shift it turns the camera.
  void on_event(unsigned long event) {
    int ex = 0, ey = 0;
    interactor->GetEventPosition(ex, ey);
    if (event == vtkCommand::LeftButtonPressEvent) {
      (interactor->GetShiftKey() ? cutting : turning) = true;
      stroke = false;
      hand_distance.reset();
      press_x = ex;
      press_y = ey;
    }
    if (event == vtkCommand::LeftButtonReleaseEvent) cutting = turning = stroke = false;
    if (event == vtkCommand::MouseMoveEvent && cutting && std::hypot(ex - press_x, ey - press_y) >= stroke_pixels) stroke = true;
    if (event == vtkCommand::MouseMoveEvent && turning) {
      vtkCamera* camera = view.renderer().GetActiveCamera();
      camera->Azimuth(-0.4 * (ex - x));
      camera->Elevation(-0.4 * (ey - y));
      camera->OrthogonalizeViewUp();
      view.renderer().ResetCameraClippingRange();
    }
    if (event == vtkCommand::KeyPressEvent && interactor->GetKeyCode() == 'q') {
      closed = true;
      interactor->TerminateApp();
    }
    x = ex;
    y = ey;
  }
};

CuttingWindow::CuttingWindow(OrganView& view, double blade_depth) : data_(std::make_unique<Data>(view, blade_depth)) {
  Data& d = *data_;
  d.interactor = vtkRenderWindowInteractor::New();
  d.interactor->SetRenderWindow(&view.window());
  d.interactor->SetInteractorStyle(nullptr);
  d.interactor->Initialize();
  d.picker->SetTolerance(0.0005);
  d.events->SetClientData(&d);
  d.events->SetCallback([](vtkObject*, unsigned long id, void* data, void*) { static_cast<Data*>(data)->on_event(id); });
  for (unsigned long id : {vtkCommand::LeftButtonPressEvent, vtkCommand::LeftButtonReleaseEvent, vtkCommand::MouseMoveEvent,
                           vtkCommand::KeyPressEvent})
    d.interactor->AddObserver(id, d.events, 1.0);
  d.timer->SetClientData(&d);
  d.timer->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
    Data& self = *static_cast<Data*>(data);
    if (self.tick) self.tick();
  });
  d.interactor->AddObserver(vtkCommand::TimerEvent, d.timer);
}

CuttingWindow::~CuttingWindow() { data_->interactor->Delete(); }

std::optional<BladeEdge> CuttingWindow::blade() {
  Data& d = *data_;
  if (!d.cutting || !d.stroke) return std::nullopt;
  vtkRenderer& renderer = d.view.renderer();
  double camera[3];
  renderer.GetActiveCamera()->GetPosition(camera);
  const Eigen::Vector3d c(camera[0], camera[1], camera[2]);
  // The hand's distance from the eye: the skin's under the cursor, found once per stroke, when
  // the cursor first lies over the organ. After that the skin moving under the blade (the organ
  // sags, the wound opens) does not move it: a scalpel is held by the hand, not by the tissue.
  if (!d.hand_distance) {
    if (!d.picker->Pick(d.x, d.y, 0.0, &renderer)) return std::nullopt;
    double picked[3];
    d.picker->GetPickPosition(picked);
    d.hand_distance = (Eigen::Vector3d(picked[0], picked[1], picked[2]) - c).norm();
  }
  // The line of sight through the cursor: from the eye through the cursor's point on the near
  // plane.
  renderer.SetDisplayPoint(d.x, d.y, 0.0);
  renderer.DisplayToWorld();
  double near[4];
  renderer.GetWorldPoint(near);
  const Eigen::Vector3d direction = (Eigen::Vector3d(near[0], near[1], near[2]) / near[3] - c).normalized();
  const Eigen::Vector3d p = c + *d.hand_distance * direction;
  return BladeEdge{p - 0.03 * direction, p + d.depth * direction};
}

bool CuttingWindow::cutting() const { return data_->cutting; }

void CuttingWindow::close() { data_->interactor->TerminateApp(); }

bool CuttingWindow::closed() const { return data_->closed; }

void CuttingWindow::deliver(const ScriptedEvent& e) {
  vtkRenderWindowInteractor& interactor = *data_->interactor;
  interactor.SetEventInformation(e.x, e.y, 0, e.shift ? 1 : 0, e.event == WindowEvent::key_q ? 'q' : 0);
  switch (e.event) {
  case WindowEvent::press: interactor.InvokeEvent(vtkCommand::LeftButtonPressEvent); break;
  case WindowEvent::release: interactor.InvokeEvent(vtkCommand::LeftButtonReleaseEvent); break;
  case WindowEvent::move: interactor.InvokeEvent(vtkCommand::MouseMoveEvent); break;
  case WindowEvent::key_q: interactor.InvokeEvent(vtkCommand::KeyPressEvent); break;
  }
}

void CuttingWindow::run(int tick_ms, const std::function<void()>& tick) {
  data_->tick = tick;
  data_->interactor->CreateRepeatingTimer(static_cast<unsigned long>(std::max(1, tick_ms)));
  data_->interactor->Start();
  data_->tick = nullptr;
}

} // namespace kerf
