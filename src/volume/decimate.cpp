#include "decimate.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <vector>

#include "palpate/core/error.hpp"

namespace palpate::volume {

void decimate_keeping_topology(Mesh& mesh, std::size_t triangles, const std::filesystem::path& source) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
  namespace collapse = CGAL::Surface_mesh_simplification;

  SurfaceMesh surface;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(mesh.vertex_count());
  for (const glm::vec3& p : mesh.positions_mm) vertices.push_back(surface.add_vertex({p.x, p.y, p.z}));
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const auto face = surface.add_face(vertices[mesh.indices[t]], vertices[mesh.indices[t + 1]],
                                       vertices[mesh.indices[t + 2]]);
    if (face == SurfaceMesh::null_face())
      throw Error(
          source, 0,
          "the isosurface is not a manifold here (triangle " + std::to_string(t / 3) + "): cannot decimate");
  }
  // Each collapse removes one edge; on a manifold every triangle has three edges, each shared by two.
  const std::size_t edges =
      surface.number_of_edges() * triangles / std::max<std::size_t>(surface.number_of_faces(), 1);
  collapse::Count_stop_predicate<SurfaceMesh> stop(edges);
  collapse::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel> quadrics(surface);
  collapse::edge_collapse(
      surface, stop, CGAL::parameters::get_cost(quadrics.get_cost()).get_placement(quadrics.get_placement()));
  surface.collect_garbage();

  mesh.positions_mm.clear();
  mesh.indices.clear();
  for (const auto vertex : surface.vertices()) {
    const Kernel::Point_3& p = surface.point(vertex);
    mesh.positions_mm.emplace_back(float(p.x()), float(p.y()), float(p.z()));
  }
  for (const auto face : surface.faces()) {
    for (const auto vertex : CGAL::vertices_around_face(surface.halfedge(face), surface))
      mesh.indices.push_back(std::uint32_t(vertex));
  }
  mesh.normals.clear();
}

}  // namespace palpate::volume
