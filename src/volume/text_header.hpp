#pragma once
// NRRD and MetaImage: a text header, then (or in another file) the voxels. Read by hand: VTK 9.1's
// readers take NRRD's "space directions" for extra components and ignore MetaImage's TransformMatrix,
// so a rotated scan would be placed wrongly without a word. Both formats' world is LPS; palpate's is
// RAS (NIfTI's), so x and y are negated.
#include <filesystem>

#include "palpate/volume/volume.hpp"

namespace palpate::volume {

Volume load_nrrd(const std::filesystem::path& file);
Volume load_metaimage(const std::filesystem::path& file);

}  // namespace palpate::volume
