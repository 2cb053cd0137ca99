#pragma once
#include <filesystem>

#include "palpate/volume/volume.hpp"

namespace palpate::volume {

// The one DICOM series in `folder` (searched with its subfolders): slices or one multi-frame file.
// Throws palpate::Error naming the folder or file: no DICOM files, several series (listed), a tilted,
// gapped or duplicated slice, a colour or undecodable image.
Volume load_dicom(const std::filesystem::path& folder);

}  // namespace palpate::volume
