#include "RecoveryFiles.h"

#include <cmath>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
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

RecoveryFiles::RecoveryFiles(const QString& dir) : dir_(dir) {
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

QString RecoveryFiles::originalPath(std::uint64_t revision) const {
  return path("original-" + QString::number(revision) + ".ply");
}

bool RecoveryFiles::writeOriginal(std::uint64_t revision, const std::function<void(const QString&)>& write,
                                  QString& error) const {
  const QString final = originalPath(revision);
  if (QFile::exists(final)) return true;
  const QString part = final + ".part.ply";  // the writer picks the format from the suffix
  try {
    write(part);
  } catch (const std::exception& e) {
    QFile::remove(part);
    error = QString::fromStdString(e.what());
    return false;
  }
  if (!QFile::rename(part, final)) {
    QFile::remove(part);
    error = final + ": cannot write it (renaming " + part + " failed)";
    return false;
  }
  return true;
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
  r.cuts = d.value("cuts").toInt();
  r.written = QDateTime::fromString(d.value("written").toString(), Qt::ISODate).toLocalTime();
  if (d.value("removed_mm3").isDouble()) r.removedMm3 = d.value("removed_mm3").toDouble();
  const QJsonArray beside = d.value("beside").toArray();
  for (int i = 0; i < beside.size(); ++i) {
    const QString file = besidePath(slot, i);
    if (QFile::exists(file)) r.beside.push_back({beside[i].toString(), file});
  }
  const QString original = d.value("original").toString();
  if (!original.isEmpty() && QFile::exists(path(original))) r.originalPath = path(original);
  return r;
}

bool RecoveryFiles::commit(const QString& name, int cuts, double removedMm3, const QStringList& besideNames,
                           std::uint64_t originalRevision, QString& error) const {
  const QString original = originalRevision ? QFileInfo(originalPath(originalRevision)).fileName() : QString();
  QJsonObject d;
  d.insert("slot", nextSlot());
  d.insert("name", name);
  d.insert("cuts", cuts);
  if (!besideNames.isEmpty()) d.insert("beside", QJsonArray::fromStringList(besideNames));
  if (!original.isEmpty()) d.insert("original", original);
  if (std::isfinite(removedMm3)) d.insert("removed_mm3", removedMm3);
  d.insert("written", QDateTime::currentDateTimeUtc().toString(Qt::ISODate));
  QSaveFile f(path(kDescription));
  if (!f.open(QIODevice::WriteOnly) || f.write(QJsonDocument(d).toJson()) < 0 || !f.commit()) {
    error = path(kDescription) + ": cannot write it (" + f.errorString() + ")";
    return false;
  }
  for (const QString& f : QDir(dir_).entryList({"original-*.ply"}, QDir::Files))  // an earlier bone's
    if (f != original) QFile::remove(path(f));
  return true;
}

void RecoveryFiles::remove() const {
  QFile::remove(path(kDescription));
  for (const char* f : {"bone.a.ply", "bone.b.ply", "cut_log.a.csv", "cut_log.b.csv"}) QFile::remove(path(f));
  for (const QString& f : QDir(dir_).entryList({"beside*.ply", "original-*.ply"}, QDir::Files)) QFile::remove(path(f));
}

}  // namespace reamsim::ui
