#pragma once
// Two small live charts drawn with QPainter (no chart library needed): cumulative removed volume per
// step (line) and cut time per step (bars).
#include <QWidget>
#include <vector>

namespace reamsim::ui {

class CutPlot : public QWidget {
  Q_OBJECT
 public:
  explicit CutPlot(QWidget* parent = nullptr);
  void setData(std::vector<double> cumulativeMm3, std::vector<double> cutMs);
  QSize sizeHint() const override { return {360, 180}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  std::vector<double> cumulative_, cutMs_;
};

}  // namespace reamsim::ui
