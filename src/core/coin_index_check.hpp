#pragma once
// Index checks Coin3D does not make: Coin's face sets read their coordinate, normal and colour
// arrays through the file's indices unchecked (an out-of-range coordIndex crashes it), so each
// triangle-producing shape is checked before Coin generates its triangles.
#include <optional>
#include <string>

class SoNode;
class SoState;

namespace palpate::detail {

// A description of the first bad index of `shape` in the traversal state `state` (which holds the
// coordinates, normals and bindings of Inventor shapes), or nothing when its indices are in range.
std::optional<std::string> check_shape_indices(const SoNode& shape, SoState& state);

}  // namespace palpate::detail
