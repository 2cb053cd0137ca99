// palpate bench table1: the paper's Table I in one run. For brain, skin and skin + brain, the graphics
// frame rate and the haptic rate measured together while a scripted probe is in contact, then the same
// with the CPU-naive renderer (the approach the paper argues against), with the ratio. Prints a
// markdown table, writes --json and a plot of the haptic period and the frame time over the run.
#include <cstdio>
#include <fstream>

#include "commands.hpp"
#include "demo_phases.hpp"
#include "format.hpp"
#include "gl_session.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/gl/probe_run.hpp"
#include "plot.hpp"
#include "report.hpp"

namespace palpate::cli {
namespace {

struct Table1Options {
  SceneChoice scene;
  double seconds = 5.0;
  std::string json;
  std::string plot = "table1";
  bool headless = false;
  int width = 1280, height = 1024;
};

void print_markdown(const std::string& device, const Table1Options& options, const std::vector<ModelRun>& gpu,
                    const std::vector<ModelRun>& naive) {
  std::printf("\nTable I, this run: %s, %dx%d, %.0f s a row in contact\n\n", device.c_str(), options.width,
              options.height, options.seconds);
  std::printf(
      "| 3D model | vertices | faces | graphics fps | haptics Hz | contact age p50 / p99 ms | CPU-naive fps "
      "| GPU / CPU-naive |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    const gl::ProbeRunResult& r = gpu[i].run;
    const double naive_fps = naive[i].run.graphics_fps;
    std::printf("| %s | %s | %s | %.1f | %.1f | %.2f / %.2f | %.1f | %.2fx |\n", gpu[i].model.c_str(),
                with_thousands(r.vertices).c_str(), with_thousands(r.faces).c_str(), r.graphics_fps,
                r.haptics_hz, r.contact_age_ms.p50, r.contact_age_ms.p99, naive_fps,
                naive_fps > 0 ? r.graphics_fps / naive_fps : 0.0);
  }
  std::printf(
      "\nHaptic thread during each GPU row: missed deadlines, period error p50 / p99 / p99.9 / max us\n\n");
  for (const ModelRun& row : gpu) {
    const gl::ProbeRunResult& r = row.run;
    std::printf("- %s: %llu ticks, %llu missed, %.1f / %.1f / %.1f / %.1f us\n", row.model.c_str(),
                static_cast<unsigned long long>(r.haptics.ticks),
                static_cast<unsigned long long>(r.haptics.missed_deadlines), r.haptics.period_error_us.p50,
                r.haptics.period_error_us.p99, r.haptics.period_error_us.p999, r.haptics.period_error_us.max);
  }
}

// The haptic period and the frame time over the whole run, rows one after the other.
std::filesystem::path plot_run(const std::string& file, const std::vector<ModelRun>& rows) {
  PlotPanel haptic{"Haptic thread period (1 kHz target)", "time in run, s", "period, us", {}};
  PlotPanel frames{"Graphics frame time", "time in run, s", "frame, ms", {}};
  double offset = 0.0;
  for (const ModelRun& row : rows) {
    const gl::ProbeRunResult& r = row.run;
    Series period{row.model, {}, {}};
    const double period_s = r.haptics.target_hz > 0 ? 1.0 / r.haptics.target_hz : 1e-3;
    // The window holds the last ticks of the row: lay them out backwards from its end.
    const double start = offset + r.seconds - double(r.haptics.periods_us.size()) * period_s;
    for (std::size_t i = 0; i < r.haptics.periods_us.size(); ++i) {
      period.x.push_back(start + double(i) * period_s);
      period.y.push_back(r.haptics.periods_us[i]);
    }
    Series frame{row.model, {}, {}};
    for (std::size_t i = 0; i < r.frame_ms.size(); ++i) {
      frame.x.push_back(offset + r.frame_times_s[i]);
      frame.y.push_back(r.frame_ms[i]);
    }
    haptic.series.push_back(std::move(period));
    frames.series.push_back(std::move(frame));
    offset += r.seconds;
  }
  return plot_panels(file, {haptic, frames});
}

int bench_table1(const Table1Options& options) {
  const Scene scene = scene_for_option(options.scene);
  GlSession session = open_gl(options.headless, options.width, options.height, "palpate bench table1");
  gl::Framebuffer framebuffer(
      {.width = options.width, .height = options.height, .color = gl::ColorFormat::rgba8, .samples = 0});
  gl::Renderer renderer;
  const std::vector<Phase> phases =
      table1_phases(scene, options.seconds, glm::vec2(options.width, options.height));
  std::vector<ModelRun> gpu, naive;
  for (const Phase& phase : phases) {
    for (const gl::Deformation deformation : {gl::Deformation::gpu, gl::Deformation::cpu_naive}) {
      std::fprintf(stderr, "bench table1: %s, %s, %.0f s\n", phase.model.c_str(),
                   deformation == gl::Deformation::gpu ? "GPU deformation" : "CPU-naive", options.seconds);
      gl::ProbeRunParams run;
      run.draw.deformation = deformation;
      run.draw.probe_radius_mm = phase.probe_radius_mm;
      run.max_seconds = options.seconds;
      run.window = session.window.get();
      (deformation == gl::Deformation::gpu ? gpu : naive)
          .push_back({phase.model, gl::run_probe_script(phase.scene, phase.camera, phase.script, renderer,
                                                        framebuffer, run)});
    }
  }
  print_markdown(session.renderer, options, gpu, naive);
  if (!options.plot.empty()) std::printf("\nplot: %s\n", plot_run(options.plot, gpu).string().c_str());
  if (!options.json.empty()) {
    nlohmann::json report = run_report_json(session.renderer, options.width, options.height, gpu);
    for (std::size_t i = 0; i < gpu.size(); ++i)
      report["rows"][i]["cpu_naive_fps"] = naive[i].run.graphics_fps;
    report["seconds_per_row"] = options.seconds;
    write_json_file(options.json, report);
  }
  return 0;
}

}  // namespace

void add_bench_table1_command(CLI::App& app) {
  auto options = std::make_shared<Table1Options>();
  CLI::App* table1 = add_bench_command(app).add_subcommand(
      "table1",
      "The paper's Table I: graphics fps and haptic Hz together, in contact, with the CPU-naive baseline");
  add_scene_options(table1, options->scene);
  table1->add_option("--seconds", options->seconds, "Seconds of contact for each row and renderer")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 600.0));
  table1->add_option("--json", options->json, "Also write the results to this JSON file");
  table1
      ->add_option("--plot", options->plot,
                   "Plot file, without extension (PNG through gnuplot, else SVG); '' for none")
      ->capture_default_str();
  table1->add_flag("--headless", options->headless, "Render through EGL even when there is a display");
  add_size_options(table1, options->width, options->height, "Frame");
  on_selected(table1, [options] { return bench_table1(*options); });
}

}  // namespace palpate::cli
