#pragma once
// A scalar volume (an MRI or CT scan) and where its voxels lie in the scanner's millimetres.
//
// load_volume reads NIfTI-1 (.nii, .nii.gz; through niftiio: the scale slope and intercept applied, the
// sform used where its code is set, else the qform, else the voxel sizes), NRRD (.nrrd, .nhdr: raw or
// gzip, attached or detached data, space directions and origin) and MetaImage (.mha, .mhd: raw or
// compressed, Offset, ElementSpacing and TransformMatrix). Millimetres are RAS, as NIfTI's: NRRD's and
// MetaImage's LPS coordinates have x and y negated) and DICOM series (a folder, or a .dcm file in it,
// through GDCM: slices ordered by Image Position along the normal of Image Orientation, rescale slope and
// intercept applied per slice, LPS to RAS; or one multi-frame file). Every error is a palpate::Error naming
// the file and what was wrong: not a volume, an unsupported data type or encoding, a volume with fewer than 2
// voxels along an axis, short data; for DICOM, a folder holding several series (they are listed) or a tilted,
// gapped or duplicated slice.
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <string>
#include <vector>

namespace palpate::volume {

struct Volume {
  glm::ivec3 size{0};           // voxels along i, j, k
  std::vector<float> values;    // i fastest, then j, then k; in the scan's units (slope applied)
  glm::dmat4 voxel_to_mm{1.0};  // voxel centre (i, j, k) to scanner millimetres, RAS (right-handed or not)
  std::string frame;            // where voxel_to_mm came from, e.g. "NIfTI sform (code 4)"
  std::filesystem::path source;

  std::size_t voxel_count() const noexcept { return values.size(); }
  float at(int i, int j, int k) const noexcept {
    return values[std::size_t(i) +
                  std::size_t(size.x) * (std::size_t(j) + std::size_t(size.y) * std::size_t(k))];
  }
};

struct IntensityRange {
  float min = 0.0f, max = 0.0f;
};
IntensityRange intensity_range(const Volume& volume) noexcept;

// Throws palpate::Error (see above).
Volume load_volume(const std::filesystem::path& file);

// A threshold between background and tissue from the intensity histogram (Otsu's, 256 bins), of the
// intensities up to `below` only when given: what `from-volume` uses when no --iso is given.
float otsu_threshold(const Volume& volume, float below = std::numeric_limits<float>::infinity());
// Between air and the darkest tissue: Otsu's threshold of the intensities below Otsu's threshold. On an
// MRI of the head the skin's edge, where Otsu's alone cuts through the skull and CSF (and the skin
// comes out full of holes): what a closed surface (--closed, the skin of `scene from-volume`) uses.
float air_threshold(const Volume& volume);

}  // namespace palpate::volume
