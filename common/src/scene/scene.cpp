#include "kerf/scene/scene.hpp"

#include "kerf/quadrature/front_quadrature.hpp"

#include "kerf/app/input_error.hpp"
#include "kerf/mesh/liver_mesh.hpp"
#include "kerf/solve/cholmod_ordering.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <sstream>

namespace kerf {

namespace {

using nlohmann::json;

std::string type_name(const json& value) { return value.is_number() ? "a number" : std::string("a ") + value.type_name(); }

/// Reads one JSON object field by field, checking types, ranges and unknown keys, and names
/// every problem by its path in the file ("traction[1].region.box.min").
class ObjectReader {
public:
  ObjectReader(const json& object, std::string path, const std::string& file) : object_(object), path_(std::move(path)), file_(file) {
    if (!object_.is_object()) fail(path_, "expected an object, got " + type_name(object_));
  }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(file_, field.empty() ? "(top level)" : field, problem);
  }

  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  /// Unknown keys are errors: a typo such as "poison" must not silently fall back to a default.
  void allow_only(std::initializer_list<const char*> keys) const {
    for (const auto& item : object_.items()) {
      bool known = false;
      std::string list;
      for (const char* k : keys) {
        known = known || item.key() == k;
        list += std::string(list.empty() ? "" : ", ") + k;
      }
      if (!known) fail(field(item.key()), "unknown field (expected one of: " + list + ")");
    }
  }

  bool has(const std::string& key) const { return object_.contains(key); }
  const json& at(const std::string& key) const {
    if (!has(key)) fail(field(key), "required field is missing");
    return object_.at(key);
  }

  double number(const std::string& key, double fallback) const {
    if (!has(key)) return fallback;
    return as_number(object_.at(key), field(key));
  }
  double as_number(const json& value, const std::string& name) const {
    if (!value.is_number()) fail(name, "expected a number, got " + type_name(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(name, "expected a finite number");
    return x;
  }
  int integer(const std::string& key, int fallback) const {
    if (!has(key)) return fallback;
    const json& value = object_.at(key);
    if (!value.is_number_integer()) fail(field(key), "expected an integer, got " + type_name(value));
    return as_int(value, field(key));
  }
  /// A JSON integer as an int; get<int>() alone would wrap 4294967297 round to 1 without a word.
  int as_int(const json& value, const std::string& name) const {
    constexpr long long lowest = std::numeric_limits<int>::min();
    constexpr long long highest = std::numeric_limits<int>::max();
    const bool fits = value.is_number_unsigned()
                          ? value.get<unsigned long long>() <= static_cast<unsigned long long>(highest)
                          : value.get<long long>() >= lowest && value.get<long long>() <= highest;
    if (!fits) fail(name, "expected an integer that fits in 32 bits, got " + value.dump());
    return value.get<int>();
  }
  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& value = object_.at(key);
    if (!value.is_boolean()) fail(field(key), "expected true or false, got " + type_name(value));
    return value.get<bool>();
  }
  std::string text(const std::string& key, const std::string& fallback) const {
    if (!has(key)) return fallback;
    const json& value = object_.at(key);
    if (!value.is_string()) fail(field(key), "expected a string, got " + type_name(value));
    return value.get<std::string>();
  }
  template <int n>
  Eigen::Matrix<double, n, 1> vector(const std::string& key, const Eigen::Matrix<double, n, 1>& fallback) const {
    if (!has(key)) return fallback;
    const json& value = object_.at(key);
    if (!value.is_array() || value.size() != n)
      fail(field(key), "expected an array of " + std::to_string(n) + " numbers");
    Eigen::Matrix<double, n, 1> v;
    for (int i = 0; i < n; ++i) v[i] = as_number(value[static_cast<std::size_t>(i)], field(key) + "[" + std::to_string(i) + "]");
    return v;
  }
  const json& array(const std::string& key) const {
    const json& value = at(key);
    if (!value.is_array()) fail(field(key), "expected an array, got " + type_name(value));
    return value;
  }

  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

private:
  const json& object_;
  std::string path_;
  const std::string& file_;
};

NodeRegion read_region(const json& value, const std::string& path, const std::string& file) {
  ObjectReader r(value, path, file);
  r.allow_only({"box", "nodes"});
  NodeRegion region;
  if (r.has("box") == r.has("nodes")) r.fail(path, "expected exactly one of \"box\" or \"nodes\"");
  if (r.has("box")) {
    ObjectReader box(r.at("box"), r.field("box"), file);
    box.allow_only({"min", "max"});
    box.at("min");
    box.at("max");
    region.box_min = box.vector<3>("min", Eigen::Vector3d::Zero());
    region.box_max = box.vector<3>("max", Eigen::Vector3d::Zero());
    if ((region.box_max.array() < region.box_min.array()).any()) box.fail(box.field("max"), "expected max >= min in x, y and z");
  } else {
    region.is_box = false;
    const json& nodes = r.array("nodes");
    if (nodes.empty()) r.fail(r.field("nodes"), "expected at least one node index");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string name = r.field("nodes") + "[" + std::to_string(i) + "]";
      if (!nodes[i].is_number_integer() || (!nodes[i].is_number_unsigned() && nodes[i].get<long long>() < 0))
        r.fail(name, "expected a non-negative integer node index");
      region.node_list.push_back(r.as_int(nodes[i], name));
    }
  }
  return region;
}

MeshSpec read_mesh(const ObjectReader& scene, const std::filesystem::path& base) {
  ObjectReader r(scene.at("mesh"), "mesh", scene.file());
  r.allow_only({"box", "file", "liver", "order", "scale"});
  MeshSpec mesh;
  if (int(r.has("box")) + int(r.has("file")) + int(r.has("liver")) != 1)
    r.fail("mesh", "expected exactly one of \"box\", \"file\" or \"liver\"");
  if (r.has("liver")) {
    // Chapter 7's liver (mesh/liver_mesh.hpp): Mesh_3 makes it from an implicit surface in code.
    mesh.is_box = false;
    mesh.is_liver = true;
    ObjectReader liver(r.at("liver"), "mesh.liver", scene.file());
    liver.allow_only({"tets", "shape"});
    mesh.liver_tets = liver.integer("tets", mesh.liver_tets);
    const std::string shape = liver.text("shape", to_string(mesh.liver_shape));
    if (shape == "wedge") mesh.liver_shape = LiverShape::wedge;
    else if (shape != "lobes") liver.fail("mesh.liver.shape", "expected \"lobes\" or \"wedge\", got \"" + shape + "\"");
    if (mesh.liver_tets < liver_min_tets || mesh.liver_tets > liver_max_tets)
      liver.fail("mesh.liver.tets", "expected an integer in [" + std::to_string(liver_min_tets) + ", " + std::to_string(liver_max_tets) +
                                        "]: below, Mesh_3 cannot resolve the lobes; above, the mesh would take minutes");
  } else if (r.has("box")) {
    ObjectReader box(r.at("box"), "mesh.box", scene.file());
    box.allow_only({"min", "max", "cells"});
    box.at("min");
    box.at("max");
    box.at("cells");
    mesh.box_min = box.vector<3>("min", Eigen::Vector3d::Zero());
    mesh.box_max = box.vector<3>("max", Eigen::Vector3d::Zero());
    if ((mesh.box_max.array() <= mesh.box_min.array()).any()) box.fail("mesh.box.max", "expected max > min in x, y and z");
    const json& cells = box.at("cells");
    if (!cells.is_array() || cells.size() != 3) box.fail("mesh.box.cells", "expected an array of 3 positive integers");
    for (int i = 0; i < 3; ++i) {
      const json& c = cells[static_cast<std::size_t>(i)];
      if (!c.is_number_integer() || c.get<long long>() < 1 || c.get<long long>() > 100000)
        box.fail("mesh.box.cells[" + std::to_string(i) + "]", "expected a positive integer (at most 100000)");
      mesh.box_cells[i] = c.get<int>();
    }
  } else {
    mesh.is_box = false;
    const std::filesystem::path file = r.text("file", "");
    if (file.empty()) r.fail("mesh.file", "expected a non-empty path");
    mesh.file = file.is_absolute() ? file : base / file;
    mesh.scale = r.number("scale", 1.0);
    if (!(mesh.scale > 0.0)) r.fail("mesh.scale", "expected a positive number");
  }
  if (r.has("scale") && (mesh.is_box || mesh.is_liver)) r.fail("mesh.scale", "only meaningful with \"file\"");
  mesh.order = r.integer("order", 1);
  if (mesh.order != 1 && mesh.order != 2) r.fail("mesh.order", "expected 1 (Tet4) or 2 (Tet10)");
  return mesh;
}


/// The list r[key] read entry by entry: read(entry, "key[i]") for each, in order; an absent
/// key is an empty list.
template <class Entry, class ReadEntry>
std::vector<Entry> read_list(const ObjectReader& r, const std::string& key, ReadEntry read) {
  std::vector<Entry> entries;
  if (!r.has(key)) return entries;
  const json& list = r.array(key);
  for (std::size_t i = 0; i < list.size(); ++i) entries.push_back(read(list[i], key + "[" + std::to_string(i) + "]"));
  return entries;
}

/// "material": E, nu and rho, each checked (LinearMaterial::check says the same for library callers).
LinearMaterial read_material(const ObjectReader& r) {
  LinearMaterial material;
  if (!r.has("material")) return material;
  ObjectReader m(r.at("material"), "material", r.file());
  m.allow_only({"young", "poisson", "density"});
  material.young = m.number("young", material.young);
  material.poisson = m.number("poisson", material.poisson);
  material.density = m.number("density", material.density);
  if (!(material.young > 0.0)) m.fail("material.young", "expected a positive number (Pa)");
  if (!(material.poisson > -1.0 && material.poisson <= LinearMaterial::max_poisson))
    m.fail("material.poisson", "expected a number in (-1, 0.5 - 1e-6]: at 0.5 the material is incompressible, lambda is "
                               "infinite, and a displacement formulation has no answer");
  if (!(material.density >= 0.0)) m.fail("material.density", "expected a non-negative number (kg/m^3)");
  return material;
}

/// "williams": the stress intensity factors of Williams's field, each in Pa sqrt(m) and 0 when
/// not given, at least one given. A negative K_I would push the crack's faces through each other
/// (the field's opening 2 A_I (kappa + 1) sqrt(r) < 0), which no open cut does: refused.
StressIntensityFactors read_williams(const ObjectReader& d) {
  ObjectReader w(d.at("williams"), d.field("williams"), d.file());
  w.allow_only({"K_I", "K_II", "K_III"});
  if (!w.has("K_I") && !w.has("K_II") && !w.has("K_III"))
    w.fail(w.path(), "expected at least one of \"K_I\", \"K_II\", \"K_III\" (stress intensity factors, Pa sqrt(m))");
  StressIntensityFactors K;
  K.K_I = w.number("K_I", 0.0);
  K.K_II = w.number("K_II", 0.0);
  K.K_III = w.number("K_III", 0.0);
  if (K.K_I < 0.0)
    w.fail(w.field("K_I"), "expected a number >= 0 (Pa sqrt(m)): a negative K_I closes the crack through its own faces");
  return K;
}

/// "dirichlet": regions with a displacement, and optionally a rotation about an axis, or with a
/// displacement file (a path relative to the scene), read here so that a malformed file is
/// reported before any mesh is made, or with Williams's field ("williams").
std::vector<DirichletSpec> read_dirichlet(const ObjectReader& r, const std::filesystem::path& base) {
  return read_list<DirichletSpec>(r, "dirichlet", [&](const json& entry, const std::string& path) {
    ObjectReader d(entry, path, r.file());
    d.allow_only({"region", "displacement", "rotation", "displacement_file", "williams", "ramp_time"});
    DirichletSpec spec;
    spec.region = read_region(d.at("region"), path + ".region", r.file());
    spec.ramp_time = d.number("ramp_time", 0.0);
    if (!(spec.ramp_time >= 0.0)) d.fail(path + ".ramp_time", "expected a non-negative time (s)");
    if (d.has("williams")) {
      for (const char* other : {"displacement", "rotation", "displacement_file"})
        if (d.has(other))
          d.fail(d.field("williams"), std::string("expected either \"williams\" or \"") + other + "\", not both");
      spec.williams = true;
      spec.williams_K = read_williams(d);
      return spec;
    }
    if (d.has("displacement_file")) {
      if (d.has("displacement") || d.has("rotation"))
        d.fail(d.field("displacement_file"), "expected either \"displacement_file\" or \"displacement\" and \"rotation\", not both");
      const std::filesystem::path file = d.text("displacement_file", "");
      if (file.empty()) d.fail(d.field("displacement_file"), "expected a non-empty path");
      const std::filesystem::path resolved = file.is_absolute() ? file : base / file;
      if (!std::filesystem::is_regular_file(resolved)) d.fail(d.field("displacement_file"), "no such file: " + resolved.string());
      spec.from_file = true;
      spec.file = read_displacement_file(resolved);
      return spec;
    }
    spec.displacement = d.vector<3>("displacement", Eigen::Vector3d::Zero());
    if (d.has("rotation")) {
      ObjectReader rotation(d.at("rotation"), path + ".rotation", r.file());
      rotation.allow_only({"axis", "degrees", "center"});
      rotation.at("axis");
      rotation.at("degrees");
      spec.has_rotation = true;
      spec.axis = rotation.vector<3>("axis", Eigen::Vector3d::UnitZ());
      if (!(spec.axis.norm() > 0.0)) rotation.fail(path + ".rotation.axis", "expected a non-zero vector");
      spec.axis.normalize();
      spec.degrees = rotation.number("degrees", 0.0);
      spec.center = rotation.vector<3>("center", Eigen::Vector3d::Zero());
    }
    return spec;
  });
}

/// "traction": regions with a total force, spread by area over their boundary faces.
std::vector<TractionSpec> read_tractions(const ObjectReader& r) {
  return read_list<TractionSpec>(r, "traction", [&](const json& entry, const std::string& path) {
    ObjectReader t(entry, path, r.file());
    t.allow_only({"region", "total_force"});
    TractionSpec spec;
    spec.region = read_region(t.at("region"), path + ".region", r.file());
    t.at("total_force");
    spec.total_force = t.vector<3>("total_force", Eigen::Vector3d::Zero());
    return spec;
  });
}

/// "cuts": rectangles (a corner and two edges) or triangle-mesh surfaces (paths relative to the
/// scene, with an optional scale).
std::vector<CutSpec> read_cuts(const ObjectReader& r, const std::filesystem::path& base) {
  return read_list<CutSpec>(r, "cuts", [&](const json& entry, const std::string& path) {
    ObjectReader c(entry, path, r.file());
    c.allow_only({"rectangle", "surface"});
    CutSpec spec;
    if (c.has("rectangle") == c.has("surface")) c.fail(path, "expected exactly one of \"rectangle\" or \"surface\"");
    if (c.has("rectangle")) {
      ObjectReader rect(c.at("rectangle"), path + ".rectangle", r.file());
      rect.allow_only({"origin", "edge1", "edge2"});
      rect.at("origin");
      rect.at("edge1");
      rect.at("edge2");
      spec.origin = rect.vector<3>("origin", Eigen::Vector3d::Zero());
      spec.edge1 = rect.vector<3>("edge1", Eigen::Vector3d::Zero());
      spec.edge2 = rect.vector<3>("edge2", Eigen::Vector3d::Zero());
      if (spec.edge1.cross(spec.edge2).norm() == 0.0)
        rect.fail(path + ".rectangle.edge2", "expected edge1 and edge2 to span a rectangle (they are parallel or zero)");
    } else {
      // A path alone, or {"file": path, "scale": s} for a file in other units than metres.
      spec.is_rectangle = false;
      std::filesystem::path surface;
      std::string surface_field = path + ".surface";
      if (c.at("surface").is_object()) {
        ObjectReader surface_object(c.at("surface"), path + ".surface", r.file());
        surface_object.allow_only({"file", "scale"});
        surface_object.at("file");
        surface = surface_object.text("file", "");
        surface_field = surface_object.field("file");
        spec.surface_scale = surface_object.number("scale", 1.0);
        if (!(spec.surface_scale > 0.0)) surface_object.fail(surface_object.field("scale"), "expected a positive number");
      } else if (c.at("surface").is_string()) {
        surface = c.text("surface", "");
      } else {
        c.fail(surface_field, "expected a path or {\"file\": path, \"scale\": s}, got " + type_name(c.at("surface")));
      }
      if (surface.empty()) c.fail(surface_field, "expected a non-empty path");
      spec.surface = surface.is_absolute() ? surface : base / surface;
    }
    return spec;
  });
}

/// "time": static, or a time integrator with its step, count, parameters, mass and damping
/// (chapter 6). Each integrator takes only the fields that mean something for it, and
/// a Newmark or HHT pair outside its unconditionally stable range is refused unless
/// "allow_unstable" says it is meant (the chapter charts what happens then).
TimeSpec read_time(const ObjectReader& r) {
  TimeSpec time;
  if (!r.has("time")) return time;
  ObjectReader t(r.at("time"), "time", r.file());
  t.allow_only({"integrator", "dt", "steps", "beta", "gamma", "alpha", "rayleigh", "mass", "tolerance", "initial_velocity",
                "allow_unstable", "corotation", "iterations"});
  time.integrator = t.text("integrator", "static");
  const bool newmark = time.integrator == "newmark", hht = time.integrator == "hht_alpha";
  const bool dynamic = newmark || hht || time.integrator == "backward_euler" || time.integrator == "central_difference";
  if (time.integrator == "static") {
    for (const char* key : {"dt", "steps", "beta", "gamma", "alpha", "rayleigh", "mass", "tolerance", "initial_velocity", "allow_unstable",
                            "corotation", "iterations"})
      if (t.has(key)) t.fail(t.field(key), "only meaningful with a dynamic integrator");
    return time;
  }
  if (!dynamic)
    t.fail("time.integrator", "expected \"static\", \"newmark\", \"hht_alpha\", \"backward_euler\" or \"central_difference\", got \"" +
                                  time.integrator + "\"");
  if (!newmark)
    for (const char* key : {"beta", "gamma"})
      if (t.has(key)) t.fail(t.field(key), "only meaningful with \"newmark\" (" + time.integrator + " fixes its own)");
  if (!hht && t.has("alpha")) t.fail("time.alpha", "only meaningful with \"hht_alpha\"");
  t.at("dt");
  t.at("steps");
  time.dt = t.number("dt", 0.0);
  time.steps = t.integer("steps", 0);
  time.rayleigh = t.vector<2>("rayleigh", Eigen::Vector2d::Zero());
  time.tolerance = t.number("tolerance", time.tolerance);
  time.initial_velocity = t.vector<3>("initial_velocity", Eigen::Vector3d::Zero());
  time.allow_unstable = t.boolean("allow_unstable", false);
  time.mass = t.text("mass", time.integrator == "central_difference" ? "lumped" : "consistent");
  time.corotation = t.text("corotation", "");
  if (t.has("corotation") && time.corotation != "frozen" && time.corotation != "checked" && time.corotation != "newton")
    t.fail("time.corotation", "expected \"frozen\", \"checked\" or \"newton\", got \"" + time.corotation + "\"");
  if (t.has("iterations")) {
    time.iterations = t.integer("iterations", 0);
    if (*time.iterations < 0) t.fail("time.iterations", "expected an integer >= 0 (0: iterate to time.tolerance)");
  }
  if (!(time.dt > 0.0)) t.fail("time.dt", "expected a positive time step (s)");
  if (time.steps < 1) t.fail("time.steps", "expected a positive integer");
  if ((time.rayleigh.array() < 0.0).any()) t.fail("time.rayleigh", "expected non-negative coefficients");
  if (!(time.tolerance > 0.0 && time.tolerance < 1.0)) t.fail("time.tolerance", "expected a relative residual in (0, 1)");
  const std::string lumped_schemes[] = {"lumped", "bernstein", "row_sum", "hrz", "virtual_tet", "schoch_eq_81_82"};
  const bool lumped = std::find(std::begin(lumped_schemes), std::end(lumped_schemes), time.mass) != std::end(lumped_schemes);
  if (!lumped && time.mass != "consistent")
    t.fail("time.mass", "expected \"consistent\", \"lumped\" (per-piece \"bernstein\"), \"row_sum\", \"hrz\", \"virtual_tet\" or "
                        "\"schoch_eq_81_82\", got \"" +
                            time.mass + "\"");
  if (time.integrator == "central_difference" && !lumped)
    t.fail("time.mass", "the central difference is explicit: it needs a lumped (diagonal) mass");
  if (newmark) {
    time.beta = t.number("beta", 0.25);
    time.gamma = t.number("gamma", 0.5);
    if (!(time.beta > 0.0 && time.beta <= 0.5)) t.fail("time.beta", "expected a number in (0, 0.5] (beta = 0 is \"central_difference\")");
    if (!(time.gamma >= 0.0 && time.gamma <= 1.0)) t.fail("time.gamma", "expected a number in [0, 1]");
    // Unconditionally stable iff 2 beta >= gamma >= 1/2 (newmark.hpp).
    if (!(2.0 * time.beta >= time.gamma && time.gamma >= 0.5) && !time.allow_unstable)
      t.fail("time.gamma", "beta = " + std::to_string(time.beta) + ", gamma = " + std::to_string(time.gamma) +
                               " is not unconditionally stable (it needs 2 beta >= gamma >= 1/2); set \"allow_unstable\": true to run it anyway");
  }
  if (hht) {
    time.alpha = t.number("alpha", time.alpha);
    if (!(time.alpha >= -1.0 / 3.0 && time.alpha <= 0.0)) t.fail("time.alpha", "expected a number in [-1/3, 0]");
  }
  return time;
}

/// "output": how often a time-stepping chapter writes its results.
int read_output_every(const ObjectReader& r) {
  int every = 1;
  if (!r.has("output")) return every;
  ObjectReader o(r.at("output"), "output", r.file());
  o.allow_only({"every"});
  every = o.integer("every", 1);
  if (every < 1) o.fail("output.every", "expected a positive integer");
  return every;
}

/// "quasi_static": load steps and the Newton iteration of chapters 2 and 3.
QuasiStaticSpec read_quasi_static(const ObjectReader& r) {
  QuasiStaticSpec spec;
  if (!r.has("quasi_static")) return spec;
  ObjectReader q(r.at("quasi_static"), "quasi_static", r.file());
  q.allow_only({"load_steps", "max_iterations", "tolerance", "tangent", "rotation", "predictor"});
  spec.load_steps = q.integer("load_steps", spec.load_steps);
  spec.max_iterations = q.integer("max_iterations", spec.max_iterations);
  spec.tolerance = q.number("tolerance", spec.tolerance);
  spec.tangent = q.text("tangent", spec.tangent);
  spec.rotation = q.text("rotation", spec.rotation);
  spec.predictor = q.text("predictor", spec.predictor);
  if (spec.load_steps < 1 || spec.load_steps > 100000) q.fail("quasi_static.load_steps", "expected an integer in [1, 100000]");
  if (spec.max_iterations < 1) q.fail("quasi_static.max_iterations", "expected a positive integer");
  if (!(spec.tolerance > 0.0 && spec.tolerance < 1.0)) q.fail("quasi_static.tolerance", "expected a number in (0, 1)");
  if (spec.tangent != "consistent" && spec.tangent != "warped")
    q.fail("quasi_static.tangent", "expected \"consistent\" or \"warped\", got \"" + spec.tangent + "\"");
  if (spec.predictor != "secant" && spec.predictor != "previous")
    q.fail("quasi_static.predictor", "expected \"secant\" or \"previous\", got \"" + spec.predictor + "\"");
  if (spec.rotation != "automatic" && spec.rotation != "higham" && spec.rotation != "svd")
    q.fail("quasi_static.rotation", "expected \"automatic\", \"higham\" or \"svd\", got \"" + spec.rotation + "\"");
  return spec;
}

/// "quadrature": the rule for the pieces of cut elements (chapter 4 on).
QuadratureSpec read_quadrature(const ObjectReader& r) {
  QuadratureSpec spec;
  if (!r.has("quadrature")) return spec;
  spec.given = true;
  ObjectReader q(r.at("quadrature"), "quadrature", r.file());
  q.allow_only({"rule"});
  spec.rule = q.text("rule", spec.rule);
  const std::vector<std::string> rules{"exact", "subtets", "moment_fitting", "volume_ratio", "lattice", "regular"};
  if (std::find(rules.begin(), rules.end(), spec.rule) == rules.end())
    q.fail("quadrature.rule", "expected \"exact\", \"subtets\", \"moment_fitting\", \"volume_ratio\", \"lattice\" or "
                              "\"regular\", got \"" + spec.rule + "\"");
  return spec;
}

/// "crack_tip": branch enrichment where a cut ends inside the body (chapter 5 on).
CrackTipSpec read_crack_tip(const ObjectReader& r) {
  CrackTipSpec spec;
  if (!r.has("crack_tip")) return spec;
  spec.given = true;
  ObjectReader c(r.at("crack_tip"), "crack_tip", r.file());
  c.allow_only({"enrichment", "radius", "blending", "front_points", "front_grading"});
  spec.enrichment = c.text("enrichment", spec.enrichment);
  if (spec.enrichment != "branch" && spec.enrichment != "none")
    c.fail("crack_tip.enrichment", "expected \"branch\" or \"none\", got \"" + spec.enrichment + "\"");
  if (c.has("radius")) {
    spec.radius = c.number("radius", 0.0);
    if (!(*spec.radius >= 0.0) || !std::isfinite(*spec.radius)) c.fail("crack_tip.radius", "expected a finite number >= 0 (m)");
  }
  spec.blending = c.text("blending", spec.blending);
  if (spec.blending != "corrected" && spec.blending != "none")
    c.fail("crack_tip.blending", "expected \"corrected\" or \"none\", got \"" + spec.blending + "\"");
  spec.front_points = c.integer("front_points", spec.front_points);
  if (c.has("front_points") && (spec.front_points < 1 || spec.front_points > 8))
    c.fail("crack_tip.front_points", "expected an integer from 1 to 8 (points per direction of each collapsed sub-tet)");
  spec.front_grading = c.integer("front_grading", spec.front_grading);
  if (spec.front_grading < 0 || spec.front_grading > default_front_grading)
    c.fail("crack_tip.front_grading", "expected an integer from 0 to 12 (the most times the grading may split a part)");
  return spec;
}

/// "blade" (chapter 7): the cutting edge's keyframes, each {"time": s, "edge": [[x,y,z], [x,y,z]]}.
BladeSpec read_blade(const ObjectReader& r) {
  BladeSpec spec;
  if (!r.has("blade")) return spec;
  spec.given = true;
  ObjectReader b(r.at("blade"), "blade", r.file());
  b.allow_only({"path", "quad_length", "samples"});
  const json& path = b.array("path");
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string name = "blade.path[" + std::to_string(i) + "]";
    ObjectReader k(path[i], name, r.file());
    k.allow_only({"time", "edge"});
    k.at("time");
    BladeKeyframe frame;
    frame.time = k.number("time", 0.0);
    const json& edge = k.array("edge");
    if (edge.size() != 2) k.fail(name + ".edge", "expected two points [[x,y,z], [x,y,z]]: the ends of the cutting edge (m)");
    for (std::size_t e = 0; e < 2; ++e) {
      const std::string point = name + ".edge[" + std::to_string(e) + "]";
      if (!edge[e].is_array() || edge[e].size() != 3) k.fail(point, "expected an array of 3 numbers");
      Eigen::Vector3d x;
      for (int c = 0; c < 3; ++c) x[c] = k.as_number(edge[e][static_cast<std::size_t>(c)], point + "[" + std::to_string(c) + "]");
      (e == 0 ? frame.edge.start : frame.edge.end) = x;
    }
    spec.path.push_back(frame);
  }
  // BladePath states the path's own rules (at least two keyframes, times increasing, edges of
  // non-zero length) in one line, which we pass on with the field.
  try {
    BladePath check(spec.path);
  } catch (const std::invalid_argument& error) {
    b.fail("blade.path", error.what());
  }
  spec.quad_length = b.number("quad_length", spec.quad_length);
  if (!(spec.quad_length >= 0.0)) b.fail("blade.quad_length", "expected a length >= 0 (m; 0: a quarter of the mesh's mean edge)");
  spec.samples = b.integer("samples", spec.samples);
  if (spec.samples < 2 || spec.samples > 1000) b.fail("blade.samples", "expected an integer in [2, 1000]");
  return spec;
}

/// "render" (chapter 7): the PNG frames of the visual surface and their camera.
RenderSpec read_render(const ObjectReader& r, const std::filesystem::path& base) {
  RenderSpec spec;
  if (!r.has("render")) return spec;
  ObjectReader o(r.at("render"), "render", r.file());
  o.allow_only({"every", "width", "height", "camera", "visual_size", "animation", "surface", "surface_scale"});
  spec.every = o.integer("every", spec.every);
  if (spec.every < 0) o.fail("render.every", "expected an integer >= 0 (0: no frames)");
  spec.width = o.integer("width", spec.width);
  spec.height = o.integer("height", spec.height);
  if (spec.width < 16 || spec.width > 8192) o.fail("render.width", "expected an integer in [16, 8192] (pixels)");
  if (spec.height < 16 || spec.height > 8192) o.fail("render.height", "expected an integer in [16, 8192] (pixels)");
  spec.visual_size = o.number("visual_size", spec.visual_size);
  if (!(spec.visual_size > 0.0)) o.fail("render.visual_size", "expected a positive length (m)");
  spec.animation = o.boolean("animation", spec.animation);
  if (o.has("surface")) {
    const std::filesystem::path file = o.text("surface", "");
    if (file.empty()) o.fail("render.surface", "expected a non-empty path");
    spec.surface = file.is_absolute() ? file : base / file;
    if (!std::filesystem::is_regular_file(spec.surface)) o.fail("render.surface", "no such file: " + spec.surface.string());
  }
  spec.surface_scale = o.number("surface_scale", spec.surface_scale);
  if (!(spec.surface_scale > 0.0)) o.fail("render.surface_scale", "expected a positive number");
  if (o.has("camera")) {
    ObjectReader c(o.at("camera"), "render.camera", r.file());
    c.allow_only({"azimuth", "elevation", "zoom"});
    spec.azimuth = c.number("azimuth", spec.azimuth);
    spec.elevation = c.number("elevation", spec.elevation);
    spec.zoom = c.number("zoom", spec.zoom);
    if (!(std::abs(spec.elevation) < 90.0)) c.fail("render.camera.elevation", "expected degrees in (-90, 90): z stays up on the screen");
    if (!(spec.zoom > 0.0)) c.fail("render.camera.zoom", "expected a positive number");
  }
  return spec;
}

/// "solver": which linear solver, and how hard an iterative one works.
SolverSettings read_solver(const ObjectReader& r) {
  SolverSettings solver;
  if (!r.has("solver")) return solver;
  ObjectReader s(r.at("solver"), "solver", r.file());
  s.allow_only({"type", "ordering", "tolerance", "max_iterations", "refresh_iterations", "basis"});
  solver.type = s.text("type", "cholmod");
  solver.ordering = s.text("ordering", solver.ordering);
  solver.tolerance = s.number("tolerance", solver.tolerance);
  solver.max_iterations = s.integer("max_iterations", solver.max_iterations);
  solver.refresh_iterations = s.integer("refresh_iterations", solver.refresh_iterations);
  solver.basis = s.text("basis", solver.basis);
  const auto& type = solver.type;
  if (type != "cholmod" && type != "ldlt" && type != "cg-jacobi" && type != "cg-ichol" && type != "cg-cholmod")
    s.fail("solver.type",
           "expected \"cholmod\", \"ldlt\", \"cg-jacobi\", \"cg-ichol\" or \"cg-cholmod\", got \"" + type + "\"");
  if (!is_cholmod_ordering(solver.ordering))
    s.fail("solver.ordering",
           "expected \"nested-dissection\", \"metis\", \"amd\" or \"cholmod\", got \"" + solver.ordering + "\"");
  if (!(solver.tolerance > 0.0 && solver.tolerance < 1.0)) s.fail("solver.tolerance", "expected a number in (0, 1)");
  if (solver.max_iterations < 1) s.fail("solver.max_iterations", "expected a positive integer");
  if (solver.refresh_iterations < 1) s.fail("solver.refresh_iterations", "expected a positive integer");
  if (solver.basis != "parts" && solver.basis != "unknowns")
    s.fail("solver.basis", "expected \"parts\" or \"unknowns\", got \"" + solver.basis + "\"");
  return solver;
}

} // namespace

Eigen::Vector3d DirichletSpec::displacement_at(const Eigen::Vector3d& X) const {
  if (!has_rotation) return displacement;
  const double radians = degrees * 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(radians, axis).toRotationMatrix();
  return (Q - Eigen::Matrix3d::Identity()) * (X - center) + displacement;
}

// The scene file, section by section: each reader above checks its own fields and names every
// problem by its path in the file.
Scene parse_scene(const std::string& json_text, const std::filesystem::path& source, const std::filesystem::path& base) {
  const std::string file = source.string();
  json document;
  try {
    document = json::parse(json_text);
  } catch (const json::exception& error) {
    // Mostly a parse_error, but a number too large for a double ("3e666") is an out_of_range.
    // nlohmann's message names the byte offset; keep it to one line.
    std::string what = error.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    throw InputError(file, "JSON", what);
  }
  ObjectReader r(document, "", file);
  r.allow_only({"name", "mesh", "material", "model", "dirichlet", "gravity", "traction", "cuts", "quadrature", "crack_tip", "time",
                "output", "solver", "quasi_static", "blade", "render"});

  Scene scene;
  scene.source = source;
  scene.name = r.text("name", source.stem().string());
  scene.mesh = read_mesh(r, base);
  scene.material = read_material(r);
  scene.model = r.text("model", "linear");
  if (scene.model != "linear" && scene.model != "corotational")
    r.fail("model", "expected \"linear\" or \"corotational\", got \"" + scene.model + "\"");
  scene.dirichlet = read_dirichlet(r, base);
  scene.gravity = r.vector<3>("gravity", Eigen::Vector3d::Zero());
  scene.traction = read_tractions(r);
  scene.cuts = read_cuts(r, base);
  scene.quadrature = read_quadrature(r);
  scene.crack_tip = read_crack_tip(r);
  // Fries's ramp nodes carry functions that are nearly linearly dependent far from the front
  // (Jacobi-scaled condition number 5e9 against 3e5 without them on chapter 5's beam): a
  // corotated tangent, whose geometric terms are not definite, then loses definiteness and
  // Newton stalls (chapter 5's results). Linear XFEM factorises it fine.
  if (scene.crack_tip.blending == "corrected" && scene.model == "corotational")
    throw InputError(file, "crack_tip.blending",
                     "\"corrected\" is for the linear model only: with \"model\": \"corotational\" Newton stalls on its ramp nodes (use \"none\")");
  scene.time = read_time(r);
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i)
    if (scene.dirichlet[i].ramp_time > 0.0 && scene.time.integrator == "static")
      r.fail("dirichlet[" + std::to_string(i) + "].ramp_time", "only meaningful with a dynamic time integrator (chapter 6 on)");
  scene.output_every = read_output_every(r);
  scene.quasi_static = read_quasi_static(r);
  scene.solver = read_solver(r);
  scene.solver_given = r.has("solver");
  scene.blade = read_blade(r);
  scene.render = read_render(r, base);
  scene.render_given = r.has("render");
  return scene;
}

Scene read_scene_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "file", "cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), file, file.parent_path());
}

void require_features(const Scene& scene, const SceneFeatures& taught) {
  const std::string file = scene.source.string();
  if (scene.model == "corotational" && !taught.corotational)
    throw InputError(file, "model", "\"corotational\" is taught from chapter 2 on (02_corotation)");
  if (!scene.cuts.empty() && !taught.cuts)
    throw InputError(file, "cuts", "cuts are taught from chapter 3 on (03_xfem_heaviside)");
  if (scene.quadrature.given && !taught.cut_quadrature)
    throw InputError(file, "quadrature", "quadrature rules for cut elements are taught from chapter 4 on (04_cut_quadrature)");
  if (!taught.cut_quadrature)
    for (std::size_t i = 0; i < scene.cuts.size(); ++i)
      if (!scene.cuts[i].is_rectangle)
        throw InputError(file, "cuts[" + std::to_string(i) + "].surface",
                         "triangle-mesh cuts are taught from chapter 4 on (04_cut_quadrature)");
  if (scene.crack_tip.given && !taught.crack_tip)
    throw InputError(file, "crack_tip", "crack-tip enrichment is taught from chapter 5 on (05_crack_tip)");
  for (std::size_t i = 0; i < scene.dirichlet.size(); ++i)
    if (scene.dirichlet[i].williams && !taught.williams)
      throw InputError(file, "dirichlet[" + std::to_string(i) + "].williams",
                       "Williams's field is prescribed by chapter 5's static program only (05_crack_tip)");
  if (!taught.organ) {
    if (scene.mesh.is_liver) throw InputError(file, "mesh.liver", "the liver mesh is made from chapter 7 on (07_liver)");
    if (scene.blade.given) throw InputError(file, "blade", "a moving blade cuts from chapter 7 on (07_liver)");
    if (scene.render_given) throw InputError(file, "render", "rendered frames are drawn from chapter 7 on (07_liver)");
  }
  if (scene.time.iterations && !taught.real_time)
    throw InputError(file, "time.iterations", "a step of a fixed number of quasi-Newton iterations is taught from chapter 8 on (08_real_time)");
  if (scene.time.integrator != "static" && !taught.dynamics)
    throw InputError(file, "time.integrator", "\"" + scene.time.integrator + "\" is taught from chapter 6 on (06_newmark)");
}

} // namespace kerf
