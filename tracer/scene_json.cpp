#include "scene_json.h"

#include "scene_mesh.h"
#include "unit_vector.h"

#include "input/json_read.h"
#include "input/message.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace tracer {

using nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------------
// Error messages

/// A JSON value as the user wrote it, shortened to stay on one line.
std::string show(const json& v) { return input::brief(v); }

/// A float in its shortest exact decimal form.
std::string show(float f) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::string(buf, r.ptr);
}

std::string escape_pointer_token(std::string_view key) { return input::pointer_token(key); }

std::string display_path(const std::string& path) { return input::display_pointer(path); }

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw SceneError(display_path(path) + ": " + message);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string join(const std::vector<std::string_view>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + std::string(names[i]);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Typed readers. Each takes the value and its JSON pointer, and fails naming that pointer.

float read_float(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, "must be a number, got " + show(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path, "must be a finite number, got " + show(v));
  // Rounding to float must not overflow: a finite double past float's range is its own error.
  if (std::abs(d) > double(std::numeric_limits<float>::max()))
    fail(path, "is beyond float range (magnitude at most 3.4e38), got " + show(v));
  return static_cast<float>(d);
}

int read_int(const json& v, const std::string& path) {
  if (!v.is_number_integer()) fail(path, "must be an integer, got " + show(v));
  if (v.is_number_unsigned()
          ? v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())
          : (v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
             v.get<std::int64_t>() > std::numeric_limits<int>::max()))
    fail(path, "is out of range, got " + show(v));
  return v.get<int>();
}

std::string read_string(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, "must be a string, got " + show(v));
  return v.get<std::string>();
}

const json& read_array(const json& v, const std::string& path) {
  if (!v.is_array()) fail(path, "must be an array, got " + show(v));
  return v;
}

Vec3 read_vec3(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != 3) fail(path, "must be an array of 3 numbers, got " + show(v));
  Vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = read_float(v[std::size_t(i)], path + "/" + std::to_string(i));
  return out;
}

/// A colour: [r, g, b] or one number for grey; each channel in [0, max] (max may be infinite).
Color read_color(const json& v, const std::string& path, float max = accel::kInfinity) {
  Color c;
  if (v.is_number()) {
    c = Color(read_float(v, path));
    if (!(c.x >= 0.0f && c.x <= max))
      fail(path, (max < accel::kInfinity ? "must be in [0, " + show(max) + "]"
                                         : std::string("must be >= 0")) +
                     ", got " + show(v));
    return c;
  }
  if (!v.is_array() || v.size() != 3)
    fail(path, "must be an array of 3 numbers (or one number for grey), got " + show(v));
  for (int i = 0; i < 3; ++i) {
    const std::string p = path + "/" + std::to_string(i);
    c[i] = read_float(v[std::size_t(i)], p);
    if (!(c[i] >= 0.0f && c[i] <= max))
      fail(p, (max < accel::kInfinity ? "must be in [0, " + show(max) + "]"
                                      : std::string("must be >= 0")) +
                  ", got " + show(v[std::size_t(i)]));
  }
  return c;
}

/// An object whose keys must all be in `allowed`; members are read by name.
class Object {
 public:
  Object(const json& v, std::string path, std::vector<std::string_view> allowed,
         std::string_view what)
      : v_(v), path_(std::move(path)) {
    if (!v.is_object()) fail(path_, "must be an object, got " + show(v));
    for (const auto& [key, value] : v.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string msg = "unknown key in " + std::string(what);
      std::string_view best;
      std::size_t best_d = 3;  // suggest only close misspellings
      for (std::string_view a : allowed) {
        const std::size_t d = edit_distance(key, a);
        if (d < best_d) best = a, best_d = d;
      }
      if (!best.empty())
        msg += "; did you mean '" + std::string(best) + "'?";
      else
        msg += " (expected one of " + join(allowed) + ")";
      fail(path_ + "/" + escape_pointer_token(key), msg);
    }
  }

  bool has(std::string_view key) const { return v_.contains(key); }
  const json& operator[](std::string_view key) const { return v_.at(std::string(key)); }
  std::string path(std::string_view key) const { return path_ + "/" + std::string(key); }
  const std::string& path() const { return path_; }

  /// Fails at `key` with "must be <rule>, got <the value as written>" unless ok.
  void expect(std::string_view key, bool ok, const std::string& rule) const {
    if (!ok)
      fail(path(key), "must be " + rule + ", got " + (has(key) ? show((*this)[key]) : "(default)"));
  }

  const json& require(std::string_view key) const {
    if (!has(key)) fail(path_, "missing required key '" + std::string(key) + "'");
    return (*this)[key];
  }

  /// Optional members: read into `out` when present; otherwise `out` keeps its default.
  void number(std::string_view key, float& out) const {
    if (has(key)) out = read_float((*this)[key], path(key));
  }
  void integer(std::string_view key, int& out) const {
    if (has(key)) out = read_int((*this)[key], path(key));
  }
  void vec3(std::string_view key, Vec3& out) const {
    if (has(key)) out = read_vec3((*this)[key], path(key));
  }
  void boolean(std::string_view key, bool& out) const {
    if (!has(key)) return;
    const json& v = (*this)[key];
    if (!v.is_boolean()) fail(path(key), "must be true or false, got " + show(v));
    out = v.get<bool>();
  }
  void color(std::string_view key, Color& out, float max = accel::kInfinity) const {
    if (has(key)) out = read_color((*this)[key], path(key), max);
  }

 private:
  const json& v_;
  std::string path_;
};

void check(bool ok, const std::string& path, const std::string& rule, const std::string& got) {
  if (!ok) fail(path, "must be " + rule + ", got " + got);
}

// ---------------------------------------------------------------------------------------------
// Sections

const std::vector<std::string_view> kTopKeys = {"camera",  "background", "lights",   "materials",
                                                "spheres", "planes",     "boxes",    "triangles",
                                                "meshes",  "cones",      "polygons", "render",
                                                "integrator"};

Camera read_camera(const json& v, const std::string& path) {
  const Object o(v, path,
                 {"position", "look_at", "up", "vfov", "resolution", "samples_per_pixel", "hither",
                  "left_handed"},
                 "camera");
  Camera c;
  o.vec3("position", c.position);
  o.vec3("look_at", c.look_at);
  o.vec3("up", c.up);
  o.number("vfov", c.vfov_deg);
  o.expect("vfov", c.vfov_deg > 0.0f && c.vfov_deg < 180.0f, "in (0, 180) degrees");
  if (o.has("resolution")) {
    const json& r = o["resolution"];
    if (!r.is_array() || r.size() != 2)
      fail(o.path("resolution"), "must be [width, height] in pixels, got " + show(r));
    c.width = read_int(r[0], o.path("resolution") + "/0");
    c.height = read_int(r[1], o.path("resolution") + "/1");
    check(c.width > 0 && c.width <= 65536, o.path("resolution") + "/0", "in [1, 65536]",
          std::to_string(c.width));
    check(c.height > 0 && c.height <= 65536, o.path("resolution") + "/1", "in [1, 65536]",
          std::to_string(c.height));
  }
  o.integer("samples_per_pixel", c.samples_per_pixel);
  o.expect("samples_per_pixel", c.samples_per_pixel >= 1 && c.samples_per_pixel <= 65536,
           "in [1, 65536]");
  o.number("hither", c.hither);
  o.expect("hither", c.hither >= 0.0f, ">= 0");
  o.boolean("left_handed", c.left_handed);
  const Vec3 view = c.look_at - c.position;
  if (!(glm::dot(view, view) > 0.0f)) fail(o.path("look_at"), "must differ from position");
  if (!(glm::dot(c.up, c.up) > 0.0f)) fail(o.path("up"), "must be non-zero");
  const Vec3 side = glm::cross(glm::normalize(view), glm::normalize(c.up));
  if (!(glm::length(side) > 1e-6f))
    fail(o.path("up"), "must not be parallel to the view direction");
  return c;
}

PointLight read_light(const json& v, const std::string& path) {
  const Object o(v, path, {"position", "power", "color"}, "light");
  PointLight l;
  l.position = read_vec3(o.require("position"), o.path("position"));
  o.number("power", l.power_w);
  o.expect("power", l.power_w >= 0.0f, ">= 0 watts");
  o.color("color", l.color);
  return l;
}

const std::map<std::string_view, MaterialType> kMaterialTypes = {
    {"diffuse", MaterialType::Diffuse},
    {"mirror", MaterialType::Mirror},
    {"dielectric", MaterialType::Dielectric},
    {"nff", MaterialType::Nff}};

std::string_view type_name(MaterialType t) {
  for (const auto& [name, type] : kMaterialTypes)
    if (type == t) return name;
  return "?";
}

Material read_material(const json& v, const std::string& path) {
  if (!v.is_object()) fail(path, "must be an object, got " + show(v));
  if (!v.contains("type")) fail(path, "missing required key 'type'");
  const std::string type = read_string(v["type"], path + "/type");
  const auto it = kMaterialTypes.find(type);
  if (it == kMaterialTypes.end())
    fail(path + "/type",
         "unknown material type \"" + type + "\" (expected diffuse, mirror, dielectric or nff)");
  Material m;
  m.type = it->second;
  std::vector<std::string_view> keys = {"name", "type"};
  switch (m.type) {
    case MaterialType::Diffuse:
      keys.insert(keys.end(), {"albedo", "specular", "shininess"});
      break;
    case MaterialType::Mirror:
      keys.insert(keys.end(), {"reflectance"});
      break;
    case MaterialType::Dielectric:
      keys.insert(keys.end(), {"ior", "absorption"});
      break;
    case MaterialType::Nff:
      keys.insert(keys.end(), {"color", "kd", "ks", "shininess", "transmittance", "ior"});
      break;
  }
  const Object o(v, path, keys, type + " material");
  m.name = read_string(o.require("name"), o.path("name"));
  if (m.name.empty()) fail(o.path("name"), "must not be empty");
  switch (m.type) {
    case MaterialType::Diffuse:
      o.color("albedo", m.albedo, 1.0f);
      o.number("specular", m.specular);
      o.expect("specular", m.specular >= 0.0f && m.specular <= 1.0f, "in [0, 1]");
      o.number("shininess", m.shininess);
      o.expect("shininess", m.shininess > 0.0f, "> 0");
      break;
    case MaterialType::Mirror:
      o.color("reflectance", m.reflectance, 1.0f);
      break;
    case MaterialType::Dielectric:
      o.number("ior", m.ior);
      o.expect("ior", m.ior > 0.0f, "> 0");
      o.color("absorption", m.absorption);
      break;
    case MaterialType::Nff:
      o.color("color", m.albedo);
      o.number("kd", m.kd);
      o.expect("kd", m.kd >= 0.0f, ">= 0");
      o.number("ks", m.ks);
      o.expect("ks", m.ks >= 0.0f, ">= 0");
      o.number("shininess", m.shininess);
      o.expect("shininess", m.shininess >= 0.0f, ">= 0");
      o.number("transmittance", m.transmittance);
      o.expect("transmittance", m.transmittance >= 0.0f, ">= 0");
      o.number("ior", m.ior);
      o.expect("ior", m.ior >= 0.0f, ">= 0 (0 on opaque surfaces)");
      break;
  }
  return m;
}

}  // namespace

const knobs::KnobTable<RenderSettings>& RenderSettings::knobs() {
  using K = knobs::Knob<RenderSettings>;
  static const knobs::KnobTable<RenderSettings> table(
      "render",
      {K::integer("max_depth", &RenderSettings::max_depth, 1, 1000, "rays",
                  "Longest chain of rays; the camera ray is depth 1."),
       K::number("min_weight", &RenderSettings::min_weight, 0.0, 1.0, "fraction",
                 "A reflected or refracted ray whose path weight (largest channel of the product of the "
                 "reflectances, Fresnel weights and absorption along its path) falls below this is not traced.")});
  return table;
}

namespace {

RenderSettings read_render(const json& v, const std::string& path) {
  const knobs::KnobTable<RenderSettings>& table = RenderSettings::knobs();
  const std::vector<std::string> names = table.names();
  const Object o(v, path, std::vector<std::string_view>(names.begin(), names.end()), "render settings");
  RenderSettings r;
  for (const auto& [key, value] : v.items()) {
    const knobs::Knob<RenderSettings>& k = *table.find(key);
    const std::string why = k.why_not(value);
    if (!why.empty()) fail(o.path(key), why);
    k.set(r, value, table.owner());
  }
  return r;
}

/// Material names to indices, for the primitives' "material" keys.
class MaterialIndex {
 public:
  explicit MaterialIndex(const std::vector<Material>& materials) : materials_(&materials) {}

  std::uint32_t lookup(const Object& o) const {
    const std::string name = read_string(o.require("material"), o.path("material"));
    for (std::size_t i = 0; i < materials_->size(); ++i)
      if ((*materials_)[i].name == name) return std::uint32_t(i);
    std::string known;
    for (const Material& m : *materials_) known += (known.empty() ? "" : ", ") + m.name;
    fail(o.path("material"),
         "unknown material \"" + name + "\"" +
             (known.empty() ? " (no materials are defined)" : " (known: " + known + ")"));
  }

 private:
  const std::vector<Material>* materials_;
};

/// A unit normal from a non-zero vector; an already unit vector (to 4 ulps of its squared
/// length) is kept as written, so that saving and loading again gives the same bits.
Vec3 read_normal(const json& v, const std::string& path) {
  const Vec3 n = read_vec3(v, path);
  const Vec3 unit = unit_vector(n);
  if (unit == Vec3(0.0f)) fail(path, "must be a non-zero vector, got " + show(v));
  const float len2 = glm::dot(n, n);
  if (std::abs(len2 - 1.0f) <= 4.0f * std::numeric_limits<float>::epsilon()) return n;
  return unit;
}

template <class Fn>
void for_each_element(const json& doc, std::string_view key, Fn&& fn) {
  if (!doc.contains(key)) return;
  const std::string path = "/" + std::string(key);
  const json& arr = read_array(doc.at(std::string(key)), path);
  for (std::size_t i = 0; i < arr.size(); ++i) fn(arr[i], path + "/" + std::to_string(i));
}

void read_triangle(const json& v, const std::string& path, const MaterialIndex& mats, Geometry& g) {
  const Object o(v, path, {"vertices", "normals", "material"}, "triangle");
  const json& vs = o.require("vertices");
  if (!vs.is_array() || vs.size() != 3)
    fail(o.path("vertices"), "must be an array of 3 points, got " + show(vs));
  Triangle t;
  t.p0 = read_vec3(vs[0], o.path("vertices") + "/0");
  t.p1 = read_vec3(vs[1], o.path("vertices") + "/1");
  t.p2 = read_vec3(vs[2], o.path("vertices") + "/2");
  t.material = mats.lookup(o);
  if (o.has("normals")) {
    const json& ns = o["normals"];
    if (!ns.is_array() || ns.size() != 3)
      fail(o.path("normals"), "must be an array of 3 vectors, got " + show(ns));
    t.normals = std::int32_t(g.vertex_normals.size());
    for (std::size_t k = 0; k < 3; ++k)
      g.vertex_normals.push_back(read_normal(ns[k], o.path("normals") + "/" + std::to_string(k)));
  }
  g.triangles.push_back(t);
}

MeshTransform read_mesh_transform(const json& v, const std::string& path) {
  const Object o(v, path, {"translate", "rotate", "scale"}, "transform");
  MeshTransform t;
  if (o.has("translate")) t.translate = glm::dvec3(read_vec3(o["translate"], o.path("translate")));
  if (o.has("rotate")) t.rotate = glm::dvec3(read_vec3(o["rotate"], o.path("rotate")));
  if (o.has("scale")) {
    const json& s = o["scale"];
    t.scale = s.is_number() ? glm::dvec3(double(read_float(s, o.path("scale"))))
                            : glm::dvec3(read_vec3(s, o.path("scale")));
    for (int a = 0; a < 3; ++a)
      if (t.scale[a] == 0.0) fail(o.path("scale"), "must be non-zero on every axis, got " + show(s));
  }
  return t;
}

/// The model files one scene has read, by path: a file that many meshes place (mesh_grid's
/// instances) is read and checked once.
using LoadedMeshes = std::map<std::string, MeshData>;

/// A mesh from a model file, placed by its transform, appended to the triangles.
void read_mesh_file(const Object& o, std::uint32_t material, const SceneReadContext& context, LoadedMeshes& loaded,
                    Scene& scene) {
  for (const char* inline_key : {"vertices", "indices", "normals"})
    if (o.has(inline_key))
      fail(o.path(inline_key), "a mesh has either \"file\" or inline vertices and indices, not both");
  const std::string file = read_string(o["file"], o.path("file"));
  if (file.empty()) fail(o.path("file"), "must be a path to a model file, got \"\"");
  const std::filesystem::path p(file);
  MeshInstance m;
  m.path = (p.is_absolute() || context.base_dir.empty() ? p : std::filesystem::path(context.base_dir) / p)
               .lexically_normal()
               .string();
  if (o.has("transform")) m.transform = read_mesh_transform(o["transform"], o.path("transform"));
  m.material = material;
  auto it = loaded.find(m.path);
  if (it == loaded.end()) {
    try {
      it = loaded.emplace(m.path, load_mesh_file(m.path, context.max_memory_bytes)).first;
    } catch (const SceneError& e) {
      fail(o.path("file"), e.what());
    }
  }
  add_mesh(scene, it->second, std::move(m));
}

void read_mesh(const json& v, const std::string& path, const MaterialIndex& mats, const SceneReadContext& context,
               LoadedMeshes& loaded, Scene& scene) {
  Geometry& g = scene.geometry;
  const Object o(v, path, {"file", "transform", "vertices", "indices", "normals", "material"}, "mesh");
  const std::uint32_t material = mats.lookup(o);
  if (o.has("file")) return read_mesh_file(o, material, context, loaded, scene);
  if (o.has("transform")) fail(o.path("transform"), "applies to a mesh read from a \"file\" only");
  const json& vs = read_array(o.require("vertices"), o.path("vertices"));
  std::vector<Vec3> points(vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i)
    points[i] = read_vec3(vs[i], o.path("vertices") + "/" + std::to_string(i));
  std::vector<Vec3> normals;
  if (o.has("normals")) {
    const json& ns = read_array(o["normals"], o.path("normals"));
    if (ns.size() != points.size())
      fail(o.path("normals"), "must have one normal per vertex (" + std::to_string(points.size()) +
                                  "), got " + std::to_string(ns.size()));
    normals.resize(ns.size());
    for (std::size_t i = 0; i < ns.size(); ++i)
      normals[i] = read_normal(ns[i], o.path("normals") + "/" + std::to_string(i));
  }
  const json& is = read_array(o.require("indices"), o.path("indices"));
  for (std::size_t i = 0; i < is.size(); ++i) {
    const std::string ip = o.path("indices") + "/" + std::to_string(i);
    if (!is[i].is_array() || is[i].size() != 3)
      fail(ip, "must be an array of 3 vertex indices, got " + show(is[i]));
    std::uint32_t idx[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::string kp = ip + "/" + std::to_string(k);
      const json& e = is[i][k];
      if (!e.is_number_integer()) fail(kp, "must be an integer vertex index, got " + show(e));
      if (e.is_number_integer() && !e.is_number_unsigned() && e.get<std::int64_t>() < 0)
        fail(kp, "must be >= 0, got " + show(e));
      if (e.get<std::uint64_t>() >= points.size())
        fail(kp, "vertex index " + show(e) + " is out of range (the mesh has " +
                     std::to_string(points.size()) + " vertices)");
      idx[k] = e.get<std::uint32_t>();
    }
    Triangle t{points[idx[0]], points[idx[1]], points[idx[2]], material, -1};
    if (!normals.empty()) {
      t.normals = std::int32_t(g.vertex_normals.size());
      for (std::uint32_t k : idx) g.vertex_normals.push_back(normals[k]);
    }
    g.triangles.push_back(t);
  }
}

void read_cone(const json& v, const std::string& path, const MaterialIndex& mats, Geometry& g) {
  const Object o(v, path,
                 {"base", "base_radius", "apex", "axis", "height", "apex_radius", "material"},
                 "cone");
  Cone c;
  c.base = read_vec3(o.require("base"), o.path("base"));
  c.base_radius = read_float(o.require("base_radius"), o.path("base_radius"));
  c.apex_radius = read_float(o.require("apex_radius"), o.path("apex_radius"));
  // Negative radii (both) make the inside the visible side, as in NFF.
  o.expect("apex_radius", !(c.base_radius * c.apex_radius < 0.0f),
           "of the same sign as base_radius");
  if (c.base_radius == 0.0f && c.apex_radius == 0.0f)
    fail(o.path("apex_radius"), "must be non-zero when base_radius is 0");
  if (o.has("apex") == (o.has("axis") || o.has("height")))
    fail(o.path(), "needs either 'apex' or both 'axis' and 'height'");
  if (o.has("apex")) {
    const Vec3 apex = read_vec3(o["apex"], o.path("apex"));
    if (apex == c.base) fail(o.path("apex"), "must differ from base");
    if (!cone_ends_usable(c.base, apex))
      fail(o.path("apex"), "is too far from base or too close for float (their distance is not a finite non-zero float)");
    c = make_cone(c.base, c.base_radius, apex, c.apex_radius);
  } else {
    c.axis = read_normal(o.require("axis"), o.path("axis"));
    c.height = read_float(o.require("height"), o.path("height"));
    o.expect("height", c.height > 0.0f, "> 0");
  }
  c.material = mats.lookup(o);
  g.cones.push_back(c);
}

void read_polygon(const json& v, const std::string& path, const MaterialIndex& mats, Geometry& g) {
  const Object o(v, path, {"vertices", "material"}, "polygon");
  const json& vs = read_array(o.require("vertices"), o.path("vertices"));
  if (vs.size() < 3)
    fail(o.path("vertices"), "must have at least 3 points, got " + std::to_string(vs.size()));
  std::vector<Vec3> points(vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i)
    points[i] = read_vec3(vs[i], o.path("vertices") + "/" + std::to_string(i));
  const Polygon poly =
      make_polygon(points, std::uint32_t(g.polygon_vertices.size()), mats.lookup(o));
  if (poly.normal == Vec3(0.0f))
    fail(o.path("vertices"), "must span a plane (the polygon is degenerate)");
  g.polygon_vertices.insert(g.polygon_vertices.end(), points.begin(), points.end());
  g.polygons.push_back(poly);
}

// ---------------------------------------------------------------------------------------------
// Writing

/// A float as the JSON number with the shortest decimal form that reads back to the same float.
json number(float f) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::stod(std::string(buf, r.ptr));
}
json vec(const Vec3& v) {
  return json::array({number(v.x), number(v.y), number(v.z)});
}

json material_json(const Material& m) {
  json j = {{"name", m.name}, {"type", type_name(m.type)}};
  switch (m.type) {
    case MaterialType::Diffuse:
      j["albedo"] = vec(m.albedo);
      j["specular"] = number(m.specular);
      j["shininess"] = number(m.shininess);
      break;
    case MaterialType::Mirror:
      j["reflectance"] = vec(m.reflectance);
      break;
    case MaterialType::Dielectric:
      j["ior"] = number(m.ior);
      j["absorption"] = vec(m.absorption);
      break;
    case MaterialType::Nff:
      j["color"] = vec(m.albedo);
      j["kd"] = number(m.kd);
      j["ks"] = number(m.ks);
      j["shininess"] = number(m.shininess);
      j["transmittance"] = number(m.transmittance);
      j["ior"] = number(m.ior);
      break;
  }
  return j;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

Scene scene_from_json(const json& doc, const SceneReadContext& context) {
  const Object top(doc, "", kTopKeys, "scene");
  Scene scene;
  if (top.has("camera")) scene.camera = read_camera(top["camera"], "/camera");
  top.color("background", scene.background);
  for_each_element(doc, "lights", [&](const json& v, const std::string& p) {
    scene.lights.push_back(read_light(v, p));
  });
  for_each_element(doc, "materials", [&](const json& v, const std::string& p) {
    Material m = read_material(v, p);
    for (const Material& other : scene.materials)
      if (other.name == m.name) fail(p + "/name", "duplicate material name \"" + m.name + "\"");
    scene.materials.push_back(std::move(m));
  });
  if (top.has("render")) scene.render = read_render(top["render"], "/render");
  if (top.has("integrator")) {
    // The name and the knobs are only stored here: integrators/ knows the integrators and checks both.
    const json& v = top["integrator"];
    if (v.is_string()) {
      scene.integrator.name = v.get<std::string>();
    } else if (v.is_object() && v.contains("name") && v["name"].is_string()) {
      scene.integrator.name = v["name"].get<std::string>();
      scene.integrator.knobs = v;
      scene.integrator.knobs.erase("name");
    } else {
      fail("/integrator",
           "must be an integrator name or an object {\"name\": ..., knob: value, ...}, got " +
               show(v));
    }
    if (scene.integrator.name.empty()) fail("/integrator", "the integrator name must not be empty");
  }

  const MaterialIndex mats(scene.materials);
  Geometry& g = scene.geometry;
  for_each_element(doc, "spheres", [&](const json& v, const std::string& p) {
    const Object o(v, p, {"center", "radius", "inside_visible", "material"}, "sphere");
    Sphere s;
    s.center = read_vec3(o.require("center"), o.path("center"));
    s.radius = read_float(o.require("radius"), o.path("radius"));
    o.expect("radius", s.radius > 0.0f, "> 0");
    bool inside_visible = false;
    o.boolean("inside_visible", inside_visible);
    if (inside_visible) s.radius = -s.radius;  // NFF's convention, kept in the Sphere
    s.material = mats.lookup(o);
    g.spheres.push_back(s);
  });
  for_each_element(doc, "planes", [&](const json& v, const std::string& p) {
    const Object o(v, p, {"normal", "offset", "material"}, "plane");
    Plane pl;
    pl.normal = read_normal(o.require("normal"), o.path("normal"));
    o.number("offset", pl.offset);
    pl.material = mats.lookup(o);
    g.planes.push_back(pl);
  });
  for_each_element(doc, "boxes", [&](const json& v, const std::string& p) {
    const Object o(v, p, {"min", "max", "material"}, "box");
    Box b;
    b.lo = read_vec3(o.require("min"), o.path("min"));
    b.hi = read_vec3(o.require("max"), o.path("max"));
    for (int a = 0; a < 3; ++a)
      if (!(b.hi[a] > b.lo[a]))
        fail(o.path("max") + "/" + std::to_string(a), "must be > min/" + std::to_string(a) + " (" +
                                                          show(b.lo[a]) + "), got " +
                                                          show(b.hi[a]));
    b.material = mats.lookup(o);
    g.boxes.push_back(b);
  });
  for_each_element(doc, "triangles",
                   [&](const json& v, const std::string& p) { read_triangle(v, p, mats, g); });
  LoadedMeshes loaded;
  for_each_element(doc, "meshes",
                   [&](const json& v, const std::string& p) { read_mesh(v, p, mats, context, loaded, scene); });
  for_each_element(doc, "cones",
                   [&](const json& v, const std::string& p) { read_cone(v, p, mats, g); });
  for_each_element(doc, "polygons",
                   [&](const json& v, const std::string& p) { read_polygon(v, p, mats, g); });

  const std::size_t bounded =
      g.spheres.size() + g.triangles.size() + g.boxes.size() + g.cones.size() + g.polygons.size();
  // The top bit of a primitive id marks planes (Hit::kPlaneBit).
  if (bounded >= (std::size_t(1) << 31))
    fail("", "too many primitives (" + std::to_string(bounded) + ")");
  g.finalize();
  return scene;
}

Scene parse_scene_json(std::string_view text, const SceneReadContext& context) {
  json doc;
  try {
    doc = input::parse_json(text);
  } catch (const input::InputError& e) {
    throw SceneError(e.what());
  }
  return scene_from_json(doc, context);
}

json scene_to_json(const Scene& scene) {
  json j;
  const Camera& c = scene.camera;
  j["camera"] = {{"position", vec(c.position)},
                 {"look_at", vec(c.look_at)},
                 {"up", vec(c.up)},
                 {"vfov", number(c.vfov_deg)},
                 {"resolution", {c.width, c.height}},
                 {"samples_per_pixel", c.samples_per_pixel},
                 {"hither", number(c.hither)},
                 {"left_handed", c.left_handed}};
  j["background"] = vec(scene.background);
  j["render"] = RenderSettings::knobs().to_json(scene.render);
  if (!scene.integrator.name.empty()) {
    json integrator = scene.integrator.knobs.is_object() ? scene.integrator.knobs : json::object();
    integrator["name"] = scene.integrator.name;
    j["integrator"] = integrator;
  }
  j["lights"] = json::array();
  for (const PointLight& l : scene.lights)
    j["lights"].push_back(
        {{"position", vec(l.position)}, {"power", number(l.power_w)}, {"color", vec(l.color)}});
  j["materials"] = json::array();
  for (const Material& m : scene.materials) j["materials"].push_back(material_json(m));

  const Geometry& g = scene.geometry;
  auto mat = [&scene](std::uint32_t i) { return scene.materials.at(i).name; };
  j["spheres"] = json::array();
  for (const Sphere& s : g.spheres) {
    json sphere = {{"center", vec(s.center)},
                   {"radius", number(std::abs(s.radius))},
                   {"material", mat(s.material)}};
    if (s.radius < 0.0f) sphere["inside_visible"] = true;
    j["spheres"].push_back(std::move(sphere));
  }
  j["planes"] = json::array();
  for (const Plane& p : g.planes)
    j["planes"].push_back(
        {{"normal", vec(p.normal)}, {"offset", number(p.offset)}, {"material", mat(p.material)}});
  j["boxes"] = json::array();
  for (const Box& b : g.boxes)
    j["boxes"].push_back({{"min", vec(b.lo)}, {"max", vec(b.hi)}, {"material", mat(b.material)}});
  // A mesh read from a file is written as its reference (the file's path as the loader opened
  // it; save_scene_file makes it relative to the saved scene), not as its triangles.
  std::vector<bool> from_file(g.triangles.size(), false);
  if (!scene.meshes.empty()) {
    j["meshes"] = json::array();
    for (const MeshInstance& m : scene.meshes) {
      std::fill(from_file.begin() + m.first_triangle, from_file.begin() + m.first_triangle + m.triangle_count, true);
      json mj = {{"file", m.path}, {"material", mat(m.material)}};
      if (!m.transform.is_identity()) {
        const auto v3 = [](const glm::dvec3& v) { return vec(Vec3(v)); };
        mj["transform"] = {{"translate", v3(m.transform.translate)},
                           {"rotate", v3(m.transform.rotate)},
                           {"scale", v3(m.transform.scale)}};
      }
      j["meshes"].push_back(std::move(mj));
    }
  }
  j["triangles"] = json::array();
  for (std::size_t i = 0; i < g.triangles.size(); ++i) {
    if (from_file[i]) continue;
    const Triangle& t = g.triangles[i];
    json tj = {{"vertices", {vec(t.p0), vec(t.p1), vec(t.p2)}}, {"material", mat(t.material)}};
    if (t.normals >= 0) {
      const Vec3* n = &g.vertex_normals.at(std::size_t(t.normals));
      tj["normals"] = {vec(n[0]), vec(n[1]), vec(n[2])};
    }
    j["triangles"].push_back(std::move(tj));
  }
  if (!g.cones.empty()) {
    j["cones"] = json::array();
    for (const Cone& c2 : g.cones)
      j["cones"].push_back({{"base", vec(c2.base)},
                            {"base_radius", number(c2.base_radius)},
                            {"axis", vec(c2.axis)},
                            {"height", number(c2.height)},
                            {"apex_radius", number(c2.apex_radius)},
                            {"material", mat(c2.material)}});
  }
  if (!g.polygons.empty()) {
    j["polygons"] = json::array();
    for (const Polygon& p : g.polygons) {
      json vs = json::array();
      for (std::uint32_t i = 0; i < p.vertex_count; ++i)
        vs.push_back(vec(g.polygon_vertices.at(p.first_vertex + i)));
      j["polygons"].push_back({{"vertices", std::move(vs)}, {"material", mat(p.material)}});
    }
  }
  return j;
}

}  // namespace tracer
