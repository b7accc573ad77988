// Chapter 8's liver (mesh/liver_wedge.hpp): a wedge, thick and round at the back of the right
// lobe, thin at the sharp inferior border in front and at the left lobe's tip, where chapter 7's
// two lobes are round everywhere; inside its bounding box; Mesh_3 meshes it with about the tets
// asked for and its volume; a scene asks for it by name and a wrong name is refused in one line.
#include "kerf/app/input_error.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/mesh/liver_shape.hpp"
#include "kerf/mesh/liver_wedge.hpp"
#include "kerf/mesh/check_tet_mesh.hpp"
#include "kerf/mesh/tet_quality.hpp"
#include "kerf/scene/scene.hpp"
#include "support/relative_approx.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>

namespace {

using Phi = std::function<double(const Eigen::Vector3d&)>;

// The length of the vertical line through (x, y) inside {phi < 0}, on 0.25 mm samples (m).
double thickness(const Phi& phi, double x, double y) {
  constexpr double dz = 0.00025;
  double inside = 0.0;
  for (double z = -0.2; z < 0.2; z += dz) inside += phi(Eigen::Vector3d(x, y, z)) < 0.0 ? dz : 0.0;
  return inside;
}

// The most anterior y (smallest) at which the vertical line through x meets the shape, on 0.25 mm steps.
double front(const Phi& phi, double x) {
  for (double y = -0.2; y < 0.2; y += 0.00025)
    if (thickness(phi, x, y) > 0.0) return y;
  return 0.2;
}

// The thickest vertical line at x over y (m).
double thickest(const Phi& phi, double x) {
  double most = 0.0;
  for (double y = -0.15; y < 0.15; y += 0.002) most = std::max(most, thickness(phi, x, y));
  return most;
}

} // namespace

TEST_CASE("the wedge has a sharp inferior border where the two lobes are round, and its left lobe thins to a tip") {
  const Phi wedge = kerf::liver_wedge_phi;
  const Phi lobes = [](const Eigen::Vector3d& x) { return kerf::liver_phi(x); };
  // Behind the front of the right lobe (x = -3 cm for the wedge, +2.5 cm for chapter 7's, whose
  // right lobe lies at +x), along the vertical lines d behind it: a wedge's thickness grows
  // linearly with d, a round front's like sqrt(d), so from d = 5 to 20 mm a wedge's grows four
  // times and a round front's two. Measured: wedge 18.0 -> 44.8 mm (2.5 times: the 2 mm blend
  // and the dome's curvature round the edge), lobes 42.8 -> 76.0 mm (1.8 times).
  const double wedge_front = front(wedge, -0.03), lobes_front = front(lobes, 0.025);
  const double wedge_5 = thickness(wedge, -0.03, wedge_front + 0.005), wedge_20 = thickness(wedge, -0.03, wedge_front + 0.02);
  const double lobes_5 = thickness(lobes, 0.025, lobes_front + 0.005), lobes_20 = thickness(lobes, 0.025, lobes_front + 0.02);
  CHECK(wedge_5 < 0.5 * lobes_5);
  CHECK(wedge_20 > 2.2 * wedge_5);
  CHECK(lobes_20 < 2.0 * lobes_5);
  // Thick at the back of the right lobe, the left lobe less than half of it: measured 9.5 and
  // 4.2 cm.
  const double right = thickest(wedge, -0.03), left = thickest(wedge, 0.09);
  CHECK(right > 0.09);
  CHECK(left < 0.45 * right);
  // The notch cuts into the border between the lobes: the front there lies behind the front on
  // either side of it. Measured 2.3 mm behind the deeper of its neighbours (4.5 cm behind the
  // body's front).
  CHECK(front(wedge, 0.025) > std::max(front(wedge, 0.0), front(wedge, 0.05)) + 0.001);
}

TEST_CASE("the wedge lies inside its bounding box and liver_domain sizes it") {
  const kerf::LiverDomain domain = kerf::liver_domain(kerf::LiverShape::wedge);
  const Eigen::AlignedBox3d box = kerf::liver_wedge_bounding_box();
  CHECK(kerf::liver_wedge_phi(domain.centre) < 0.0);
  CHECK(domain.radius > 0.5 * box.diagonal().norm());
  // Every inside midpoint of 1.5 mm cubes over the box grown by 5 mm lies in the box; their volume
  // agrees with the domain's 2 mm count to well within the mesher's needs (measured 0.01 %).
  const Eigen::AlignedBox3d search(box.min() - Eigen::Vector3d::Constant(0.005), box.max() + Eigen::Vector3d::Constant(0.005));
  const double h = 0.0015;
  double volume = 0.0;
  bool all_inside_box = true;
  for (double z = search.min().z() + 0.5 * h; z < search.max().z(); z += h)
    for (double y = search.min().y() + 0.5 * h; y < search.max().y(); y += h)
      for (double x = search.min().x() + 0.5 * h; x < search.max().x(); x += h) {
        const Eigen::Vector3d p(x, y, z);
        if (kerf::liver_wedge_phi(p) >= 0.0) continue;
        volume += h * h * h;
        all_inside_box = all_inside_box && box.contains(p);
      }
  CHECK(all_inside_box);
  CHECK(domain.volume == kerf_test::relative(volume, 0.01));
}

TEST_CASE("Mesh_3 meshes the wedge with about the tets asked for and its volume") {
  const kerf::TetMesh mesh = kerf::make_liver_mesh(3000, kerf::LiverShape::wedge);
  CHECK(mesh.num_tets() > 0.7 * 3000);
  CHECK(mesh.num_tets() < 1.3 * 3000);
  double volume = 0.0;
  Eigen::Index non_positive = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    const double v = kerf::signed_tet_volume(mesh, t);
    volume += v;
    non_positive += v > 0.0 ? 0 : 1;
  }
  CHECK(non_positive == 0);
  // Chords of a convex surface cut a little off: chapter 7's lobes lose 2.15 % at 3000 tets, the
  // wedge 1.55 % (3364 tets: Mesh_3's factors were measured on the lobes, 12 % over here).
  const double domain_volume = kerf::liver_domain(kerf::LiverShape::wedge).volume;
  CHECK(volume < domain_volume);
  CHECK(volume > 0.95 * domain_volume);
  CHECK(kerf::tet_quality_summary(mesh).min_dihedral_angle > 5.0);
}

TEST_CASE("a scene asks for the wedge by name; another name is refused naming the field") {
  const auto scene_with = [](const std::string& shape) {
    return kerf::parse_scene(R"({"name": "w", "mesh": {"liver": {"tets": 2000, "shape": ")" + shape +
                                 R"("}}, "material": {"young": 4000, "poisson": 0.45}, "dirichlet": []})",
                             "wedge.json", ".");
  };
  CHECK(scene_with("wedge").mesh.liver_shape == kerf::LiverShape::wedge);
  CHECK(scene_with("lobes").mesh.liver_shape == kerf::LiverShape::lobes);
  try {
    (void)scene_with("round");
    FAIL("a liver shape \"round\" was accepted");
  } catch (const kerf::InputError& error) {
    CHECK(std::string(error.what()) == "wedge.json: mesh.liver.shape: expected \"lobes\" or \"wedge\", got \"round\"");
  }
}
