#pragma once
// GIfTI surfaces (.gii, .gii.gz) through giftiio (setup code: allocates, throws palpate::Error).
#include <filesystem>
#include <string>

#include "palpate/core/scene.hpp"

namespace palpate::detail {

// The POINTSET and TRIANGLE arrays of the file as one object, honouring each array's
// RowMajorOrder / ColumnMajorOrder. Positions are in the file's own space (mm for FreeSurfer and
// SPM surfaces); the coordinate-system transform is not applied. `content` is the decompressed
// file, `was_gzip` whether the file itself was gzipped (giftiio reads only from a named file).
Scene read_gifti_model(const std::string& content, bool was_gzip, const std::filesystem::path& file);

}  // namespace palpate::detail
