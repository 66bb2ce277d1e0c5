#include "scene_io.h"

#include "nff.h"
#include "scene_json.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace tracer {

namespace {

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneError(path + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": read error");
  return text.str();
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

Scene load_scene_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".json") {
    const std::string text = read_file(path);
    try {
      return parse_scene_json(text);
    } catch (const SceneError& e) {
      throw SceneError(path + ": " + e.what());
    }
  }
  if (ext == ".nff") return load_nff(path);  // errors read "<file>.nff:<line>: ..."
  throw SceneError(path + ": unknown scene format '" + ext + "' (expected .json or .nff)");
}

void save_scene_file(const Scene& scene, const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".json") throw SceneError(path + ": scenes are written as .json, not '" + ext + "'");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw SceneError(path + ": cannot write file");
  out << scene_to_json(scene).dump(1) << '\n';
  if (!out) throw SceneError(path + ": write error");
}

}  // namespace tracer
