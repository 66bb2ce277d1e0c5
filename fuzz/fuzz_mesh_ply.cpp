// Fuzz target: the PLY loader (tracer::parse_mesh with MeshFormat::Ply: our header check, then
// assimp), ASCII and binary, faces and triangle strips.
// Properties: as fuzz_mesh_obj: one-line refusals "fuzz.ply: ...", and a loaded mesh is sound.

#include "fuzz_mesh_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::check_mesh(data, size, tracer::MeshFormat::Ply, "fuzz.ply");
  return 0;
}
