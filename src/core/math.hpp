// nscd/core/math.hpp — 2D vector algebra used everywhere (header only, no dependencies).
//
// Conventions: angles in radians, counter-clockwise positive; cross(a, b) is the scalar
// z-component a.x*b.y - a.y*b.x; perp(a) rotates a by +90 degrees.
#pragma once

#include <cmath>

/// Forces inlining of the small functions of a solver's inner loop (a contact visit), so that
/// the loop's state stays in registers.
#if defined(__GNUC__) || defined(__clang__)
#define NSCD_HOT_INLINE __attribute__((always_inline))
#else
#define NSCD_HOT_INLINE
#endif

namespace nscd {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2& operator+=(Vec2 o) { x += o.x; y += o.y; return *this; }
  constexpr Vec2& operator-=(Vec2 o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec2& operator*=(double s) { x *= s; y *= s; return *this; }
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
constexpr bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// Rotation by +90 degrees: perp((1,0)) = (0,1).
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Vec2 normalized(Vec2 a) { const double n = norm(a); return {a.x / n, a.y / n}; }

/// Rotation R(angle) given by its cosine and sine, applied as R*v.
struct Rot2 {
  double c = 1.0;
  double s = 0.0;
  static Rot2 of(double angle) { return {std::cos(angle), std::sin(angle)}; }
  constexpr Vec2 apply(Vec2 v) const { return {c * v.x - s * v.y, s * v.x + c * v.y}; }
  constexpr Vec2 apply_inverse(Vec2 v) const { return {c * v.x + s * v.y, -s * v.x + c * v.y}; }
};

inline constexpr double kPi = 3.14159265358979323846;

/// An axis-aligned box in world coordinates (the broad phase's input).
struct Aabb {
  double xmin, ymin, xmax, ymax;
};

}  // namespace nscd
