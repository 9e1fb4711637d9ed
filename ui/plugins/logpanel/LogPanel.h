#pragma once
// The cut log dock: one row per cut (time, removed and cumulative mm³, cut ms, faces, contact point),
// live plots of cumulative removed volume and cut time per step, CSV export. Follows the document's
// first LogNode, whichever it is (a new bone brings a new log).
#include <QDockWidget>
#include <QTime>
#include <vector>

#include "reamsim/core/Document.h"

class QTableWidget;
class QPushButton;

namespace reamsim::ui {

class CutPlot;

class LogPanel : public QDockWidget {
  Q_OBJECT
 public:
  LogPanel(Document& document, QWidget* parent);

  int rowCount() const;

 public Q_SLOTS:
  // Writes the log as CSV; returns an error message, empty on success (also shown in a dialog if
  // `interactive`).
  QString exportCsv(const QString& path, bool interactive = false);
  void exportCsvInteractive();

 private:
  void sync();

  Document& document_;
  Subscription subscription_;
  NodeId logId_;
  std::size_t shown_ = 0;
  QTableWidget* table_ = nullptr;
  CutPlot* plot_ = nullptr;
  QPushButton* exportButton_ = nullptr;
};

}  // namespace reamsim::ui
