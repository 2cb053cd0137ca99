#pragma once
// Reading and writing model files. Setup code: allocates, throws palpate::Error naming the file
// (and the line where the parser knows it) for a missing, empty, truncated or malformed file, bad
// indices, NaN or Inf coordinates, or a file with no triangle geometry.
//
// Readers, chosen by the file name's extension (a trailing .gz is looked through; gzip content is
// recognised by its magic bytes whatever the name):
//   VRML97 / VRML 2.0 (.wrl, .wrz, .vrml), VRML 1.0 and Open Inventor (.iv) through Coin3D;
//   OBJ, PLY, STL, OFF, glTF (.gltf/.glb) and X3D XML (.x3d, .x3d.gz) through assimp;
//   GIfTI surfaces (.gii, .gii.gz) through giftiio.
// A file with another extension is read through Coin when it starts with a VRML or Inventor header.
// NIfTI volumes and X3D's classic encoding (.x3dv) are rejected with a message saying so.
// Writers: VRML97 (.wrl) and PLY (.ply).
//
// Vertices: each shape's triangles are welded into one vertex per distinct position, normal and
// colour (VRML, Inventor), so a closed surface stays closed except along creases and colour seams;
// for OBJ and STL, whose importer splits positions, one vertex per distinct position. Where vertices
// still share a position, Mesh::directions gives them one direction to move along under a dent
// (compute_displacement_directions), so the surface does not crack.
//
// Threads: loading and saving may be called from several threads. Coin3D and giftiio keep global
// state, so their part of the work runs under one process-wide lock each; while palpate holds the
// Coin lock it also routes Coin's error handlers to itself (restoring them afterwards), so a host
// application that uses Coin on other threads at the same time must not rely on its own handlers then.
#include <filesystem>
#include <functional>
#include <string>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate {

struct LoadParams {
  // Coin rejects a VRML or Inventor file that has a field its node type does not define, as some
  // exporters write (e.g. `mirror` in Material). When true, such a file is read again with those
  // fields removed (by name, in nodes of the type Coin named) and each dropped field is reported
  // through on_warning. When false the first unknown field is an error.
  bool drop_unknown_fields = true;
  // Receives what the load noticed but did not fail on: dropped fields, skipped text and line or
  // point sets, Coin's warnings. May be empty (then warnings are discarded, never printed).
  std::function<void(const std::string&)> on_warning;
};

// Every drawn shape of the file as one object, its transform hierarchy baked into the positions
// (object transform = identity), its material colour in material.color, vertex colours where given.
// Text is not geometry here: Text / AsciiText / Text2 / Text3 are skipped (with a warning), as are
// line and point sets; Collision proxies are not drawn.
Scene load_model(const std::filesystem::path& file);
Scene load_model(const std::filesystem::path& file, const LoadParams& options);

// All shapes of the file merged into one mesh (vertex colours kept where any shape has them: the
// shapes without get their material colour).
Mesh load_mesh(const std::filesystem::path& file);
Mesh load_mesh(const std::filesystem::path& file, const LoadParams& options);

// Writes by extension: .wrl (VRML97, through Coin) or .ply (binary little-endian PLY with normals
// and 8-bit colours). Throws palpate::Error for another extension, an invalid mesh or a write error.
void save_mesh(const Mesh& mesh, const std::filesystem::path& file);

}  // namespace palpate
