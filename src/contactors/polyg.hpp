// nscd/contactors/polyg.hpp — POLYG: convex polygon contactors (LMGC90's name).
//
// A Polygon is a list of vertices, counter-clockwise. Every polygon is validated before it
// enters a scene: at least 3 vertices, all finite, no repeated vertex, strictly convex (no
// three consecutive vertices collinear), counter-clockwise, area > 0. A clockwise list is
// rejected, not silently reversed. Errors name the body and the defect.
//
// Mass properties are per unit thickness (2D): mass = density × area (kg/m), inertia in
// kg·m²/m. See docs/theory.md.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "nscd/registry/registry.hpp"

namespace nscd {

using Polygon = std::vector<Vec2>;

/// Largest vertex count of a POLYG (contact feature ids store vertex indices in 12 bits).
inline constexpr std::size_t kMaxPolygVertices = 4096;

/// Throws nscd::Error "POLYG of <context>: <defect>" if the polygon is not valid.
void validate_polygon(std::span<const Vec2> vertices, const std::string& context = "polygon");

/// Regular n-gon centred at the origin, vertices on the circle of diameter
/// `circumscribed_diameter`, the first vertex at angle `orientation` (rad).
Polygon regular_polygon(int n, double circumscribed_diameter, double orientation = 0.0);
/// Axis-aligned rectangle centred at the origin.
Polygon rectangle(double width, double height);
/// Translates and rotates a polygon: p -> offset + R(angle) p.
Polygon transformed(std::span<const Vec2> vertices, Vec2 offset, double angle = 0.0);

struct MassProperties {
  double area = 0.0;
  Vec2 centroid;
  double polar_moment = 0.0;  ///< ∫ |p - centroid|² dA (m⁴ per unit thickness)
};
/// Area, centroid and second polar moment about the centroid (shoelace formulas). Expects a
/// valid polygon; throws nscd::Error on fewer than 3 vertices.
MassProperties mass_properties(std::span<const Vec2> vertices);

/// Creates a rigid body made of one or more polygons, given in a shape frame, with the
/// material's density. The shape frame's origin is placed at `position` and rotated by
/// `angle`; the body's centre of mass is where the shapes' centroid lands. Each polygon
/// becomes a POLYG contactor of the body. Validates every polygon (context: the body name).
BodyId add_polygon_body(Registry& reg, std::span<const Polygon> shapes, MaterialId material, Vec2 position,
                        double angle = 0.0, const std::string& name = "");
/// Single-polygon convenience.
BodyId add_polygon_body(Registry& reg, const Polygon& shape, MaterialId material, Vec2 position,
                        double angle = 0.0, const std::string& name = "");

/// Attaches a polygon given in the body frame (origin = centre of mass) to an existing body
/// without changing its mass. Returns the contactor's id.
PolygId attach_polyg(Registry& reg, BodyId body, std::span<const Vec2> vertices_body_frame);

/// Changes a material's density and rescales the mass and inertia of every body made of it
/// (mass and inertia are proportional to the density). Throws unless density is finite and > 0.
void set_material_density(Registry& reg, MaterialId material, double density);

/// World coordinates of vertex k of a POLYG, from the body's current configuration.
Vec2 world_vertex(const Registry& reg, PolygId p, std::uint32_t k);
/// All world vertices of a POLYG.
Polygon world_polygon(const Registry& reg, PolygId p);

}  // namespace nscd
