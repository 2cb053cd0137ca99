#include "palpate/core/load.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

#include "core/assimp_reader.hpp"
#include "core/coin_reader.hpp"
#include "core/file_bytes.hpp"
#include "core/gifti_reader.hpp"
#include "core/mesh_writers.hpp"
#include "palpate/core/displacement.hpp"
#include "palpate/core/error.hpp"

namespace palpate {
namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool one_of(const std::string& value, std::initializer_list<std::string_view> options) {
  return std::find(options.begin(), options.end(), value) != options.end();
}

bool starts_with(const std::string& text, std::string_view prefix) {
  return text.size() >= prefix.size() && std::string_view(text).substr(0, prefix.size()) == prefix;
}

// The extension that names the format: "model.wrl.gz" -> ".wrl", "mesh.PLY" -> ".ply".
std::string format_extension(const std::filesystem::path& file) {
  std::string extension = lower(file.extension().string());
  if (extension == ".gz") extension = lower(file.stem().extension().string());
  return extension;
}

constexpr std::string_view kSupported =
    ".wrl .wrz .vrml .iv (Coin), .obj .ply .stl .off .gltf .glb .x3d (assimp), .gii (giftiio), each also "
    "gzipped";

Scene read_model(const std::filesystem::path& file, const LoadParams& options) {
  const std::string extension = format_extension(file);
  if (one_of(extension, {".nii", ".hdr", ".img", ".mgz", ".mgh", ".nrrd", ".mha", ".mhd"})) {
    if (!std::filesystem::exists(file)) throw Error(file, 0, "no such file");
    throw Error(file, 0,
                "is a volume image (" + extension +
                    "), not a surface mesh: palpate loads surfaces; extract an isosurface first");
  }
  const detail::FileBytes content = detail::read_file_bytes(file);
  const std::string& text = content.bytes;
  // X3D's classic encoding looks like VRML97 but Coin rejects its header and its X3D-only nodes,
  // and assimp has no reader for it.
  if (extension == ".x3dv" || starts_with(text, "#X3D")) {
    throw Error(file, 1,
                "X3D classic encoding (.x3dv) is not supported: Coin reads VRML97 but not X3D, and assimp "
                "has no reader for it (X3D XML, .x3d, is read through assimp)");
  }
  if (one_of(extension, {".wrl", ".wrz", ".vrml", ".iv"}) || starts_with(text, "#VRML") ||
      starts_with(text, "#Inventor")) {
    return detail::read_coin_model(text, file, options);
  }
  if (one_of(extension, {".obj", ".ply", ".stl", ".off", ".gltf", ".glb", ".x3d"})) {
    detail::AssimpInput input;
    input.file = file;
    if (content.was_gzip) {
      input.memory = &text;
      input.format_hint = extension.substr(1);
    }
    input.weld_positions = one_of(extension, {".obj", ".stl"});
    return detail::read_assimp_model(input, options);
  }
  if (extension == ".gii") return detail::read_gifti_model(text, content.was_gzip, file);
  throw Error(file, 0,
              "unknown model format '" + extension + "' and no VRML or Inventor header: palpate reads " +
                  std::string(kSupported));
}

}  // namespace

Scene load_model(const std::filesystem::path& file) {
  return load_model(file, LoadParams{});
}

Scene load_model(const std::filesystem::path& file, const LoadParams& options) {
  Scene scene = read_model(file, options);
  if (scene.triangle_count() == 0) {
    throw Error(file, 0,
                "has no triangle geometry: nothing drawn in it has faces (line and point sets and text are "
                "skipped; a PROTO that is declared but never instantiated draws nothing)");
  }
  for (SceneObject& object : scene.objects) {
    try {
      validate_mesh(object.mesh, "object '" + object.name + "'");
    } catch (const Error& e) {
      throw Error(file, 0, e.detail());
    }
    compute_displacement_directions(object.mesh);
  }
  return scene;
}

Mesh load_mesh(const std::filesystem::path& file) {
  return load_mesh(file, LoadParams{});
}

Mesh load_mesh(const std::filesystem::path& file, const LoadParams& options) {
  Scene scene = load_model(file, options);
  if (scene.objects.size() == 1) return std::move(scene.objects.front().mesh);
  Mesh merged;
  for (const SceneObject& object : scene.objects) append_mesh(merged, object.mesh, object.material.color);
  compute_displacement_directions(merged);  // shared across the parts too, where they touch
  return merged;
}

void save_mesh(const Mesh& mesh, const std::filesystem::path& file) {
  try {
    validate_mesh(mesh, "mesh");
  } catch (const Error& e) {
    throw Error(file, 0, "not written: " + e.detail());
  }
  const std::string extension = lower(file.extension().string());
  if (extension == ".ply") {
    detail::write_ply(mesh, file);
  } else if (extension == ".wrl") {
    detail::write_vrml97(mesh, file);
  } else {
    throw Error(file, 0,
                "cannot write '" + extension + "': palpate writes .wrl (VRML97) and .ply (binary PLY)");
  }
}

}  // namespace palpate
