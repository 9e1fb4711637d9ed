#pragma once
// A document with a bone, a reamer, a log and alerts, wired to a ReamController.
#include <memory>

#include "reamsim/core/Document.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim::test {

struct ReamScene {
  Document doc;
  BoneNode* bone = nullptr;
  ReamerNode* reamer = nullptr;
  LogNode* log = nullptr;
  AlertNode* alerts = nullptr;
  std::unique_ptr<ReamController> controller;

  ReamScene(const TriangleMesh& boneMesh, const ReamerSpec& spec, CutBackendFactory cut = referenceCutBackendFactory()) {
    bone = &doc.create<BoneNode>("Bone", BoneState::fromMesh(boneMesh));
    reamer = &doc.create<ReamerNode>("Reamer", spec);
    reamer->setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(spec)));
    log = &doc.create<LogNode>("Log");
    alerts = &doc.create<AlertNode>("Alerts");
    controller = std::make_unique<ReamController>(doc, *bone, *reamer, *log, alerts, std::move(cut));
  }
};

}  // namespace reamsim::test
