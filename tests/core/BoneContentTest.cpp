// A whole bone swapped in and out of a node (the GUI's undoable CT import) and the patient frame kept
// with it: the swap is exact (history and cursor included) and revisions never repeat across histories,
// so caches keyed by revision (the engine, the view) cannot mistake one bone for another.
#include <gtest/gtest.h>

#include <set>

#include "TestMeshes.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"

using namespace reamsim;

TEST(BoneContent, PatientFrameNamesRoundTrip) {
  for (PatientFrame f : {PatientFrame::Unspecified, PatientFrame::LPS, PatientFrame::RAS})
    EXPECT_EQ(parsePatientFrame(toString(f)), f);
  EXPECT_EQ(parsePatientFrame("lps"), PatientFrame::LPS);
  EXPECT_EQ(parsePatientFrame("Ras"), PatientFrame::RAS);
  EXPECT_FALSE(parsePatientFrame("LAS").has_value());
  EXPECT_FALSE(parsePatientFrame("").has_value());
}

TEST(BoneContent, FrameAndSourceAreKeptAndNotified) {
  Document doc;
  BoneNode& bone = doc.create<BoneNode>("ct", BoneState::fromMesh(test::box(1, 1, 1)));
  int changes = 0;
  Subscription s = doc.observeNode(bone.id(), [&] { ++changes; });
  EXPECT_EQ(bone.patientFrame(), PatientFrame::Unspecified);
  bone.setPatientFrame(PatientFrame::LPS);
  bone.setPatientFrame(PatientFrame::LPS);  // unchanged: no notification
  bone.setSource("CT volume head.nrrd");
  EXPECT_EQ(bone.patientFrame(), PatientFrame::LPS);
  EXPECT_EQ(bone.source(), "CT volume head.nrrd");
  EXPECT_EQ(changes, 2);
}

TEST(BoneContent, SwapIsExactAndReversible) {
  Document doc;
  BoneNode& bone = doc.create<BoneNode>("scapula", BoneState::fromMesh(test::box(2, 2, 2)));
  bone.commit(BoneState::fromMesh(test::box(1, 2, 2)), "cut 1");
  bone.commit(BoneState::fromMesh(test::box(1, 1, 2)), "cut 2");
  ASSERT_TRUE(bone.undo());  // cursor in the middle, with a redo branch
  bone.setImportReport("repaired");
  const BoneState before = bone.current();
  const std::uint64_t revisionBefore = bone.currentRevision();
  const std::size_t cursorBefore = bone.history().cursor();

  BoneContent ct;
  ct.name = "head.nrrd";
  ct.history = BoneHistory(BoneState::fromMesh(test::box(3, 3, 3)), "import");
  ct.patientFrame = PatientFrame::RAS;
  ct.source = "CT volume head.nrrd";
  ct.importReport = "CT report";
  ct.cuttable = true;
  int changes = 0;
  Subscription s = doc.observeNode(bone.id(), [&] { ++changes; });
  {
    Document::BatchScope batch(doc);
    bone.swapContent(ct);
  }
  EXPECT_EQ(changes, 1);
  EXPECT_EQ(bone.name(), "head.nrrd");
  EXPECT_NEAR(bone.current().volume(), 27, 1e-12);
  EXPECT_EQ(bone.patientFrame(), PatientFrame::RAS);
  EXPECT_EQ(bone.source(), "CT volume head.nrrd");
  EXPECT_EQ(bone.importReport(), "CT report");
  EXPECT_EQ(ct.name, "scapula");
  EXPECT_EQ(ct.patientFrame, PatientFrame::Unspecified);
  EXPECT_TRUE(bone.cuttable());  // cuttability is part of the content: it goes with the bone
  EXPECT_FALSE(ct.cuttable);
  EXPECT_NE(bone.currentRevision(), revisionBefore);

  bone.swapContent(ct);  // back: the very same state object, cursor and redo branch
  EXPECT_EQ(bone.name(), "scapula");
  // The very same storage: one copy's worth of blocks for the two values.
  const StorageStats st = measureStorage({&bone.current(), &before});
  EXPECT_EQ(st.uniqueBytes, before.storageBytes());
  EXPECT_EQ(st.sharedBytes, st.uniqueBytes);
  EXPECT_EQ(bone.currentRevision(), revisionBefore);
  EXPECT_EQ(bone.history().cursor(), cursorBefore);
  EXPECT_EQ(bone.importReport(), "repaired");
  EXPECT_FALSE(bone.cuttable());
  EXPECT_TRUE(bone.redo());
  EXPECT_NEAR(bone.current().volume(), 2, 1e-12);
}

TEST(BoneContent, RevisionsAreUniqueAcrossHistories) {
  std::set<std::uint64_t> seen;
  BoneHistory a(BoneState::fromMesh(test::box(1, 1, 1)));
  BoneHistory b(BoneState::fromMesh(test::box(1, 1, 1)));
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(seen.insert(a.commit(BoneState::fromMesh(test::box(1, 1, 1)), "a")).second);
    EXPECT_TRUE(seen.insert(b.commit(BoneState::fromMesh(test::box(1, 1, 1)), "b")).second);
  }
  b.reset(BoneState::fromMesh(test::box(2, 2, 2)));
  EXPECT_TRUE(seen.insert(b.currentRevision()).second);
  EXPECT_TRUE(seen.insert(a.entries().front().revision).second);
}
