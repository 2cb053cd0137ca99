// palpate demo: the main job. A scripted probe presses into the skin at three sites, then the skin is
// hidden and the probe presses and slides across the brain, with the haptic thread at 1 kHz and the
// graphics thread drawing each frame deformed. Writes frames, key frames, a contact sheet and a report,
// and prints the paper's Table I with this run's figures.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "demo_phases.hpp"
#include "format.hpp"
#include "gl_session.hpp"
#include "image.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/gl/png.hpp"
#include "palpate/gl/probe_run.hpp"
#include "report.hpp"
#include "stereo_options.hpp"

namespace palpate::cli {
namespace {

struct DemoOptions {
  SceneChoice scene;
  std::string out_dir = "demo-out";
  int frames = -1;
  bool headless = false;
  int width = 1280, height = 1024;
  double video_fps = 30.0;
  StereoChoice stereo;
};

// Frames go to an MP4 through ffmpeg when it is installed, else to numbered PNGs.
class FrameWriter {
 public:
  FrameWriter(const std::filesystem::path& out, int width, int height, double fps) : out_(out) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
      const std::string command = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgba -s " +
                                  std::to_string(width) + "x" + std::to_string(height) + " -framerate " +
                                  std::to_string(fps) + " -i - -vf vflip -c:v libx264 -pix_fmt yuv420p '" +
                                  (out / "demo.mp4").string() + "'";
      ffmpeg_ = popen(command.c_str(), "w");
    }
    if (!ffmpeg_) std::filesystem::create_directories(out / "frames");
  }
  ~FrameWriter() { finish(); }

  void write(const Image& frame) {
    if (ffmpeg_) {
      std::fwrite(frame.rgba.data(), 1, frame.rgba.size(), ffmpeg_);
    } else {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d.png", count_);
      gl::save_png(out_ / "frames" / name, frame.width, frame.height, frame.rgba);
    }
    ++count_;
  }

  // Where the frames went, for the report.
  std::string finish() {
    if (ffmpeg_) {
      pclose(ffmpeg_);
      ffmpeg_ = nullptr;
      finished_ = "demo.mp4";
    } else if (finished_.empty()) {
      finished_ = "frames/";
    }
    return finished_;
  }

 private:
  std::filesystem::path out_;
  FILE* ffmpeg_ = nullptr;
  int count_ = 0;
  std::string finished_;
};

// A key frame of the contact sheet: the first frame, the deepest frame of each press, and for a long
// slide four frames spread along it. Only these keep their full-size image.
struct KeySlot {
  int phase = 0, press = 0;
  double at_time_s = -1.0;  // >= 0: the first frame at or after this time; < 0: the deepest frame
  int capture = -1;         // which capture fills it, -1 while empty
  float depth_mm = -1.0f;
  gl::CapturedFrame frame;
  Image full, thumbnail;

  bool wants(int frame_phase, int frame_press, const gl::CapturedFrame& f) const {
    if (frame_phase != phase) return false;
    if (at_time_s >= 0.0) return capture < 0 && f.time_s >= at_time_s;
    return frame_press == press && f.tick.contact.in_contact() && f.tick.contact.depth_mm > depth_mm;
  }
};

KeySlot slot_for(int phase, int press, double at_time_s) {
  KeySlot slot;
  slot.phase = phase;
  slot.press = press;
  slot.at_time_s = at_time_s;
  return slot;
}

std::vector<KeySlot> plan_key_frames(const std::vector<Phase>& phases) {
  std::vector<KeySlot> slots = {slot_for(0, 0, 0.0)};
  for (int p = 0; p < int(phases.size()); ++p) {
    const std::vector<ProbeScript::Stroke>& strokes = phases[std::size_t(p)].script.strokes;
    for (int stroke = 0; stroke < int(strokes.size()); ++stroke) {
      const ProbeScript::Stroke& s = strokes[std::size_t(stroke)];
      if (!s.slide) {
        slots.push_back(slot_for(p, stroke, -1.0));
        continue;
      }
      const double span = s.end_s - s.start_s;
      for (int k = 0; k < 4; ++k)
        slots.push_back(slot_for(p, stroke, s.start_s + span * (0.2 + 0.6 * k / 3.0)));
    }
  }
  if (slots.size() > 9) slots.resize(9);
  return slots;
}

int run_demo(const DemoOptions& options) {
  const std::filesystem::path out = options.out_dir;
  std::filesystem::create_directories(out);
  const Scene scene = scene_for_option(options.scene);
  GlSession gl_session = open_gl(options.headless, options.width, options.height, "palpate demo");
  const std::vector<Phase> phases = demo_phases(scene, glm::vec2(options.width, options.height));
  std::printf("palpate demo: %zu objects, %zu vertices; %s on %s; output in %s/\n", scene.objects.size(),
              scene.vertex_count(), gl_session.window ? "window" : "headless EGL",
              gl_session.renderer.c_str(), out.string().c_str());

  gl::StereoMode stereo = stereo_mode(options.stereo);
  if (stereo == gl::StereoMode::quad_buffer) {
    std::fprintf(
        stderr,
        "palpate demo: quad-buffered stereo needs a window's back buffers and the demo draws its frames "
        "offscreen (for the files): side-by-side instead\n");
    stereo = gl::StereoMode::side_by_side;
  }
  if (composited(options.stereo)) {
    std::printf("  stereo %s, mirror %s, eyes %.0f mm apart, zero parallax %s\n", options.stereo.mode.c_str(),
                options.stereo.mirror.c_str(), options.stereo.eye_separation_mm,
                options.stereo.convergence_mm > 0.0f
                    ? (std::to_string(int(options.stereo.convergence_mm)) + " mm").c_str()
                    : "at what each phase's camera looks at");
  }
  gl::Framebuffer framebuffer(
      {.width = options.width, .height = options.height, .color = gl::ColorFormat::rgba8, .samples = 0});
  gl::Renderer renderer;
  FrameWriter writer(out, options.width, options.height, options.video_fps);
  std::vector<KeySlot> slots = plan_key_frames(phases);
  std::vector<ModelRun> results;
  int captured = 0;

  for (int p = 0; p < int(phases.size()); ++p) {
    const Phase& phase = phases[std::size_t(p)];
    std::vector<double> press_starts;
    for (const ProbeScript::Stroke& stroke : phase.script.strokes) press_starts.push_back(stroke.start_s);
    gl::ProbeRunParams run;
    run.draw.probe_radius_mm = phase.probe_radius_mm;
    run.captures_so_far = captured;
    run.on_log = [](const std::string& line) { std::fprintf(stderr, "palpate: %s\n", line.c_str()); };
    run.capture_fps = options.video_fps;
    run.max_captures = options.frames;
    run.window = gl_session.window.get();
    run.stereo = stereo;
    run.mirror = mirror(options.stereo);
    run.stereo_camera = stereo_camera(options.stereo, phase.camera);
    run.on_capture = [&](const gl::CapturedFrame& frame) {
      Image full{framebuffer.width(), framebuffer.height(), frame.framebuffer->read_rgba8()};
      writer.write(full);
      const auto later = std::upper_bound(press_starts.begin(), press_starts.end(), frame.time_s);
      const int press = std::max(0, int(later - press_starts.begin()) - 1);
      for (KeySlot& slot : slots) {
        if (!slot.wants(p, press, frame)) continue;
        slot.capture = frame.index;
        slot.depth_mm = frame.tick.contact.depth_mm;
        slot.frame = frame;
        slot.full = full;
        slot.thumbnail = downsample(full, 4);
      }
      ++captured;
    };
    results.push_back({phase.model, gl::run_probe_script(phase.scene, phase.camera, phase.script, renderer,
                                                         framebuffer, run)});
    if (options.frames >= 0 && captured >= options.frames) break;
    if (gl_session.window && gl_session.window->should_close()) break;
  }
  const std::string frames_at = writer.finish();

  std::erase_if(slots, [](const KeySlot& slot) { return slot.capture < 0; });
  std::sort(slots.begin(), slots.end(),
            [](const KeySlot& a, const KeySlot& b) { return a.capture < b.capture; });
  nlohmann::json key_json = nlohmann::json::array();
  std::vector<Image> thumbnails;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const KeySlot& slot = slots[k];
    const std::string file = "keyframe_" + std::to_string(k) + ".png";
    gl::save_png(out / file, slot.full.width, slot.full.height, slot.full.rgba);
    key_json.push_back(key_frame_json(file, phases[std::size_t(slot.phase)], slot.frame));
    thumbnails.push_back(slot.thumbnail);
  }
  if (!thumbnails.empty()) {
    const Image contact_sheet = tile(thumbnails, std::min<int>(4, int(thumbnails.size())));
    gl::save_png(out / "contact_sheet.png", contact_sheet.width, contact_sheet.height, contact_sheet.rgba);
  }

  nlohmann::json report = run_report_json(gl_session.renderer, options.width, options.height, results);
  report["frames"] = {{"count", captured}, {"fps", options.video_fps}, {"at", frames_at}};
  report["key_frames"] = key_json;
  print_table1(stdout, gl_session.renderer, options.width, options.height, results);
  write_json_file(out / "report.json", report);
  std::printf("wrote %s/contact_sheet.png, %d frames (%s)\n", out.string().c_str(), captured,
              frames_at.c_str());
  return 0;
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* demo = app.add_subcommand(
      "demo", "The headless (or windowed) demo: a probe presses the skin, then slides on the brain");
  add_scene_options(demo, options->scene);
  demo->add_option("--out", options->out_dir, "Output folder")->capture_default_str();
  demo->add_option("--frames", options->frames,
                   "Stop after this many captured frames (default: the whole script)")
      ->check(CLI::PositiveNumber);
  demo->add_flag("--headless", options->headless, "Render through EGL even when there is a display");
  add_size_options(demo, options->width, options->height, "Frame");
  add_stereo_options(demo, options->stereo);
  on_selected(demo, [options] { return run_demo(*options); });
}

}  // namespace palpate::cli
