// palpate bench render: frames per second of the deforming render against the plain render and the
// CPU-naive baseline, on the paper's Table I meshes and on 1M and 10M vertices, headless.
//
// The variants of one mesh run interleaved, in short slices round after round, so that a noisy machine
// slows them alike; each frame ends with glFinish, so a frame's time is the time until its pixels are
// there. GPU time comes from timer queries, except on software rasterizers, whose queries do not time
// the rasterizer threads (gpu_ms is null there), and in the toolkits' rows (--toolkits: VTK and Coin3D
// drawing the Table I meshes plainly and with palpate's shaders, each against its own plain drawing).
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_toolkits.hpp"
#include "commands.hpp"
#include "format.hpp"
#include "interleaved.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/png.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/stereo_compositor.hpp"

namespace palpate::cli {
namespace {

struct BenchOptions {
  bool quick = false;
  double seconds = 0.0;  // per variant and mesh; 0: 2 s with --quick, else 3 s
  int width = 1280, height = 1024;
  std::string json;
  std::string frames;     // folder for one PNG of each deformed mesh
  bool toolkits = false;  // also VTK and Coin3D drawing the meshes, plain and deformed
};

struct Variant {
  const char* name;
  gl::Deformation deformation;
  bool skip_unreached;
  gl::StereoMode stereo = gl::StereoMode::mono;  // not mono: both eyes drawn and combined
};

constexpr Variant variants[] = {
    {"deform", gl::Deformation::gpu, true},
    {"plain", gl::Deformation::none, true},
    {"cpu-naive", gl::Deformation::cpu_naive, true},
    // The shaders' own cost, as an application that runs the GLSL snippet over a whole mesh pays it.
    {"deform-unculled", gl::Deformation::gpu, false},
    // Stereo: each eye at half the frame, combined side by side; each eye whole, combined red-cyan.
    {"deform-stereo-side-by-side", gl::Deformation::gpu, true, gl::StereoMode::side_by_side},
    {"deform-stereo-anaglyph", gl::Deformation::gpu, true, gl::StereoMode::anaglyph},
};

SceneObject object(std::string name, Mesh mesh, float sigma_mm, glm::vec3 color) {
  SceneObject o;
  o.name = std::move(name);
  o.mesh = std::move(mesh);
  o.material.sigma_mm = sigma_mm;
  o.material.color = color;
  return o;
}

// The paper's Table I models: the default scene's phantoms with their materials. Drawn skin first, as
// it hides the brain.
SceneObject phantom(const std::string& name) {
  for (SceneObject& o : phantom_scene().objects) {
    if (o.name == name) return std::move(o);
  }
  throw Error("bench render: the default scene has no '" + name + "'");
}

struct BenchMesh {
  std::string name;
  std::function<Scene()> make;
};

std::vector<BenchMesh> bench_meshes(bool quick) {
  std::vector<BenchMesh> meshes{
      {"brain", [] { return Scene{{phantom("brain")}}; }},
      {"skin", [] { return Scene{{phantom("skin")}}; }},
      {"both",
       [] {
         return Scene{{phantom("skin"), phantom("brain")}};
       }},
  };
  if (!quick) {
    meshes.push_back(
        {"1M", [] {
           return Scene{{object("sphere 1M", make_sphere(100.0f, 1'000'000), 8.0f, {0.8f, 0.7f, 0.65f})}};
         }});
    meshes.push_back(
        {"10M", [] {
           return Scene{{object("sphere 10M", make_sphere(100.0f, 10'000'000), 8.0f, {0.8f, 0.7f, 0.65f})}};
         }});
  }
  return meshes;
}

struct Camera {
  glm::mat4 view, projection;
  glm::vec3 eye;
  float near_mm, far_mm;
  float fov_y_rad, distance_mm;  // to the scene's centre
};

// The whole scene in view, seen from behind (-y; the face looks along +y) and a little above.
Camera frame_scene(const Scene& scene, int width, int height) {
  const glm::vec3 center = world_bounds(scene).center_mm();
  float radius = 0.0f;
  for (const SceneObject& o : scene.objects) {
    for (const glm::vec3& p : o.mesh.positions_mm) {
      radius = std::max(radius, glm::distance(center, glm::vec3(o.transform * glm::vec4(p, 1.0f))));
    }
  }
  const float fov = glm::radians(40.0f);
  const float distance = radius / std::sin(0.5f * fov) * 1.05f;
  const glm::vec3 eye = center + distance * glm::normalize(glm::vec3(0.15f, -1.0f, 0.35f));
  return {glm::lookAt(eye, center, glm::vec3(0, 0, 1)),
          glm::perspective(fov, float(width) / float(height), 0.05f * distance, 4.0f * distance),
          eye,
          0.05f * distance,
          4.0f * distance,
          fov,
          distance};
}

// A dent on the visible surface: the vertex of the first (outermost) object that reaches furthest
// toward a point slightly off the camera axis; depth 4 mm, with the touched object's sigma.
Contact visible_contact(const Scene& scene, const Camera& camera) {
  const SceneObject& touched = scene.objects.front();
  const glm::vec3 center = world_bounds(scene).center_mm();
  const glm::vec3 toward =
      glm::normalize(camera.eye - center + glm::vec3(0.1f, 0.0f, 0.12f) * glm::length(camera.eye - center));
  std::size_t best = 0;
  float best_reach = -1e30f;
  for (std::size_t i = 0; i < touched.mesh.vertex_count(); ++i) {
    const float reach = glm::dot(
        glm::vec3(touched.transform * glm::vec4(touched.mesh.positions_mm[i], 1.0f)) - center, toward);
    if (reach > best_reach) best_reach = reach, best = i;
  }
  Contact contact;
  contact.object = 0;
  contact.point_mm = glm::vec3(touched.transform * glm::vec4(touched.mesh.positions_mm[best], 1.0f));
  contact.normal = glm::normalize(glm::mat3(touched.transform) * touched.mesh.normals[best]);
  contact.depth_mm = 4.0f;
  contact.hip_mm = contact.point_mm - contact.normal * contact.depth_mm;
  return contact;
}

bool timer_queries_trustworthy(const std::string& renderer) {
  for (const char* software : {"llvmpipe", "softpipe", "lavapipe", "SwiftShader", "Software Rasterizer"}) {
    if (renderer.find(software) != std::string::npos) return false;
  }
  return true;
}

struct Row {
  std::string mesh;
  std::size_t vertices = 0, triangles = 0;
  std::string toolkit;  // who draws: palpate's renderer, or VTK or Coin3D with palpate's shaders
  std::string variant;
  double fps = 0.0, cpu_ms = 0.0;
  std::optional<double> gpu_ms;
  int frames = 0;
};

int bench_render(const BenchOptions& options) {
  const double seconds = options.seconds > 0.0 ? options.seconds : (options.quick ? 2.0 : 3.0);
  constexpr int rounds = 6;
  gl::HeadlessContext context;
  const std::string device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const bool timed = timer_queries_trustworthy(device);
  const gl::Framebuffer target({options.width, options.height});
  gl::StereoCompositor compositor;
  GLuint query = 0;
  glGenQueries(1, &query);
  std::printf("palpate bench render: %s (%s), %dx%d, %.1f s per variant in %d interleaved rounds\n",
              device.c_str(), context.platform().c_str(), options.width, options.height, seconds, rounds);
  if (!timed) std::printf("  GPU timer queries do not time a software rasterizer: gpu_ms is null\n");
  if (!options.frames.empty()) std::filesystem::create_directories(options.frames);

  std::vector<Row> rows;
  for (const BenchMesh& bench_mesh : bench_meshes(options.quick)) {
    std::printf("  %s: building...", bench_mesh.name.c_str());
    std::fflush(stdout);
    std::optional<gl::Renderer> renderer;
    std::size_t vertices = 0, triangles = 0;
    Camera camera;
    Contact contact;
    {
      const Scene scene = bench_mesh.make();
      vertices = scene.vertex_count();
      triangles = scene.triangle_count();
      camera = frame_scene(scene, options.width, options.height);
      contact = visible_contact(scene, camera);
      renderer.emplace();
      renderer->upload(scene);
    }
    std::printf(" %s vertices, %s triangles\n", with_thousands(vertices).c_str(),
                with_thousands(triangles).c_str());

    StereoCamera eyes;
    eyes.convergence_mm = camera.distance_mm;  // zero parallax at the scene's centre
    const auto frame = [&](const Variant& variant) {
      gl::DrawParams draw;
      draw.deformation = variant.deformation;
      draw.skip_unreached = variant.skip_unreached;
      target.bind();
      const auto draw_with = [&](const glm::mat4& view, const glm::mat4& projection) {
        glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        renderer->draw(view, projection, {&contact, 1}, draw);
      };
      if (variant.stereo == gl::StereoMode::mono) {
        draw_with(camera.view, camera.projection);
        return;
      }
      compositor.render(variant.stereo, gl::Mirror::none, options.width, options.height,
                        [&](const gl::EyeTarget& eye_target) {
                          const EyeView eye =
                              eyes.eye(eye_target.eye, {camera.view, camera.fov_y_rad, eye_target.aspect,
                                                        camera.near_mm, camera.far_mm});
                          draw_with(eye.view, eye.projection);
                        });
    };
    for (const Variant& variant : variants) {  // warm-up: shader compilation, CPU-naive buffers
      frame(variant);
      glFinish();
    }
    if (!options.frames.empty()) {
      frame(variants[0]);
      const auto file = std::filesystem::path(options.frames) / ("deform-" + bench_mesh.name + ".png");
      gl::save_png(file, options.width, options.height, target.read_rgba8());
    }

    std::vector<double> gpu_ns(std::size(variants), 0.0);
    std::vector<std::function<void()>> frames;
    for (std::size_t v = 0; v < std::size(variants); ++v) {
      frames.push_back([&, v] {
        if (timed) glBeginQuery(GL_TIME_ELAPSED, query);
        frame(variants[v]);
        if (timed) glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        if (timed) {
          GLuint64 ns = 0;
          glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
          gpu_ns[v] += double(ns);
        }
      });
    }
    const std::vector<Tally> tallies = measure_interleaved(frames, seconds, rounds);
    for (std::size_t v = 0; v < std::size(variants); ++v) {
      const Tally& tally = tallies[v];
      Row row{bench_mesh.name,
              vertices,
              triangles,
              "palpate",
              variants[v].name,
              tally.frames / tally.wall_s,
              1000.0 * tally.cpu_s / tally.frames,
              std::nullopt,
              tally.frames};
      if (timed) row.gpu_ms = 1e-6 * gpu_ns[v] / tally.frames;
      rows.push_back(row);
    }
    if (options.toolkits) {
      const Scene scene = bench_mesh.make();
      ToolkitView view{camera.eye,          world_bounds(scene).center_mm(),
                       glm::radians(40.0f), camera.near_mm,
                       camera.far_mm,       options.width,
                       options.height};
      context.release();
      for (const ToolkitTally& t : bench_toolkits(scene, view, contact, seconds, rounds)) {
        rows.push_back({bench_mesh.name, vertices, triangles, t.toolkit, t.variant,
                        t.tally.frames / t.tally.wall_s, 1000.0 * t.tally.cpu_s / t.tally.frames,
                        std::nullopt, t.tally.frames});
      }
      context.make_current();
    }
  }
  glDeleteQueries(1, &query);

  std::printf("\n%-6s %11s %11s  %-8s %-26s %9s %9s %9s %7s  %s\n", "mesh", "vertices", "triangles",
              "toolkit", "variant", "fps", "gpu ms", "cpu ms", "frames", "vs plain");
  for (const Row& row : rows) {
    const auto plain = std::find_if(rows.begin(), rows.end(), [&](const Row& r) {
      return r.mesh == row.mesh && r.toolkit == row.toolkit && r.variant == std::string("plain");
    });
    char gpu[16] = "null";
    if (row.gpu_ms) std::snprintf(gpu, sizeof gpu, "%.3f", *row.gpu_ms);
    std::printf("%-6s %11s %11s  %-8s %-26s %9.1f %9s %9.2f %7d  %+.1f%%\n", row.mesh.c_str(),
                with_thousands(row.vertices).c_str(), with_thousands(row.triangles).c_str(),
                row.toolkit.c_str(), row.variant.c_str(), row.fps, gpu, row.cpu_ms, row.frames,
                100.0 * (plain->fps / row.fps - 1.0));
  }
  std::printf("(vs plain: extra time per frame; cpu ms: process CPU time per frame, all threads)\n");

  if (!options.json.empty()) {
    nlohmann::json out;
    out["device"] = device;
    out["platform"] = context.platform();
    out["width"] = options.width;
    out["height"] = options.height;
    out["seconds_per_variant"] = seconds;
    out["rows"] = nlohmann::json::array();
    for (const Row& row : rows) {
      out["rows"].push_back({{"mesh", row.mesh},
                             {"vertices", row.vertices},
                             {"triangles", row.triangles},
                             {"toolkit", row.toolkit},
                             {"variant", row.variant},
                             {"fps", row.fps},
                             {"gpu_ms", row.gpu_ms ? nlohmann::json(*row.gpu_ms) : nlohmann::json(nullptr)},
                             {"cpu_ms", row.cpu_ms},
                             {"frames", row.frames}});
    }
    write_json_file(options.json, out);
  }
  return 0;
}

}  // namespace

void add_bench_render_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* render = add_bench_command(app).add_subcommand(
      "render",
      "Deforming render vs plain vs CPU-naive, headless, on the Table I meshes and 1M/10M vertices");
  render->add_flag("--quick", options->quick, "Table I meshes only, 2 s per variant");
  render
      ->add_option("--seconds", options->seconds,
                   "Seconds per variant and mesh (default 2 with --quick, else 3)")
      ->check(CLI::PositiveNumber);
  render->add_option("--width", options->width, "Framebuffer width")->check(CLI::Range(16, 16384));
  render->add_option("--height", options->height, "Framebuffer height")->check(CLI::Range(16, 16384));
  render->add_option("--json", options->json, "Write the results as JSON to this file");
  render->add_flag("--toolkits", options->toolkits,
                   "Also VTK and Coin3D drawing each Table I mesh, plain and with palpate's shaders "
                   "(VTK needs an X display: xvfb-run -a palpate bench render --toolkits)");
  render->add_option("--frames", options->frames,
                     "Save one deformed frame of each mesh as PNG into this folder");
  on_selected(render, [options] { return bench_render(*options); });
}

}  // namespace palpate::cli
