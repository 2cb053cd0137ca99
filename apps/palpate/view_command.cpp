// palpate view: an interactive window. The mouse drives a virtual 3-DOF device (the tip moves under the
// cursor in the view plane, its depth by Shift+wheel or W/S), the haptic loop runs on it at 1 kHz, and
// the scene is drawn deformed, with the force as an arrow and a panel of materials, lights and live
// rates. Written on Dear ImGui's GLFW and OpenGL3 backends.
#include <epoxy/gl.h>
// GLFW after epoxy: it must not pull in GL/gl.h first.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <glm/geometric.hpp>
#include <memory>

#include "commands.hpp"
#include "demo_phases.hpp"
#include "gl_session.hpp"
#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/pick.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/gl/png.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/haptics/haptic_loop.hpp"
#include "palpate/haptics/virtual_device.hpp"
#include "stereo_options.hpp"

namespace palpate::cli {
namespace {

struct ViewOptions {
  SceneChoice scene;
  int width = 1280, height = 1024;
  int frames = -1;              // quit after this many frames (for scripted runs)
  std::string screenshot;       // write the last frame here before quitting
  float press_depth_mm = 0.0f;  // start with the tip this deep under the window's centre
  StereoChoice stereo;
};

// Hands the panel's edited materials to the haptic loop (stiffness, damping, touchability: from its next
// tick) and the renderer (sigma, colour, visibility, falloff: from the next frame), for the objects that
// changed.
void apply_materials(const std::vector<Material>& edited, std::vector<Material>& applied, HapticLoop& loop,
                     gl::Renderer& renderer) {
  for (std::size_t i = 0; i < edited.size(); ++i) {
    const Material& now = applied[i];
    const Material& next = edited[i];
    if (now.touchable != next.touchable || now.stiffness_n_per_mm != next.stiffness_n_per_mm ||
        now.damping_ns_per_m != next.damping_ns_per_m) {
      loop.set_material(i, next);
    }
    if (now.sigma_mm != next.sigma_mm || now.visible != next.visible || now.color != next.color ||
        now.falloff != next.falloff) {
      renderer.set_material(i, next);
    }
    applied[i] = next;
  }
}

bool save_screenshot(const std::string& file, int width, int height) {
  std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  for (std::size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 255;
  try {
    gl::save_png(file, width, height, pixels);
    std::printf("palpate view: screenshot %s\n", file.c_str());
    return true;
  } catch (const Error& e) {
    std::fprintf(stderr, "palpate view: %s\n", e.what());
    return false;
  }
}

// A world point to window pixels (top-left origin); false when behind the camera.
bool to_screen(const glm::mat4& view_projection, glm::vec3 p, glm::vec2 size, ImVec2& out) {
  const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
  if (clip.w <= 0.0f) return false;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  out = ImVec2((ndc.x * 0.5f + 0.5f) * size.x, (0.5f - ndc.y * 0.5f) * size.y);
  return true;
}

void draw_force_arrow(const glm::mat4& view_projection, glm::vec2 size, glm::vec3 hip, glm::vec3 force_n,
                      float depth_mm, float mm_per_newton) {
  const float magnitude = glm::length(force_n);
  if (magnitude < 1e-3f) return;
  ImVec2 from, to;
  if (!to_screen(view_projection, hip, size, from) ||
      !to_screen(view_projection, hip + force_n * mm_per_newton, size, to))
    return;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImU32 color = IM_COL32(255, 210, 60, 255);
  draw->AddLine(from, to, color, 3.0f);
  const glm::vec2 direction = glm::normalize(glm::vec2(to.x - from.x, to.y - from.y) + glm::vec2(1e-6f));
  const glm::vec2 side{-direction.y, direction.x};
  const glm::vec2 tip{to.x, to.y};
  const glm::vec2 a = tip - direction * 14.0f + side * 7.0f, b = tip - direction * 14.0f - side * 7.0f;
  draw->AddTriangleFilled(to, ImVec2(a.x, a.y), ImVec2(b.x, b.y), color);
  char label[64];
  std::snprintf(label, sizeof label, "%.2f N  p = %.2f mm", magnitude, depth_mm);
  draw->AddText(ImVec2(to.x + 8.0f, to.y - 8.0f), color, label);
}

// Moves the tip under the cursor in the plane through it that faces the camera.
glm::vec3 tip_under_cursor(const OrbitCamera& camera, glm::vec2 cursor, glm::vec2 size, glm::vec3 tip) {
  const OrbitCamera::Ray ray = camera.ray_through(cursor, size);
  const glm::vec3 facing = glm::normalize(camera.target_mm - camera.eye());
  const float along = glm::dot(ray.direction, facing);
  if (std::abs(along) < 1e-4f) return tip;
  return ray.origin_mm + ray.direction * (glm::dot(tip - ray.origin_mm, facing) / along);
}

struct Panel {
  float scale = 1.0f;                      // scene_scale: the probe's sizes follow the scene's
  int deformation = 0;                     // gl::Deformation: gpu, cpu_naive, none
  int stereo = 0;                          // gl::StereoMode
  int mirror = 0;                          // gl::Mirror
  bool quad_buffers = false;               // the window has them: offer quad_buffer
  bool convergence_follows_camera = true;  // zero parallax at what the camera looks at
  StereoCamera eyes;
};

// The control panel. Materials are edited in `materials`, and handed on by apply_materials.
void draw_panel(const Scene& scene, std::vector<Material>& materials, gl::DrawParams& draw, Panel& panel,
                const LoopStatistics& stats, const TickResult& tick, bool& reset_tip, bool& screenshot) {
  const Contact& contact = tick.contact;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("palpate");
  ImGui::TextWrapped(
      "Left drag: move the tip. Shift+wheel or W/S: tip depth. Right drag: orbit. Wheel: zoom. "
      "R: reset tip. P: screenshot. Esc: quit. Arrows, PgUp/PgDn: move the head (stereo).");
  if (ImGui::CollapsingHeader("Rates", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Text("graphics %.1f fps (%.2f ms)", ImGui::GetIO().Framerate, 1000.0f / ImGui::GetIO().Framerate);
    ImGui::Text("haptics %.1f Hz, %llu missed, tick p99 %.1f us", stats.achieved_hz,
                static_cast<unsigned long long>(stats.missed_deadlines), stats.tick_us.p99);
    ImGui::Text("period error p50 %.1f  p99 %.1f  p99.9 %.1f us", stats.period_error_us.p50,
                stats.period_error_us.p99, stats.period_error_us.p999);
    float bins[LoopStatistics::histogram_bins];
    for (std::size_t i = 0; i < LoopStatistics::histogram_bins; ++i)
      bins[i] = float(stats.period_histogram[i]);
    ImGui::PlotHistogram("##period", bins, int(LoopStatistics::histogram_bins), 0,
                         "haptic period 0.5 .. 1.5 T", 0.0f, FLT_MAX, ImVec2(0, 70));
  }
  if (ImGui::CollapsingHeader("Contact", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (contact.in_contact()) {
      ImGui::Text("on %s, p = %.2f mm, |F| = %.2f N", scene.objects[std::size_t(contact.object)].name.c_str(),
                  contact.depth_mm, glm::length(tick.force_n));
    } else {
      ImGui::TextUnformatted("free");
    }
    ImGui::Text("tip %.1f %.1f %.1f mm", contact.hip_mm.x, contact.hip_mm.y, contact.hip_mm.z);
    reset_tip = ImGui::Button("Reset tip");
    ImGui::SameLine();
    screenshot = ImGui::Button("Screenshot");
  }
  if (ImGui::CollapsingHeader("Rendering", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Combo("deformation", &panel.deformation, "GPU (the paper)\0CPU-naive\0none\0");
    ImGui::Checkbox("probe", &draw.draw_probe);
    ImGui::SameLine();
    ImGui::Checkbox("contact point", &draw.draw_contact_points);
    ImGui::SliderFloat("probe radius mm", &draw.probe_radius_mm, 0.2f * panel.scale, 5.0f * panel.scale);
  }
  if (ImGui::CollapsingHeader("Stereo")) {
    ImGui::Combo("output", &panel.stereo,
                 panel.quad_buffers
                     ? "mono\0side by side\0top and bottom\0anaglyph (red-cyan)\0quad buffers\0"
                     : "mono\0side by side\0top and bottom\0anaglyph (red-cyan)\0");
    ImGui::Combo("mirror", &panel.mirror, "none\0left-right\0upside down\0");
    ImGui::SliderFloat("eye separation mm", &panel.eyes.eye_separation_mm, 0.0f, 100.0f);
    ImGui::Checkbox("zero parallax at the target", &panel.convergence_follows_camera);
    if (!panel.convergence_follows_camera) {
      ImGui::SliderFloat("convergence mm", &panel.eyes.convergence_mm, 10.0f * panel.scale,
                         2000.0f * panel.scale);
    }
    ImGui::Text("head %.0f %.0f %.0f mm", panel.eyes.head_mm.x, panel.eyes.head_mm.y, panel.eyes.head_mm.z);
    ImGui::SameLine();
    if (ImGui::Button("Reset head")) panel.eyes.head_mm = glm::vec3(0.0f);
  }
  if (ImGui::CollapsingHeader("Objects", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      Material& material = materials[i];
      ImGui::PushID(int(i));
      ImGui::Text("%s", scene.objects[i].name.c_str());
      ImGui::Checkbox("visible", &material.visible);
      ImGui::SameLine();
      ImGui::Checkbox("touchable", &material.touchable);
      ImGui::SliderFloat("sigma mm", &material.sigma_mm, 0.5f, 40.0f);
      int falloff = material.falloff == Falloff::geodesic ? 1 : 0;
      if (ImGui::Combo("falloff", &falloff, "straight line (the paper)\0along the surface\0")) {
        material.falloff = falloff == 1 ? Falloff::geodesic : Falloff::euclidean;
      }
      ImGui::SliderFloat("k N/mm", &material.stiffness_n_per_mm, 0.02f, 2.0f);
      ImGui::SliderFloat("b N s/m", &material.damping_ns_per_m, 0.0f, 5.0f);
      ImGui::ColorEdit3("colour", &material.color.x);
      ImGui::PopID();
    }
  }
  if (ImGui::CollapsingHeader("Lights")) {
    gl::Lighting& light = draw.lighting;
    if (ImGui::SliderFloat3("directional", &light.direction.x, -1.0f, 1.0f) &&
        glm::length(light.direction) > 1e-3f) {
      light.direction = glm::normalize(light.direction);
    }
    ImGui::ColorEdit3("directional colour", &light.color.x);
    ImGui::SliderFloat("spot inner deg", &light.spot_inner_deg, 1.0f, 60.0f);
    ImGui::SliderFloat("spot outer deg", &light.spot_outer_deg, light.spot_inner_deg, 80.0f);
    ImGui::ColorEdit3("spot colour", &light.spot_color.x);
    ImGui::ColorEdit3("ambient", &light.ambient.x);
    ImGui::SliderFloat("specular", &light.specular, 0.0f, 1.0f);
  }
  ImGui::End();
}

int run_view(const ViewOptions& options) {
  Scene scene = scene_for_option(options.scene);
  const bool quad_buffers_wanted = stereo_mode(options.stereo) == gl::StereoMode::quad_buffer;
  GlSession session = open_gl(false, options.width, options.height, "palpate view", quad_buffers_wanted);
  if (!session.window)
    throw Error("palpate view needs a display ($DISPLAY): run it under X or Xvfb, or use `palpate demo`");
  gl::Window& window = *session.window;
  auto* native = static_cast<GLFWwindow*>(window.native_handle());

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui_ImplGlfw_InitForOpenGL(native, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");

  OrbitCamera camera = demo_camera(world_bounds(scene));
  const float scale = scene_scale(scene);
  const glm::vec2 initial_size{float(window.framebuffer_width()), float(window.framebuffer_height())};
  // The tip starts 10 mm in front of the surface under the window's centre; with --press-depth it then
  // moves that deep into it (approaching from outside, as a hand would).
  // Over every object, so that the panel can make any of them touchable while the loop runs.
  const Bvh bvh = Bvh::build(scene, {});
  glm::vec3 start_tip = camera.target_mm, tip = camera.target_mm;
  std::vector<std::uint8_t> touchable;
  for (const SceneObject& object : scene.objects) touchable.push_back(object.material.touchable);
  const BvhHit hit = pick(bvh, camera, initial_size * 0.5f, initial_size, touchable);
  if (hit.hit()) {
    const glm::vec3 along = camera.ray_through(initial_size * 0.5f, initial_size).direction;
    start_tip = hit.point_mm - along * 10.0f * scale;
    tip = options.press_depth_mm > 0.0f ? hit.point_mm + along * options.press_depth_mm : start_tip;
  }
  VirtualDevice device(start_tip);
  device.set_target(tip);
  HapticLoopParams loop_params;
  loop_params.on_log = [](const std::string& line) {
    std::fprintf(stderr, "palpate view: %s\n", line.c_str());
  };
  HapticLoop loop(device, scene, bvh, loop_params);
  loop.start();
  std::vector<Material> applied, edited;
  for (const SceneObject& object : scene.objects) applied.push_back(object.material);
  edited = applied;

  gl::Renderer renderer;
  renderer.upload(scene);
  gl::DrawParams draw;
  draw.probe_radius_mm *= scale;
  Panel panel;
  panel.scale = scale;
  panel.quad_buffers = session.stereo_buffers;
  panel.stereo = int(stereo_mode(options.stereo));
  if (quad_buffers_wanted && !session.stereo_buffers) {
    std::fprintf(stderr, "palpate view: showing side-by-side instead of quad-buffered stereo\n");
    panel.stereo = int(gl::StereoMode::side_by_side);
  }
  panel.mirror = int(mirror(options.stereo));
  panel.eyes = stereo_camera(options.stereo, camera);
  panel.convergence_follows_camera = options.stereo.convergence_mm <= 0.0f;
  gl::StereoCompositor compositor;
  bool orbiting = false, dragging_tip = false;
  glm::dvec2 last_cursor{0.0};
  int frame = 0;

  while (!window.should_close()) {
    gl::Window::poll_events();
    const int width = window.framebuffer_width(), height = window.framebuffer_height();
    const glm::vec2 size{float(std::max(width, 1)), float(std::max(height, 1))};
    ImGuiIO& io = ImGui::GetIO();

    // Mouse and keys, where ImGui does not want them.
    glm::dvec2 cursor;
    glfwGetCursorPos(native, &cursor.x, &cursor.y);
    int window_width = 1, window_height = 1;
    glfwGetWindowSize(native, &window_width, &window_height);
    const glm::vec2 pixel =
        glm::vec2(cursor) * size / glm::vec2(std::max(window_width, 1), std::max(window_height, 1));
    if (!io.WantCaptureMouse) {
      const bool left = glfwGetMouseButton(native, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
      const bool right = glfwGetMouseButton(native, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
      if (right && orbiting)
        camera.orbit(float(last_cursor.x - cursor.x) * 0.008f, float(cursor.y - last_cursor.y) * 0.008f);
      orbiting = right;
      dragging_tip = left;
      if (dragging_tip) tip = tip_under_cursor(camera, pixel, size, tip);
      if (io.MouseWheel != 0.0f) {
        if (io.KeyShift) {
          tip += glm::normalize(camera.target_mm - camera.eye()) * io.MouseWheel * scale;
        } else {
          camera.zoom(std::pow(0.9f, io.MouseWheel));
        }
      }
    }
    last_cursor = cursor;
    bool reset_tip = false, screenshot = false;
    if (!io.WantCaptureKeyboard) {
      const glm::vec3 facing = glm::normalize(camera.target_mm - camera.eye());
      const float step = 40.0f * scale * io.DeltaTime;  // 40 mm/s in the default scene
      if (glfwGetKey(native, GLFW_KEY_W) == GLFW_PRESS) tip += facing * step;
      if (glfwGetKey(native, GLFW_KEY_S) == GLFW_PRESS) tip -= facing * step;
      // The head, from the keyboard until a tracker is wired in: 100 mm/s in the default scene.
      const float head_step = 100.0f * scale * io.DeltaTime;
      const auto held = [&](int key) { return glfwGetKey(native, key) == GLFW_PRESS ? head_step : 0.0f; };
      panel.eyes.head_mm +=
          glm::vec3(held(GLFW_KEY_RIGHT) - held(GLFW_KEY_LEFT), held(GLFW_KEY_UP) - held(GLFW_KEY_DOWN),
                    held(GLFW_KEY_PAGE_DOWN) - held(GLFW_KEY_PAGE_UP));
      reset_tip = ImGui::IsKeyPressed(GLFW_KEY_R);  // ImGui 1.86 indexes keys by GLFW code
      screenshot = ImGui::IsKeyPressed(GLFW_KEY_P);
      if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) window.request_close();
    }
    device.set_target(tip);

    const TickResult latest = loop.latest();
    const LoopStatistics stats = loop.statistics();

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    bool panel_reset = false, panel_shot = false;
    draw_panel(scene, edited, draw, panel, stats, latest, panel_reset, panel_shot);
    if (reset_tip || panel_reset) {
      tip = start_tip;
      device.set_target(tip);
    }
    if (panel.convergence_follows_camera) panel.eyes.convergence_mm = camera.distance_mm;
    // The head's own view (the mono camera while the head is home).
    const EyeView head = panel.eyes.eye(Eye::centre, mono_camera(camera, size.x / size.y));
    const glm::mat4 view = head.view, projection = head.projection;
    // The arrow is drawn over the picture at the head's view: not over stereo or mirrored pictures.
    const bool composited_output =
        panel.stereo != int(gl::StereoMode::mono) || panel.mirror != int(gl::Mirror::none);
    if (latest.contact.in_contact() && !composited_output) {
      draw_force_arrow(projection * view, size, latest.contact.hip_mm, latest.force_n,
                       latest.contact.depth_mm, 15.0f * scale);
    }
    ImGui::Render();

    apply_materials(edited, applied, loop, renderer);
    draw.deformation = std::array{gl::Deformation::gpu, gl::Deformation::cpu_naive,
                                  gl::Deformation::none}[std::size_t(panel.deformation)];
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const auto stereo = gl::StereoMode(panel.stereo);
    const auto flip = gl::Mirror(panel.mirror);
    if (composited_output) {
      compositor.render(stereo, flip, width, height, [&](const gl::EyeTarget& target) {
        glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        const EyeView eye = panel.eyes.eye(target.eye, mono_camera(camera, target.aspect));
        renderer.draw(eye.view, eye.projection, std::span<const Contact>(&latest.contact, 1), draw);
      });
    } else {
      renderer.draw(view, projection, std::span<const Contact>(&latest.contact, 1), draw);
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ++frame;

    const bool last_frame = options.frames > 0 && frame >= options.frames;
    if (screenshot || panel_shot) {
      char name[64];
      std::snprintf(name, sizeof name, "palpate-view-%04d.png", frame);
      save_screenshot(name, width, height);
    }
    if (last_frame && !options.screenshot.empty() && !save_screenshot(options.screenshot, width, height))
      return 1;
    window.swap_buffers();
    if (last_frame) window.request_close();
  }
  loop.stop();
  const TickResult last = loop.latest();
  if (last.contact.in_contact()) {
    std::printf("palpate view: %d frames; last tick: on '%s', p = %.2f mm, |F| = %.2f N\n", frame,
                scene.objects[std::size_t(last.contact.object)].name.c_str(), last.contact.depth_mm,
                glm::length(last.force_n));
  } else {
    std::printf("palpate view: %d frames; last tick: free\n", frame);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return 0;
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* view = app.add_subcommand("view", "Interactive viewer: the mouse drives a virtual haptic device");
  add_scene_options(view, options->scene);
  add_size_options(view, options->width, options->height, "Window");
  view->add_option("--frames", options->frames, "Quit after this many frames")->check(CLI::PositiveNumber);
  view->add_option("--screenshot", options->screenshot, "With --frames: save the last frame to this PNG");
  view->add_option("--press-depth", options->press_depth_mm,
                   "Start with the tip this many mm under the surface at the centre")
      ->check(CLI::Range(0.0, 30.0));
  add_stereo_options(view, options->stereo);
  on_selected(view, [options] { return run_view(*options); });
}

}  // namespace palpate::cli
