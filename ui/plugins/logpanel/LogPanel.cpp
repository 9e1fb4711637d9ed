#include "LogPanel.h"

#include <QDateTime>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QInputDialog>
#include <QLabel>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include "CutPlot.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/tools/ReamedSurface.h"
#include "reamsim/ui/PointText.h"

namespace reamsim::ui {

LogPanel::LogPanel(Document& document, QWidget* parent) : QDockWidget(tr("Cut log"), parent), document_(document) {
  setObjectName("LogPanel");
  auto* body = new QWidget(this);
  auto* layout = new QVBoxLayout(body);
  auto* splitter = new QSplitter(Qt::Vertical, body);
  table_ = new QTableWidget(0, 10, splitter);
  table_->setObjectName("LogTable");
  table_->setHorizontalHeaderLabels({tr("time"), tr("removed mm³"), tr("cumulative mm³"), tr("cut ms"), tr("faces"),
                                     tr("contact point (mm)"), tr("step"), tr("reamer"),
                                     tr("version / inclination"), tr("note")});
  table_->horizontalHeaderItem(kNoteColumn)
      ->setToolTip(tr("Your annotation of the cut: double-click the row, or select it and press Note…"));
  table_->horizontalHeaderItem(kAnglesColumn)
      ->setToolTip(tr("The reamer axis's version and inclination in the scapular frame of the bone's landmarks "
                      "(Planning dock; docs/PLANNING.md): – where the landmarks are not all placed"));
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setFocusPolicy(Qt::NoFocus);  // the reamer keys stay with the main window
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->verticalHeader()->setVisible(false);
  plot_ = new CutPlot(splitter);
  plot_->setObjectName("CutPlot");
  exportButton_ = new QPushButton(tr("Export CSV…"), body);
  exportButton_->setObjectName("ExportCsv");
  exportButton_->setFocusPolicy(Qt::NoFocus);
  seatButton_ = new QPushButton(tr("Measure seat"), body);
  seatButton_->setObjectName("MeasureSeat");
  seatButton_->setFocusPolicy(Qt::NoFocus);
  seatButton_->setToolTip(tr("How much of the reamer's cutting face sits on reamed bone at its pose, and how far "
                             "the bone stands off the face's ideal sphere"));
  noteButton_ = new QPushButton(tr("Note…"), body);
  noteButton_->setObjectName("AnnotateRow");
  noteButton_->setFocusPolicy(Qt::NoFocus);
  noteButton_->setToolTip(tr("Write a note on the selected cut (the last one when none is selected): saved with the "
                             "log, in the report and in an exported path, shown when the path is replayed"));
  seatLabel_ = new QLabel(body);
  seatLabel_->setObjectName("SeatReport");
  seatLabel_->setWordWrap(true);
  seatLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(noteButton_);
  buttons->addWidget(seatButton_);
  buttons->addWidget(exportButton_);
  layout->addWidget(splitter);
  layout->addWidget(seatLabel_);
  layout->addLayout(buttons);
  setWidget(body);
  connect(exportButton_, &QPushButton::clicked, this, &LogPanel::exportCsvInteractive);
  connect(seatButton_, &QPushButton::clicked, this, [this] { measureSeat(); });
  connect(noteButton_, &QPushButton::clicked, this, [this] { annotateInteractive(); });
  connect(table_, &QTableWidget::cellDoubleClicked, this, [this](int row, int) { annotateInteractive(row); });
  subscription_ = document_.subscribe([this](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Log || e.id.kind() == NodeKind::Bone) sync();
  });
  sync();
}

int LogPanel::rowCount() const { return table_->rowCount(); }

void LogPanel::sync() {
  const LogNode* log = document_.firstOf<LogNode>();
  if (!log || log->id() != logId_) {  // another log (new bone) or none: start over
    table_->setRowCount(0);
    shown_ = 0;
    notesShown_ = 0;
    undoneShown_.clear();
    logId_ = log ? log->id() : NodeId{};
  }
  if (!log) {
    plot_->setData({}, {});
    return;
  }
  const auto& entries = log->entries();
  const BoneNode* bone = document_.firstOf<BoneNode>();
  const ScapulaLandmarks landmarks = bone ? bone->landmarks() : ScapulaLandmarks{};
  const bool otherLandmarks = !(landmarks == anglesFrom_);
  anglesFrom_ = landmarks;
  if (otherLandmarks) showAngles(0);  // every row again, in the new frame
  showNotes();  // of the rows shown (a note may change in the same event as rows are added)
  if (entries.size() == shown_) return showUndone();  // an undo or redo of the bone, or a note
  seatLabel_->clear();  // measured on an earlier bone state
  for (std::size_t i = shown_; i < entries.size(); ++i) {
    const CutLogEntry& e = entries[i];
    const int row = table_->rowCount();
    table_->insertRow(row);
    auto cell = [&](int col, const QString& text) { table_->setItem(row, col, new QTableWidgetItem(text)); };
    // The time the step was committed, in local time (the CSV has it in UTC).
    cell(0, e.timeUnixMs > 0 ? QDateTime::fromMSecsSinceEpoch(e.timeUnixMs).toString("HH:mm:ss.zzz") : QString());
    // Numbers shown in the user's locale (decimal comma in de_DE), without group separators as in the CSV,
    // which keeps the C locale's.
    QLocale shown;
    shown.setNumberOptions(QLocale::OmitGroupSeparator);
    cell(1, shown.toString(e.removedMm3, 'f', 3));
    cell(2, shown.toString(e.cumulativeMm3, 'f', 3));
    cell(3, shown.toString(e.cutMs, 'f', 1));
    cell(4, shown.toString(qlonglong(e.faces)));
    cell(kContactColumn, e.contactPoint ? pointText(*e.contactPoint, 2) : QStringLiteral("–"));
    if (e.moveContactT && e.moveContactPoint)  // a move onto the bone: where it first met it
      table_->item(row, kContactColumn)->setToolTip(tr("the move first met the bone %L1 % of the way, at %2 mm")
                                           .arg(100.0 * *e.moveContactT, 0, 'f', 1)
                                           .arg(pointText(*e.moveContactPoint, 2)));
    cell(6, QString::number(e.stepIndex));
    cell(kReamerColumn, QString::fromStdString(e.reamer));  // a session may change reamers
    if (e.reamerDiameterMm > 0)
      table_->item(row, kReamerColumn)->setToolTip(e.reamerSphereRadiusMm
                                           ? tr("Ø %L1 mm, cap sphere R %L2 mm").arg(e.reamerDiameterMm).arg(*e.reamerSphereRadiusMm)
                                           : tr("Ø %L1 mm, flat").arg(e.reamerDiameterMm));
  }
  const std::size_t firstNew = shown_;
  shown_ = entries.size();
  showAngles(firstNew);
  for (std::size_t i = firstNew; i < shown_; ++i)
    table_->setItem(int(i), kNoteColumn, new QTableWidgetItem(QString::fromStdString(entries[i].note)));
  notesShown_ = log->notesRevision();
  showUndone();
  table_->scrollToBottom();
  std::vector<double> cumulative, ms;
  for (const CutLogEntry& e : entries) {
    cumulative.push_back(e.cumulativeMm3);
    ms.push_back(e.cutMs);
  }
  plot_->setData(std::move(cumulative), std::move(ms));
}

// The rows from `first` on: the axis's version and inclination in the frame of the landmarks shown.
void LogPanel::showAngles(std::size_t first) {
  const LogNode* log = document_.firstOf<LogNode>();
  if (!log) return;
  std::optional<ScapularFrame> frame;
  try {
    frame = scapularFrame(anglesFrom_);
  } catch (const std::invalid_argument&) {  // not all placed: the header's tooltip says so
  }
  QLocale shown;
  const auto& entries = log->entries();
  for (std::size_t i = first; i < shown_ && i < entries.size(); ++i) {
    QString text = QStringLiteral("–");
    if (frame) try {
        const AxisAngles a = feedAxisAngles(*frame, entries[i].pose.axis);
        text = shown.toString(a.versionDeg, 'f', 1) + QStringLiteral("° / ") + shown.toString(a.inclinationDeg, 'f', 1) +
               QStringLiteral("°");
      } catch (const std::invalid_argument&) {  // pointing medially
      }
    table_->setItem(int(i), kAnglesColumn, new QTableWidgetItem(text));
    styleUndone(int(i), kAnglesColumn);
  }
}

// The log keeps every row (it records what was done); a cut undone since, or undone when a log read back was
// written, is shown apart, as the report marks it (undoneRows).
void LogPanel::showUndone() {
  const LogNode* log = document_.firstOf<LogNode>();
  const BoneNode* bone = document_.firstOf<BoneNode>();
  if (!log || !bone) return;
  const std::vector<bool> undone = undoneRows(log->entries(), bone->history());
  undoneShown_.resize(std::min<std::size_t>(shown_, undone.size()), false);
  for (std::size_t i = 0; i < undoneShown_.size(); ++i) {
    if (undoneShown_[i] == undone[i]) continue;
    undoneShown_[i] = undone[i];
    for (int col = 0; col < table_->columnCount(); ++col) styleUndone(int(i), col);
  }
}

// One cell as its row's undone state says (also a cell made again: the angles in a new frame, a changed note).
void LogPanel::styleUndone(int row, int col) {
  QTableWidgetItem* item = table_->item(row, col);
  if (!item) return;
  const bool undone = std::size_t(row) < undoneShown_.size() && undoneShown_[std::size_t(row)];
  QFont font = item->font();
  font.setItalic(undone);
  item->setFont(font);
  item->setForeground(undone ? palette().brush(QPalette::Disabled, QPalette::Text) : palette().brush(QPalette::Text));
  if (col != kContactColumn && col != kReamerColumn)  // those keep their own tooltips
    item->setToolTip(undone ? tr("Undone: this cut is not in the bone now") : QString());
}

// Every row's note again when one has changed since they were shown (a row's note is all that can change).
void LogPanel::showNotes() {
  const LogNode* log = document_.firstOf<LogNode>();
  if (!log || log->notesRevision() == notesShown_) return;
  notesShown_ = log->notesRevision();
  const auto& entries = log->entries();
  for (std::size_t i = 0; i < shown_ && i < entries.size(); ++i) {
    const QString note = QString::fromStdString(entries[i].note);
    QTableWidgetItem* item = table_->item(int(i), kNoteColumn);
    if (!item || item->text() != note) {
      table_->setItem(int(i), kNoteColumn, new QTableWidgetItem(note));
      styleUndone(int(i), kNoteColumn);
    }
  }
}

bool LogPanel::annotateRow(int row, const QString& note) {
  LogNode* log = document_.firstOf<LogNode>();
  if (!log || row < 0 || std::size_t(row) >= log->size()) return false;
  log->setNote(std::size_t(row), note.toStdString());
  return true;
}

QString LogPanel::noteOfRow(int row) const {
  const QTableWidgetItem* item = row >= 0 && row < table_->rowCount() ? table_->item(row, kNoteColumn) : nullptr;
  return item ? item->text() : QString();
}

void LogPanel::annotateInteractive(int row) {
  if (row < 0) row = table_->currentRow() >= 0 ? table_->currentRow() : table_->rowCount() - 1;
  const LogNode* log = document_.firstOf<LogNode>();
  if (!log || row < 0 || std::size_t(row) >= log->size()) {
    QMessageBox::information(this, tr("Note"), tr("There is no cut to write a note on yet."));
    return;
  }
  const NodeId logId = log->id();
  const CutLogEntry& e = log->entries()[std::size_t(row)];
  const std::size_t step = e.stepIndex;
  const QString title = tr("Note on cut %1").arg(step);
  const QString label = tr("Step %1: %L2 mm³ removed. Your note (shown in the report, kept in an exported path):")
                            .arg(step)
                            .arg(e.removedMm3, 0, 'f', 3);
  bool ok = false;
  const QString note = QInputDialog::getMultiLineText(this, title, label, QString::fromStdString(e.note), &ok);
  // Cuts go on while the dialog is open; another bone brings another log, whose rows this note is not for.
  const LogNode* now = document_.firstOf<LogNode>();
  if (ok && now && now->id() == logId) annotateRow(row, note);
}

QString LogPanel::exportCsv(const QString& path, bool interactive) {
  const LogNode* log = document_.firstOf<LogNode>();
  QString error;
  try {
    const BoneNode* bone = document_.firstOf<BoneNode>();  // the cut bone: its undone cuts are marked
    std::vector<CutLogEntry> rows = log ? log->entries() : std::vector<CutLogEntry>{};
    if (bone) rows = withUndoneMarked(std::move(rows), bone->history());
    // With the landmarks' frame, each row's version and inclination, as the panel shows them.
    std::optional<ScapularFrame> frame;
    if (bone) try {
        frame = scapularFrame(bone->landmarks());
      } catch (const std::invalid_argument&) {  // no frame: the columns are left out
      }
    writeTextFile(path.toStdString(), frame ? cutLogCsv(rows, *frame) : cutLogCsv(rows));
  } catch (const std::exception& e) {
    error = QString::fromStdString(e.what());
  }
  if (!error.isEmpty() && interactive) {
    auto* box = new QMessageBox(QMessageBox::Critical, tr("Export CSV"), error, QMessageBox::Ok, this);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
  }
  return error;
}

QString LogPanel::measureSeat() {
  const BoneNode* bone = document_.firstOf<BoneNode>();
  const ReamerNode* reamer = document_.firstOf<ReamerNode>();
  QString text;
  if (!bone || !reamer) {
    text = tr("No bone or reamer to measure.");
  } else if (!reamer->spec().meshFile.empty()) {
    text = tr("The reamer is read from a mesh: it has no ideal face to measure the bone against.");
  } else {
    try {
      const ReamedSurfaceReport r = measureReamedSurface(bone->current().toMesh(), reamer->spec(), reamer->pose());
      text = tr("Seat at the reamer's pose: %L1 % of the cutting face on bone (%L2 faces); standoff from the ideal "
                "face %L3 to %L4 mm, rms %L5 mm (the reamer mesh's facets sag %L6 mm).")
                 .arg(100 * r.seatedFraction, 0, 'f', 1)
                 .arg(r.faces)
                 .arg(r.standoffMinMm, 0, 'f', 4)
                 .arg(r.standoffMaxMm, 0, 'f', 4)
                 .arg(r.standoffRmsMm, 0, 'f', 4)
                 .arg(r.facetSagMm, 0, 'f', 4);
    } catch (const std::exception& e) {
      text = tr("Cannot measure the seat: %1").arg(QString::fromStdString(e.what()));
    }
  }
  seatLabel_->setText(text);
  return text;
}

void LogPanel::exportCsvInteractive() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export cut log"), "cut_log.csv", tr("CSV (*.csv)"));
  if (!path.isEmpty()) exportCsv(path, true);
}

}  // namespace reamsim::ui
