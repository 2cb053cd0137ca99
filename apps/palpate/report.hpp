#pragma once
// The reports of `demo` and `bench table1`: JSON rows and the paper's Table I on a terminal.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "demo_phases.hpp"
#include "palpate/gl/probe_run.hpp"

namespace palpate::cli {

// One row of Table I: a phase's model and what its run measured.
struct ModelRun {
  std::string model;
  gl::ProbeRunResult run;
};

// {device, width, height, rows: [{model, vertices, faces, graphics_fps, haptics_hz,
//  contact_age_ms: {p50, p99}, max_force_n, frames, seconds, haptics: {...}}]}
nlohmann::json run_report_json(const std::string& device, int width, int height,
                               const std::vector<ModelRun>& rows);

// A frame's file, its scene state, camera and tick result: enough to render it again for comparison.
nlohmann::json key_frame_json(const std::string& file, const Phase& phase, const gl::CapturedFrame& frame);

// The paper's Table I with this run's figures.
void print_table1(std::FILE* out, const std::string& device, int width, int height,
                  const std::vector<ModelRun>& rows);

}  // namespace palpate::cli
