#pragma once
// The reports of `demo` and `bench table1`: JSON rows and the paper's Table I on a terminal.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "simulation.hpp"

namespace palpate::cli {

// {device, width, height, rows: [{model, vertices, faces, graphics_fps, haptics_hz,
//  contact_age_ms: {p50, p99}, frames, seconds, haptics: {...}}]}
nlohmann::json run_report_json(const std::string& device, int width, int height,
                               const std::vector<PhaseResult>& results);

// A frame's file, its scene state, camera and contact: enough to render it again for comparison.
nlohmann::json key_frame_json(const std::string& file, const Phase& phase, const CapturedFrame& frame);

// The paper's Table I with this run's figures; with `cpu_naive_fps` (one per row) two more columns.
void print_table1(std::FILE* out, const std::string& device, int width, int height,
                  const std::vector<PhaseResult>& results, const std::vector<double>& cpu_naive_fps);

}  // namespace palpate::cli
