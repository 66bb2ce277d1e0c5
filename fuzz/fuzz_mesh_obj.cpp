// Fuzz target: the OBJ loader (tracer::parse_mesh with MeshFormat::Obj, as scene "meshes" entries
// and `convert MODEL.obj` read models through tinyobjloader).
// Properties: a refusal is a SceneError "fuzz.obj: ..." of one short line; a mesh that loads has
// only finite vertices, indices in range and triangles of non-zero area.

#include "fuzz_mesh_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::check_mesh(data, size, tracer::MeshFormat::Obj, "fuzz.obj");
  return 0;
}
