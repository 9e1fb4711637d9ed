#include "RecoveryFiles.h"

#include <cmath>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
#include <QRandomGenerator>
#include <QSaveFile>

namespace reamsim::ui {
namespace {

constexpr const char* kDescription = "recovery.json";

QJsonObject readDescription(const QString& file) {
  QFile f(file);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QJsonDocument::fromJson(f.readAll()).object();
}

}  // namespace

RecoveryFiles::RecoveryFiles(const QString& dir)
    : dir_(dir), token_(QString::number(QRandomGenerator::system()->generate64(), 16)) {
  QDir().mkpath(dir_);
  lock_ = std::make_unique<QLockFile>(path("lock"));
  lock_->setStaleLockTime(0);  // held as long as its process lives (a dead holder's lock is stale at once)
  lock_->tryLock(0);
}

RecoveryFiles::~RecoveryFiles() = default;  // QLockFile unlocks

bool RecoveryFiles::owns() const { return lock_->isLocked(); }

QString RecoveryFiles::path(const QString& file) const { return QDir(dir_).filePath(file); }

QString RecoveryFiles::currentSlot() const {
  const QString slot = readDescription(path(kDescription)).value("slot").toString();
  return slot == "a" || slot == "b" ? slot : QString();
}

QString RecoveryFiles::nextBonePath() const { return path("bone." + nextSlot() + ".ply"); }
QString RecoveryFiles::nextLogPath() const { return path("cut_log." + nextSlot() + ".csv"); }
QString RecoveryFiles::besidePath(const QString& slot, int index) const {
  return path("beside" + QString::number(index) + "." + slot + ".ply");
}
QString RecoveryFiles::nextBesidePath(int index) const { return besidePath(nextSlot(), index); }

QString RecoveryFiles::historyPath(std::uint64_t firstRevision) const {
  return path("history-" + token_ + "-" + QString::number(firstRevision) + ".rsj");
}

std::optional<RecoveredBone> RecoveryFiles::found() const {
  const QJsonObject d = readDescription(path(kDescription));
  const QString slot = d.value("slot").toString();
  if (slot != "a" && slot != "b") return std::nullopt;
  RecoveredBone r;
  r.bonePath = path("bone." + slot + ".ply");
  if (!QFile::exists(r.bonePath)) return std::nullopt;
  r.logPath = path("cut_log." + slot + ".csv");
  if (!QFile::exists(r.logPath)) r.logPath.clear();
  r.name = d.value("name").toString();
  r.reamerPreset = d.value("reamer_preset").toString();
  r.reamerMesh = d.value("reamer_mesh").toString();
  r.cuts = d.value("cuts").toInt();
  if (d.value("landmarks").isObject())
    r.landmarksJson = QString::fromUtf8(QJsonDocument(d.value("landmarks").toObject()).toJson());
  r.written = QDateTime::fromString(d.value("written").toString(), Qt::ISODate).toLocalTime();
  if (d.value("removed_mm3").isDouble()) r.removedMm3 = d.value("removed_mm3").toDouble();
  const QJsonArray beside = d.value("beside").toArray();
  for (int i = 0; i < beside.size(); ++i) {
    const QString file = besidePath(slot, i);
    if (QFile::exists(file)) r.beside.push_back({beside[i].toString(), file});
  }
  // Revisions as strings: JSON numbers are doubles.
  const QJsonObject history = d.value("history").toObject();
  const QJsonArray revisions = history.value("revisions").toArray();
  for (const QJsonValue& v : revisions) {
    bool ok = false;
    const std::uint64_t revision = v.toString().toULongLong(&ok);
    if (!ok) {
      r.historyRevisions.clear();
      break;
    }
    r.historyRevisions.push_back(revision);
  }
  const QString journal = history.value("file").toString();  // a name in this folder, nothing else
  if (journal.startsWith("history-") && journal.endsWith(".rsj") && !journal.contains('/') && !journal.contains('\\') &&
      !r.historyRevisions.empty()) {
    r.historyPath = path(journal);
    r.historyCursor = std::size_t(std::max(0, history.value("cursor").toInt()));
    if (!QFile::exists(r.historyPath) || r.historyCursor >= r.historyRevisions.size()) {
      r.historyPath.clear();
      r.historyRevisions.clear();
      r.historyCursor = 0;
    }
  } else {
    r.historyRevisions.clear();
  }
  return r;
}

bool RecoveryFiles::commit(const CopyDescription& copy, QString& error) const {
  const std::optional<HistoryInCopy>& history = copy.history;
  const QString journal = history && !history->revisions.empty()
                              ? QFileInfo(historyPath(history->revisions.front())).fileName() : QString();
  QJsonObject d;
  d.insert("slot", nextSlot());
  d.insert("name", copy.name);
  d.insert("cuts", copy.cuts);
  if (!copy.besideNames.isEmpty()) d.insert("beside", QJsonArray::fromStringList(copy.besideNames));
  if (!copy.reamerPreset.isEmpty()) d.insert("reamer_preset", copy.reamerPreset);
  if (!copy.reamerMesh.isEmpty()) d.insert("reamer_mesh", copy.reamerMesh);
  if (!copy.landmarksJson.isEmpty()) d.insert("landmarks", QJsonDocument::fromJson(copy.landmarksJson.toUtf8()).object());
  if (!journal.isEmpty()) {
    QJsonArray revisions;
    for (std::uint64_t r : history->revisions) revisions.append(QString::number(r));
    d.insert("history", QJsonObject{{"file", journal}, {"revisions", revisions}, {"cursor", int(history->cursor)}});
  }
  if (std::isfinite(copy.removedMm3)) d.insert("removed_mm3", copy.removedMm3);
  d.insert("written", QDateTime::currentDateTimeUtc().toString(Qt::ISODate));
  QSaveFile f(path(kDescription));
  if (!f.open(QIODevice::WriteOnly) || f.write(QJsonDocument(d).toJson()) < 0 || !f.commit()) {
    error = path(kDescription) + ": cannot write it (" + f.errorString() + ")";
    return false;
  }
  for (const QString& f : QDir(dir_).entryList({"history-*.rsj"}, QDir::Files))  // an earlier bone's
    if (f != journal) QFile::remove(path(f));
  return true;
}

void RecoveryFiles::remove() const {
  QFile::remove(path(kDescription));
  for (const char* f : {"bone.a.ply", "bone.b.ply", "cut_log.a.csv", "cut_log.b.csv"}) QFile::remove(path(f));
  for (const QString& f : QDir(dir_).entryList({"beside*.ply", "history-*.rsj"}, QDir::Files)) QFile::remove(path(f));
}

}  // namespace reamsim::ui
