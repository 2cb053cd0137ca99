#include "occlusion_proxy.hpp"

#include <libqhull_r/libqhull_r.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>

namespace palpate::gl {
namespace {

constexpr std::size_t spread_directions = 256;

// The six axes (so that the polytope fits in the bounding box), then a Fibonacci spiral.
std::vector<glm::dvec3> bounding_directions() {
  std::vector<glm::dvec3> directions{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < spread_directions; ++i) {
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(spread_directions);
    const double r = std::sqrt(1.0 - z * z), angle = golden_angle * double(i);
    directions.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
  }
  return directions;
}

// Corner j of the unit cube [-1, 1]^3: bit 0 of j picks +x, bit 1 +y, bit 2 +z.
glm::vec3 cube_corner(std::size_t j) noexcept {
  return {(j & 1) ? 1.0f : -1.0f, (j & 2) ? 1.0f : -1.0f, (j & 4) ? 1.0f : -1.0f};
}

// One qhull run over 3-D points, freed with it.
class Qhull {
 public:
  // options: qhull's, e.g. "Qt" for triangles only.
  Qhull(std::vector<double>& coordinates, const char* options) : qh_(std::make_unique<qhT>()) {
    // A failed hull is not an error here (the object is then drawn without a query), so qhull's report
    // of why goes nowhere rather than to the application's stderr.
    errors_ = std::fopen("/dev/null", "w");
    qh_zero(qh_.get(), errors_);
    std::string command = std::string("qhull ") + options;
    ok_ = qh_new_qhull(qh_.get(), 3, static_cast<int>(coordinates.size() / 3), coordinates.data(), False,
                       command.data(), nullptr, errors_) == 0;
  }
  ~Qhull() {
    qh_freeqhull(qh_.get(), !qh_ALL);
    int long_blocks = 0, long_bytes = 0;
    qh_memfreeshort(qh_.get(), &long_blocks, &long_bytes);
    if (errors_) std::fclose(errors_);
  }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;

  bool ok() const noexcept { return ok_; }

  // Calls f(normal, offset, ids) for each facet: its outward unit normal, its offset (normal . x +
  // offset = 0 on it, < 0 inside) and the input indices of its vertices.
  template <class F>
  void for_each_facet(F&& f) const {
    qhT* qh = qh_.get();
    std::vector<int> ids;
    for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
      ids.clear();
      vertexT *vertex = nullptr, **vertexp = nullptr;
      FOREACHvertex_(facet->vertices) ids.push_back(qh_pointid(qh, vertex->point));
      f(glm::dvec3(facet->normal[0], facet->normal[1], facet->normal[2]), double(facet->offset), ids);
    }
  }

 private:
  std::unique_ptr<qhT> qh_;  // several kilobytes
  std::FILE* errors_ = nullptr;
  bool ok_ = false;
};

// The vertices of the polytope {x : n . x <= max over the points of n . p, + margin} over the bounding
// directions n. By polarity about an interior point c: plane n . (x - c) <= b is the point n / b, the
// hull of those points has a facet m . q + o = 0 for each vertex x = c - m / o of the polytope.
std::optional<std::vector<glm::vec3>> bounding_polytope(std::span<const glm::vec3> points, float margin_mm) {
  const std::vector<glm::dvec3> directions = bounding_directions();
  std::vector<double> support(directions.size(), -std::numeric_limits<double>::infinity());
  glm::dvec3 center(0.0);
  for (const glm::vec3& point : points) {
    const glm::dvec3 p(point);
    center += p;
    for (std::size_t d = 0; d < directions.size(); ++d)
      support[d] = std::max(support[d], glm::dot(directions[d], p));
  }
  center /= double(points.size());

  std::vector<double> polar;
  for (std::size_t d = 0; d < directions.size(); ++d) {
    const double distance = support[d] + margin_mm - glm::dot(directions[d], center);  // >= margin
    const glm::dvec3 q = directions[d] / distance;
    polar.insert(polar.end(), {q.x, q.y, q.z});
  }
  const Qhull hull(polar, "");
  if (!hull.ok()) return std::nullopt;
  std::vector<glm::vec3> vertices;
  hull.for_each_facet([&](glm::dvec3 normal, double offset, const std::vector<int>&) {
    vertices.emplace_back(center - normal / offset);
  });
  return vertices;
}

}  // namespace

std::optional<OcclusionProxy> make_occlusion_proxy(std::span<const glm::vec3> world_positions,
                                                   float margin_mm) {
  if (world_positions.empty()) return std::nullopt;
  const std::optional<std::vector<glm::vec3>> polytope = bounding_polytope(world_positions, margin_mm);
  if (!polytope) return std::nullopt;

  // The sum with the cube: the hull of every vertex plus every cube corner, input point 8 i + j being
  // vertex i + corner j, at a reference pad about the size of the polytope's own edges, so that qhull's
  // arithmetic is well conditioned (any pad > 0 gives the same faces).
  glm::vec3 low = polytope->front(), high = low;
  for (const glm::vec3& v : *polytope) low = glm::min(low, v), high = glm::max(high, v);
  const float reference_pad_mm = 0.02f * glm::length(high - low);
  std::vector<double> coordinates;
  for (const glm::vec3& v : *polytope) {
    for (std::size_t j = 0; j < 8; ++j) {
      const glm::vec3 p = v + reference_pad_mm * cube_corner(j);
      coordinates.insert(coordinates.end(), {double(p.x), double(p.y), double(p.z)});
    }
  }
  const Qhull sum(coordinates, "Qt");
  if (!sum.ok()) return std::nullopt;

  OcclusionProxy proxy;
  std::unordered_map<int, std::uint32_t> proxy_index;  // input point -> proxy vertex
  const auto vertex_of = [&](int id) {
    const auto [slot, added] = proxy_index.try_emplace(id, static_cast<std::uint32_t>(proxy.corners.size()));
    if (added) {
      proxy.corners.push_back((*polytope)[static_cast<std::size_t>(id / 8)]);
      proxy.directions.push_back(cube_corner(static_cast<std::size_t>(id % 8)));
    }
    return slot->second;
  };
  sum.for_each_facet([&](glm::dvec3 normal, double, const std::vector<int>& ids) {
    if (ids.size() != 3) return;  // "Qt" makes every facet a triangle
    std::array<std::uint32_t, 3> t{vertex_of(ids[0]), vertex_of(ids[1]), vertex_of(ids[2])};
    // Counter-clockwise seen from outside, at the reference pad (qhull keeps no winding).
    const glm::vec3 a = proxy.vertex(t[0], reference_pad_mm), b = proxy.vertex(t[1], reference_pad_mm),
                    c = proxy.vertex(t[2], reference_pad_mm);
    if (glm::dot(glm::dvec3(glm::cross(b - a, c - a)), normal) < 0.0) std::swap(t[1], t[2]);
    proxy.indices.insert(proxy.indices.end(), t.begin(), t.end());
  });
  return proxy;
}

}  // namespace palpate::gl
