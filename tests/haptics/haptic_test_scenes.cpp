#include "haptic_test_scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <tuple>

#include "palpate/core/shapes.hpp"

namespace palpate::test {

Scene scene_of(const std::string& name, Mesh mesh) {
  Scene scene;
  scene.objects.push_back({name, std::move(mesh), glm::mat4(1.0f), {}, {}});
  return scene;
}

Mesh make_hollow_box(float outer_mm, float inner_mm) {
  Mesh mesh = make_box(glm::vec3(outer_mm));
  Mesh cavity = make_box(glm::vec3(inner_mm));
  for (std::size_t t = 0; t < cavity.indices.size(); t += 3)
    std::swap(cavity.indices[t + 1], cavity.indices[t + 2]);
  for (glm::vec3& n : cavity.normals) n = -n;
  append_mesh(mesh, cavity);
  return mesh;
}

Mesh make_comb(int teeth, float tooth_width_mm, float gap_mm, float tooth_height_mm, float base_height_mm,
               float depth_mm) {
  const float pitch = tooth_width_mm + gap_mm;
  const float width = float(teeth) * tooth_width_mm + float(teeth - 1) * gap_mm;
  const float top = base_height_mm + tooth_height_mm;
  std::vector<float> xs;  // every tooth side
  for (int k = 0; k < teeth; ++k) xs.insert(xs.end(), {float(k) * pitch, float(k) * pitch + tooth_width_mm});
  // The outline, counter-clockwise seen from +z, with a vertex wherever a cap triangle has one.
  std::vector<glm::vec2> outline;
  for (float x : xs) outline.push_back({x, 0.0f});
  for (int k = teeth - 1; k >= 0; --k) {
    const float left = float(k) * pitch, right = left + tooth_width_mm;
    outline.insert(outline.end(),
                   {{right, base_height_mm}, {right, top}, {left, top}, {left, base_height_mm}});
  }
  // Cap quads: the base cut at every tooth side, then the teeth.
  std::vector<std::array<glm::vec2, 4>> quads;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    quads.push_back(
        {{{xs[i], 0.0f}, {xs[i + 1], 0.0f}, {xs[i + 1], base_height_mm}, {xs[i], base_height_mm}}});
  }
  for (int k = 0; k < teeth; ++k) {
    const float left = float(k) * pitch, right = left + tooth_width_mm;
    quads.push_back({{{left, base_height_mm}, {right, base_height_mm}, {right, top}, {left, top}}});
  }
  Mesh mesh;
  std::map<std::tuple<float, float, float>, std::uint32_t> index;
  const auto vertex = [&](glm::vec2 p, float z) {
    const auto key = std::make_tuple(p.x - 0.5f * width, p.y, z - 0.5f * depth_mm);
    const auto [it, added] = index.emplace(key, std::uint32_t(mesh.positions.size()));
    if (added) mesh.positions.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key)});
    return it->second;
  };
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
  };
  for (const auto& q : quads) {
    quad(vertex(q[0], depth_mm), vertex(q[1], depth_mm), vertex(q[2], depth_mm),
         vertex(q[3], depth_mm));                                                          // +z cap
    quad(vertex(q[0], 0.0f), vertex(q[3], 0.0f), vertex(q[2], 0.0f), vertex(q[1], 0.0f));  // -z cap
  }
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const glm::vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
    quad(vertex(a, 0.0f), vertex(b, 0.0f), vertex(b, depth_mm), vertex(a, depth_mm));
  }
  compute_vertex_normals(mesh);
  return mesh;
}

InsideReference::InsideReference(const Scene& scene) {
  for (const SceneObject& object : scene.objects) {
    if (!object.material.touchable) continue;
    const auto world = [&](std::uint32_t i) {
      return glm::dvec3(glm::vec3(object.transform * glm::vec4(object.mesh.positions[i], 1.0f)));
    };
    for (std::size_t t = 0; t + 2 < object.mesh.indices.size(); t += 3) {
      Triangle tri{world(object.mesh.indices[t]),
                   world(object.mesh.indices[t + 1]),
                   world(object.mesh.indices[t + 2]),
                   {}};
      tri.normal = glm::cross(tri.b - tri.a, tri.c - tri.a);
      triangles_.push_back(tri);
    }
  }
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Triangle& t : triangles_) {
    for (const glm::dvec3& v : {t.a, t.b, t.c}) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  }
  const int cells = std::clamp(int(std::sqrt(double(triangles_.size()) / 2.0)), 1, 512);
  for (int axis = 0; axis < 3; ++axis) {
    Grid& g = grids_[axis];
    g.axis = axis;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    g.cells = cells;
    g.origin = {lo[u], lo[v]};
    g.cell = glm::max(glm::dvec2(hi[u] - lo[u], hi[v] - lo[v]) / double(cells), glm::dvec2(1e-9));
    g.bins.assign(std::size_t(cells * cells), {});
    for (std::uint32_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      const double u0 = std::min({t.a[u], t.b[u], t.c[u]}), u1 = std::max({t.a[u], t.b[u], t.c[u]});
      const double v0 = std::min({t.a[v], t.b[v], t.c[v]}), v1 = std::max({t.a[v], t.b[v], t.c[v]});
      const auto cell_of = [&](double x, double origin, double size) {
        return std::clamp(int(std::floor((x - origin) / size)), 0, cells - 1);
      };
      for (int j = cell_of(v0, g.origin.y, g.cell.y); j <= cell_of(v1, g.origin.y, g.cell.y); ++j) {
        for (int k = cell_of(u0, g.origin.x, g.cell.x); k <= cell_of(u1, g.origin.x, g.cell.x); ++k) {
          g.bins[std::size_t(j * cells + k)].push_back(i);
        }
      }
    }
  }
}

int InsideReference::axis_winding(const Grid& g, glm::dvec3 p) const {
  const int a = g.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  p[u] += 1.41421356e-9;
  p[v] += 0.73205081e-9;
  const int k = int(std::floor((p[u] - g.origin.x) / g.cell.x)),
            j = int(std::floor((p[v] - g.origin.y) / g.cell.y));
  if (k < 0 || j < 0 || k >= g.cells || j >= g.cells) return 0;
  int winding = 0;
  for (const std::uint32_t i : g.bins[std::size_t(j * g.cells + k)]) {
    const Triangle& t = triangles_[i];
    if (t.normal[a] == 0.0) continue;  // seen edge-on
    // Is (p_u, p_v) inside the triangle's projection? Signed areas all of one sign.
    const auto side = [&](const glm::dvec3& e0, const glm::dvec3& e1) {
      return (e1[u] - e0[u]) * (p[v] - e0[v]) - (e1[v] - e0[v]) * (p[u] - e0[u]);
    };
    const double s0 = side(t.a, t.b), s1 = side(t.b, t.c), s2 = side(t.c, t.a);
    if (!((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0))) continue;
    // The crossing lies ahead along +axis when p is behind the plane as seen along +axis.
    const double behind = glm::dot(t.normal, p - t.a);
    if (behind * t.normal[a] < 0.0) winding += t.normal[a] > 0.0 ? 1 : -1;
  }
  return winding;
}

int InsideReference::winding(const glm::dvec3& p) const {
  const int w0 = axis_winding(grids_[0], p), w1 = axis_winding(grids_[1], p), w2 = axis_winding(grids_[2], p);
  if (w0 == w1 || w0 == w2) return w0;
  return w1;  // w1 == w2, or all differ (then any answer is as good)
}

bool InsideReference::segment_meets_surface(const glm::dvec3& from, const glm::dvec3& to) const {
  const glm::dvec3 d = to - from;
  for (const Triangle& t : triangles_) {
    // Moller-Trumbore, both sides, closed intervals.
    const glm::dvec3 e1 = t.b - t.a, e2 = t.c - t.a, pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0) continue;
    const glm::dvec3 tv = from - t.a;
    const double uu = glm::dot(tv, pv) / det;
    if (uu < 0.0 || uu > 1.0) continue;
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double vv = glm::dot(d, qv) / det;
    if (vv < 0.0 || uu + vv > 1.0) continue;
    const double s = glm::dot(e2, qv) / det;
    if (s >= 0.0 && s <= 1.0) return true;
  }
  return false;
}

}  // namespace palpate::test
