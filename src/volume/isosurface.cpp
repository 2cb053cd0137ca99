#include "palpate/volume/isosurface.hpp"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <glm/geometric.hpp>
#include <numeric>

#include "decimate.hpp"
#include "palpate/core/error.hpp"

namespace palpate::volume {
namespace {

using Clock = std::chrono::steady_clock;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Reports a VTK filter's progress as the named stage's.
class ProgressRelay {
 public:
  ProgressRelay(vtkAlgorithm& algorithm, std::string_view stage, const IsosurfaceParams& params)
      : stage_(stage), params_(params) {
    if (!params.on_progress) return;
    callback_->SetClientData(this);
    callback_->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
      auto* relay = static_cast<ProgressRelay*>(self);
      relay->params_.on_progress(relay->stage_, static_cast<vtkAlgorithm*>(caller)->GetProgress());
    });
    algorithm.AddObserver(vtkCommand::ProgressEvent, callback_);
  }

 private:
  std::string_view stage_;
  const IsosurfaceParams& params_;
  vtkNew<vtkCallbackCommand> callback_;
};

vtkNew<vtkImageData> image_of(const std::vector<float>& values, glm::ivec3 size) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(size.x, size.y, size.z);
  image->AllocateScalars(VTK_FLOAT, 1);
  std::memcpy(image->GetScalarPointer(), values.data(), values.size() * sizeof(float));
  return image;
}

// Pads the grid by one voxel of air on every side, floods the air reachable from outside (6-connected
// voxels below the threshold), and lifts every other voxel below it above it, mirrored about the
// threshold so that values next to reached air keep their distance to it. A flood fill by hand: a
// breadth-first walk over the grid, simpler than any filter chain that would do the same.
std::vector<float> close_against_border(const std::vector<float>& values, glm::ivec3 size, float iso,
                                        glm::ivec3& padded_size) {
  padded_size = size + glm::ivec3(2);
  const auto index = [&](int i, int j, int k) {
    return std::size_t(i) +
           std::size_t(padded_size.x) * (std::size_t(j) + std::size_t(padded_size.y) * std::size_t(k));
  };
  float lowest = iso;
  for (const float value : values) lowest = std::min(lowest, value);
  std::vector<float> padded(
      std::size_t(padded_size.x) * std::size_t(padded_size.y) * std::size_t(padded_size.z), lowest - 1.0f);
  for (int k = 0; k < size.z; ++k)
    for (int j = 0; j < size.y; ++j)
      for (int i = 0; i < size.x; ++i)
        padded[index(i + 1, j + 1, k + 1)] =
            values[std::size_t(i) +
                   std::size_t(size.x) * (std::size_t(j) + std::size_t(size.y) * std::size_t(k))];

  std::vector<bool> reached(padded.size(), false);
  std::deque<glm::ivec3> queue{glm::ivec3(0)};
  reached[0] = true;
  static constexpr glm::ivec3 steps[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!queue.empty()) {
    const glm::ivec3 voxel = queue.front();
    queue.pop_front();
    for (const glm::ivec3 step : steps) {
      const glm::ivec3 next = voxel + step;
      if (glm::any(glm::lessThan(next, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(next, padded_size)))
        continue;
      const std::size_t at = index(next.x, next.y, next.z);
      if (reached[at] || padded[at] >= iso) continue;
      reached[at] = true;
      queue.push_back(next);
    }
  }
  for (std::size_t at = 0; at < padded.size(); ++at)
    if (!reached[at] && padded[at] < iso) padded[at] = iso + (iso - padded[at]);
  return padded;
}

// The triangles of `poly` with only the points they use, positions taken to millimetres.
Mesh mesh_of(vtkPolyData& poly, const glm::dmat4& voxel_to_mm) {
  Mesh mesh;
  vtkCellArray* polys = poly.GetPolys();
  std::vector<std::int64_t> remap(std::size_t(poly.GetNumberOfPoints()), -1);
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  mesh.indices.reserve(std::size_t(polys->GetNumberOfCells()) * 3);
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);) {
    if (count != 3) continue;
    for (int corner = 0; corner < 3; ++corner) {
      std::int64_t& to = remap[std::size_t(ids[corner])];
      if (to < 0) {
        to = std::int64_t(mesh.positions_mm.size());
        double p[3];
        poly.GetPoint(ids[corner], p);
        mesh.positions_mm.push_back(glm::vec3(voxel_to_mm * glm::dvec4(p[0], p[1], p[2], 1.0)));
      }
      mesh.indices.push_back(std::uint32_t(to));
    }
  }
  return mesh;
}

// Six times the signed volume: positive when the triangles face outward.
double signed_volume6(const Mesh& mesh) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = mesh.positions_mm[mesh.indices[t]], b = mesh.positions_mm[mesh.indices[t + 1]],
                     c = mesh.positions_mm[mesh.indices[t + 2]];
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum;
}

// Decimates to a vertex or triangle count. For a closed surface V - T/2 is fixed by its genus, so a
// vertex target is a triangle target.
void decimate(Mesh& mesh, const IsosurfaceParams& params, const std::filesystem::path& source) {
  const std::int64_t euler_offset =
      std::int64_t(mesh.vertex_count()) - std::int64_t(mesh.triangle_count()) / 2;
  const std::int64_t triangles =
      params.triangles ? std::int64_t(params.triangles) : 2 * (std::int64_t(params.vertices) - euler_offset);
  if (triangles <= 0) {
    throw Error(source, 0,
                "cannot decimate to " + std::to_string(params.vertices) +
                    " vertices: the surface's topology needs more than " + std::to_string(euler_offset));
  }
  if (std::size_t(triangles) >= mesh.triangle_count()) return;
  if (params.on_progress) params.on_progress("decimate", 0.0);
  decimate_keeping_topology(mesh, std::size_t(triangles), source);
  if (params.on_progress) params.on_progress("decimate", 1.0);
  const bool on_target = params.triangles ? mesh.triangle_count() <= params.triangles * 101 / 100
                                          : mesh.vertex_count() <= params.vertices * 101 / 100;
  if (!on_target) {
    throw Error(source, 0,
                "could not decimate to " +
                    std::to_string(params.triangles ? params.triangles : params.vertices) +
                    (params.triangles ? " triangles" : " vertices") + " keeping the topology: stopped at " +
                    std::to_string(mesh.vertex_count()) + " vertices, " +
                    std::to_string(mesh.triangle_count()) + " triangles");
  }
}

}  // namespace

Isosurface extract_isosurface(const Volume& volume, const IsosurfaceParams& params) {
  const IntensityRange range = intensity_range(volume);
  if (!(params.iso > range.min && params.iso < range.max)) {
    throw Error(volume.source, 0,
                "threshold " + number(params.iso) + " is outside the intensity range (" + number(range.min) +
                    ", " + number(range.max) + ")");
  }
  Isosurface result;
  auto stage_start = Clock::now();
  const auto finish_stage = [&](std::string name, const Mesh* mesh) {
    const auto now = Clock::now();
    result.stages.push_back({std::move(name), mesh ? mesh->vertex_count() : 0,
                             mesh ? mesh->triangle_count() : 0,
                             std::chrono::duration<double>(now - stage_start).count()});
    stage_start = now;
  };

  std::vector<float> values = volume.values;
  glm::ivec3 size = volume.size;
  glm::dmat4 voxel_to_mm = volume.voxel_to_mm;
  if (params.smooth_voxels > 0.0f) {
    vtkNew<vtkImageGaussianSmooth> smooth;
    const ProgressRelay relay(*smooth, "smooth", params);
    smooth->SetInputData(image_of(values, size));
    smooth->SetDimensionality(3);
    smooth->SetStandardDeviations(params.smooth_voxels, params.smooth_voxels, params.smooth_voxels);
    smooth->SetRadiusFactors(3.0, 3.0, 3.0);  // the kernel to 3 sigma (VTK cuts it at 1.5 by default)
    smooth->Update();
    const float* smoothed = static_cast<const float*>(smooth->GetOutput()->GetScalarPointer());
    values.assign(smoothed, smoothed + values.size());
    finish_stage("smooth", nullptr);
  }
  if (params.closed) {
    if (params.on_progress) params.on_progress("close", 0.0);
    values = close_against_border(values, size, params.iso, size);
    voxel_to_mm = voxel_to_mm * glm::dmat4(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0,
                                           -1.0, -1.0, 1.0);
    if (params.on_progress) params.on_progress("close", 1.0);
    finish_stage("close", nullptr);
  }

  vtkNew<vtkFlyingEdges3D> edges;
  const ProgressRelay edges_relay(*edges, "isosurface", params);
  edges->SetInputData(image_of(values, size));
  edges->SetValue(0, params.iso);
  edges->ComputeNormalsOff();
  edges->ComputeGradientsOff();
  edges->ComputeScalarsOff();
  edges->Update();
  vtkPolyData* surface = edges->GetOutput();
  if (surface->GetNumberOfPolys() == 0)
    throw Error(volume.source, 0, "the isosurface at " + number(params.iso) + " is empty");
  Mesh mesh;
  if (params.largest) {
    Mesh all = mesh_of(*surface, voxel_to_mm);
    finish_stage("isosurface", &all);
    vtkNew<vtkPolyDataConnectivityFilter> pieces;
    const ProgressRelay pieces_relay(*pieces, "largest piece", params);
    pieces->SetInputData(surface);
    pieces->SetExtractionModeToLargestRegion();
    pieces->Update();
    mesh = mesh_of(*pieces->GetOutput(), voxel_to_mm);
    finish_stage("largest piece", &mesh);
  } else {
    mesh = mesh_of(*surface, voxel_to_mm);
    finish_stage("isosurface", &mesh);
  }
  if (signed_volume6(mesh) < 0.0) {  // inward (the threshold rises inward, or the frame mirrors)
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
  if (params.vertices || params.triangles) {
    decimate(mesh, params, volume.source);
    finish_stage("decimate", &mesh);
  }
  compute_vertex_normals(mesh);
  finish_stage("normals", &mesh);
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace palpate::volume
