#pragma once
// Small value type for points and directions. Kept free of Eigen/CGAL so that every module and the
// GUI can include it cheaply; heavy geometry lives in a few CGAL translation units.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>

namespace reamsim {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
  constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
  constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }
};

inline constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
inline constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline constexpr double squaredNorm(const Vec3& v) { return dot(v, v); }
inline Vec3 normalized(const Vec3& v) {
  const double n = norm(v);
  return n > 0 ? v / n : Vec3{};
}
// A unit vector perpendicular to n (n nonzero): across n from whichever of x and y is farther from it.
inline Vec3 anyPerpendicular(const Vec3& n) {
  return normalized(cross(n, std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
}
// The smallest interior angle of the triangle abc, in radians: the angle opposite the shortest edge (atan2
// of |u × w| and u · w: accurate for slivers, where acos of the cosine is not).
inline double smallestAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto at = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, w = r - p;
    return std::atan2(norm(cross(u, w)), dot(u, w));
  };
  const double bc = dot(c - b, c - b), ca = dot(a - c, a - c), ab = dot(b - a, b - a);
  if (bc <= ca && bc <= ab) return at(a, b, c);
  return ca <= ab ? at(b, c, a) : at(c, a, b);
}
inline bool isFinite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Hash of an exact position, consistent with operator== (-0 and +0 hash alike): for maps that weld or
// count vertices at identical coordinates.
struct Vec3PositionHash {
  std::size_t operator()(const Vec3& v) const {
    std::size_t h = 1469598103934665603ull;
    for (double d : {v.x, v.y, v.z}) {
      if (d == 0) d = 0;  // -0 and +0 are the same position
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
      h ^= h >> 29;
    }
    return h;
  }
};

}  // namespace reamsim
