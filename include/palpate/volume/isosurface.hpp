#pragma once
// From a volume to a surface palpate can touch and draw: optional Gaussian smoothing, Flying Edges
// (VTK), the largest connected piece, closing against the volume's border, topology-preserving
// decimation (CGAL), outward normals; the mesh in the scan's millimetres.
//
// Closing: a scan whose field of view cuts the body (at the neck, the brow) gives an open surface, and
// one with inner cavities (sinuses, ventricles, the skull's inner sheet) gives surfaces inside. With
// `closed`, the volume is padded by a voxel of air, the air reachable from outside is flood-filled, and
// every voxel it does not reach counts as inside: the result is the one closed outer surface.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "palpate/core/mesh.hpp"
#include "palpate/volume/volume.hpp"

namespace palpate::volume {

struct IsosurfaceParams {
  float iso = 0.0f;            // the threshold, in the scan's units
  float smooth_voxels = 0.0f;  // Gaussian standard deviation before extraction, in voxels; 0: none
  bool largest = false;        // keep only the largest connected piece
  bool closed = false;         // close against the border and fill what outside air cannot reach
  std::size_t vertices = 0;    // decimate to about this many vertices (topology kept); 0: keep all
  std::size_t triangles = 0;   // or to about this many triangles; 0: keep all
  // Called as each stage advances, with its name and the fraction done in [0, 1]. May be empty.
  std::function<void(std::string_view stage, double fraction)> on_progress{};
};

struct StageSummary {
  std::string name;  // "read", "smooth", "close", "isosurface", "largest piece", "decimate", "normals"
  std::size_t vertices = 0, triangles = 0;
  double seconds = 0.0;
};

struct Isosurface {
  Mesh mesh;                         // scanner mm, outward normals, counter-clockwise from outside
  std::vector<StageSummary> stages;  // in order
};

// Throws palpate::Error naming the volume's file for a threshold outside its intensity range (giving
// the range), an empty isosurface, or a decimation target the surface cannot reach.
Isosurface extract_isosurface(const Volume& volume, const IsosurfaceParams& params);

}  // namespace palpate::volume
