#include "kerf/scene/scene_dynamic_mass.hpp"

#include "kerf/scene/cut_xfem_loads.hpp"
#include "kerf/xfem/cut_xfem_mass.hpp"

namespace kerf {

std::optional<LumpingScheme> scene_lumping_scheme(const Scene& scene) {
  const std::string& mass = scene.time.mass;
  if (mass == "consistent") return std::nullopt;
  if (mass == "row_sum") return LumpingScheme::row_sum;
  if (mass == "hrz") return LumpingScheme::hrz;
  if (mass == "virtual_tet") return LumpingScheme::virtual_tet;
  if (mass == "schoch_eq_81_82") return LumpingScheme::schoch_eq_81_82;
  return LumpingScheme::bernstein; // "lumped" and "bernstein" (read_time accepts nothing else)
}

Eigen::SparseMatrix<double> scene_cut_xfem_mass(const Scene& scene, const CutXfemModel& model, const PieceRuleFunction& rule) {
  const std::optional<LumpingScheme> scheme = scene_lumping_scheme(scene);
  if (!scheme) return assemble_cut_xfem_mass(model, scene.material.density, rule);
  return lump_cut_xfem_mass(model, scene.material.density, *scheme, rule);
}

Eigen::SparseMatrix<double> scene_cut_xfem_mass(const Scene& scene, const CutXfemModel& model, const SplitTetMasses& masses) {
  const std::optional<LumpingScheme> scheme = scene_lumping_scheme(scene);
  if (!scheme) return assemble_cut_xfem_mass(model, scene.material.density, masses);
  return lump_cut_xfem_mass(model, scene.material.density, *scheme, masses);
}

Eigen::VectorXd scene_cut_xfem_dynamic_loads(const Scene& scene, const CutXfemModel& model, const BoundaryFaces& boundary,
                                             const PieceRuleFunction& rule) {
  const std::optional<LumpingScheme> scheme = scene_lumping_scheme(scene);
  if (!scheme) return cut_xfem_scene_loads(scene, model, boundary);
  Scene without_gravity = scene;
  without_gravity.gravity.setZero();
  return cut_xfem_scene_loads(without_gravity, model, boundary) +
         lumped_gravity_load(model, scene.material.density, scene.gravity, *scheme, rule);
}

} // namespace kerf
