#include "scene_io.h"

#include "nff.h"
#include "scene_json.h"

#include "input/file_read.h"

#include <cctype>
#include <filesystem>
#include <fstream>

namespace tracer {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// The file's text, refused before reading when it is not a regular file or is too large.
std::string read_scene_text(const std::string& path) {
  try {
    return input::read_file(path, input::kMaxSceneFileBytes, "scene file");
  } catch (const input::InputError& e) {
    throw SceneError(e.what());
  }
}

std::string folder_of(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

}  // namespace

Scene load_scene_file(const std::string& path, std::uint64_t max_memory_bytes) {
  const std::string ext = lower_extension(path);
  if (ext == ".json") {
    const std::string text = read_scene_text(path);
    try {
      return parse_scene_json(text, {folder_of(path), max_memory_bytes});
    } catch (const SceneError& e) {
      throw SceneError(path + ": " + e.what());
    }
  }
  if (ext == ".nff") return parse_nff(read_scene_text(path), path);  // errors read "<path>:<line>: ..."
  throw SceneError(path + ": unknown scene format '" + ext + "' (expected .json or .nff)");
}

void save_scene_file(const Scene& scene, const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".json") throw SceneError(path + ": scenes are written as .json, not '" + ext + "'");
  // The text is read back before it is written: a scene the loader would refuse is never saved
  // (a conversion that loses a rule of the scene model fails here, naming what is wrong).
  nlohmann::json doc = scene_to_json(scene);
  // Mesh files are referred to relative to the saved scene's folder, so the two move together.
  if (doc.contains("meshes")) {
    // A bare file name's folder is "", which std::filesystem::absolute refuses: that is ".".
    const std::string dir = folder_of(path);
    const std::filesystem::path folder = std::filesystem::absolute(dir.empty() ? "." : dir);
    for (nlohmann::json& m : doc["meshes"]) {
      const std::filesystem::path file = std::filesystem::absolute(m["file"].get<std::string>());
      m["file"] = file.lexically_relative(folder).string();
    }
  }
  const std::string text = doc.dump(1) + '\n';
  try {
    parse_scene_json(text, {folder_of(path), 0});
  } catch (const SceneError& e) {
    throw SceneError(path + ": not written: the scene would not load back: " + e.what());
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw SceneError(path + ": cannot write file");
  out << text;
  if (!out.flush()) throw SceneError(path + ": write error");
}

}  // namespace tracer
