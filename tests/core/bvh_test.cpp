#include "palpate/core/bvh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <random>
#include <vector>

#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

Scene scene_of(Mesh mesh, glm::mat4 transform = glm::mat4(1.0f)) {
  Scene scene;
  scene.objects.push_back({"object", std::move(mesh), transform, {}, {}});
  return scene;
}

struct WorldTriangle {
  glm::dvec3 a, b, c;
  int object, triangle;
};

std::vector<WorldTriangle> world_triangles(const Scene& scene) {
  std::vector<WorldTriangle> out;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const SceneObject& obj = scene.objects[o];
    if (!obj.material.touchable) continue;
    const auto at = [&](std::size_t corner) {
      return glm::dvec3(
          glm::vec3(obj.transform * glm::vec4(obj.mesh.positions_mm[obj.mesh.indices[corner]], 1.0f)));
    };
    for (std::size_t t = 0; t < obj.mesh.triangle_count(); ++t)
      out.push_back({at(3 * t), at(3 * t + 1), at(3 * t + 2), int(o), int(t)});
  }
  return out;
}

// Reference segment cast: Moller-Trumbore over every triangle (a different algorithm from the BVH's).
struct ReferenceHit {
  double t = 2.0;
  int object = -1, triangle = -1;
};

ReferenceHit brute_first_hit(const std::vector<WorldTriangle>& tris, glm::dvec3 from, glm::dvec3 to,
                             bool front_only) {
  ReferenceHit best;
  const glm::dvec3 d = to - from;
  for (const WorldTriangle& tri : tris) {
    const glm::dvec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
    const glm::dvec3 pv = glm::cross(d, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0 || (front_only && det < 0.0)) continue;  // det > 0: d runs against the normal e1 x e2
    const glm::dvec3 tv = from - tri.a;
    const double u = glm::dot(tv, pv) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double v = glm::dot(d, qv) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, qv) / det;
    if (t < 0.0 || t > 1.0) continue;
    if (t < best.t) best = {t, tri.object, tri.triangle};
  }
  return best;
}

// Reference point-triangle distance: the plane distance when the projection falls inside, else the
// nearest of the three edges (Ericson's Voronoi-region walk is what the BVH uses).
double segment_distance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 ab = b - a;
  const double s = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + s * ab));
}

double brute_distance(const std::vector<WorldTriangle>& tris, glm::dvec3 p) {
  double best = 1e300;
  for (const WorldTriangle& tri : tris) {
    const glm::dvec3 n = glm::normalize(glm::cross(tri.b - tri.a, tri.c - tri.a));
    const glm::dvec3 q = p - glm::dot(p - tri.a, n) * n;
    const bool inside = glm::dot(glm::cross(tri.b - tri.a, q - tri.a), n) >= 0 &&
                        glm::dot(glm::cross(tri.c - tri.b, q - tri.b), n) >= 0 &&
                        glm::dot(glm::cross(tri.a - tri.c, q - tri.c), n) >= 0;
    const double d = inside ? std::abs(glm::dot(p - tri.a, n))
                            : std::min({segment_distance(p, tri.a, tri.b), segment_distance(p, tri.b, tri.c),
                                        segment_distance(p, tri.c, tri.a)});
    best = std::min(best, d);
  }
  return best;
}

glm::dvec3 random_point(std::mt19937& rng, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  return {u(rng), u(rng), u(rng)};
}

TEST(Bvh, EmptySceneHasNoTrianglesAndNeverHits) {
  const Bvh bvh = Bvh::build(Scene{});
  EXPECT_EQ(bvh.triangle_count(), 0u);
  EXPECT_FALSE(bvh.first_hit({0, 0, -1}, {0, 0, 1}).hit());
  EXPECT_FALSE(bvh.closest_point({0, 0, 0}, 1e9).hit());
}

// Two grids of right triangles (longest edge: the cell's diagonal), the finer one the more numerous,
// then the coarser: the typical size is the diagonal of the more numerous, whichever object it is.
TEST(Bvh, TypicalTriangleSizeIsTheMedianLongestEdge) {
  EXPECT_EQ(Bvh::build(Scene{}).typical_triangle_size_mm(), 0.0f);
  for (const std::size_t coarse_cells : {std::size_t(20), std::size_t(60)}) {
    Scene scene;
    scene.objects.push_back({"fine", make_grid(10.0f, 40), glm::mat4(1.0f), {}, {}});  // 3,200 triangles
    scene.objects.push_back({"coarse", make_grid(100.0f, coarse_cells), glm::mat4(1.0f), {}, {}});
    const Bvh bvh = Bvh::build(scene);
    const double fine = 10.0 / 40.0 * std::sqrt(2.0), coarse = 100.0 / double(coarse_cells) * std::sqrt(2.0);
    const double expected = 2 * coarse_cells * coarse_cells > 3200 ? coarse : fine;
    EXPECT_NEAR(bvh.typical_triangle_size_mm(), expected, 1e-6 * expected) << coarse_cells;
  }
}

TEST(Bvh, EveryTriangleSitsInExactlyOneLeafInsideEveryBoxAbove) {
  const Scene scene = scene_of(make_bumpy_sphere(50.0f, 1.5f, 20000));
  const Bvh bvh = Bvh::build(scene);
  ASSERT_EQ(bvh.triangle_count(), scene.triangle_count());
  const auto& nodes = bvh.nodes();
  std::vector<int> seen(bvh.triangle_count(), 0);
  std::vector<int> ids(bvh.triangle_count(), 0);
  // Walk with the parent's box, checking containment.
  struct Item {
    std::uint32_t node;
    glm::vec3 min, max;
    std::size_t depth;
  };
  std::vector<Item> todo{{0, nodes[0].min, nodes[0].max, 1}};
  std::size_t deepest = 0;
  while (!todo.empty()) {
    const Item item = todo.back();
    todo.pop_back();
    const Bvh::Node& n = nodes[item.node];
    deepest = std::max(deepest, item.depth);
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(n.min, item.min)) &&
                glm::all(glm::lessThanEqual(n.max, item.max)));
    if (n.count > 0) {
      EXPECT_LE(n.count, 4u);
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        ++seen[i];
        ++ids[bvh.triangle(i).id];
        for (const glm::vec3& v : bvh.triangle(i).vertices) {
          EXPECT_TRUE(glm::all(glm::greaterThanEqual(v, n.min)) && glm::all(glm::lessThanEqual(v, n.max)));
        }
      }
    } else {
      ASSERT_LT(n.first + 1, nodes.size());
      todo.push_back({n.first, n.min, n.max, item.depth + 1});
      todo.push_back({n.first + 1, n.min, n.max, item.depth + 1});
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }));
  EXPECT_TRUE(std::all_of(ids.begin(), ids.end(), [](int k) { return k == 1; }));
  EXPECT_LE(deepest, Bvh::max_depth);
  // Compact: nodes and triangles together stay well under 100 bytes per triangle.
  EXPECT_LT(double(bvh.memory_bytes()) / double(bvh.triangle_count()), 100.0);
  EXPECT_EQ(sizeof(Bvh::Node), 32u);
  EXPECT_EQ(sizeof(Bvh::Triangle), 56u);
}

TEST(Bvh, SegmentCastMatchesBruteForce) {
  const Scene scene = scene_of(make_bumpy_sphere(50.0f, 1.5f, 4000));
  const Bvh bvh = Bvh::build(scene);
  const auto tris = world_triangles(scene);
  std::mt19937 rng(7);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 from = random_point(rng, 70.0), to = random_point(rng, 70.0);
    for (bool front_only : {true, false}) {
      const ReferenceHit expected = brute_first_hit(tris, from, to, front_only);
      const BvhHit got = bvh.first_hit(from, to, front_only ? Faces::front : Faces::both);
      ASSERT_EQ(got.hit(), expected.object >= 0) << "segment " << i;
      if (!got.hit()) continue;
      ++hits;
      EXPECT_NEAR(got.t, expected.t, 1e-6) << "segment " << i;
      // Ties on a shared edge may pick either triangle; elsewhere the triangle is the same.
      if (got.triangle != expected.triangle) {
        EXPECT_NEAR(got.t, expected.t, 1e-9);
      }
      const glm::dvec3 point = from + double(got.t) * (to - from);
      EXPECT_NEAR(glm::length(glm::dvec3(got.point_mm) - point), 0.0, 1e-4);
      if (front_only) {
        EXPECT_LT(glm::dot(glm::dvec3(got.normal), to - from), 0.0);
      }
    }
  }
  EXPECT_GT(hits, 2000);  // the sample really exercises hits
}

TEST(Bvh, ClosestPointMatchesBruteForce) {
  const Scene scene = scene_of(make_bumpy_sphere(50.0f, 1.5f, 4000));
  const Bvh bvh = Bvh::build(scene);
  const auto tris = world_triangles(scene);
  std::mt19937 rng(11);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 p = random_point(rng, 70.0);
    const double expected = brute_distance(tris, p);
    const BvhHit got = bvh.closest_point(p, 1e9);
    ASSERT_TRUE(got.hit());
    EXPECT_NEAR(got.distance_mm, expected, 1e-4) << "point " << i;
    EXPECT_NEAR(glm::length(glm::dvec3(got.point_mm) - p), expected, 1e-4);
    // A search radius below the distance finds nothing; one just above finds it.
    EXPECT_FALSE(bvh.closest_point(p, expected * 0.99).hit());
    EXPECT_TRUE(bvh.closest_point(p, expected * 1.01 + 1e-6).hit());
  }
}

// Segments aimed exactly through vertices and edge midpoints of a closed mesh must hit it: the edge
// test is watertight.
TEST(Bvh, SegmentsThroughVerticesAndEdgesNeverSlipThrough) {
  const Mesh mesh = make_sphere(30.0f, 642);
  const Bvh bvh = Bvh::build(scene_of(mesh));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  int tested = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::vec3 a = mesh.positions_mm[mesh.indices[3 * t]],
                    b = mesh.positions_mm[mesh.indices[3 * t + 1]];
    for (const glm::vec3 target : {a, 0.5f * (a + b)}) {
      // From outside toward (through) the target, at several angles.
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 out =
            glm::normalize(target + 10.0f * glm::vec3(jitter(rng), jitter(rng), jitter(rng)));
        const glm::dvec3 from = glm::dvec3(target) + 20.0 * glm::dvec3(out);
        const glm::dvec3 to = glm::dvec3(target) + (glm::dvec3(target) - from) * 0.5;  // ends inside
        EXPECT_TRUE(bvh.first_hit(from, to).hit()) << "triangle " << t << " angle " << k;
        ++tested;
      }
    }
  }
  EXPECT_GT(tested, 5000);
}

TEST(Bvh, AppliesTransformsSkipsUntouchableObjectsAndNamesTheObject) {
  Scene scene;
  scene.objects.push_back({"ghost", make_box({10, 10, 10}), glm::mat4(1.0f), {}, {}});
  scene.objects.back().material.touchable = false;
  scene.objects.push_back(
      {"left", make_box({10, 10, 10}), glm::translate(glm::mat4(1.0f), {-20, 0, 0}), {}, {}});
  scene.objects.push_back(
      {"right", make_box({10, 10, 10}), glm::translate(glm::mat4(1.0f), {20, 0, 0}), {}, {}});
  const Bvh bvh = Bvh::build(scene);
  EXPECT_EQ(bvh.triangle_count(), 24u);
  // Down onto the right box's top face (z = 5) at x = 21.
  const BvhHit right = bvh.first_hit({21, 1, 20}, {21, 1, -20});
  ASSERT_TRUE(right.hit());
  EXPECT_EQ(right.object, 2);
  EXPECT_NEAR(right.point_mm.z, 5.0f, 1e-5f);
  EXPECT_NEAR(right.t, 15.0f / 40.0f, 1e-6f);
  EXPECT_EQ(right.normal, glm::vec3(0, 0, 1));
  const Mesh& box = scene.objects[2].mesh;
  const std::uint32_t* corners = &box.indices[3 * std::size_t(right.triangle)];
  for (int k = 0; k < 3; ++k) EXPECT_EQ(box.positions_mm[corners[k]].z, 5.0f);  // a top-face triangle
  // The untouchable box at the origin is not there.
  EXPECT_FALSE(bvh.first_hit({0, 0, 20}, {0, 0, -20}).hit());
  const BvhHit left = bvh.first_hit({-21, 1, 20}, {-21, 1, -20});
  ASSERT_TRUE(left.hit());
  EXPECT_EQ(left.object, 1);
  // From inside the left box, only its back faces are in the way: front-only passes, both-sided hits.
  EXPECT_FALSE(bvh.first_hit({-20, 0, 0}, {-20, 0, 20}, Faces::front).hit());
  EXPECT_TRUE(bvh.first_hit({-20, 0, 0}, {-20, 0, 20}, Faces::both).hit());
}

// The reference: for each edge of each triangle, the other triangles of its object that use both of the
// edge's vertex indices, counted over the whole mesh.
TEST(Bvh, NeighboursAreTheOneTriangleAcrossEachEdgeInTheOppositeOrder) {
  Scene scene;
  scene.objects.push_back({"ghost", make_bumpy_sphere(5.0f, 0.2f, 200), glm::mat4(1.0f), {}, {}});
  scene.objects.back().material.touchable = false;
  scene.objects.push_back({"sphere", make_bumpy_sphere(50.0f, 1.5f, 4000), glm::mat4(1.0f), {}, {}});
  Mesh odd;  // a border, a fin on a shared edge, a misoriented pair and a split vertex
  odd.positions_mm = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},  {0, 1, 0}, {0, 0, 1}, {0.5f, 0.5f, 1}, {3, 0, 0},
                      {4, 0, 0}, {4, 1, 0}, {4, -1, 0}, {6, 0, 0}, {7, 0, 0}, {7, 1, 0},       {7, 1, 0}};
  odd.indices = {0,  1,  2,  0,  2,  3,    // a square: 0-2 shared, the rest a border
                 2,  0,  5,                // ... and a fin on 0-2, in the first triangle's order
                 1,  4,  2,                // across the square's edge 1-2
                 6,  7,  8,  6,  7,  9,    // 6-7 in the same order twice
                 10, 11, 12, 10, 13, 11};  // across 10-11; 11-12 and 13-11 meet only through positions
  odd.normals.assign(odd.positions_mm.size(), glm::vec3(0, 0, 1));
  scene.objects.push_back({"odd", odd, glm::translate(glm::mat4(1.0f), {100, 0, 0}), {}, {}});
  const Bvh bvh = Bvh::build(scene);
  ASSERT_EQ(bvh.triangle_count(), 4000u + 8u);

  std::map<std::pair<int, int>, std::uint32_t> primitive_of;
  for (std::uint32_t i = 0; i < bvh.triangle_count(); ++i) {
    const Bvh::Location where = bvh.locate(i);
    primitive_of[{where.object, where.triangle}] = i;
  }
  int across = 0, none = 0;
  for (std::uint32_t i = 0; i < bvh.triangle_count(); ++i) {
    const Bvh::Location where = bvh.locate(i);
    const std::vector<std::uint32_t>& indices = scene.objects[std::size_t(where.object)].mesh.indices;
    const std::uint32_t* corners = &indices[3 * std::size_t(where.triangle)];
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = corners[e], b = corners[(e + 1) % 3];
      int sharing = 0;
      std::uint32_t expected = Bvh::no_neighbour;
      for (std::size_t u = 0; u < indices.size() / 3; ++u) {
        if (int(u) == where.triangle) continue;
        const std::uint32_t* other = &indices[3 * u];
        if (std::find(other, other + 3, a) == other + 3) continue;
        for (int m = 0; m < 3; ++m) {
          if (other[m] != b) continue;
          ++sharing;
          if (other[(m + 1) % 3] == a) expected = primitive_of[{where.object, int(u)}];
        }
      }
      if (sharing != 1) expected = Bvh::no_neighbour;
      ASSERT_EQ(bvh.neighbour(i, e), expected)
          << "object " << where.object << " triangle " << where.triangle << " edge " << e;
      // The edge's corners in the BVH's copy are the mesh's, and the neighbour holds them reversed.
      if (expected != Bvh::no_neighbour) {
        const auto& mine = bvh.triangle(i).vertices;
        const auto& theirs = bvh.triangle(expected).vertices;
        bool reversed = false;
        for (int m = 0; m < 3; ++m) {
          reversed = reversed || (theirs[std::size_t(m)] == mine[std::size_t((e + 1) % 3)] &&
                                  theirs[std::size_t((m + 1) % 3)] == mine[std::size_t(e)]);
        }
        EXPECT_TRUE(reversed);
      }
      expected == Bvh::no_neighbour ? ++none : ++across;
    }
  }
  EXPECT_EQ(across, 3 * 4000 + 4) << "every edge of the closed sphere, and 1-2 and 10-11 twice";
  EXPECT_EQ(none, 3 * 8 - 4);
}

// A look from just above a vertex of a closed surface meets one of the faces around it: going round the
// vertex must give the tree's answer, triangle and parameter, bit for bit.
TEST(Bvh, AroundAVertexALookMeetsWhatTheTreeFinds) {
  const Scene scene = scene_of(make_bumpy_sphere(50.0f, 1.5f, 20000));
  const Bvh bvh = Bvh::build(scene);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(bvh.triangle_count() - 1));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int met = 0, missed = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t primitive = pick(rng);
    const int corner = int(rng() % 3);
    const Bvh::Triangle& tri = bvh.triangle(primitive);
    const glm::dvec3 v(tri.vertices[std::size_t(corner)]);
    const glm::dvec3 normal =
        glm::normalize(glm::cross(glm::dvec3(tri.vertices[1]) - glm::dvec3(tri.vertices[0]),
                                  glm::dvec3(tri.vertices[2]) - glm::dvec3(tri.vertices[0])));
    // 1 um above the vertex, toward a point up to 3 mm in and 2 mm aside.
    const glm::dvec3 from = v + 1e-3 * normal;
    const glm::dvec3 to =
        v - 3.0 * std::abs(unit(rng)) * normal + 2.0 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    const BvhHit around = bvh.first_hit_around(from, to, primitive, v, 1e-6);
    const BvhHit tree = bvh.first_hit(from, to, Faces::front, 1e-6);
    if (!around.hit()) {
      ++missed;
      continue;
    }
    ++met;
    ASSERT_TRUE(tree.hit()) << i;
    ASSERT_EQ(around.primitive, tree.primitive) << i;
    ASSERT_EQ(around.t, tree.t) << i;
    ASSERT_EQ(around.point_mm, tree.point_mm) << i;
    EXPECT_EQ(around.object, 0);
  }
  EXPECT_GT(met, 15000) << "most looks from a vertex meet a face around it";
  EXPECT_GT(missed, 2000) << "those that leave along the surface meet none";
  // Objects the mask leaves out are not met.
  const std::uint8_t none[] = {0};
  const Bvh::Triangle& tri = bvh.triangle(0);
  const glm::dvec3 v(tri.vertices[0]);
  EXPECT_TRUE(bvh.first_hit_around(v * 1.001, v * 0.9, 0, v, 1e-6).hit());
  EXPECT_FALSE(bvh.first_hit_around(v * 1.001, v * 0.9, 0, v, 1e-6, none).hit());
  // A point that is not one of the triangle's corners has no faces around it.
  const glm::dvec3 beside = (v + glm::dvec3(tri.vertices[1])) * 0.5;
  EXPECT_FALSE(bvh.first_hit_around(beside * 1.001, beside * 0.9, 0, beside, 1e-6).hit());
}

// Where the faces do not close around the vertex, going round it cannot tell what else the look meets.
TEST(Bvh, AroundABorderOrSplitVertexThereIsNoAnswer) {
  // Each triangle with a corner at `at`, and a look straight down through each one's middle from 1 um
  // above it, starting from each.
  const auto looks_around = [](const Bvh& bvh, glm::dvec3 at) {
    std::vector<std::uint32_t> around;
    for (std::uint32_t i = 0; i < bvh.triangle_count(); ++i) {
      for (const glm::vec3& corner : bvh.triangle(i).vertices) {
        if (glm::dvec3(corner) == at) around.push_back(i);
      }
    }
    int hits = 0, looks = 0;
    for (const std::uint32_t start : around) {
      for (const std::uint32_t through : around) {
        const auto& corners = bvh.triangle(through).vertices;
        const glm::dvec3 middle =
            (glm::dvec3(corners[0]) + glm::dvec3(corners[1]) + glm::dvec3(corners[2])) / 3.0;
        hits += bvh.first_hit_around(middle + glm::dvec3(0, 0, 1e-3), middle - glm::dvec3(0, 0, 1), start, at,
                                     1e-6)
                    .hit();
        ++looks;
      }
    }
    return std::pair{hits, looks};
  };
  const Bvh grid = Bvh::build(scene_of(make_grid(10.0f, 4)));
  EXPECT_EQ(looks_around(grid, {0, 0, 0}), std::pair(36, 36)) << "six faces around an inner vertex";
  EXPECT_EQ(looks_around(grid, {-5, 0, 0}), std::pair(0, 9)) << "three on the border";
  // Straight down through the edge between two faces around the inner vertex: the tie goes to the lower
  // index, as in the tree.
  std::uint32_t inner = 0;
  while (glm::dvec3(grid.triangle(inner).vertices[0]) != glm::dvec3(0) &&
         glm::dvec3(grid.triangle(inner).vertices[1]) != glm::dvec3(0) &&
         glm::dvec3(grid.triangle(inner).vertices[2]) != glm::dvec3(0))
    ++inner;
  const BvhHit tie = grid.first_hit_around({1.0, 0.0, 1e-3}, {1.0, 0.0, -1}, inner, glm::dvec3(0), 1e-6);
  ASSERT_TRUE(tie.hit());
  EXPECT_EQ(tie.primitive, grid.first_hit({1.0, 0.0, 1e-3}, {1.0, 0.0, -1}, Faces::front, 1e-6).primitive);

  Mesh split = make_grid(10.0f, 4);  // every triangle with corners of its own
  Mesh apart;
  for (const std::uint32_t i : split.indices) {
    apart.indices.push_back(std::uint32_t(apart.positions_mm.size()));
    apart.positions_mm.push_back(split.positions_mm[i]);
    apart.normals.push_back(split.normals[i]);
  }
  EXPECT_EQ(looks_around(Bvh::build(scene_of(apart)), {0, 0, 0}), std::pair(0, 36));
}

// Going round a vertex lists every triangle with a corner there (found here by looking at them all),
// each once, in order: each shares with the one before the edge from the vertex to that one's next
// corner.
TEST(Bvh, FacesAroundAVertexAreAllThoseWithACornerThereInOrderRoundIt) {
  const Bvh bvh = Bvh::build(scene_of(make_bumpy_sphere(50.0f, 1.5f, 20000)));
  std::mt19937 rng(12);
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(bvh.triangle_count() - 1));
  std::array<std::uint32_t, 16> around;
  std::map<std::size_t, int> valences;
  for (int i = 0; i < 2000; ++i) {
    const std::uint32_t primitive = pick(rng);
    const glm::vec3 corner = bvh.triangle(primitive).vertices[rng() % 3];
    std::vector<std::uint32_t> with_corner;
    for (std::uint32_t t = 0; t < bvh.triangle_count(); ++t) {
      const auto& v = bvh.triangle(t).vertices;
      if (v[0] == corner || v[1] == corner || v[2] == corner) with_corner.push_back(t);
    }
    const std::size_t count = bvh.faces_around(primitive, glm::dvec3(corner), around);
    ASSERT_EQ(count, with_corner.size()) << i;
    ++valences[count];
    EXPECT_EQ(around[0], primitive);
    std::vector<std::uint32_t> listed(around.begin(), around.begin() + std::ptrdiff_t(count));
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, with_corner) << i;
    for (std::size_t k = 0; k < count; ++k) {
      const auto& before = bvh.triangle(around[k]).vertices;
      const std::size_t at = before[0] == corner ? 0 : before[1] == corner ? 1 : 2;
      const glm::vec3 next_corner = before[(at + 1) % 3];
      const auto& after = bvh.triangle(around[(k + 1) % count]).vertices;
      EXPECT_TRUE(after[0] == next_corner || after[1] == next_corner || after[2] == next_corner) << i;
    }
  }
  EXPECT_GE(valences.size(), 3u) << "vertices of several valences";
  // No answer where none of the triangle's corners is the point, where there are more triangles than
  // room, or at a border.
  const glm::dvec3 v(bvh.triangle(0).vertices[0]);
  EXPECT_EQ(bvh.faces_around(0, (v + glm::dvec3(bvh.triangle(0).vertices[1])) * 0.5, around), 0u);
  EXPECT_EQ(bvh.faces_around(0, v, std::span(around).first(3)), 0u);
  const Bvh grid = Bvh::build(scene_of(make_grid(10.0f, 4)));
  for (std::uint32_t t = 0; t < grid.triangle_count(); ++t) {
    for (const glm::vec3& corner : grid.triangle(t).vertices) {
      const bool border = std::abs(corner.x) == 5.0f || std::abs(corner.y) == 5.0f;
      EXPECT_EQ(grid.faces_around(t, glm::dvec3(corner), around) == 0, border) << t;
    }
  }
}

// The part of a triangle a closest point lies on: from points beyond each corner and edge and over the
// face, and the point is the same as without asking.
TEST(ClosestPointOnTriangle, NamesTheCornerEdgeOrFaceItLiesOn) {
  const glm::dvec3 a(0.0, 0.0, 0.0), b(4.0, 0.0, 0.0), c(1.0, 3.0, 0.0);
  const glm::dvec3 up(0.0, 0.0, 2.0);
  const struct {
    glm::dvec3 from;
    TriangleFeature feature;
  } cases[] = {
      {glm::dvec3(-1.0, -1.0, 0.0) + up, TriangleFeature::a},
      {glm::dvec3(5.0, -1.0, 0.0) - up, TriangleFeature::b},
      {glm::dvec3(1.0, 4.0, 0.0) + up, TriangleFeature::c},
      {glm::dvec3(2.0, -1.0, 0.0) + up, TriangleFeature::ab},
      {glm::dvec3(-1.0, 1.0, 0.0) - up, TriangleFeature::ac},
      {glm::dvec3(3.5, 2.0, 0.0) + up, TriangleFeature::bc},
      {glm::dvec3(1.5, 1.0, 0.0) - up, TriangleFeature::face},
  };
  for (const auto& [from, want] : cases) {
    TriangleFeature feature;
    const glm::dvec3 q = closest_point_on_triangle(from, a, b, c, feature);
    EXPECT_EQ(feature, want) << from.x << " " << from.y;
    EXPECT_EQ(q, closest_point_on_triangle(from, a, b, c));
  }
  TriangleFeature feature;
  EXPECT_EQ(closest_point_on_triangle({-1.0, -1.0, 1.0}, a, b, c, feature), a) << "a corner bit for bit";
  EXPECT_EQ(closest_point_on_triangle({1.0, 4.0, 0.0}, a, b, c, feature), c);
}

TEST(Bvh, StartToleranceCatchesASegmentStartingJustBehindAFace) {
  const Bvh bvh = Bvh::build(scene_of(make_box({10, 10, 10})));
  // From 1e-7 mm below the top face (inside) further in.
  EXPECT_FALSE(bvh.first_hit({1, 1, 5 - 1e-7}, {1, 1, 0}, Faces::front, 0.0).hit());
  const BvhHit hit = bvh.first_hit({1, 1, 5 - 1e-7}, {1, 1, 0}, Faces::front, 1e-6);
  ASSERT_TRUE(hit.hit());
  EXPECT_EQ(hit.t, 0.0f);
}

TEST(Bvh, CoincidentTrianglesBuildABoundedTree) {
  // Thousands of copies of one triangle: binning cannot separate them.
  Mesh mesh;
  mesh.positions_mm = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals.assign(3, {0, 0, 1});
  for (int i = 0; i < 5000; ++i) mesh.indices.insert(mesh.indices.end(), {0, 1, 2});
  const Bvh bvh = Bvh::build(scene_of(mesh));
  EXPECT_EQ(bvh.triangle_count(), 5000u);
  const BvhHit hit = bvh.first_hit({0.2, 0.2, 1}, {0.2, 0.2, -1});
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.t, 0.5f, 1e-7f);
}

TEST(Bvh, RejectsBadMeshesNamingTheObject) {
  Mesh mesh = make_box({1, 1, 1});
  mesh.indices.back() = 99;
  Scene scene = scene_of(mesh);
  scene.objects[0].name = "bad box";
  try {
    (void)Bvh::build(scene);
    FAIL() << "expected palpate::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad box"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vertex 99"), std::string::npos) << e.what();
  }
  Mesh nan_mesh = make_box({1, 1, 1});
  nan_mesh.positions_mm[3].y = std::nanf("");
  EXPECT_THROW((void)Bvh::build(scene_of(nan_mesh)), Error);
}

}  // namespace
}  // namespace palpate
