#include "BoneSurface.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericCell.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkStaticCellLocator.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <vector>

namespace reamsim::ui {
namespace {

vtkSmartPointer<vtkPolyData> plainPolyData(const BoneState& s, std::vector<vtkIdType>* pointOfSlot) {
  std::vector<vtkIdType> local;
  std::vector<vtkIdType>& index = pointOfSlot ? *pointOfSlot : local;
  index.assign(s.vertexSlotCount(), -1);
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->Allocate(static_cast<vtkIdType>(s.liveVertexCount()));
  for (std::uint32_t v = 0; v < s.vertexSlotCount(); ++v) {
    if (!s.isVertexLive(v)) continue;
    const Vec3& p = s.vertex(v);
    index[v] = points->InsertNextPoint(p.x, p.y, p.z);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(static_cast<vtkIdType>(s.liveTriangleCount()), 3 * static_cast<vtkIdType>(s.liveTriangleCount()));
  s.forEachLiveTriangle([&](std::uint32_t, const Triangle& t) {
    const vtkIdType ids[3] = {index[t[0]], index[t[1]], index[t[2]]};
    cells->InsertNextCell(3, ids);
  });
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

bool sameTriangle(const BoneState& a, const BoneState& b, std::uint32_t slot) {
  if (!b.isTriangleLive(slot)) return false;
  const Triangle& ta = a.triangle(slot);
  const Triangle& tb = b.triangle(slot);
  for (int k = 0; k < 3; ++k)
    if (ta[k] != tb[k] || !(a.vertex(ta[k]) == b.vertex(tb[k]))) return false;
  return true;
}

}  // namespace

BoneSurfaceBuilder::BoneSurfaceBuilder() = default;
BoneSurfaceBuilder::~BoneSurfaceBuilder() = default;

void BoneSurfaceBuilder::setInitial(const BoneState& initial) {
  initial_ = initial;
  locator_ = nullptr;
}

BoneSurfaceBuilder::Result BoneSurfaceBuilder::build(const BoneState& s, const BoneState* previous, const QColor& bone,
                                                     const QColor& fresh, bool smoothNormals) {
  Result r;
  std::vector<vtkIdType> pointOfSlot;
  vtkSmartPointer<vtkPolyData> poly = plainPolyData(s, &pointOfSlot);

  auto colour = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colour->SetName("colour");
  colour->SetNumberOfComponents(3);
  colour->SetNumberOfTuples(static_cast<vtkIdType>(s.liveTriangleCount()));
  vtkIdType cell = 0;
  s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) {
    const bool isFresh = previous && !sameTriangle(s, *previous, slot);
    r.freshTriangles += isFresh;
    const QColor& c = isFresh ? fresh : bone;
    const unsigned char rgb[3] = {static_cast<unsigned char>(c.red()), static_cast<unsigned char>(c.green()),
                                  static_cast<unsigned char>(c.blue())};
    colour->SetTypedTuple(cell++, rgb);
  });
  poly->GetCellData()->AddArray(colour);

  // Depth: only vertices that are not the initial surface's own need a distance query.
  auto depth = vtkSmartPointer<vtkFloatArray>::New();
  depth->SetName("depth_mm");
  depth->SetNumberOfTuples(poly->GetNumberOfPoints());
  depth->FillValue(0.0f);
  vtkSmartPointer<vtkGenericCell> scratch = vtkSmartPointer<vtkGenericCell>::New();
  for (std::uint32_t v = 0; v < s.vertexSlotCount(); ++v) {
    if (pointOfSlot[v] < 0) continue;
    if (initial_.isVertexLive(v) && initial_.vertex(v) == s.vertex(v)) continue;
    if (!locator_) {
      locator_ = vtkSmartPointer<vtkStaticCellLocator>::New();
      locator_->SetDataSet(plainPolyData(initial_, nullptr));
      locator_->BuildLocator();
    }
    const Vec3& p = s.vertex(v);
    double x[3] = {p.x, p.y, p.z}, closest[3];
    vtkIdType cellId;
    int subId;
    double d2 = 0;
    locator_->FindClosestPoint(x, closest, scratch, cellId, subId, d2);
    const double d = std::sqrt(d2);
    depth->SetValue(pointOfSlot[v], static_cast<float>(d));
    r.maxDepthMm = std::max(r.maxDepthMm, d);
  }
  poly->GetPointData()->AddArray(depth);

  if (smoothNormals) {
    auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
    normals->SetInputData(poly);
    normals->SplittingOff();
    normals->ConsistencyOff();  // the bone is consistently oriented already
    normals->ComputeCellNormalsOff();
    normals->Update();
    r.polyData = normals->GetOutput();
  } else {
    r.polyData = poly;
  }
  return r;
}

}  // namespace reamsim::ui
