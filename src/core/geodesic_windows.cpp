// The exact part of GeodesicField: window propagation out to exact_mm_ (see palpate/core/geodesic.hpp).
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>
#include <numbers>

#include "in_plane.hpp"
#include "palpate/core/geodesic.hpp"

namespace palpate {
namespace {

constexpr float infinity = std::numeric_limits<float>::infinity();
constexpr std::uint32_t no_vertex = std::numeric_limits<std::uint32_t>::max(), no_window = no_vertex;
constexpr std::uint8_t pseudo_source_event = 3;
constexpr std::size_t bucket_count = 512;

// p in the frame of the edge from `origin` to `toward`, `length` long, the side of `inside` up.
glm::dvec2 in_edge_frame(glm::dvec2 origin, glm::dvec2 toward, double length, glm::dvec2 inside,
                         glm::dvec2 p) {
  const glm::dvec2 u = (toward - origin) / length;
  glm::dvec2 n(-u.y, u.x);
  if (glm::dot(inside - origin, n) < 0.0) n = -n;
  return {glm::dot(p - origin, u), glm::dot(p - origin, n)};
}

// How near the source at (sx, -sy) comes to the interval [b0, b1] of the edge.
double nearest(double b0, double b1, double sx, double sy) {
  const double dx = sx < b0 ? b0 - sx : sx > b1 ? sx - b1 : 0.0;
  return std::sqrt(dx * dx + sy * sy);
}

}  // namespace

// The windows out to exact_mm_. The contact lights its triangle's edges; where it lies on a corner,
// that corner is the source, and where it lies on an edge, the triangle beyond lights its two other edges.
void GeodesicField::light(std::uint32_t triangle, glm::vec3 point_mm) {
  windows_.clear();
  buckets_.assign(bucket_count, no_window);
  bucket_ = 0;
  const std::uint32_t* corners = triangle_[triangle].corner;
  const glm::dvec3 point = point_mm;
  // Where the path arrives at a corner of a triangle with the contact: its angle round the corner.
  const auto toward_contact = [&](std::uint32_t t, int k) {
    const std::uint32_t* c = triangle_[t].corner;
    const glm::dvec3 corner = mesh_.positions_mm[c[k]],
                     edge = glm::dvec3(mesh_.positions_mm[c[(k + 1) % 3]]) - corner;
    return fan_start_[3 * std::size_t(t) + k] +
           float(std::acos(
               std::clamp(glm::dot(glm::normalize(edge), glm::normalize(point - corner)), -1.0, 1.0)));
  };
  for (int k = 0; k < 3; ++k)
    lower(corners[k], glm::distance(mesh_.positions_mm[corners[k]], point_mm), toward_contact(triangle, k));
  const auto lit_from = [&](std::uint32_t t, int skipped_edge) {
    const std::uint32_t* c = triangle_[t].corner;
    for (int e = 0; e < 3; ++e) {
      const float length = triangle_[t].layout[(e + 2) % 3].edge_mm;
      if (e == skipped_edge || !(length > 0.0f)) continue;
      const glm::dvec2 source =
          in_plane(mesh_.positions_mm[c[e]], mesh_.positions_mm[c[(e + 1) % 3]], point_mm);
      leave(t, e, 0.0, length, source, 0.0, no_vertex);
    }
  };
  int on_edge = -1;
  for (int e = 0; e < 3 && on_edge < 3; ++e) {
    const float length = triangle_[triangle].layout[(e + 2) % 3].edge_mm;
    const glm::dvec3 p = mesh_.positions_mm[corners[e]], q = mesh_.positions_mm[corners[(e + 1) % 3]];
    const double tolerance = 1e-6 * double(length);
    if (glm::distance(p, point) <= tolerance || glm::distance(q, point) <= tolerance) {
      const std::uint32_t corner = glm::distance(p, point) <= tolerance ? corners[e] : corners[(e + 1) % 3];
      // The source itself: every way round it.
      vertex_[corner].arrival = std::numeric_limits<float>::quiet_NaN();
      emit(corner, vertex_[corner].distance);
      on_edge = 3;
    } else if (length > 0.0f && in_plane(p, q, point_mm).y <= tolerance) {
      on_edge = e;
    }
  }
  if (on_edge < 3) {
    lit_from(triangle, on_edge);
    const std::int32_t beyond = on_edge < 0 ? -1 : triangle_[triangle].across[on_edge];
    if (beyond >= 0) {
      const std::uint32_t* far = triangle_[beyond].corner;
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t third = far[(e + 2) % 3];
        if (third != corners[on_edge] && third != corners[(on_edge + 1) % 3]) {
          lower(third, glm::distance(mesh_.positions_mm[third], point_mm),
                toward_contact(std::uint32_t(beyond), (e + 2) % 3));
          lit_from(std::uint32_t(beyond), e);
        }
      }
    }
  }
  for (; bucket_ < bucket_count; ++bucket_) {
    while (buckets_[bucket_] != no_window) {
      if (windows_.size() > window_budget_) {  // exact as far as the bucket, fast marching from there on
        exact_mm_ = float(double(bucket_) / double(bucket_count) * std::max(double(exact_mm_), 1e-6));
        return;
      }
      const Window window = windows_[buckets_[bucket_]];
      buckets_[bucket_] = window.next;
      if (window.edge == pseudo_source_event) {
        if (double(vertex_[window.source].distance) == window.sigma)
          emit(window.source, window.sigma);  // else lowered since
      } else if (window.source == no_vertex || !(double(vertex_[window.source].distance) < window.sigma)) {
        propagate(window);  // else its pseudo-source was lowered since
      }
    }
  }
}

void GeodesicField::enqueue(const Window& window, double key) {
  const std::size_t bucket = std::max(
      bucket_, std::min(bucket_count - 1,
                        std::size_t(key / std::max(double(exact_mm_), 1e-6) * double(bucket_count))));
  windows_.push_back(window);
  windows_.back().next = buckets_[bucket];
  buckets_[bucket] = std::uint32_t(windows_.size() - 1);
}

void GeodesicField::lower(std::uint32_t vertex, float distance, float arrival) {
  if (!(distance < vertex_[vertex].distance)) return;
  if (vertex_[vertex].distance == infinity) touched_.push_back(vertex);
  vertex_[vertex].distance = distance;
  vertex_[vertex].arrival = arrival;
  if (vertex_[vertex].pseudo_source && distance <= exact_mm_) {
    enqueue({0.0, 0.0, 0.0, 0.0, double(distance), 0, vertex, no_window, pseudo_source_event}, distance);
  }
}

// A pseudo-source lights the edges across from it in its triangles: those that a path arriving from
// vertex_[vertex].arrival and turning there by pi or more on either side can reach. Were it to turn by less
// on one side, the path that does not pass through the vertex would be shorter (Mitchell, Mount and
// Papadimitriou, 1987). On the Colin27 brain 55% of the vertices are saddles, most by a few degrees, so
// their paths can turn into one or two of their triangles, not all.
void GeodesicField::emit(std::uint32_t vertex, double sigma) {
  const float arrival = vertex_[vertex].arrival, fan = fan_angle_[vertex], pi = std::numbers::pi_v<float>;
  const bool turns = arrival == arrival && fan == fan;  // else it lights every triangle
  const float slack = 1e-4f;
  for (const std::uint32_t t : triangles_around(vertex)) {
    const std::uint32_t* c = triangle_[t].corner;
    const int k = c[0] == vertex ? 0 : c[1] == vertex ? 1 : 2;
    const std::size_t at_corner = 3 * std::size_t(t) + k;
    if (turns) {
      // The triangle's sector round the vertex, measured from pi past the arrival: the turns of pi or
      // more lie in [0, fan - 2 pi].
      float from = std::fmod(fan_start_[at_corner] - arrival - pi, fan);
      if (from < 0.0f) from += fan;
      if (from > fan - 2.0f * pi + slack && from + corner_angle_[at_corner] < fan - slack) continue;
    }
    // Along its two edges (their lengths from the corners across from them: the vertex's own layout is
    // nothing where the edge across from it has no length).
    const std::size_t at_a = 3 * std::size_t(t) + (k + 1) % 3, at_b = 3 * std::size_t(t) + (k + 2) % 3;
    lower(c[(k + 1) % 3], float(sigma + double(triangle_[t].layout[(k + 2) % 3].edge_mm)),
          fan_start_[at_a] + corner_angle_[at_a]);
    lower(c[(k + 2) % 3], float(sigma + double(triangle_[t].layout[(k + 1) % 3].edge_mm)), fan_start_[at_b]);
    const Layout& layout = triangle_[t].layout[k];
    if (layout.edge_mm > 0.0f) leave(t, (k + 1) % 3, 0.0, layout.edge_mm, layout.corner, sigma, vertex);
  }
}

// The window [b0, b1] of edge `edge` of `triangle`, lit from `source` (in that edge's frame, on the
// triangle's side), goes on into the triangle across the edge.
void GeodesicField::leave(std::uint32_t triangle, int edge, double b0, double b1, glm::dvec2 source,
                          double sigma, std::uint32_t from) {
  const std::int32_t next = triangle_[triangle].across[edge];
  if (next < 0) return;
  const int e = triangle_[triangle].across_edge[edge];
  const double length = triangle_[triangle].layout[(edge + 2) % 3].edge_mm;
  Window window{b0, b1, source.x, source.y, sigma, std::uint32_t(next), from, no_window, std::uint8_t(e)};
  if (triangle_[next].corner[e] != triangle_[triangle].corner[edge]) {
    window.b0 = length - b1, window.b1 = length - b0;
    window.sx = length - source.x;
  }
  if (!trim(window)) return;
  const double key = sigma + nearest(window.b0, window.b1, window.sx, window.sy);
  if (key > exact_mm_) return;
  enqueue(window, key);
}

// Leaves out the parts of the window that its edge's corners reach sooner along the edge: where a
// corner's distance plus the way along the edge passes the window's own, which holds up to one point of
// the edge (the difference only falls with the distance from the corner) that a linear equation gives.
// False where nothing is left.
bool GeodesicField::trim(Window& w) const noexcept {
  const std::uint32_t* c = triangle_[w.triangle].corner;
  const double length = triangle_[w.triangle].layout[(w.edge + 2) % 3].edge_mm;
  // Most windows keep their ends: that is told without a division.
  const auto reaches_sooner = [&](double corner_minus_sigma, double along, double across) {
    const double corner_way = corner_minus_sigma + along;
    return corner_way <= 0.0 || corner_way * corner_way <= across * across + w.sy * w.sy;
  };
  const double c0 = double(vertex_[c[w.edge]].distance) - w.sigma;
  if (reaches_sooner(c0, w.b0, w.b0 - w.sx)) {
    if (w.sx + c0 <= 0.0) return false;
    w.b0 = std::max(w.b0, (w.sx * w.sx + w.sy * w.sy - c0 * c0) / (2.0 * (w.sx + c0)));
  }
  const double c1 = double(vertex_[c[(w.edge + 1) % 3]].distance) - w.sigma, mirrored = length - w.sx;
  if (reaches_sooner(c1, length - w.b1, w.b1 - w.sx)) {
    if (mirrored + c1 <= 0.0) return false;
    w.b1 = std::min(w.b1, length - (mirrored * mirrored + w.sy * w.sy - c1 * c1) / (2.0 * (mirrored + c1)));
  }
  return w.b1 - w.b0 > 1e-9 * length;
}

// The window lights its triangle: the third corner where the window sees it, and the parts of the two
// other edges it sees, which go on as windows of their own.
void GeodesicField::propagate(const Window& w) {
  const std::uint32_t* c = triangle_[w.triangle].corner;
  const Layout& layout = triangle_[w.triangle].layout[(w.edge + 2) % 3];
  const double length = layout.edge_mm, cx = layout.corner.x, cy = layout.corner.y;
  if (!(cy > 0.0)) return;  // a flat triangle: nothing crosses it
  const glm::dvec2 a(0.0), b(length, 0.0), corner(cx, cy), source(w.sx, -w.sy);
  // Where the ray from the source through the third corner crosses the edge.
  const double through_corner = w.sx + (cx - w.sx) * w.sy / (w.sy + cy);
  const std::uint32_t third = c[(w.edge + 2) % 3];
  if (through_corner >= w.b0 && through_corner <= w.b1) {
    const double to_source = glm::distance(source, corner);
    if (float(w.sigma + to_source) < vertex_[third].distance) {
      // It arrives from the source, at this angle from the corner's edge to a: asked only of the vertices
      // that bend paths.
      const double turn =
          vertex_[third].pseudo_source
              ? std::acos(std::clamp(
                    glm::dot(a - corner, source - corner) / (glm::length(corner) * to_source), -1.0, 1.0))
              : 0.0;
      lower(third, float(w.sigma + to_source),
            fan_start_[3 * std::size_t(w.triangle) + (w.edge + 2) % 3] + float(turn));
    }
  }
  // On the edge from a to the corner, the ray through x on the edge meets it at this fraction from a.
  if (through_corner > w.b0) {
    const auto fraction = [&](double x) {
      return std::clamp(x * w.sy / (cx * w.sy - (x - w.sx) * cy), 0.0, 1.0);
    };
    const double t0 = fraction(w.b0), t1 = through_corner < w.b1 ? 1.0 : fraction(w.b1);
    const double edge_length = triangle_[w.triangle].layout[(w.edge + 1) % 3].edge_mm;  // to a
    leave(w.triangle, (w.edge + 2) % 3, (1.0 - t1) * edge_length, (1.0 - t0) * edge_length,
          in_edge_frame(corner, a, edge_length, b, source), w.sigma, w.source);
  }
  // On the edge from the corner to b.
  if (through_corner < w.b1) {
    const auto fraction = [&](double x) {
      return std::clamp(
          ((x - w.sx) * (w.sy + cy) - (cx - w.sx) * w.sy) / ((length - cx) * w.sy + (x - w.sx) * cy), 0.0,
          1.0);
    };
    const double t0 = through_corner > w.b0 ? 0.0 : fraction(w.b0), t1 = fraction(w.b1);
    const double edge_length = triangle_[w.triangle].layout[w.edge].edge_mm;  // b to the corner
    leave(w.triangle, (w.edge + 1) % 3, (1.0 - t1) * edge_length, (1.0 - t0) * edge_length,
          in_edge_frame(b, corner, edge_length, a, source), w.sigma, w.source);
  }
}

}  // namespace palpate
