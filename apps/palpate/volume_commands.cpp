// palpate mesh from-volume | scene from-volume: scans to surfaces and scenes.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "format.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/volume/anatomy.hpp"
#include "palpate/volume/isosurface.hpp"
#include "palpate/volume/volume.hpp"
#include "progress.hpp"

namespace palpate::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void print_stages(const std::vector<volume::StageSummary>& stages, double read_seconds) {
  std::printf("  %-14s %10s %10s %9s\n", "stage", "vertices", "triangles", "time");
  if (read_seconds >= 0.0) std::printf("  %-14s %10s %10s %7.2f s\n", "read", "", "", read_seconds);
  for (const volume::StageSummary& stage : stages) {
    const bool counted = stage.vertices || stage.triangles;
    std::printf("  %-14s %10s %10s %7.2f s\n", stage.name.c_str(),
                counted ? with_thousands(stage.vertices).c_str() : "",
                counted ? with_thousands(stage.triangles).c_str() : "", stage.seconds);
  }
}

void print_surface(const Mesh& mesh) {
  const MeshTopology topo = analyze_topology(mesh);
  const Bounds box = bounds(mesh);
  std::printf("  closed %s (%zu boundary edges), manifold %s (%zu non-manifold edges), oriented %s",
              topo.closed() ? "yes" : "no", topo.boundary_edges, topo.manifold() ? "yes" : "no",
              topo.nonmanifold_edges, topo.oriented() ? "yes" : "no");
  if (topo.closed() && topo.manifold() && topo.oriented()) std::printf(", genus %ld", topo.genus());
  std::printf(", %zu component%s\n", topo.components, topo.components == 1 ? "" : "s");
  std::printf("  bounds [%.1f, %.1f, %.1f] .. [%.1f, %.1f, %.1f] mm\n", box.min_mm.x, box.min_mm.y,
              box.min_mm.z, box.max_mm.x, box.max_mm.y, box.max_mm.z);
}

struct FromVolumeOptions {
  std::string scan, output;
  std::optional<float> iso;
  float smooth_voxels = 0.0f;
  bool largest = false, closed = false;
  std::size_t vertices = 0, triangles = 0;
};

int mesh_from_volume(const FromVolumeOptions& options) {
  const auto start = Clock::now();
  const volume::Volume scan = volume::load_volume(options.scan);
  const double read_seconds = seconds_since(start);
  const volume::IntensityRange range = volume::intensity_range(scan);
  volume::IsosurfaceParams params;
  params.iso = options.iso      ? *options.iso
               : options.closed ? volume::air_threshold(scan)
                                : volume::otsu_threshold(scan);
  params.smooth_voxels = options.smooth_voxels;
  params.largest = options.largest;
  params.closed = options.closed;
  params.vertices = options.vertices;
  params.triangles = options.triangles;
  volume::Isosurface surface;
  {
    Progress progress;
    params.on_progress = [&](std::string_view stage, double fraction) {
      progress.update("", stage, fraction);
    };
    surface = volume::extract_isosurface(scan, params);
  }
  save_mesh(surface.mesh, options.output);
  std::printf("%s: %d x %d x %d voxels, %s, intensities %g .. %g, threshold %g%s\n", options.scan.c_str(),
              scan.size.x, scan.size.y, scan.size.z, scan.frame.c_str(), range.min, range.max, params.iso,
              options.iso ? "" : " (from the histogram; --iso to choose)");
  print_stages(surface.stages, read_seconds);
  print_surface(surface.mesh);
  std::printf("  total %.2f s\nwrote %s: %s vertices, %s triangles\n", seconds_since(start),
              options.output.c_str(), with_thousands(surface.mesh.vertex_count()).c_str(),
              with_thousands(surface.mesh.triangle_count()).c_str());
  return 0;
}

struct SceneFromVolumeOptions {
  std::string head, brain, output;
  std::optional<float> skin_iso, brain_iso;
  std::size_t skin_vertices = skin_phantom_vertices, brain_vertices = brain_phantom_vertices;
};

int scene_from_volume(const SceneFromVolumeOptions& options) {
  const auto start = Clock::now();
  volume::AnatomyParams params;
  params.head_scan = options.head;
  params.brain_scan = options.brain;
  params.skin_iso = options.skin_iso;
  params.brain_iso = options.brain_iso;
  params.skin_vertices = options.skin_vertices;
  params.brain_vertices = options.brain_vertices;
  volume::Anatomy anatomy;
  {
    Progress progress;
    params.on_progress = [&](std::string_view object, std::string_view stage, double fraction) {
      progress.update(object, stage, fraction);
    };
    anatomy = volume::anatomy_from_scans(params);
  }
  save_scene(anatomy.scene, options.output);
  for (std::size_t i = 0; i < anatomy.reports.size(); ++i) {
    const volume::AnatomyObjectReport& report = anatomy.reports[i];
    std::printf("%s from %s, threshold %g%s\n", report.name.c_str(), report.scan.c_str(), report.iso,
                report.iso_from_histogram
                    ? (" (from the histogram; --iso-" + report.name + " to choose)").c_str()
                    : "");
    print_stages(report.stages, -1.0);
    print_surface(anatomy.scene.objects[i].mesh);
  }
  std::printf("total %.2f s\nwrote %s and its meshes beside it\n", seconds_since(start),
              options.output.c_str());
  return 0;
}

}  // namespace

void add_mesh_from_volume_command(CLI::App& mesh_group) {
  auto opts = std::make_shared<FromVolumeOptions>();
  CLI::App* command = mesh_group.add_subcommand(
      "from-volume", "An isosurface of a scan (NIfTI .nii/.nii.gz, NRRD .nrrd/.nhdr, MetaImage .mha/.mhd)");
  command->add_option("scan", opts->scan, "The scan")->required();
  command->add_option("--iso", opts->iso,
                      "Threshold in the scan's units (default: from the histogram, Otsu)");
  command
      ->add_option("--smooth", opts->smooth_voxels, "Gaussian smoothing first, standard deviation in voxels")
      ->check(CLI::Range(0.0f, 10.0f));
  command->add_flag("--largest", opts->largest, "Keep only the largest connected piece");
  command->add_flag("--closed", opts->closed,
                    "Close against the scan's border and fill what the outside air cannot reach");
  auto* vertices =
      command->add_option("--vertices", opts->vertices, "Decimate to this many vertices (topology kept)")
          ->check(CLI::Range(std::size_t(100), std::size_t(100'000'000)));
  auto* triangles =
      command->add_option("--triangles", opts->triangles, "Decimate to this many triangles (topology kept)")
          ->check(CLI::Range(std::size_t(100), std::size_t(100'000'000)));
  vertices->excludes(triangles);
  command->add_option("-o,--output", opts->output, "Mesh file to write (.ply or .wrl)")->required();
  on_selected(command, [opts] { return mesh_from_volume(*opts); });
}

void add_scene_command(CLI::App& app) {
  CLI::App* group = app.add_subcommand("scene", "Make scenes");
  group->require_subcommand(1);
  auto opts = std::make_shared<SceneFromVolumeOptions>();
  CLI::App* command = group->add_subcommand(
      "from-volume",
      "A skin (closed) from a head scan and a brain from a brain-extracted scan, as a scene file");
  command->add_option("head", opts->head, "Head scan (the skin)")->required();
  command->add_option("--brain", opts->brain, "Brain-extracted scan (the brain)");
  command->add_option("--iso-skin", opts->skin_iso, "Skin threshold (default: from the histogram)");
  command->add_option("--iso-brain", opts->brain_iso, "Brain threshold (default: from the histogram)");
  command->add_option("--skin-vertices", opts->skin_vertices, "Skin vertex count")->capture_default_str();
  command->add_option("--brain-vertices", opts->brain_vertices, "Brain vertex count")->capture_default_str();
  command->add_option("-o,--output", opts->output, "Scene file to write (.toml); meshes go beside it")
      ->required();
  on_selected(command, [opts] { return scene_from_volume(*opts); });
}

}  // namespace palpate::cli
