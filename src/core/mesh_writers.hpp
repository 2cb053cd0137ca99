#pragma once
// The two mesh writers behind save_mesh (setup code: allocates, throws palpate::Error).
#include <filesystem>

#include "palpate/core/mesh.hpp"

namespace palpate::detail {

// Binary little-endian PLY: x y z nx ny nz as float, red green blue as uchar (when the mesh has
// colours), faces as `list uchar uint`. Written directly rather than through assimp's exporter,
// which writes colours as float r g b a properties that common tools (MeshLab, Blender) do not
// read as colours, and would need the mesh copied into an aiScene first.
void write_ply(const Mesh& mesh, const std::filesystem::path& file);

// VRML97: one Shape with an IndexedFaceSet (coordinates, per-vertex normals and colours), written
// by Coin's SoWriteAction with floats at 9 significant digits so that positions read back exactly.
void write_vrml97(const Mesh& mesh, const std::filesystem::path& file);

}  // namespace palpate::detail
