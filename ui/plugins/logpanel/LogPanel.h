#pragma once
// The cut log dock: one row per cut (time, removed and cumulative mm³, cut ms, faces, contact point, step,
// reamer, and the axis's version and inclination when the bone's landmarks are placed),
// live plots of cumulative removed volume and cut time per step, CSV export, and on request the reamed
// surface at the reamer's pose (how much of the cutting face is seated on bone, how far the bone stands off
// the face's ideal sphere: modules/tools ReamedSurface.h), and a note per row (an educator's annotation:
// double-click a row or *Note…*; kept in the log, so saved, copied for a crash, exported). Follows the document's first LogNode, whichever
// it is (a new bone brings a new log).
#include <QDockWidget>
#include <QTime>
#include <vector>

#include "reamsim/core/Document.h"
#include "reamsim/core/ScapulaLandmarks.h"

class QLabel;
class QTableWidget;
class QPushButton;

namespace reamsim::ui {

class CutPlot;

class LogPanel : public QDockWidget {
  Q_OBJECT
 public:
  LogPanel(Document& document, QWidget* parent);

  int rowCount() const;
  // Row `row`'s note becomes `note` (in the document's log); false when there is no such row.
  Q_INVOKABLE bool annotateRow(int row, const QString& note);
  Q_INVOKABLE QString noteOfRow(int row) const;  // as the table shows it

 public Q_SLOTS:
  // Writes the log as CSV; returns an error message, empty on success (also shown in a dialog if
  // `interactive`).
  QString exportCsv(const QString& path, bool interactive = false);
  void exportCsvInteractive();
  // Asks for the note of `row` (the selected row, or the last, for -1) in a dialog.
  void annotateInteractive(int row = -1);
  // Measures the first bone's surface against the first reamer's ideal face at its pose and shows the
  // result (or why there is none); returns the text shown. O(bone faces), on request only.
  QString measureSeat();

 private:
  void sync();
  void showAngles(std::size_t firstRow);
  void showNotes();
  void showUndone();  // rows whose cut is undone (not in the bone now) in grey italics, with a tooltip
  void styleUndone(int row, int col);
  static constexpr int kContactColumn = 5;  // its tooltip says where a move met the bone
  static constexpr int kReamerColumn = 7;   // its tooltip gives the reamer's size
  static constexpr int kAnglesColumn = 8;
  static constexpr int kNoteColumn = 9;

  Document& document_;
  Subscription subscription_;
  NodeId logId_;
  ScapulaLandmarks anglesFrom_;  // the landmarks the angles column was computed with
  std::size_t shown_ = 0;
  std::uint64_t notesShown_ = 0;  // the log's notesRevision the note column shows
  std::vector<bool> undoneShown_;  // by row, as shown
  QTableWidget* table_ = nullptr;
  CutPlot* plot_ = nullptr;
  QPushButton* exportButton_ = nullptr;
  QPushButton* seatButton_ = nullptr;
  QPushButton* noteButton_ = nullptr;
  QLabel* seatLabel_ = nullptr;
};

}  // namespace reamsim::ui
