#pragma once
// Internal: a parametric reamer's cutting face as a height field over the plane across its axis, for the
// axial penetration query (PenetrationQuery.cpp).
//
// Every face triangle of a parametric reamer faces forward (normal z > 0, reamer frame), so the face is the
// graph of top(x, y) over its shadow, linear on each triangle's shadow. Backing out by d moves a bone point
// q (reamer frame) to q + d z; it lies on the face when d = top(q.xy) - q.z. So a bone triangle touches the
// face for d over the image of its part within the shadow under that function: one interval (a connected
// set's image), whose ends are at vertices of the triangle's shadow clipped by the face triangles' shadows
// (on each, the function is linear). That replaces the pairs of the bone triangle with every face triangle
// above it, and the traversal pairing bone nodes with reamer nodes, by a grid lookup and a few 2D clips.
#include <cstdint>
#include <memory>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim::detail {

class CapShadow {
 public:
  // Null unless every face triangle's normal has z >= kMinForward (unit normal): only then is the face a
  // height field whose triangles' shadows do not fold.
  static std::shared_ptr<const CapShadow> build(const TriangleMesh& solid, const std::vector<std::uint32_t>& face);

  // The interval of back-out distances over which the bone triangle q (reamer frame) touches the face, and
  // the point (reamer frame, on the bone triangle) where it last touches. False when its shadow misses the
  // face's. Only for triangles whose unit normal has |z| >= kMinSteepness (see `steep`): others have a thin
  // shadow over which their height is ill-conditioned, and are paired with the face triangles instead
  // (`facesUnder`).
  bool interval(const Vec3 (&q)[3], double& lo, double& hi, Vec3& hiPoint) const;
  static bool steep(const Vec3 (&q)[3]);

  // Face triangles (solid triangle indices) whose shadows' boxes meet the box of q's shadow (q in the reamer
  // frame), each once.
  void facesUnder(const Vec3 (&q)[3], std::vector<std::uint32_t>& out) const;

  double rimRadius() const { return rimRadius_; }  // largest distance of a face vertex from the axis
  double top() const { return top_; }              // the face's highest and lowest vertex (z)
  double bottom() const { return bottom_; }

  static constexpr double kMinForward = 1e-6;
  static constexpr double kMinSteepness = 1e-2;

 private:
  struct Face {
    double x[3], y[3];  // shadow corners, counter-clockwise
    double a, b, c;     // height over the shadow: a x + b y + c
    double xlo, xhi, ylo, yhi;
    int firstCellX, firstCellY;  // the grid cell of (xlo, ylo): a face is visited in the first cell only
    std::uint32_t solidTriangle;
  };
  std::vector<Face> faces_;
  double x0_ = 0, y0_ = 0, cell_ = 1, rimRadius_ = 0, top_ = 0, bottom_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cellStart_, cellFaces_;

  struct ShadowBox {
    double xlo, xhi, ylo, yhi;
  };
  static ShadowBox shadowBox(const Vec3 (&q)[3]);
  // The grid column (v: x, v0: x0_, n: nx_) or row holding coordinate v, clamped to the grid.
  int cellOf(double v, double v0, int n) const;
  // Calls visit(face) for each face whose shadow's box meets `box`, once each, until it returns false.
  template <class Visit>
  void forFacesUnder(const ShadowBox& box, Visit&& visit) const;
};

}  // namespace reamsim::detail
