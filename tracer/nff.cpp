#include "nff.h"

#include "nff_shading.h"
#include "unit_vector.h"

#include "input/file_read.h"

#include <array>
#include <charconv>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

namespace tracer {
namespace {

/// One whitespace-separated word of the file and the line it starts on (1-based).
struct Token {
  std::string_view text;
  int line = 0;
};

/// Splits the text into tokens; `#` starts a comment that runs to the end of the line.
std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  const auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (is_space(c)) {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      const std::size_t start = i;
      while (i < text.size() && !is_space(text[i])) ++i;
      tokens.push_back({text.substr(start, i - start), line});
    }
  }
  return tokens;
}

/// A token read as a number: its value, or why it is not one.
struct Number {
  enum class Kind { Ok, NotANumber, OutOfRange } kind = Kind::NotANumber;
  double value = 0.0;
};

Number parse_number(std::string_view s) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);  // from_chars rejects '+'
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (end != s.data() + s.size()) return {};
  if (ec == std::errc::result_out_of_range) return {Number::Kind::OutOfRange, 0.0};
  if (ec != std::errc()) return {};
  return {Number::Kind::Ok, v};
}

constexpr double kFloatMax = double(std::numeric_limits<float>::max());

/// Shortens a token for an error message (garbled files can hold very long or binary words).
std::string quoted(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 24)) out += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > 24) out += "...";
  return "'" + out + "'";
}

class Parser {
 public:
  Parser(std::string_view text, std::string name) : tokens_(tokenize(text)), name_(std::move(name)) {}

  Scene parse() {
    while (pos_ < tokens_.size()) {
      const Token cmd = tokens_[pos_++];
      if (cmd.text == "b") parse_background(cmd);
      else if (cmd.text == "v") parse_view(cmd);
      else if (cmd.text == "l") parse_light(cmd);
      else if (cmd.text == "f") parse_material(cmd);
      else if (cmd.text == "s") parse_sphere(cmd);
      else if (cmd.text == "c") parse_cone(cmd);
      else if (cmd.text == "p") parse_polygon(cmd);
      else if (cmd.text == "pp") parse_patch(cmd);
      else fail(cmd.line, "unknown entity " + quoted(cmd.text));
    }
    if (!have_view_) fail(last_line(), "no 'v' viewpoint in the file");
    finish_lights();
    scene_.geometry.finalize();
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw SceneError(name_ + ":" + std::to_string(line) + ": " + what);
  }
  int last_line() const { return tokens_.empty() ? 1 : tokens_.back().line; }

  /// Reads exactly `count` numbers following `cmd`, or fails with "expected N numbers after
  /// '<what>', got M" at the entity's line.
  std::vector<double> numbers(const Token& cmd, std::size_t count, const std::string& what) {
    std::vector<double> out;
    out.reserve(std::min<std::size_t>(count, 1024));
    while (out.size() < count && pos_ < tokens_.size()) {
      const Token& tok = tokens_[pos_];
      const Number n = parse_number(tok.text);
      if (n.kind == Number::Kind::NotANumber) break;
      if (n.kind == Number::Kind::OutOfRange || (std::isfinite(n.value) && std::abs(n.value) > kFloatMax))
        fail(tok.line, "number " + quoted(tok.text) + " is beyond float range (magnitude at most 3.4e38)");
      if (!std::isfinite(n.value)) fail(tok.line, "number " + quoted(tok.text) + " is not finite");
      out.push_back(n.value);
      ++pos_;
    }
    if (out.size() < count)
      fail(cmd.line, "expected " + std::to_string(count) + " numbers after " + what + ", got " +
                         std::to_string(out.size()));
    return out;
  }
  std::vector<double> numbers(const Token& cmd, std::size_t count) {
    return numbers(cmd, count, quoted(cmd.text));
  }

  static Vec3 vec(const std::vector<double>& v, std::size_t at) {
    return Vec3(float(v[at]), float(v[at + 1]), float(v[at + 2]));
  }

  /// A vertex count: a positive integer of at least `min`.
  std::uint32_t vertex_count(const Token& cmd, std::uint32_t min) {
    if (pos_ >= tokens_.size()) fail(cmd.line, "expected a vertex count after " + quoted(cmd.text));
    const Token tok = tokens_[pos_++];
    const Number n = parse_number(tok.text);
    // A count past double's range is a count out of range, not a word.
    const double v = n.kind == Number::Kind::OutOfRange ? HUGE_VAL : n.value;
    if (n.kind == Number::Kind::NotANumber || v != std::floor(v))
      fail(tok.line, "expected a vertex count after " + quoted(cmd.text) + ", got " + quoted(tok.text));
    if (v < min || v > 1e6)
      fail(tok.line, quoted(cmd.text) + " needs " + std::to_string(min) +
                         " to 1000000 vertices, got " + quoted(tok.text));
    return std::uint32_t(v);
  }

  /// A colour: three numbers, each >= 0 (the scene model's rule for every colour).
  Color colour(const Token& cmd, const std::vector<double>& v, std::size_t at) const {
    for (std::size_t i = at; i < at + 3; ++i)
      if (!(v[i] >= 0.0)) fail(cmd.line, quoted(cmd.text) + " colour values must be >= 0, got " + std::to_string(v[i]));
    return vec(v, at);
  }

  void parse_background(const Token& cmd) { scene_.background = colour(cmd, numbers(cmd, 3), 0); }

  void parse_view(const Token& cmd) {
    if (have_view_) fail(cmd.line, "second 'v' viewpoint");
    have_view_ = true;
    static constexpr std::array<std::pair<std::string_view, std::size_t>, 6> kFields{{
        {"from", 3}, {"at", 3}, {"up", 3}, {"angle", 1}, {"hither", 1}, {"resolution", 2}}};
    std::array<std::optional<std::vector<double>>, kFields.size()> got;
    while (pos_ < tokens_.size()) {
      const Token& key = tokens_[pos_];
      std::size_t f = 0;
      while (f < kFields.size() && kFields[f].first != key.text) ++f;
      if (f == kFields.size()) break;
      ++pos_;
      if (got[f]) fail(key.line, "'v' gives " + quoted(key.text) + " twice");
      got[f] = numbers(key, kFields[f].second, quoted(key.text));
    }
    for (std::size_t f = 0; f < kFields.size(); ++f)
      if (!got[f]) fail(cmd.line, "'v' is missing '" + std::string(kFields[f].first) + "'");
    Camera& cam = scene_.camera;
    cam.position = vec(*got[0], 0);
    cam.look_at = vec(*got[1], 0);
    cam.up = vec(*got[2], 0);
    const double angle = (*got[3])[0];
    const double hither = (*got[4])[0];
    const double w = (*got[5])[0], h = (*got[5])[1];
    const Vec3 view = cam.look_at - cam.position;
    if (glm::length(view) == 0.0f) fail(cmd.line, "'v' has 'from' equal to 'at'");
    if (glm::length(glm::cross(view, cam.up)) <= 1e-6f * glm::length(view) * glm::length(cam.up))
      fail(cmd.line, "'v' has an 'up' parallel to the view direction (or zero)");
    if (!(angle > 0.0 && angle < 180.0))
      fail(cmd.line, "'v' angle must be in (0, 180) degrees, got " + std::to_string(angle));
    if (!(hither >= 0.0)) fail(cmd.line, "'v' hither must be >= 0");
    if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > 16384 || h > 16384)
      fail(cmd.line, "'v' resolution must be two integers in [1, 16384]");
    cam.vfov_deg = float(angle);
    cam.hither = float(hither);
    cam.left_handed = true;  // the SPD's coordinate system is left-handed (SPD README)
    cam.width = int(w);
    cam.height = int(h);
  }

  void parse_light(const Token& cmd) {
    const auto p = numbers(cmd, 3);
    PointLight light;
    light.position = vec(p, 0);
    light.color = Color(1.0f);
    // The colour is optional: take it only when three more numbers follow.
    std::size_t extra = 0;
    while (extra < 3 && pos_ + extra < tokens_.size() &&
           parse_number(tokens_[pos_ + extra].text).kind != Number::Kind::NotANumber)
      ++extra;
    if (extra == 3) light.color = colour(cmd, numbers(cmd, 3), 0);
    else if (extra > 0)
      fail(cmd.line, "expected 3 or 6 numbers after 'l', got " + std::to_string(3 + extra));
    scene_.lights.push_back(light);
    light_lines_.push_back(cmd.line);
  }

  void parse_material(const Token& cmd) {
    const auto v = numbers(cmd, 8);
    const std::array<double, 8> key{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
    for (const double x : v)
      if (x < 0.0) fail(cmd.line, "'f' values must be >= 0, got " + std::to_string(x));
    const double transmittance = v[6], ior = v[7];
    if (transmittance > 0.0 && !(ior > 0.0))
      fail(cmd.line, "'f' with T > 0 needs an index of refraction > 0");
    if (const auto it = material_ids_.find(key); it != material_ids_.end()) {
      material_ = it->second;
      return;
    }
    Material m;
    m.name = "nff" + std::to_string(scene_.materials.size());
    m.type = MaterialType::Nff;
    m.albedo = vec(v, 0);
    m.kd = float(v[3]);
    m.ks = float(v[4]);
    m.shininess = float(v[5]);
    m.transmittance = float(transmittance);
    m.ior = ior > 0.0 ? float(ior) : 1.0f;  // ior 0 is legal on opaque materials
    // Plausible values for the other integrators, from the same numbers.
    m.specular = std::min(1.0f, m.ks);
    material_ = std::uint32_t(scene_.materials.size());
    material_ids_.emplace(key, *material_);
    scene_.materials.push_back(m);
  }

  std::uint32_t material() {
    if (!material_) {
      Material m;
      m.name = "nff_default";
      m.type = MaterialType::Nff;
      m.albedo = Color(1.0f);
      material_ = std::uint32_t(scene_.materials.size());
      scene_.materials.push_back(m);
    }
    return *material_;
  }

  void parse_sphere(const Token& cmd) {
    const auto v = numbers(cmd, 4);
    if (v[3] == 0.0) fail(cmd.line, "'s' radius must be non-zero");
    Sphere s;
    s.center = vec(v, 0);
    s.radius = float(v[3]);
    s.material = material();
    scene_.geometry.spheres.push_back(s);
  }

  void parse_cone(const Token& cmd) {
    const auto v = numbers(cmd, 8);
    const Vec3 base = vec(v, 0), apex = vec(v, 4);
    const double r0 = v[3], r1 = v[7];
    if (base == apex) fail(cmd.line, "'c' base and apex are the same point");
    if (!cone_ends_usable(base, apex))
      fail(cmd.line, "'c' base and apex are too far apart or too close for float (their distance is not a finite non-zero float)");
    if ((r0 < 0.0 && r1 > 0.0) || (r0 > 0.0 && r1 < 0.0))
      fail(cmd.line, "'c' radii must have the same sign (both < 0: inside visible)");
    if (r0 == 0.0 && r1 == 0.0) fail(cmd.line, "'c' radii are both zero");
    // A zero radius takes the sign of the other so that the visible side is well defined.
    const float sign = (r0 < 0.0 || r1 < 0.0) ? -1.0f : 1.0f;
    scene_.geometry.cones.push_back(
        make_cone(base, sign * float(std::abs(r0)), apex, sign * float(std::abs(r1)), material()));
  }

  void parse_polygon(const Token& cmd) {
    const std::uint32_t n = vertex_count(cmd, 3);
    const auto v = numbers(cmd, 3 * std::size_t(n),
                           "'p' (" + std::to_string(n) + " vertices)");
    Geometry& g = scene_.geometry;
    if (n == 3) {
      Triangle t;
      t.p0 = vec(v, 0);
      t.p1 = vec(v, 3);
      t.p2 = vec(v, 6);
      t.material = material();
      g.triangles.push_back(t);
      return;
    }
    const auto first = std::uint32_t(g.polygon_vertices.size());
    for (std::uint32_t i = 0; i < n; ++i) g.polygon_vertices.push_back(vec(v, 3 * i));
    const Polygon poly = make_polygon(std::span<const Vec3>(g.polygon_vertices.data() + first, n), first, material());
    // The scene model's rule (the JSON loader's too): a polygon spans a plane.
    if (poly.normal == Vec3(0.0f))
      fail(cmd.line, "'p' polygon is degenerate: its vertices do not span a plane");
    g.polygons.push_back(poly);
  }

  void parse_patch(const Token& cmd) {
    const std::uint32_t n = vertex_count(cmd, 3);
    const auto v = numbers(cmd, 6 * std::size_t(n),
                           "'pp' (" + std::to_string(n) + " vertices with normals)");
    Geometry& g = scene_.geometry;
    std::vector<Vec3> normals(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      const Vec3 nv = vec(v, 6 * i + 3);
      normals[i] = unit_vector(nv);
      if (normals[i] == Vec3(0.0f))
        fail(cmd.line, "'pp' vertex " + std::to_string(i + 1) + " has a zero normal");
    }
    // SPD patches are triangles; larger ones become a fan around the first vertex.
    for (std::uint32_t i = 1; i + 1 < n; ++i) {
      Triangle t;
      t.p0 = vec(v, 0);
      t.p1 = vec(v, 6 * i);
      t.p2 = vec(v, 6 * (i + 1));
      t.material = material();
      t.normals = std::int32_t(g.vertex_normals.size());
      g.vertex_normals.push_back(normals[0]);
      g.vertex_normals.push_back(normals[i]);
      g.vertex_normals.push_back(normals[i + 1]);
      g.triangles.push_back(t);
    }
  }

  /// Gives each light the SPD relative intensity, as a power (see nff.h): a white Lambertian
  /// surface at the look-at point, facing the light, reflects radiance equal to the intensity
  /// (irradiance power / (4 pi d^2) times albedo / pi).
  void finish_lights() {
    const float intensity = spd_light_intensity(scene_.lights.size());
    for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
      PointLight& l = scene_.lights[i];
      const float d = glm::length(l.position - scene_.camera.look_at);
      constexpr float kPi = std::numbers::pi_v<float>;
      l.power_w = 4.0f * kPi * kPi * std::max(d * d, 1e-6f) * intensity;
      if (!std::isfinite(l.power_w))
        fail(light_lines_[i], "'l' light is too far from the look-at point (its power overflows float)");
    }
  }

  std::vector<Token> tokens_;
  std::string name_;
  std::size_t pos_ = 0;
  Scene scene_;
  bool have_view_ = false;
  std::vector<int> light_lines_;  ///< The line of each light, for messages.
  std::optional<std::uint32_t> material_;
  std::map<std::array<double, 8>, std::uint32_t> material_ids_;
};

}  // namespace

Scene parse_nff(std::string_view text, const std::string& name_for_errors) {
  return Parser(text, name_for_errors).parse();
}

Scene load_nff(std::istream& in, const std::string& name_for_errors) {
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    if (text.size() + std::size_t(in.gcount()) > input::kMaxSceneFileBytes)
      throw SceneError(name_for_errors + ": more than " + input::byte_text(input::kMaxSceneFileBytes) +
                       " (the limit for scene files)");
    text.append(buf, std::size_t(in.gcount()));
  }
  if (in.bad()) throw SceneError(name_for_errors + ": read error");
  return parse_nff(text, name_for_errors);
}

Scene load_nff(const std::string& path) {
  try {
    return parse_nff(input::read_file(path, input::kMaxSceneFileBytes, "scene file"), path);
  } catch (const input::InputError& e) {
    throw SceneError(e.what());
  }
}

}  // namespace tracer
