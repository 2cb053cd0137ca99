// palpate mesh info | convert | phantom (from-volume: volume_commands.cpp)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "format.hpp"
#include "palpate/core/displacement.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/scene_file.hpp"

namespace palpate::cli {
namespace {

// Loader warnings (fields dropped, text skipped; each names its file) go to stderr.
LoadParams warn_on_stderr() {
  LoadParams options;
  options.on_warning = [](const std::string& warning) {
    std::fprintf(stderr, "palpate: warning: %s\n", warning.c_str());
  };
  return options;
}

int mesh_info(const std::vector<std::string>& files) {
  int status = 0;
  for (const std::string& file : files) {
    try {
      const auto start = std::chrono::steady_clock::now();
      const bool scene_file = std::filesystem::path(file).extension() == ".toml";
      const Scene model = scene_file ? load_scene(file) : load_model(file, warn_on_stderr());
      const double load_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      Mesh merged;
      for (const SceneObject& object : model.objects) {
        Mesh world = object.mesh;
        for (glm::vec3& p : world.positions_mm) p = glm::vec3(object.transform * glm::vec4(p, 1.0f));
        append_mesh(merged, world);
      }
      const Bounds box = bounds(merged);
      // The surface's topology, by position: shading splits (flat faces, creases) are not holes.
      const Mesh surface = weld_by_position(merged, default_weld_tolerance_mm(merged));
      const MeshTopology topo = analyze_topology(surface);
      std::printf("%s\n", file.c_str());
      std::printf("  objects     %zu\n", model.objects.size());
      std::printf("  vertices    %s (%s positions)\n", with_thousands(merged.vertex_count()).c_str(),
                  with_thousands(surface.vertex_count()).c_str());
      std::printf("  triangles   %s\n", with_thousands(merged.triangle_count()).c_str());
      std::printf("  bounds      [%.2f, %.2f, %.2f] .. [%.2f, %.2f, %.2f] (size %.2f x %.2f x %.2f)\n",
                  box.min_mm.x, box.min_mm.y, box.min_mm.z, box.max_mm.x, box.max_mm.y, box.max_mm.z,
                  box.size_mm().x, box.size_mm().y, box.size_mm().z);
      std::printf("  closed      %s (%zu boundary edges)\n", topo.closed() ? "yes" : "no",
                  topo.boundary_edges);
      std::printf("  manifold    %s (%zu non-manifold edges, %zu degenerate triangles)\n",
                  topo.manifold() ? "yes" : "no", topo.nonmanifold_edges, topo.degenerate_triangles);
      std::printf("  oriented    %s (%zu misoriented edges)\n", topo.oriented() ? "yes" : "no",
                  topo.misoriented_edges);
      std::printf("  components  %zu, Euler characteristic %ld", topo.components, topo.euler_characteristic);
      if (topo.closed() && topo.manifold() && topo.oriented()) std::printf(", genus %ld", topo.genus());
      std::printf("\n");
      std::printf("  load time   %.1f ms\n", load_ms);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "palpate: error: %s\n", e.what());
      status = 1;
    }
  }
  return status;
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  CLI::App* group = app.add_subcommand("mesh", "Inspect, convert and generate meshes");
  group->require_subcommand(1);

  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* info =
      group->add_subcommand("info", "Objects, vertices, triangles, bounds, topology and load time");
  info->add_option(
          "files", *files,
          "Model files (.wrl .wrl.gz .iv .obj .ply .stl .off .gltf .glb .gii) or scene files (.toml)")
      ->required();
  on_selected(info, [files] { return mesh_info(*files); });

  auto in = std::make_shared<std::string>(), out = std::make_shared<std::string>();
  CLI::App* convert = group->add_subcommand("convert", "Convert a model to VRML97 (.wrl) or PLY (.ply)");
  convert->add_option("input", *in, "Model file to read")->required();
  convert->add_option("output", *out, "File to write; the format follows the extension")->required();
  on_selected(convert, [in, out] {
    const Mesh mesh = load_mesh(*in, warn_on_stderr());
    save_mesh(mesh, *out);
    std::printf("wrote %s: %s vertices, %s triangles\n", out->c_str(),
                with_thousands(mesh.vertex_count()).c_str(), with_thousands(mesh.triangle_count()).c_str());
    return 0;
  });

  struct PhantomOptions {
    bool brain = false, skin = false;
    std::size_t vertices = 0;
    std::string output;
  };
  auto opts = std::make_shared<PhantomOptions>();
  CLI::App* phantom = group->add_subcommand("phantom", "Generate the brain or skin phantom (deterministic)");
  auto* brain_flag =
      phantom->add_flag("--brain", opts->brain, "Brain: gyri, deep sulci, longitudinal fissure");
  auto* skin_flag = phantom->add_flag("--skin", opts->skin, "Head-shaped skin that encloses the brain");
  brain_flag->excludes(skin_flag);
  phantom->add_option("--vertices", opts->vertices,
                      "Vertex count (default: the paper's Table I, brain 68856, skin 90207)");
  phantom->add_option("-o,--output", opts->output, "File to write (.ply or .wrl)")->required();
  on_selected(phantom, [opts] {
    if (!opts->brain && !opts->skin) throw CLI::ValidationError("mesh phantom", "give --brain or --skin");
    const std::size_t n =
        opts->vertices ? opts->vertices : (opts->brain ? brain_phantom_vertices : skin_phantom_vertices);
    const Mesh mesh = opts->brain ? make_brain_phantom(n) : make_skin_phantom(n);
    save_mesh(mesh, opts->output);
    std::printf("wrote %s: %s vertices, %s triangles\n", opts->output.c_str(),
                with_thousands(mesh.vertex_count()).c_str(), with_thousands(mesh.triangle_count()).c_str());
    return 0;
  });
  add_mesh_from_volume_command(*group);
}

}  // namespace palpate::cli
