#include "plot.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "palpate/core/error.hpp"

namespace palpate::cli {
namespace {

const char* const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::filesystem::path with_gnuplot(const std::filesystem::path& file, const std::vector<PlotPanel>& panels) {
  const std::filesystem::path png = std::filesystem::path(file).replace_extension(".png");
  const std::filesystem::path data_dir = std::filesystem::path(file).replace_extension(".plotdata");
  std::filesystem::create_directories(data_dir);
  std::ofstream script(data_dir / "plot.gp");
  script << "set terminal pngcairo size 1200," << 320 * panels.size() << " font ',10'\n"
         << "set output '" << png.string() << "'\nset multiplot layout " << panels.size() << ",1\nset grid\n"
         << "set key outside right top\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const PlotPanel& panel = panels[p];
    script << "set title '" << panel.title << "'\nset xlabel '" << panel.x_label << "'\nset ylabel '"
           << panel.y_label << "'\nplot ";
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      const std::filesystem::path data =
          data_dir / ("panel" + std::to_string(p) + "_" + std::to_string(s) + ".dat");
      std::ofstream out(data);
      for (std::size_t i = 0; i < panel.series[s].x.size(); ++i)
        out << panel.series[s].x[i] << ' ' << panel.series[s].y[i] << '\n';
      script << (s ? ", " : "") << "'" << data.string() << "' with lines lw 1 lc rgb '" << colors[s % 6]
             << "' title '" << panel.series[s].title << "'";
    }
    script << "\n";
  }
  script << "unset multiplot\n";
  script.close();
  const std::string command = "gnuplot '" + (data_dir / "plot.gp").string() + "' 2>&1";
  if (std::system(command.c_str()) != 0) throw Error(png, 0, "gnuplot failed to draw the plot");
  std::filesystem::remove_all(data_dir);
  return png;
}

std::filesystem::path with_svg(const std::filesystem::path& file, const std::vector<PlotPanel>& panels) {
  const std::filesystem::path svg = std::filesystem::path(file).replace_extension(".svg");
  const double width = 1200, height = 320, left = 70, right = 220, top = 30, bottom = 45;
  std::ofstream out(svg);
  if (!out) throw Error(svg, 0, "cannot write the plot");
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='"
      << height * double(panels.size())
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const PlotPanel& panel = panels[p];
    double x0 = 1e300, x1 = -1e300, y0 = 0, y1 = -1e300;
    for (const Series& s : panel.series) {
      for (double v : s.x) x0 = std::min(x0, v), x1 = std::max(x1, v);
      for (double v : s.y) y1 = std::max(y1, v);
    }
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    const double oy = height * double(p);
    const auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (width - left - right); };
    const auto py = [&](double y) {
      return oy + height - bottom - (y - y0) / (y1 - y0) * (height - top - bottom);
    };
    out << "<text x='" << left << "' y='" << oy + 18 << "' font-weight='bold'>" << panel.title << "</text>\n"
        << "<rect x='" << left << "' y='" << oy + top << "' width='" << width - left - right << "' height='"
        << height - top - bottom << "' fill='none' stroke='#888'/>\n"
        << "<text x='" << left << "' y='" << oy + height - 8 << "'>" << panel.x_label << ": " << x0 << " .. "
        << x1 << "</text>\n"
        << "<text x='5' y='" << oy + top + 10 << "'>" << y1 << "</text><text x='5' y='"
        << oy + height - bottom << "'>0</text>\n"
        << "<text x='5' y='" << oy + height / 2 << "'>" << panel.y_label << "</text>\n";
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      out << "<polyline fill='none' stroke-width='1' stroke='" << colors[s % 6] << "' points='";
      for (std::size_t i = 0; i < panel.series[s].x.size(); ++i)
        out << px(panel.series[s].x[i]) << ',' << py(panel.series[s].y[i]) << ' ';
      out << "'/>\n<text x='" << width - right + 10 << "' y='" << oy + top + 14 * double(s + 1) << "' fill='"
          << colors[s % 6] << "'>" << panel.series[s].title << "</text>\n";
    }
  }
  out << "</svg>\n";
  return svg;
}

}  // namespace

std::filesystem::path plot_panels(const std::filesystem::path& file, const std::vector<PlotPanel>& panels) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) return with_gnuplot(file, panels);
  return with_svg(file, panels);
}

}  // namespace palpate::cli
