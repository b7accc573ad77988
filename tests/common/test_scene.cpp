// The scene file: a full scene is read with every field; every malformed variant is an
// InputError whose one-line message names the file and the field.
#include "kerf/app/input_error.hpp"
#include "kerf/scene/scene.hpp"

#include <doctest/doctest.h>

#include <string>

namespace {

const char* full_scene = R"({
  "name": "full",
  "mesh": {"file": "beam.msh", "order": 2, "scale": 0.001},
  "material": {"young": 5000, "poisson": 0.45, "density": 1000},
  "model": "corotational",
  "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [1, 1, 0]}}, "displacement": [0, 0, 0.01]},
                {"region": {"nodes": [3, 39, 64]}}],
  "gravity": [0, -9.81, 0],
  "traction": [{"region": {"box": {"min": [0, 0, 1], "max": [1, 1, 1]}}, "total_force": [0, 0, -2]}],
  "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}, {"surface": "cut.obj"}],
  "time": {"integrator": "newmark", "dt": 0.01, "steps": 100, "rayleigh": [0.1, 0.01]},
  "output": {"every": 5},
  "solver": {"type": "cg-ichol", "ordering": "amd", "tolerance": 1e-8, "max_iterations": 500}
})";

// Parses `text` and returns the error message, or "" if it parsed.
std::string error_of(const std::string& text) {
  try {
    kerf::parse_scene(text, "scene.json", "/data");
  } catch (const kerf::InputError& error) {
    return error.what();
  }
  return "";
}

const std::string box_mesh = R"("mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}})";

} // namespace

TEST_CASE("a full scene is read field by field") {
  const kerf::Scene scene = kerf::parse_scene(full_scene, "full.json", "/data");
  CHECK(scene.name == "full");
  CHECK_FALSE(scene.mesh.is_box);
  CHECK(scene.mesh.file == std::filesystem::path("/data/beam.msh"));
  CHECK(scene.mesh.order == 2);
  CHECK(scene.mesh.scale == 0.001);
  CHECK(scene.material.poisson == 0.45);
  CHECK(scene.model == "corotational");
  REQUIRE(scene.dirichlet.size() == 2);
  CHECK(scene.dirichlet[0].displacement.z() == 0.01);
  CHECK(scene.dirichlet[1].region.node_list == std::vector<int>{3, 39, 64});
  CHECK(scene.dirichlet[1].displacement.isZero());
  CHECK(scene.gravity.y() == -9.81);
  CHECK(scene.traction[0].total_force.z() == -2.0);
  REQUIRE(scene.cuts.size() == 2);
  CHECK(scene.cuts[0].edge1.x() == 0.015);
  CHECK(scene.cuts[1].surface == std::filesystem::path("/data/cut.obj"));
  CHECK(scene.cuts[1].surface_scale == 1.0);
  CHECK(scene.time.integrator == "newmark");
  CHECK(scene.time.steps == 100);
  CHECK(scene.time.beta == 0.25);
  CHECK(scene.output_every == 5);
  CHECK(scene.solver.type == "cg-ichol");
  CHECK(scene.solver.ordering == "amd");
}

TEST_CASE("a cut surface is a path, or a file with a scale") {
  const kerf::Scene scene = kerf::parse_scene(
      "{" + box_mesh + R"(, "cuts": [{"surface": {"file": "cut_mm.stl", "scale": 0.001}}, {"surface": {"file": "/abs/cut.off"}}]})",
      "scene.json", "/data");
  REQUIRE(scene.cuts.size() == 2);
  CHECK_FALSE(scene.cuts[0].is_rectangle);
  CHECK(scene.cuts[0].surface == std::filesystem::path("/data/cut_mm.stl"));
  CHECK(scene.cuts[0].surface_scale == 0.001);
  CHECK(scene.cuts[1].surface == std::filesystem::path("/abs/cut.off"));
  CHECK(scene.cuts[1].surface_scale == 1.0);
}

TEST_CASE("defaults: the paper's material, linear, static, CHOLMOD") {
  const kerf::Scene scene = kerf::parse_scene("{" + box_mesh + "}", "min.json", ".");
  CHECK(scene.name == "min");
  CHECK(scene.material.young == 300e3);
  CHECK(scene.material.poisson == 0.35);
  CHECK(scene.material.density == 1070.0);
  CHECK(scene.model == "linear");
  CHECK(scene.time.integrator == "static");
  CHECK(scene.solver.type == "cholmod");
  CHECK(scene.solver.ordering == "nested-dissection");
  CHECK(scene.mesh.order == 1);
}

TEST_CASE("the time integrators of chapter 6 read their own fields, and their defaults") {
  const std::string m = box_mesh;
  const auto time_of = [&](const std::string& time) { return kerf::parse_scene("{" + m + R"(, "time": )" + time + "}", "t.json", ".").time; };
  const kerf::TimeSpec newmark = time_of(R"({"integrator": "newmark", "dt": 0.01, "steps": 5, "initial_velocity": [0, 0, -1]})");
  CHECK(newmark.beta == 0.25);
  CHECK(newmark.gamma == 0.5);
  CHECK(newmark.mass == "consistent");
  CHECK(newmark.initial_velocity.z() == -1.0);
  CHECK(newmark.corotation.empty()); // the chapter's default
  CHECK(time_of(R"({"integrator": "newmark", "dt": 0.01, "steps": 5, "corotation": "newton"})").corotation == "newton");
  CHECK(time_of(R"({"integrator": "newmark", "dt": 0.01, "steps": 5, "corotation": "checked"})").corotation == "checked");
  CHECK_FALSE(newmark.allow_unstable);
  // A pair outside the unconditionally stable range, asked for on purpose.
  const kerf::TimeSpec unstable = time_of(R"({"integrator": "newmark", "dt": 0.01, "steps": 5, "beta": 0.1, "allow_unstable": true})");
  CHECK(unstable.beta == 0.1);
  CHECK(unstable.allow_unstable);
  const kerf::TimeSpec damped = time_of(R"({"integrator": "newmark", "dt": 0.01, "steps": 5, "gamma": 0.6, "beta": 0.3025, "mass": "hrz"})");
  CHECK(damped.gamma == 0.6);
  CHECK(damped.mass == "hrz");
  // The explicit scheme lumps by default; HHT-alpha's alpha defaults to -0.1.
  CHECK(time_of(R"({"integrator": "central_difference", "dt": 1e-4, "steps": 5})").mass == "lumped");
  CHECK(time_of(R"({"integrator": "hht_alpha", "dt": 0.01, "steps": 5})").alpha == -0.1);
  CHECK(time_of(R"({"integrator": "hht_alpha", "dt": 0.01, "steps": 5, "alpha": -0.3})").alpha == -0.3);
  CHECK(time_of(R"({"integrator": "backward_euler", "dt": 0.01, "steps": 5, "rayleigh": [0.1, 0.001]})").rayleigh.x() == 0.1);
}

TEST_CASE("every malformed scene names the file and the field on one line") {
  struct Case {
    std::string text, field;
  };
  const std::string m = box_mesh;
  const Case cases[] = {
      {R"({"mesh": {"box": )", "JSON"},                                                           // truncated
      {"{" + m + R"(, "materal": {}})", "materal"},                                                 // unknown field (typo)
      {"{" + m + R"(, "material": {"young": "soft"}})", "material.young"},                           // wrong type
      {"{" + m + R"(, "material": {"poisson": 0.5}})", "material.poisson"},                          // out of range
      {"{" + m + R"(, "material": {"young": -1}})", "material.young"},
      {"{" + m + R"(, "material": {"poison": 0.3}})", "material.poison"},                            // typo inside
      {R"({"material": {}})", "mesh"},                                                                // missing mesh
      {"{" + m + R"(, "crack_tip": {"enrichment": "tip"}})", "crack_tip.enrichment"},
      {"{" + m + R"(, "crack_tip": {"radius": -0.01}})", "crack_tip.radius"},
      {"{" + m + R"(, "crack_tip": {"radius": "far"}})", "crack_tip.radius"},
      {"{" + m + R"(, "crack_tip": {"radius": 0.01, "shifted": true}})", "crack_tip.shifted"},
      {"{" + m + R"(, "crack_tip": {"front_points": 0}})", "crack_tip.front_points"},
      {"{" + m + R"(, "crack_tip": {"front_points": 2.5}})", "crack_tip.front_points"},
      {"{" + m + R"(, "crack_tip": {"front_grading": 13}})", "crack_tip.front_grading"},
      {"{" + m + R"(, "crack_tip": {"front_grading": -1}})", "crack_tip.front_grading"},
      {R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "cells": [1, 0, 1]}}})", "mesh.box.cells[1]"},
      {R"({"mesh": {"box": {"min": [0,0,0], "max": [1,0,1], "cells": [1, 1, 1]}}})", "mesh.box.max"},
      {R"({"mesh": {"box": {"min": [0,0], "max": [1,1,1], "cells": [1, 1, 1]}}})", "mesh.box.min"},
      {R"({"mesh": {"file": "a.msh", "order": 3}})", "mesh.order"},
      {R"({"mesh": {"file": "a.msh", "box": {}}})", "mesh"},
      {"{" + m + R"(, "model": "hyperelastic"})", "model"},
      {"{" + m + R"(, "dirichlet": {"region": {}}})", "dirichlet"},
      {"{" + m + R"(, "dirichlet": [{"region": {"sphere": 1}}]})", "dirichlet[0].region.sphere"},
      {"{" + m + R"(, "dirichlet": [{"region": {"nodes": [1, -2]}}]})", "dirichlet[0].region.nodes[1]"},
      {"{" + m + R"(, "dirichlet": [{"displacement": [0, 0, 0]}]})", "dirichlet[0].region"},
      {"{" + m + R"(, "gravity": [0, 0, "down"]})", "gravity[2]"},
      {"{" + m + R"(, "traction": [{"region": {"nodes": [1]}}]})", "traction[0].total_force"},
      {"{" + m + R"(, "cuts": [{"rectangle": {"origin": [0,0,0], "edge1": [1,0,0], "edge2": [2,0,0]}}]})", "cuts[0].rectangle.edge2"},
      {"{" + m + R"(, "cuts": [{"surface": "a.obj"}, {"surface": {"file": "b.stl", "scale": 0}}]})", "cuts[1].surface.scale"},
      {"{" + m + R"(, "cuts": [{"surface": {"file": "b.stl", "scale": "mm"}}]})", "cuts[0].surface.scale"},
      {"{" + m + R"(, "cuts": [{"surface": {"file": "b.stl", "scal": 0.001}}]})", "cuts[0].surface.scal"},
      {"{" + m + R"(, "cuts": [{"surface": {"scale": 0.001}}]})", "cuts[0].surface.file"},
      {"{" + m + R"(, "cuts": [{"surface": {"file": ""}}]})", "cuts[0].surface.file"},
      {"{" + m + R"(, "cuts": [{"surface": ""}]})", "cuts[0].surface"},
      {"{" + m + R"(, "cuts": [{"surface": 7}]})", "cuts[0].surface"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0, "steps": 10}})", "time.dt"},
      {"{" + m + R"(, "time": {"integrator": "euler"}})", "time.integrator"},
      {"{" + m + R"(, "time": {"integrator": "static", "dt": 0.1}})", "time.dt"},
      {"{" + m + R"(, "time": {"integrator": "static", "mass": "lumped"}})", "time.mass"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 0}})", "time.steps"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "beta": 0.1}})", "time.gamma"},   // 2 beta < gamma
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "gamma": 0.4}})", "time.gamma"},  // gamma < 1/2
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "alpha": -0.1}})", "time.alpha"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "rayleigh": [-1, 0]}})", "time.rayleigh"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "mass": "lumpy"}})", "time.mass"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "tolerance": 0}})", "time.tolerance"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "allow_unstable": "yes"}})", "time.allow_unstable"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "initial_velocity": [1, 2]}})", "time.initial_velocity"},
      {"{" + m + R"(, "time": {"integrator": "backward_euler", "dt": 0.01, "steps": 5, "beta": 0.25}})", "time.beta"},
      {"{" + m + R"(, "time": {"integrator": "central_difference", "dt": 0.01, "steps": 5, "mass": "consistent"}})", "time.mass"},
      {"{" + m + R"(, "time": {"integrator": "hht_alpha", "dt": 0.01, "steps": 5, "alpha": -0.5}})", "time.alpha"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "corotation": "lagged"}})", "time.corotation"},
      {"{" + m + R"(, "time": {"integrator": "newmark", "dt": 0.01, "steps": 5, "corotation": ""}})", "time.corotation"},
      {"{" + m + R"(, "time": {"integrator": "static", "corotation": "newton"}})", "time.corotation"},
      {"{" + m + R"(, "dirichlet": [{"region": {"nodes": [0]}, "ramp_time": -1}], "time": {"integrator": "newmark", "dt": 0.01, "steps": 5}})",
       "dirichlet[0].ramp_time"},
      {"{" + m + R"(, "dirichlet": [{"region": {"nodes": [0]}, "ramp_time": 0.5}]})", "dirichlet[0].ramp_time"},  // static: nothing moves
      {"{" + m + R"(, "output": {"every": 0}})", "output.every"},
      {"{" + m + R"(, "solver": {"type": "umfpack"}})", "solver.type"},
      {"{" + m + R"(, "solver": {"ordering": "colamd"}})", "solver.ordering"},
      {"{" + m + R"(, "solver": {"basis": "nodes"}})", "solver.basis"},
      {"{" + m + R"(, "solver": {"basis": 1}})", "solver.basis"},
      {"[1, 2, 3]", "(top level)"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const std::string message = error_of(c.text);
    REQUIRE_FALSE(message.empty());
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.rfind("scene.json: " + c.field + ": ", 0) == 0);
  }
}

TEST_CASE("a chapter refuses the methods it has not taught yet") {
  const kerf::Scene scene = kerf::parse_scene(full_scene, "full.json", "/data");
  CHECK_THROWS_WITH_AS(kerf::require_features(scene, {}), doctest::Contains("chapter 2"), kerf::InputError);
  CHECK_THROWS_WITH_AS(kerf::require_features(scene, {.corotational = true, .cuts = false, .dynamics = true}),
                       doctest::Contains("chapter 3"), kerf::InputError);
  // Its second cut is a triangle-mesh surface: chapter 4.
  CHECK_THROWS_WITH_AS(kerf::require_features(scene, {.corotational = true, .cuts = true, .dynamics = true}),
                       doctest::Contains("chapter 4"), kerf::InputError);
  CHECK_NOTHROW(kerf::require_features(scene, {.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true}));
}

TEST_CASE("the crack_tip field of chapter 5: branch by default, a radius only when given, refused before chapter 5") {
  const std::string m = box_mesh;
  const kerf::Scene plain = kerf::parse_scene("{" + m + "}", "plain.json", "/data");
  CHECK_FALSE(plain.crack_tip.given);
  CHECK(plain.crack_tip.enrichment == "branch");
  CHECK_FALSE(plain.crack_tip.radius.has_value());
  const kerf::Scene topological = kerf::parse_scene("{" + m + R"(, "crack_tip": {"radius": 0}})", "tip.json", "/data");
  CHECK(topological.crack_tip.given);
  REQUIRE(topological.crack_tip.radius.has_value());
  CHECK(*topological.crack_tip.radius == 0.0);
  CHECK(topological.crack_tip.front_points == 0);   // the model's default
  CHECK(topological.crack_tip.front_grading == 12); // front_quadrature.hpp's default
  const kerf::Scene cheap = kerf::parse_scene("{" + m + R"(, "crack_tip": {"front_points": 2, "front_grading": 4}})", "cheap.json", "/data");
  CHECK(cheap.crack_tip.front_points == 2);
  CHECK(cheap.crack_tip.front_grading == 4);
  const kerf::Scene none = kerf::parse_scene("{" + m + R"(, "crack_tip": {"enrichment": "none"}})", "none.json", "/data");
  CHECK(none.crack_tip.enrichment == "none");
  CHECK_THROWS_WITH_AS(kerf::require_features(topological, {.corotational = true, .cuts = true, .cut_quadrature = true}),
                       doctest::Contains("chapter 5"), kerf::InputError);
  CHECK_NOTHROW(kerf::require_features(topological, {.crack_tip = true}));
}

TEST_CASE("a scene file that does not exist is an InputError naming it") {
  CHECK_THROWS_WITH_AS(kerf::read_scene_file("no/such/scene.json"), doctest::Contains("no/such/scene.json"), kerf::InputError);
}

TEST_CASE("the williams field of a Dirichlet entry: K in Pa sqrt(m), 0 unless given; bad input names the field; chapter 5 alone runs it") {
  const std::string m = box_mesh;
  const auto entry = [&](const std::string& condition) {
    return "{" + m + R"(, "dirichlet": [{"region": {"nodes": [0]}}, {"region": {"nodes": [1, 2]}, )" + condition + "}]}";
  };
  const kerf::Scene mixed = kerf::parse_scene(entry(R"("williams": {"K_I": 1e4, "K_III": -250})"), "williams.json", "/data");
  REQUIRE(mixed.dirichlet.size() == 2);
  CHECK_FALSE(mixed.dirichlet[0].williams);
  CHECK(mixed.dirichlet[1].williams);
  CHECK(mixed.dirichlet[1].williams_K.K_I == 1e4);
  CHECK(mixed.dirichlet[1].williams_K.K_II == 0.0); // not given
  CHECK(mixed.dirichlet[1].williams_K.K_III == -250.0); // tearing either way is meaningful
  const kerf::Scene sliding = kerf::parse_scene(entry(R"("williams": {"K_II": -3})"), "williams.json", "/data");
  CHECK(sliding.dirichlet[1].williams_K.K_I == 0.0);
  CHECK(sliding.dirichlet[1].williams_K.K_II == -3.0);

  struct Case {
    std::string condition, field;
  };
  const Case cases[] = {
      {R"("williams": {})", "dirichlet[1].williams"},                                   // no K at all
      {R"("williams": 1e4)", "dirichlet[1].williams"},                                  // not an object
      {R"("williams": [1e4, 0, 0])", "dirichlet[1].williams"},
      {R"("williams": {"K_I": "1e4"})", "dirichlet[1].williams.K_I"},                   // wrong type
      {R"("williams": {"K_I": null})", "dirichlet[1].williams.K_I"},
      {R"("williams": {"K_II": true})", "dirichlet[1].williams.K_II"},
      {R"("williams": {"K_III": [1]})", "dirichlet[1].williams.K_III"},
      {R"("williams": {"K_I": -1})", "dirichlet[1].williams.K_I"},                      // the faces would interpenetrate
      {R"("williams": {"K_I": -1e-300})", "dirichlet[1].williams.K_I"},
      {R"("williams": {"K_I": 1e400})", "JSON"},                                        // not a double
      {R"("williams": {"K_1": 1e4})", "dirichlet[1].williams.K_1"},                     // typo: not silently 0
      {R"("williams": {"K_I": 1e4, "front": [0, 0, 0]})", "dirichlet[1].williams.front"}, // the front comes from the cut
      {R"("williams": {"K_I": 1e4}, "displacement": [0, 0, 0])", "dirichlet[1].williams"},
      {R"("williams": {"K_I": 1e4}, "rotation": {"axis": [0, 0, 1], "degrees": 5})", "dirichlet[1].williams"},
      {R"("williams": {"K_I": 1e4}, "displacement_file": "u.csv")", "dirichlet[1].williams"},
      {R"("williams": {"K_I": 1e4}, "ramp_time": -1)", "dirichlet[1].ramp_time"},
      {R"("williams": {"K_I": 1e4}, "ramp_time": 0.5)", "dirichlet[1].ramp_time"},      // static: nothing moves
  };
  for (const auto& c : cases) {
    const std::string text = entry(c.condition);
    CAPTURE(text);
    const std::string message = error_of(text);
    REQUIRE_FALSE(message.empty());
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.rfind("scene.json: " + c.field + ": ", 0) == 0);
  }
  // Only chapter 5's static program prescribes it on the cut body's enrichments.
  const kerf::SceneFeatures chapter_07{.corotational = true, .cuts = true, .dynamics = true, .cut_quadrature = true, .crack_tip = true,
                                       .organ = true};
  CHECK_THROWS_WITH_AS(kerf::require_features(mixed, chapter_07), doctest::Contains("williams.json: dirichlet[1].williams: "), kerf::InputError);
  CHECK_NOTHROW(kerf::require_features(mixed, {.cuts = true, .cut_quadrature = true, .crack_tip = true, .williams = true}));
}
