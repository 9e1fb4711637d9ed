#pragma once
// A document with a bone, a reamer, a log and alerts, wired to a ReamController; and the small analytic
// scene several suites cut: a flat 20 mm reamer and a block whose top face is z = 0.
#include <memory>

#include "reamsim/core/Document.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim::test {

// Flat face, 20 mm across (32 segments), 10 mm body behind the tip.
inline ReamerSpec flatReamer20() {
  ReamerSpec spec;
  spec.name = "flat-20";
  spec.diameterMm = 20;
  spec.bodyLengthMm = 10;
  spec.segments = 32;
  return spec;
}

// 30 mm deep, 80 mm along y, 2 x halfX along x; top face at z = 0.
inline TriangleMesh blockBelowZ0(double halfX = 40) {
  return buildBox(Bounds{{-halfX, -40, -30}, {halfX, 40, 0}}, 4);
}

struct ReamScene {
  Document doc;
  BoneNode* bone = nullptr;
  ReamerNode* reamer = nullptr;
  LogNode* log = nullptr;
  AlertNode* alerts = nullptr;
  std::unique_ptr<ReamController> controller;

  ReamScene(const TriangleMesh& boneMesh, const ReamerSpec& spec, CutBackendFactory cut = referenceCutBackendFactory(),
            std::unique_ptr<ContactBackend> contact = makeBvhContactBackend()) {
    bone = &doc.create<BoneNode>("Bone", BoneState::fromMesh(boneMesh));
    reamer = &doc.create<ReamerNode>("Reamer", spec);
    reamer->setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(spec)));
    log = &doc.create<LogNode>("Log");
    alerts = &doc.create<AlertNode>("Alerts");
    controller =
        std::make_unique<ReamController>(doc, *bone, *reamer, *log, alerts, std::move(cut), std::move(contact));
  }
};

}  // namespace reamsim::test
