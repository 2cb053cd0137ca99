#pragma once
// The god-object (Zilles & Salisbury 1995) / virtual proxy (Ruspini, Kolarov & Khatib 1997): a point
// that follows the haptic interaction point (HIP, the tool tip) as closely as it can without ever
// crossing a touchable surface. The spring between the two is the force (see force.hpp).
//
// Each tick the proxy moves from where it was toward the HIP. Every segment it travels is cast against
// the BVH (continuous collision, so a fast move through a thin plate is stopped at the plate); each
// triangle it runs into adds its plane as a constraint. With two or three planes (a concave crease or
// corner) the goal is the point nearest the HIP on their free side, by an exact active-set solve; if
// that leads past the end of their triangles, the constraints are found again from there (at a vertex
// they share, the faces round it are taken together first, as below). On a lone
// face the goal is the nearest point of the triangle itself (raised off it); when that lies on its
// edge, the face across the edge (Bvh::neighbour) takes over and the walk goes on over it, or on into
// free space when the HIP is in front of that face. At a vertex, or where the mesh gives no face across
// (a border, a split vertex), the proxy looks from there toward the HIP (from a vertex, among the faces
// around it first: Bvh::first_hit_around): a clear view means the HIP is outside and reachable
// (contact ends); at a vertex with the HIP behind the faces round it, the proxy rests where those
// faces come nearest the HIP (Bvh::faces_around), when the way there, straight or by the vertex, is
// free; otherwise another face in view takes over. So the proxy slides
// over convex edges and vertices, settles on an edge or vertex that is the surface's nearest point
// (handed back to where it came from, it stops), and meets a concave neighbour as a wall on its walk.
// A tick takes at most `max_iterations` steps; a search cut short resumes the next tick (a tip
// jumping right across a curved object is followed a triangle per segment). A search that comes back
// to where one of its steps started would go round that loop to the cap: it ends as the cap would have
// ended it, without the steps between.
//
// The proxy floats `surface_epsilon_mm` above the planes it touches. Only front faces (crossed from
// outside, against the outward normal) stop it: meshes are closed, and a proxy that starts inside an
// object leaves through back faces freely.
//
// Starting inside: the first step after construction or reset() puts the proxy at the HIP. If that is
// inside an object, the proxy follows the HIP with no contact and no force until the HIP has left the
// object; touching it again from outside then starts at zero depth, so the force ramps in from zero.
// There is no jolt.
//
// Precision: positions and planes are in double. At 10M triangles the triangles are ~0.08 mm across
// and nearly coplanar; the crease and corner solves divide by the Gram determinant of the planes'
// normals (1e-4 for a 1 degree crease), which would leave float with no correct digit at the 1 um
// epsilon. Double keeps the proxy within 1e-9 mm of the exact constraint geometry.
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>

#include "palpate/core/bvh.hpp"
#include "palpate/core/contact.hpp"

namespace palpate {

struct ProxyParams {
  // How far outside the surfaces it touches the proxy floats, mm (> 0): far above double rounding at
  // scene scale (1e-13 mm), far below anything a hand feels or a screen shows.
  double surface_epsilon_mm = 1e-3;
  // Steps per tick at most (each casts a segment that reaches its goal or meets one more plane, looks
  // from an edge, or hands the proxy over to the face across one). Sliding inside a face needs 1,
  // across an edge 2-4, into a corner 3-4.
  int max_iterations = 16;
};

// A plane the proxy rests on: n . x >= offset, the offset already raised by the surface epsilon.
struct ProxyConstraint {
  glm::dvec3 normal{0.0};  // unit, outward
  double offset_mm = 0.0;
  double multiplier_mm = 0.0;   // how hard the HIP pushes into it (the Lagrange multiplier)
  std::uint32_t primitive = 0;  // the triangle's index in the BVH
};

struct ProxyState {
  glm::dvec3 position_mm{0.0};                   // the proxy (SCP), world mm
  std::array<ProxyConstraint, 3> constraints{};  // the planes active at the end of the last step
  int constraint_count = 0;
  bool placed = false;      // false until reset() or the first step, which puts the proxy at the HIP
  int last_iterations = 0;  // steps the last tick took (for statistics and tests)
  // Whether the last tick's search stopped before it finished: at the step cap, or on coming back to
  // where it had been (it resumes the next tick either way).
  bool last_cut_short = false;
  // Where its casts start in the BVH (gathered as it moves, in free space too; see Bvh::first_hit).
  Bvh::Neighbourhood neighbourhood;

  bool in_contact() const noexcept { return constraint_count > 0; }
  // Puts the proxy at `position` with no constraints (e.g. at the first HIP).
  void reset(glm::vec3 position) noexcept;
};

// One god-object step toward `hip_mm` (world). Returns the contact: object and triangle of the plane
// the HIP pushes into hardest, SCP = the proxy, the HIP, the outward normal, depth = |HIP - SCP|; no
// contact (object -1, zero depth) when the proxy reached the HIP. The contact normal is the direction
// of the constraint force, (SCP - HIP) / |SCP - HIP|: on a face it is that face's normal, on a crease,
// edge or corner it is the combination of the active faces' normals that pushes the proxy back.
// A non-finite `hip_mm` leaves the state unchanged and returns no contact, with the HIP copied as given
// (spring_damper then flags it). tick and time_s are left 0 for the caller to fill. Only the objects
// `touchable` names stop the proxy (an empty mask: every object of the BVH); a plane of an object that
// stops being touchable is let go at the next step.
// noexcept, no allocation, no locks: safe in the haptic tick.
Contact proxy_step(ProxyState& state, const Bvh& bvh, glm::vec3 hip_mm, const ProxyParams& params = {},
                   ObjectMask touchable = {}) noexcept;

// Work for between ticks, after the force is out: gathers the proxy's neighbourhood again around where
// the last step left it once it is a quarter of the box's half-width from the box's centre, so that
// the next step finds it ready, and prefetches the triangles of its leaves, which the next step's
// searches and walks read. A gather reads the tree's lower levels over a new stretch of surface (at
// 10 M triangles several reads from memory in a row, most of a slow tick's time); here it costs the
// period's slack instead of the force's latency. Without it the answers are the same: a step gathers
// the box itself once the proxy has left it. noexcept, no allocation, no locks.
void proxy_prepare(ProxyState& state, const Bvh& bvh) noexcept;

}  // namespace palpate
