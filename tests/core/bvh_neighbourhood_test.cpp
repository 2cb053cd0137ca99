// Bvh::Neighbourhood: a segment cast that starts from the leaves gathered around a box must give
// the root's answer, bit for bit, for every segment: random ones from inside the box and adversarial
// ones (through vertices and edges, along the surface a micrometre above it, from the box's faces and
// corners, out of the box and through the object).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>

#include "palpate/core/bvh.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

Scene bumpy_sphere_scene(std::size_t triangles) {
  Scene scene;
  scene.objects.push_back(
      {"bumpy sphere", make_bumpy_sphere(50.0f, 1.5f, triangles), glm::mat4(1.0f), {}, {}});
  return scene;
}

// Asserts that the cast from `from` to `to` gives the same answer with and without `near`; counts
// the casts the neighbourhood answered from its leaves.
struct Comparison {
  const Bvh& bvh;
  const Bvh::Neighbourhood& near;
  long compared = 0, hits = 0, started_near = 0;

  void operator()(const glm::dvec3& from, const glm::dvec3& to) {
    for (const Faces faces : {Faces::front, Faces::both}) {
      const BvhHit root = bvh.first_hit(from, to, faces, 1e-6);
      const BvhHit local = bvh.first_hit(from, to, faces, 1e-6, {}, &near);
      ++compared;
      hits += root.hit();
      started_near += near.covers(from);
      ASSERT_EQ(local.hit(), root.hit()) << "from " << from.x << ' ' << from.y << ' ' << from.z;
      if (!root.hit()) continue;
      ASSERT_EQ(local.primitive, root.primitive);
      ASSERT_EQ(local.t, root.t);
    }
  }
};

TEST(BvhNeighbourhood, CastsFromItsLeavesMatchTheRootsOverAMillionRandomAndAdversarialSegments) {
  const Scene scene = bumpy_sphere_scene(60000);
  const Mesh& mesh = scene.objects[0].mesh;
  const Bvh bvh = Bvh::build(scene);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick_vertex(0, mesh.positions_mm.size() - 1);
  std::uniform_int_distribution<std::size_t> pick_triangle(0, mesh.triangle_count() - 1);
  const auto random_vector = [&](double length) {
    return length * glm::dvec3(unit(rng), unit(rng), unit(rng));
  };

  Bvh::Neighbourhood near;
  Comparison compare{bvh, near};
  int neighbourhoods = 0;
  while (compare.compared < 1'000'000) {
    // A box around a surface point, from a tenth of a triangle to a few triangles wide.
    const glm::dvec3 centre(mesh.positions_mm[pick_vertex(rng)]);
    const float half = float(0.05 + 2.0 * fraction(rng) * fraction(rng));
    if (!bvh.gather(near, glm::vec3(centre) - half, glm::vec3(centre) + half)) continue;
    ++neighbourhoods;
    const glm::dvec3 low(near.low), high(near.high);
    for (int k = 0; k < 60; ++k) {
      const glm::dvec3 inside = low + (high - low) * glm::dvec3(0.5 + 0.5 * unit(rng), 0.5 + 0.5 * unit(rng),
                                                                0.5 + 0.5 * unit(rng));
      // Random: short and long, inward, outward, through the sphere.
      compare(inside, inside + random_vector(0.2 * half));
      compare(inside, inside + random_vector(3.0 * half));
      compare(inside, -inside);
      compare(inside, inside * 1.2);
      // Through a vertex or an edge's midpoint near the centre, from above to below.
      const std::size_t t = pick_triangle(rng);
      const glm::dvec3 a(mesh.positions_mm[mesh.indices[3 * t]]),
          b(mesh.positions_mm[mesh.indices[3 * t + 1]]);
      for (const glm::dvec3& target : {a, 0.5 * (a + b)}) {
        const glm::dvec3 out = glm::normalize(target);
        compare(target + 0.01 * out + random_vector(0.002), target - 0.5 * out);
        compare(target + 0.01 * out, target - 0.5 * out);  // exactly through it: ties between its faces
      }
      const glm::dvec3 v(mesh.positions_mm[pick_vertex(rng)]);
      const glm::dvec3 out = glm::normalize(v);
      compare(v + double(half) * out, v - double(half) * out);
      // Along the surface, a micrometre above it, as the proxy walks.
      const glm::dvec3 c(mesh.positions_mm[mesh.indices[3 * t + 2]]);
      const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
      compare((a + b + c) / 3.0 + 1e-3 * normal, a + 1e-3 * normal + (a - c) * fraction(rng));
      // From the box's faces and corners (at the edge of what the neighbourhood trusts) inward and out.
      glm::dvec3 on_face = inside;
      const int axis = int(rng() % 3);
      on_face[axis] =
          (rng() % 2 ? low : high)[axis] + (rng() % 2 ? 1.0 : -1.0) * Bvh::Neighbourhood::inner_margin_mm;
      compare(on_face, centre);
      compare(on_face, on_face + random_vector(half));
      const glm::dvec3 corner(rng() % 2 ? low.x : high.x, rng() % 2 ? low.y : high.y,
                              rng() % 2 ? low.z : high.z);
      compare(corner, centre);
      compare(centre, corner + random_vector(0.1 * half));
      // Zero length.
      compare(inside, inside);
    }
  }
  EXPECT_GE(compare.compared, 1'000'000);
  EXPECT_GT(neighbourhoods, 500);
  // The sample really exercises hits and casts answered from the leaves.
  EXPECT_GT(compare.hits, compare.compared / 4);
  EXPECT_GT(compare.started_near, compare.compared * 2 / 5);  // 46% measured
}

TEST(BvhNeighbourhood, NearestPointsOfTheFacesAroundAPointMatchTheRoots) {
  const Scene scene = bumpy_sphere_scene(60000);
  const Mesh& mesh = scene.objects[0].mesh;
  const Bvh bvh = Bvh::build(scene);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick_triangle(0, mesh.triangle_count() - 1);
  Bvh::Neighbourhood near;
  long compared = 0, found = 0, started_near = 0;
  while (compared < 200'000) {
    const std::size_t t = pick_triangle(rng);
    const glm::dvec3 a(mesh.positions_mm[mesh.indices[3 * t]]), b(mesh.positions_mm[mesh.indices[3 * t + 1]]),
        c(mesh.positions_mm[mesh.indices[3 * t + 2]]);
    const float half = float(0.05 + 1.5 * fraction(rng));
    if (!bvh.gather(near, glm::vec3(a) - half, glm::vec3(a) + half)) continue;
    const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
    for (int k = 0; k < 20; ++k) {
      // Where the proxy rests: on a vertex, an edge or inside the face, a micrometre above it, and
      // anywhere in the box; the tip under it or off to a side.
      const double u = fraction(rng), v = fraction(rng) * (1.0 - u);
      const glm::dvec3 around = k % 4 == 0   ? a + 1e-3 * normal
                                : k % 4 == 1 ? a + u * (b - a) + 1e-3 * normal
                                : k % 4 == 2 ? a + u * (b - a) + v * (c - a) + 1e-3 * normal
                                             : a + double(half) * glm::dvec3(unit(rng), unit(rng), unit(rng));
      const glm::dvec3 tip =
          around - (0.5 + 2.0 * fraction(rng)) * normal + 0.5 * glm::dvec3(unit(rng), unit(rng), unit(rng));
      const double radius = k % 2 ? 0.01 : 0.2 * double(half) * fraction(rng);
      const BvhHit root = bvh.closest_point_near(tip, around, radius);
      const BvhHit local = bvh.closest_point_near(tip, around, radius, {}, &near);
      ++compared;
      found += root.hit();
      started_near += near.covers(around - radius) && near.covers(around + radius);
      ASSERT_EQ(local.hit(), root.hit());
      if (!root.hit()) continue;
      ASSERT_EQ(local.primitive, root.primitive);
      ASSERT_EQ(local.distance_mm, root.distance_mm);
    }
  }
  EXPECT_GT(found, compared / 2);
  EXPECT_GT(started_near, compared / 2);
}

// Leaving faces out of the search: the nearest of the others, against a brute force over every
// triangle, from the root and from the leaves alike.
TEST(BvhNeighbourhood, NearestPointsLeaveOutTheFacesNamed) {
  const Scene scene = bumpy_sphere_scene(4000);
  const Mesh& mesh = scene.objects[0].mesh;
  const Bvh bvh = Bvh::build(scene);
  const auto brute_force = [&](const glm::dvec3& tip, const glm::dvec3& around, double radius,
                               std::array<std::uint32_t, 2> left_out) {
    double best_d2 = std::numeric_limits<double>::infinity();
    std::uint32_t best = Bvh::no_neighbour;
    for (std::uint32_t i = 0; i < bvh.triangle_count(); ++i) {
      if (i == left_out[0] || i == left_out[1]) continue;
      const auto& v = bvh.triangle(i).vertices;
      const glm::dvec3 a(v[0]), b(v[1]), c(v[2]);
      const glm::dvec3 touch = closest_point_on_triangle(around, a, b, c) - around;
      if (glm::dot(touch, touch) > radius * radius) continue;
      const glm::dvec3 q = closest_point_on_triangle(tip, a, b, c);
      const double d2 = glm::dot(q - tip, q - tip);
      if (d2 < best_d2) best_d2 = d2, best = i;  // ascending: a tie keeps the lowest index
    }
    return std::pair{best, float(std::sqrt(best_d2))};
  };
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick_triangle(0, mesh.triangle_count() - 1);
  std::uniform_int_distribution<std::uint32_t> pick_primitive(0, std::uint32_t(bvh.triangle_count() - 1));
  Bvh::Neighbourhood near;
  long compared = 0, left_out_answer = 0, found = 0, started_near = 0;
  while (compared < 3000) {
    const std::size_t t = pick_triangle(rng);
    const glm::dvec3 a(mesh.positions_mm[mesh.indices[3 * t]]), b(mesh.positions_mm[mesh.indices[3 * t + 1]]),
        c(mesh.positions_mm[mesh.indices[3 * t + 2]]);
    if (!bvh.gather(near, glm::vec3(a) - 8.0f, glm::vec3(a) + 8.0f)) continue;
    const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
    const double u = fraction(rng);
    const glm::dvec3 around = (compared % 2 ? a : a + u * (b - a)) + 1e-3 * normal;
    const glm::dvec3 tip =
        around - (0.5 + 2.0 * fraction(rng)) * normal + 2.0 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    const double radius = 0.5 + 3.0 * fraction(rng);
    // The answer itself and another face, or two faces at random.
    const BvhHit all = bvh.closest_point_near(tip, around, radius);
    std::array<std::uint32_t, 2> left_out = {pick_primitive(rng), pick_primitive(rng)};
    if (compared % 3 != 0 && all.hit()) left_out[compared % 3 - 1] = all.primitive;
    const auto [expected, distance] = brute_force(tip, around, radius, left_out);
    for (const Bvh::Neighbourhood* from : std::array<const Bvh::Neighbourhood*, 2>{nullptr, &near}) {
      const BvhHit hit = bvh.closest_point_near(tip, around, radius, {}, from, left_out);
      ASSERT_EQ(hit.hit(), expected != Bvh::no_neighbour) << compared;
      if (!hit.hit()) continue;
      ASSERT_EQ(hit.primitive, expected) << compared;
      ASSERT_EQ(hit.distance_mm, distance) << compared;
    }
    ++compared;
    found += expected != Bvh::no_neighbour;
    started_near += near.covers(around - radius) && near.covers(around + radius);
    left_out_answer += all.hit() && all.primitive != expected;
  }
  EXPECT_GT(found, compared * 9 / 10);
  EXPECT_GT(left_out_answer, compared / 2);
  EXPECT_GT(started_near, compared * 9 / 10);
}

TEST(BvhNeighbourhood, GathersEveryLeafThatMeetsTheBoxWithItsBounds) {
  const Scene scene = bumpy_sphere_scene(20000);
  const Bvh bvh = Bvh::build(scene);
  const glm::vec3 low(-2.0f, -2.0f, 48.0f), high(2.0f, 2.0f, 53.0f);
  Bvh::Neighbourhood near;
  ASSERT_TRUE(bvh.gather(near, low, high));
  EXPECT_GT(near.count, 1);
  EXPECT_TRUE(near.covers(glm::dvec3(0.0, 0.0, 50.0)));
  EXPECT_FALSE(near.covers(glm::dvec3(0.0, 0.0, 47.0)));
  // The leaves listed are exactly those whose bounds meet the box, each once, with its bounds: so each
  // triangle whose bounds meet the box is in one of them. They come in the order of their triangles
  // (casts rely on it to break ties between them by the lowest index).
  const auto& nodes = bvh.nodes();
  std::vector<int> leaf_of(bvh.triangle_count(), -1);  // the leaf that holds each triangle first
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (nodes[n].count > 0) leaf_of[nodes[n].first] = int(n);
  }
  std::vector<int> listed(nodes.size(), 0);
  for (std::size_t k = 0; k < std::size_t(near.count); ++k) {
    ASSERT_LT(near.first[k], bvh.triangle_count());
    const int n = leaf_of[near.first[k]];
    ASSERT_GE(n, 0) << "listed " << k << " is no leaf's first triangle";
    const Bvh::Node& leaf = nodes[std::size_t(n)];
    ++listed[std::size_t(n)];
    EXPECT_EQ(near.size[k], leaf.count);
    if (k > 0) {
      EXPECT_GT(near.first[k], near.first[k - 1]);
    }
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(near.min[a][k], leaf.min[int(a)]);
      EXPECT_EQ(near.max[a][k], leaf.max[int(a)]);
    }
  }
  int meeting = 0;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const Bvh::Node& node = nodes[n];
    if (node.count == 0) continue;
    const bool meets =
        glm::all(glm::lessThanEqual(node.min, high)) && glm::all(glm::lessThanEqual(low, node.max));
    meeting += meets;
    EXPECT_EQ(listed[n], meets ? 1 : 0) << "leaf " << n;
  }
  EXPECT_GT(meeting, 5);
}

TEST(BvhNeighbourhood, AHitPastTheBoxGivesWayToAnEarlierTriangleThatIsNotListed) {
  // The segment leaves the box [-1, 1]^3 along x. A long triangle whose bounds reach into the box
  // (listed) crosses it at x = 2.1; a cluster of small ones at x = 1.5, whose leaf stays outside the box
  // (not listed), crosses it first.
  Mesh mesh;
  mesh.positions_mm = {{0.5f, 0.0f, 0.9f}, {3.0f, -0.5f, -0.5f}, {3.0f, 0.5f, -0.5f}};
  for (int k = 0; k < 4; ++k) {
    const float x = 1.5f + 0.01f * float(k);
    const auto first = std::uint32_t(mesh.positions_mm.size());
    mesh.positions_mm.insert(mesh.positions_mm.end(), {{x, -0.1f, -0.1f}, {x, 0.1f, -0.1f}, {x, 0.0f, 0.1f}});
    mesh.indices.insert(mesh.indices.end(), {first, first + 2, first + 1});  // facing -x: met from the front
  }
  mesh.indices.insert(mesh.indices.end(), {0, 2, 1});
  Scene scene;
  scene.objects.push_back({"comb", std::move(mesh), glm::mat4(1.0f), {}, {}});
  const Bvh bvh = Bvh::build(scene);
  Bvh::Neighbourhood near;
  ASSERT_TRUE(bvh.gather(near, glm::vec3(-1.0f), glm::vec3(1.0f)));
  ASSERT_EQ(near.count, 1);
  ASSERT_EQ(near.size[0], 1u);
  ASSERT_EQ(bvh.locate(near.first[0]).triangle, 4) << "the long triangle alone is listed";
  for (const Faces faces : {Faces::front, Faces::both}) {
    const BvhHit root = bvh.first_hit(glm::dvec3(0.0), glm::dvec3(4.0, 0.0, 0.0), faces);
    const BvhHit local = bvh.first_hit(glm::dvec3(0.0), glm::dvec3(4.0, 0.0, 0.0), faces, 0.0, {}, &near);
    ASSERT_TRUE(root.hit());
    EXPECT_EQ(root.triangle, 0);
    EXPECT_NEAR(root.point_mm.x, 1.5f, 1e-6f);
    EXPECT_EQ(local.primitive, root.primitive);
    EXPECT_EQ(local.t, root.t);
  }
}

TEST(BvhNeighbourhood, TooManyLeavesOrAnotherTreeFallBackToTheRoot) {
  const Scene scene = bumpy_sphere_scene(20000);
  const Bvh bvh = Bvh::build(scene);
  Bvh::Neighbourhood near;
  // The whole sphere: far more leaves than the capacity.
  EXPECT_FALSE(bvh.gather(near, glm::vec3(-60.0f), glm::vec3(60.0f)));
  EXPECT_EQ(near.count, 0);
  EXPECT_FALSE(near.covers(glm::dvec3(0.0)));
  // The hollow middle of the sphere: inside the root's bounds, but no leaf's.
  EXPECT_FALSE(bvh.gather(near, glm::vec3(-1.0f), glm::vec3(1.0f)));
  EXPECT_EQ(near.count, 0);
  EXPECT_FALSE(near.covers(glm::dvec3(0.0)));
  // Gathered in one tree, ignored by another (its node indices mean nothing there).
  ASSERT_TRUE(bvh.gather(near, glm::vec3(-2.0f, -2.0f, 48.0f), glm::vec3(2.0f, 2.0f, 53.0f)));
  // A finer sphere turned on its side: a larger tree, where the node indices are valid but hold other
  // parts of the surface. Segments inside the box, so no search from the root could mend it.
  Scene turned = bumpy_sphere_scene(40000);
  turned.objects[0].transform = glm::rotate(glm::mat4(1.0f), 1.5707964f, glm::vec3(1.0f, 0.0f, 0.0f));
  const Bvh other = Bvh::build(turned);
  ASSERT_GT(other.node_count(), bvh.node_count());
  int hits = 0;
  for (double x = -1.5; x <= 1.5; x += 0.25) {
    const glm::dvec3 from(x, 0.3 * x, 52.5), to(x, 0.3 * x, 48.5);
    const BvhHit expected = other.first_hit(from, to);
    const BvhHit got = other.first_hit(from, to, Faces::front, 0.0, {}, &near);
    hits += expected.hit();
    ASSERT_EQ(got.hit(), expected.hit());
    if (!expected.hit()) continue;
    EXPECT_EQ(got.primitive, expected.primitive);
    EXPECT_EQ(got.t, expected.t);
  }
  EXPECT_GT(hits, 8);
}

}  // namespace
}  // namespace palpate
