#include "palpate/core/phantom.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>
#include <numbers>
#include <queue>
#include <unordered_map>
#include <vector>

#include "mesh_expectations.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/mesh_topology.hpp"

namespace palpate {
namespace {

// The defaults take a fraction of a second each: build them once for all tests.
const Mesh& brain() {
  static const Mesh mesh = make_brain_phantom();
  return mesh;
}
const Mesh& skin() {
  static const Mesh mesh = make_skin_phantom();
  return mesh;
}

glm::dvec3 corner(const Mesh& m, std::size_t t, int k) {
  return glm::dvec3(m.positions_mm[m.indices[3 * t + k]]);
}

double min_angle_deg(const Mesh& m, std::size_t t) {
  double smallest = 180.0;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 e1 = glm::normalize(corner(m, t, (k + 1) % 3) - corner(m, t, k));
    const glm::dvec3 e2 = glm::normalize(corner(m, t, (k + 2) % 3) - corner(m, t, k));
    smallest =
        std::min(smallest, std::acos(std::clamp(glm::dot(e1, e2), -1.0, 1.0)) * 180.0 / std::numbers::pi);
  }
  return smallest;
}

void expect_closed_sphere(const Mesh& m, std::size_t vertices) {
  EXPECT_EQ(m.vertex_count(), vertices);
  EXPECT_EQ(m.triangle_count(), 2 * vertices - 4);
  EXPECT_EQ(m.normals.size(), vertices);
  test::expect_sphere_topology(m);
}

// Star-shaped about `centre` with outward normals: every triangle turns counter-clockwise seen from the
// centre, and the triangles' solid angles seen from it add up to exactly one sphere. Then each ray from
// the centre crosses the surface exactly once, so the surface cannot intersect itself; and each face
// normal (hence each area-weighted vertex normal) points away from the centre.
void expect_star_shaped(const Mesh& m, glm::dvec3 centre) {
  std::size_t turned = 0;
  double solid_angle = 0.0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::dvec3 a = corner(m, t, 0) - centre, b = corner(m, t, 1) - centre, c = corner(m, t, 2) - centre;
    const double volume = glm::dot(a, glm::cross(b, c));
    if (!(volume > 0.0)) ++turned;
    // Van Oosterom and Strackee's solid angle of a triangle.
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    solid_angle += 2.0 * std::atan2(volume, la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb +
                                                glm::dot(b, c) * la);
  }
  EXPECT_EQ(turned, 0u) << "triangles facing the star centre";
  EXPECT_NEAR(solid_angle, 4.0 * std::numbers::pi, 1e-6);
  std::size_t inward = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    if (!(glm::dot(glm::dvec3(m.normals[v]), glm::dvec3(m.positions_mm[v]) - centre) > 0.0)) ++inward;
    EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-5f);
  }
  EXPECT_EQ(inward, 0u) << "vertex normals pointing toward the star centre";
}

TEST(BrainPhantom, HasThePapersVertexCountAndIsOneClosedSurface) {
  expect_closed_sphere(brain(), 68856);
  expect_star_shaped(brain(), glm::dvec3(brain_phantom_star_centre));
}

TEST(SkinPhantom, HasThePapersVertexCountAndIsOneClosedSurface) {
  expect_closed_sphere(skin(), 90207);
  expect_star_shaped(skin(), glm::dvec3(skin_phantom_star_centre));
}

class PhantomCount : public ::testing::TestWithParam<std::size_t> {};

TEST_P(PhantomCount, HasExactlyTheVerticesAskedAndStaysValid) {
  const Mesh b = make_brain_phantom(GetParam());
  expect_closed_sphere(b, GetParam());
  expect_star_shaped(b, glm::dvec3(brain_phantom_star_centre));
  const Mesh s = make_skin_phantom(GetParam());
  expect_closed_sphere(s, GetParam());
  expect_star_shaped(s, glm::dvec3(skin_phantom_star_centre));
}

INSTANTIATE_TEST_SUITE_P(Counts, PhantomCount, ::testing::Values(500, 501, 2000, 9999, 30000));

TEST(Phantoms, TooFewVerticesAreAnError) {
  EXPECT_THROW(make_brain_phantom(phantom_min_vertices - 1), Error);
  EXPECT_THROW(make_skin_phantom(0), Error);
  try {
    make_brain_phantom(12);
    FAIL() << "no error for 12 vertices";
  } catch (const Error& e) {
    EXPECT_NE(e.detail().find("make_brain_phantom"), std::string::npos) << e.what();
    EXPECT_NE(e.detail().find("12"), std::string::npos) << e.what();
  }
}

TEST(Phantoms, AreTheSameBitForBitOnEveryCall) {
  const Mesh b = make_brain_phantom();
  EXPECT_TRUE(b.positions_mm == brain().positions_mm);
  EXPECT_TRUE(b.normals == brain().normals);
  EXPECT_TRUE(b.indices == brain().indices);
  const Mesh s = make_skin_phantom();
  EXPECT_TRUE(s.positions_mm == skin().positions_mm);
  EXPECT_TRUE(s.indices == skin().indices);
}

TEST(BrainPhantom, HasTheSizeOfAnAdultBrainAroundTheOrigin) {
  const Bounds b = bounds(brain());
  EXPECT_NEAR(b.size_mm().x, 140.0f, 4.0f);  // width
  EXPECT_NEAR(b.size_mm().y, 165.0f, 4.0f);  // length, front to back
  EXPECT_NEAR(b.size_mm().z, 115.0f, 5.0f);  // height
  EXPECT_LT(glm::length(b.center_mm()), 3.0f);
}

TEST(SkinPhantom, HasTheSizeOfAHeadWithAFaceInFront) {
  const Bounds b = bounds(skin());
  EXPECT_NEAR(b.size_mm().x, 158.0f, 8.0f);
  EXPECT_GT(b.max_mm.y, 105.0f);   // the nose
  EXPECT_LT(b.min_mm.z, -180.0f);  // the neck
  // Back of the head to the forehead, at the level of the brain's centre: about 190 mm.
  float back = 0.0f, front = 0.0f;
  for (const glm::vec3& p : skin().positions_mm) {
    if (std::abs(p.x) < 3.0f && std::abs(p.z) < 3.0f)
      back = std::min(back, p.y), front = std::max(front, p.y);
  }
  EXPECT_NEAR(front - back, 192.0f, 8.0f);
  // The nose is the frontmost part, in the middle, below the eyes.
  const auto nose = *std::max_element(skin().positions_mm.begin(), skin().positions_mm.end(),
                                      [](glm::vec3 p, glm::vec3 q) { return p.y < q.y; });
  EXPECT_LT(std::abs(nose.x), 3.0f);
  EXPECT_LT(nose.z, -40.0f);
  EXPECT_GT(nose.z, -90.0f);
}

// Distance from p to triangle (a, b, c): to its plane if p projects inside, else to the nearest edge.
double distance_to_triangle(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const glm::dvec3 q = p - glm::dot(p - a, n) * n;
  const bool inside_ab = glm::dot(glm::cross(b - a, q - a), n) >= 0.0;
  const bool inside_bc = glm::dot(glm::cross(c - b, q - b), n) >= 0.0;
  const bool inside_ca = glm::dot(glm::cross(a - c, q - c), n) >= 0.0;
  if (inside_ab && inside_bc && inside_ca) return glm::length(p - q);
  const auto to_segment = [&](glm::dvec3 u, glm::dvec3 v) {
    const double t = std::clamp(glm::dot(p - u, v - u) / glm::dot(v - u, v - u), 0.0, 1.0);
    return glm::length(p - (u + t * (v - u)));
  };
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

// A uniform grid of points for neighbour searches in the tests.
class PointGrid {
 public:
  PointGrid(const std::vector<glm::vec3>& points, float cell) : points_(points), cell_(cell) {
    for (std::uint32_t i = 0; i < points.size(); ++i) cells_[key(points[i])].push_back(i);
  }
  // Calls f(index) for every point within `radius` of p.
  void near(glm::vec3 p, float radius, const std::function<void(std::uint32_t)>& f) const {
    const int reach = int(std::ceil(radius / cell_));
    const glm::ivec3 c = glm::ivec3(glm::floor(p / cell_));
    for (int dz = -reach; dz <= reach; ++dz) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          const auto found = cells_.find(pack(c + glm::ivec3(dx, dy, dz)));
          if (found == cells_.end()) continue;
          for (std::uint32_t i : found->second) {
            if (glm::length(points_[i] - p) <= radius) f(i);
          }
        }
      }
    }
  }

 private:
  static std::int64_t pack(glm::ivec3 c) {
    return (std::int64_t(c.x + 4096) << 26) | (std::int64_t(c.y + 4096) << 13) | std::int64_t(c.z + 4096);
  }
  std::int64_t key(glm::vec3 p) const { return pack(glm::ivec3(glm::floor(p / cell_))); }

  const std::vector<glm::vec3>& points_;
  float cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

// Parity of the crossings of the upward ray from p with the mesh's triangles: odd means inside. The ray
// is nudged off the grid of float coordinates so that it meets no edge exactly.
bool inside(const Mesh& m, const std::vector<std::vector<std::uint32_t>>& columns, glm::dvec2 origin,
            double cell, int width, glm::dvec3 p) {
  const glm::dvec2 q(p.x + 1.234567e-4, p.y + 2.345678e-4);
  const glm::ivec2 c(int(std::floor((q.x - origin.x) / cell)), int(std::floor((q.y - origin.y) / cell)));
  if (c.x < 0 || c.y < 0 || c.x >= width || std::size_t(c.y) * std::size_t(width) >= columns.size())
    return false;
  int crossings = 0;
  for (std::uint32_t t : columns[std::size_t(c.y) * std::size_t(width) + std::size_t(c.x)]) {
    const glm::dvec3 a = corner(m, t, 0), b = corner(m, t, 1), d = corner(m, t, 2);
    const double area = (b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y);
    if (area == 0.0) continue;
    const double wb = ((q.x - a.x) * (d.y - a.y) - (d.x - a.x) * (q.y - a.y)) / area;
    const double wd = ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area;
    if (wb < 0.0 || wd < 0.0 || wb + wd > 1.0) continue;
    if (a.z + wb * (b.z - a.z) + wd * (d.z - a.z) > p.z) ++crossings;
  }
  return crossings % 2 == 1;
}

TEST(Phantoms, SkinEnclosesTheBrainWithRoomForSkullAndCsf) {
  const Mesh& s = skin();
  // Skin triangles binned by the columns (x, y) their bounding boxes cover.
  const Bounds sb = bounds(s);
  const double cell = 4.0;
  const glm::dvec2 origin(sb.min_mm.x - 1.0, sb.min_mm.y - 1.0);
  const int width = int((sb.size_mm().x + 2.0) / cell) + 1, height = int((sb.size_mm().y + 2.0) / cell) + 1;
  std::vector<std::vector<std::uint32_t>> columns(std::size_t(width) * std::size_t(height));
  for (std::uint32_t t = 0; t < s.triangle_count(); ++t) {
    glm::dvec2 lo(1e9), hi(-1e9);
    for (int k = 0; k < 3; ++k)
      lo = glm::min(lo, glm::dvec2(corner(s, t, k))), hi = glm::max(hi, glm::dvec2(corner(s, t, k)));
    for (int y = int((lo.y - origin.y) / cell); y <= int((hi.y - origin.y) / cell); ++y) {
      for (int x = int((lo.x - origin.x) / cell); x <= int((hi.x - origin.x) / cell); ++x) {
        columns[std::size_t(y) * std::size_t(width) + std::size_t(x)].push_back(t);
      }
    }
  }
  // The gap. A skin point within `margin` of a brain vertex lies in a triangle whose corners are all
  // within margin + (longest skin edge) of it: where skin vertices come that close, measure the distance
  // to their triangles exactly.
  double longest = 0.0;
  std::vector<std::vector<std::uint32_t>> triangles_at(s.vertex_count());
  for (std::uint32_t t = 0; t < s.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, glm::length(corner(s, t, k) - corner(s, t, (k + 1) % 3)));
      triangles_at[s.indices[3 * t + k]].push_back(t);
    }
  }
  constexpr double margin = 8.0;
  const PointGrid skin_points(s.positions_mm, 8.0f);
  std::size_t outside = 0, too_close = 0, measured = 0;
  double smallest_gap = 1e9;
  for (const glm::vec3& p : brain().positions_mm) {
    if (!inside(s, columns, origin, cell, width, glm::dvec3(p))) ++outside;
    std::vector<std::uint32_t> near;
    skin_points.near(p, float(margin + longest), [&](std::uint32_t v) { near.push_back(v); });
    if (near.empty()) continue;
    ++measured;
    double gap = 1e9;
    for (std::uint32_t v : near) {
      for (std::uint32_t t : triangles_at[v]) {
        gap = std::min(
            gap, distance_to_triangle(glm::dvec3(p), corner(s, t, 0), corner(s, t, 1), corner(s, t, 2)));
      }
    }
    smallest_gap = std::min(smallest_gap, gap);
    if (gap < margin) ++too_close;
  }
  EXPECT_EQ(outside, 0u) << "brain vertices outside the skin";
  EXPECT_EQ(too_close, 0u) << "brain vertices closer than " << margin << " mm to the skin; smallest gap "
                           << smallest_gap << " mm (" << measured << " measured)";
}

// Shortest paths along the mesh's edges (Dijkstra), from one vertex out to a limit.
class SurfaceDistances {
 public:
  explicit SurfaceDistances(const Mesh& m)
      : mesh_(m), next_(m.vertex_count()), distance_(m.vertex_count(), far) {
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      for (int k = 0; k < 3; ++k) next_[m.indices[3 * t + k]].push_back(m.indices[3 * t + (k + 1) % 3]);
    }
  }

  // Distances (mm) from `source` to the vertices up to `limit` away along the surface; infinity beyond.
  // Valid until the next call.
  const std::vector<double>& from(std::uint32_t source, double limit) {
    for (std::uint32_t v : touched_) distance_[v] = far;
    touched_.clear();
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    set(source, 0.0);
    queue.push({0.0, source});
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > distance_[v] || d > limit) continue;
      for (std::uint32_t w : next_[v]) {
        const double via =
            d + glm::length(glm::dvec3(mesh_.positions_mm[v]) - glm::dvec3(mesh_.positions_mm[w]));
        if (via < distance_[w]) set(w, via), queue.push({via, w});
      }
    }
    return distance_;
  }

 private:
  static constexpr double far = std::numeric_limits<double>::infinity();
  void set(std::uint32_t v, double d) {
    if (distance_[v] == far) touched_.push_back(v);
    distance_[v] = d;
  }
  const Mesh& mesh_;
  std::vector<std::vector<std::uint32_t>> next_;
  std::vector<double> distance_;
  std::vector<std::uint32_t> touched_;
};

TEST(BrainPhantom, HasADeepLongitudinalFissureOverTheTop) {
  // Over the middle of the top, the surface on the midline is the fissure's bottom.
  float top = -1e9f, midline = -1e9f;
  for (const glm::vec3& p : brain().positions_mm) {
    if (std::abs(p.y) > 20.0f) continue;
    top = std::max(top, p.z);
    if (std::abs(p.x) < 0.75f) midline = std::max(midline, p.z);
  }
  EXPECT_GT(top - midline, 20.0f);
  EXPECT_LT(top - midline, 30.0f);
}

TEST(BrainPhantom, FissureBanksAreCloseInSpaceButFarApartAlongTheSurface) {
  // The limitation of a Euclidean falloff the paper names: points a few mm apart across the fissure are
  // more than 30 mm apart along the surface, down one bank and up the other.
  const Mesh& b = brain();
  const PointGrid grid(b.positions_mm, 4.0f);
  SurfaceDistances surface(b);
  std::size_t pairs = 0;
  double closest = 1e9, furthest_along = 0.0;
  for (std::uint32_t v = 0; v < b.vertex_count() && pairs < 5; ++v) {
    const glm::vec3 p = b.positions_mm[v];
    // On the right bank, halfway down, over the middle of the top.
    if (p.x <= 0.0f || p.x > 4.0f || std::abs(p.y) > 10.0f || p.z < 42.0f || p.z > 50.0f) continue;
    std::uint32_t across = v;
    double nearest = 5.0;
    grid.near(p, 5.0f, [&](std::uint32_t w) {
      const double d = glm::length(b.positions_mm[w] - p);
      if (b.positions_mm[w].x < 0.0f && d < nearest) nearest = d, across = w;
    });
    if (across == v) continue;
    const double along = surface.from(v, 100.0)[across];
    EXPECT_GT(along, 30.0) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
    closest = std::min(closest, nearest);
    furthest_along = std::max(furthest_along, along);
    ++pairs;
  }
  EXPECT_EQ(pairs, 5u) << "no vertices on opposite banks within 5 mm";
  EXPECT_LT(closest, 5.0);
  EXPECT_GT(furthest_along, 30.0);
}

TEST(BrainPhantom, SulciMakeNeighboursInSpaceFarApartAlongTheSurface) {
  // Away from the fissure, the banks of narrow deep sulci: many vertices have another within 5 mm in
  // space that is more than 15 mm away along the surface (a smooth or egg-crate surface has none).
  const Mesh& b = brain();
  const PointGrid grid(b.positions_mm, 4.0f);
  SurfaceDistances surface(b);
  std::size_t seeds = 0, across_sulcus = 0;
  for (std::uint32_t v = 0; v < b.vertex_count(); v += 53) {
    if (std::abs(b.positions_mm[v].x) < 30.0f) continue;
    ++seeds;
    const std::vector<double>& along = surface.from(v, 15.0);
    bool found = false;
    grid.near(b.positions_mm[v], 5.0f, [&](std::uint32_t w) { found = found || along[w] > 15.0; });
    if (found) ++across_sulcus;
  }
  ASSERT_GT(seeds, 300u);
  EXPECT_GT(double(across_sulcus) / double(seeds), 0.15) << across_sulcus << " of " << seeds;
}

// Triangle quality. A folded surface at a fixed vertex count has some stretched triangles where grooves
// end and meet; the bounds hold every triangle away from a needle (2 degrees: an aspect ratio of about 30)
// and nearly all near equilateral. Adjacent triangles turn sharply at the bottom of a sulcus about 2 mm
// wide sampled every 1.3 mm, but only there: few edges turn more than 150 degrees.
struct QualityBounds {
  double min_angle_deg, angle_at_1_percent_deg;
  double sharp_turn_deg, sharp_turn_share;  // at most this share of edges turn more than sharp_turn_deg
};

void expect_quality(const Mesh& m, QualityBounds bounds) {
  std::vector<double> angles(m.triangle_count());
  for (std::size_t t = 0; t < m.triangle_count(); ++t) angles[t] = min_angle_deg(m, t);
  std::sort(angles.begin(), angles.end());
  EXPECT_GE(angles.front(), bounds.min_angle_deg);
  EXPECT_GE(angles[angles.size() / 100], bounds.angle_at_1_percent_deg);
  EXPECT_GE(angles[angles.size() / 2], 40.0);  // the median triangle is near equilateral
  // The turn between the normals of the two triangles at each edge.
  std::unordered_map<std::uint64_t, std::uint32_t> first;
  std::size_t edges = 0, sharp = 0;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = m.indices[3 * t + k], b = m.indices[3 * t + (k + 1) % 3];
      const auto [found, inserted] = first.try_emplace(std::min(a, b) << 32 | std::max(a, b), t);
      if (inserted) continue;
      const auto normal = [&](std::size_t u) {
        return glm::normalize(
            glm::cross(corner(m, u, 1) - corner(m, u, 0), corner(m, u, 2) - corner(m, u, 0)));
      };
      const double turn = std::acos(std::clamp(glm::dot(normal(t), normal(found->second)), -1.0, 1.0));
      ++edges;
      if (turn * 180.0 / std::numbers::pi > bounds.sharp_turn_deg) ++sharp;
    }
  }
  EXPECT_EQ(edges, 3 * m.vertex_count() - 6);
  EXPECT_LE(double(sharp) / double(edges), bounds.sharp_turn_share) << sharp << " of " << edges << " edges";
}

TEST(BrainPhantom, TrianglesAreWellShaped) {
  expect_quality(brain(), {2.0, 20.0, 150.0, 2e-4});
}

TEST(SkinPhantom, TrianglesAreWellShaped) {
  expect_quality(skin(), {12.0, 18.0, 90.0, 0.0});
}

}  // namespace
}  // namespace palpate
