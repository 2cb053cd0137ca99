#pragma once
// Closed, consistently oriented test shapes (mm): building blocks for phantoms, tests and benchmarks.
// All allocate; all are deterministic.
#include <cstddef>
#include <glm/vec3.hpp>

#include "palpate/core/mesh.hpp"

namespace palpate {

// A unit-sphere-like surface with exactly `vertices` vertices (>= 5) and 2 * vertices - 4 triangles:
// two poles on the z axis and latitude rings whose vertex counts follow the ring's circumference, so
// triangles stay close to equilateral. Rings are stitched to their neighbours by angle.
Mesh make_sphere(float radius_mm, std::size_t vertices);

// A sphere of `radius_mm` whose radius varies by +/- `bump_mm` in smooth bumps about 12 degrees
// apart, with the even triangle count nearest to `triangles`.
Mesh make_bumpy_sphere(float radius_mm, float bump_mm, std::size_t triangles);

// An axis-aligned box centred at the origin: 8 shared vertices, 12 triangles.
Mesh make_box(glm::vec3 size_mm);

// A flat square grid in the z = 0 plane, centred at the origin, normal +z: (cells+1)^2 vertices.
// Open (it has a boundary); for rendering tests.
Mesh make_grid(float size_mm, std::size_t cells);

}  // namespace palpate
