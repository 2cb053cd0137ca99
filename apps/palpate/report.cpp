#include "report.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "format.hpp"

namespace palpate::cli {
namespace {

nlohmann::json matrix_json(const glm::mat4& m) {
  const float* v = glm::value_ptr(m);
  return nlohmann::json(std::vector<float>(v, v + 16));
}

nlohmann::json vec_json(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

}  // namespace

nlohmann::json run_report_json(const std::string& device, int width, int height,
                               const std::vector<ModelRun>& rows) {
  nlohmann::json json_rows = nlohmann::json::array();
  for (const ModelRun& row : rows) {
    const gl::ProbeRunResult& r = row.run;
    json_rows.push_back({{"model", row.model},
                         {"vertices", r.vertices},
                         {"faces", r.faces},
                         {"graphics_fps", r.graphics_fps},
                         {"haptics_hz", r.haptics_hz},
                         {"contact_age_ms", {{"p50", r.contact_age_ms.p50}, {"p99", r.contact_age_ms.p99}}},
                         {"max_force_n", r.max_force_n},
                         {"frames", r.frames},
                         {"seconds", r.seconds},
                         {"haptics",
                          {{"ticks", r.haptics.ticks},
                           {"achieved_hz_last_second", r.haptics.achieved_hz},
                           {"missed_deadlines", r.haptics.missed_deadlines},
                           {"tick_us", percentiles_json(r.haptics.tick_us)},
                           {"period_error_us", percentiles_json(r.haptics.period_error_us)}}}});
  }
  return {{"device", device}, {"width", width}, {"height", height}, {"rows", json_rows}};
}

nlohmann::json key_frame_json(const std::string& file, const Phase& phase, const gl::CapturedFrame& frame) {
  nlohmann::json shown = nlohmann::json::array();
  for (const SceneObject& object : phase.scene.objects) shown.push_back(object.material.visible);
  const Contact& c = frame.tick.contact;
  return {{"file", file},
          {"model", phase.model},
          {"time_s", frame.time_s},
          {"visible", shown},
          {"view", matrix_json(frame.view)},
          {"projection", matrix_json(frame.projection)},
          {"contact",
           {{"object", c.object},
            {"point_mm", vec_json(c.point_mm)},
            {"hip_mm", vec_json(c.hip_mm)},
            {"depth_mm", c.depth_mm}}},
          {"force_n", vec_json(frame.tick.force_n)},
          {"clamped", frame.tick.clamped}};
}

void print_table1(std::FILE* out, const std::string& device, int width, int height,
                  const std::vector<ModelRun>& rows) {
  std::fprintf(out, "\nTABLE I  PERFORMANCE RESULTS (this run: %s, %dx%d)\n", device.c_str(), width, height);
  std::fprintf(out, "%-14s %10s %10s %13s %12s %17s\n", "3D model", "vertices", "faces", "graphics fps",
               "haptics Hz", "contact age ms");
  for (const ModelRun& row : rows) {
    const gl::ProbeRunResult& r = row.run;
    char age[32];
    std::snprintf(age, sizeof age, "%.2f / %.2f", r.contact_age_ms.p50, r.contact_age_ms.p99);
    std::fprintf(out, "%-14s %10s %10s %13.1f %12.1f %17s\n", row.model.c_str(),
                 with_thousands(r.vertices).c_str(), with_thousands(r.faces).c_str(), r.graphics_fps,
                 r.haptics_hz, age);
  }
  std::fprintf(out,
               "(paper, 2004 hardware: Brain 68,856 v 61 fps 1000 Hz; Skin 90,207 v 60 fps 1000 Hz; "
               "Skin + Brain 159,063 v 59 fps 999 Hz. Contact age: p50 / p99.)\n");
}

}  // namespace palpate::cli
