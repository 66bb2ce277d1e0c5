#include "cli/cli_util.h"
#include "tracer/scene_mesh.h"
#include "input/file_read.h"

#include "accel/accel.h"
#include "input/file_read.h"
#include "input/message.h"

#include <cctype>
#include <charconv>
#include <stdexcept>
#include <vector>

namespace cli {


void parse_image_size(const std::string& text, const std::string& flag, int& width, int& height) {
  const auto bad = [&] {
    return std::runtime_error(
        flag + ": expected WIDTHxHEIGHT with each in [1, 65536], e.g. 640x480, got '" + text + "'");
  };
  const std::size_t x = text.find('x');
  if (x == std::string::npos) throw bad();
  int w = 0, h = 0;
  const char* end = text.data() + text.size();
  const auto rw = std::from_chars(text.data(), text.data() + x, w);
  const auto rh = std::from_chars(text.data() + x + 1, end, h);
  if (x == 0 || rw.ec != std::errc() || rw.ptr != text.data() + x || rh.ec != std::errc() ||
      rh.ptr != end || w < 1 || h < 1 || w > 65536 || h > 65536)
    throw bad();
  width = w;
  height = h;
}

std::uint64_t parse_bytes(const std::string& text, const std::string& flag) {
  const auto bad = [&] {
    return std::runtime_error(flag + ": expected a byte count such as 1000000, 512M or 2G, got '" +
                              text + "'");
  };
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, value);
  if (r.ec != std::errc() || r.ptr == text.data()) throw bad();
  std::string suffix(r.ptr, end);
  for (char& c : suffix) c = char(std::toupper(static_cast<unsigned char>(c)));
  int shift = 0;
  if (suffix.empty() || suffix == "B")
    shift = 0;
  else if (suffix == "K" || suffix == "KB" || suffix == "KIB")
    shift = 10;
  else if (suffix == "M" || suffix == "MB" || suffix == "MIB")
    shift = 20;
  else if (suffix == "G" || suffix == "GB" || suffix == "GIB")
    shift = 30;
  else if (suffix == "T" || suffix == "TB" || suffix == "TIB")
    shift = 40;
  else
    throw bad();
  if (shift && value > (~std::uint64_t(0) >> shift)) throw bad();
  return value << shift;
}

std::uint64_t parse_seed(const std::string& text, const std::string& flag) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, value);
  if (text.empty() || r.ec != std::errc() || r.ptr != end)
    throw std::runtime_error(flag + ": expected an integer in [0, 18446744073709551615], got '" +
                             input::one_line(text, 40) + "'");
  return value;
}

std::uint64_t image_bytes(int width, int height) {
  // Linear RGB floats, twice (a counting pass's image beside the timed one), and 8-bit RGB for
  // the PNG.
  return std::uint64_t(width) * std::uint64_t(height) * (2 * 3 * sizeof(float) + 3);
}

void check_image_memory(int width, int height, std::uint64_t budget_bytes, const std::string& flag) {
  accel::BuildLimits limits;
  limits.max_memory_bytes = budget_bytes;
  const std::uint64_t budget = accel::memory_budget_bytes(limits);
  const std::uint64_t need = image_bytes(width, height);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (need <= budget) return;
  if (budget_bytes)  // the user's budget is what is too small
    throw std::runtime_error("--max-memory: " + input::byte_text(budget) + " cannot hold the " + size + " image (" +
                             input::byte_text(need) + " needed)");
  throw std::runtime_error(flag + ": a " + size + " image needs " + input::byte_text(need) +
                           ", over the memory budget of " + input::byte_text(budget) + " (25% of RAM; see --max-memory)");
}

nlohmann::json mesh_stats_json(const tracer::Scene& scene) {
  nlohmann::json out = nlohmann::json::array();
  for (const tracer::MeshInstance& m : scene.meshes)
    out.push_back({{"file", m.path},
                   {"file_bytes", m.stats.file_bytes},
                   {"vertices", m.stats.vertices},
                   {"triangles", m.triangle_count},
                   {"degenerate_dropped", m.stats.degenerate},
                   {"triangle_bytes", std::uint64_t(m.triangle_count) *
                                          (sizeof(tracer::Triangle) + sizeof(accel::Aabb))}});
  return out;
}

std::string describe_scene(const tracer::Scene& scene) {
  const tracer::Geometry& g = scene.geometry;
  std::vector<std::string> parts;
  auto add = [&parts](std::size_t n, const char* one, const char* many) {
    if (n) parts.push_back(std::to_string(n) + " " + (n == 1 ? one : many));
  };
  add(g.spheres.size(), "sphere", "spheres");
  add(g.triangles.size(), "triangle", "triangles");
  add(g.boxes.size(), "box", "boxes");
  add(g.cones.size(), "cone", "cones");
  add(g.polygons.size(), "polygon", "polygons");
  add(g.planes.size(), "plane", "planes");
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  if (out.empty()) out = "no primitives";
  if (!scene.meshes.empty()) {
    std::uint64_t vertices = 0, degenerate = 0;
    for (const tracer::MeshInstance& m : scene.meshes) vertices += m.stats.vertices, degenerate += m.stats.degenerate;
    out += " (" + std::to_string(scene.meshes.size()) + (scene.meshes.size() == 1 ? " mesh file: " : " mesh files: ") +
           std::to_string(vertices) + " vertices, " + std::to_string(degenerate) + " degenerate triangles dropped, " +
           input::byte_text(tracer::triangle_bytes(g)) + " of triangles)";
  }
  out += "; " + std::to_string(scene.lights.size()) +
         (scene.lights.size() == 1 ? " light, " : " lights, ") +
         std::to_string(scene.materials.size()) +
         (scene.materials.size() == 1 ? " material" : " materials");
  return out;
}

}  // namespace cli
