#pragma once
// Plots of series over time for benchmark reports: through gnuplot (PNG) when it is installed, else
// drawn by palpate as SVG. Returns the file written (the extension says which).
#include <filesystem>
#include <string>
#include <vector>

namespace palpate::cli {

struct Series {
  std::string title;
  std::vector<double> x, y;
};

struct PlotPanel {
  std::string title, x_label, y_label;
  std::vector<Series> series;
};

// Stacks the panels vertically. `file` without extension; ".png" or ".svg" is added.
std::filesystem::path plot_panels(const std::filesystem::path& file, const std::vector<PlotPanel>& panels);

}  // namespace palpate::cli
