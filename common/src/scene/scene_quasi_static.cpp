#include "kerf/scene/scene_quasi_static.hpp"

namespace kerf {

QuasiStaticSettings scene_quasi_static_settings(const Scene& scene) {
  QuasiStaticSettings settings;
  settings.load_steps = scene.quasi_static.load_steps;
  settings.max_iterations = scene.quasi_static.max_iterations;
  settings.tolerance = scene.quasi_static.tolerance;
  settings.tangent = scene.quasi_static.tangent == "warped" ? CorotationalTangent::warped : CorotationalTangent::consistent;
  settings.rotation = scene.quasi_static.rotation == "higham" ? RotationMethod::higham
                      : scene.quasi_static.rotation == "svd" ? RotationMethod::svd
                                                             : RotationMethod::automatic;
  settings.predictor = scene.quasi_static.predictor == "previous" ? LoadStepPredictor::previous_state : LoadStepPredictor::secant;
  settings.solver = scene.solver;
  return settings;
}

} // namespace kerf
