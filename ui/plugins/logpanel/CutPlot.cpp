#include "CutPlot.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>

namespace reamsim::ui {
namespace {

void drawChart(QPainter& p, const QRectF& area, const QString& title, const std::vector<double>& v, bool bars,
               const QColor& colour) {
  p.setPen(QColor(90, 90, 90));
  p.drawRect(area);
  const double top = v.empty() ? 1.0 : std::max(1e-9, *std::max_element(v.begin(), v.end()));
  p.drawText(area.adjusted(4, 2, -4, 0), Qt::AlignLeft | Qt::AlignTop,
             QStringLiteral("%1 (max %2)").arg(title).arg(top, 0, 'f', top < 10 ? 2 : 0));
  if (v.empty()) return;
  const QRectF plot = area.adjusted(4, 18, -4, -4);
  const double dx = plot.width() / std::max<std::size_t>(v.size(), 1);
  auto y = [&](double value) { return plot.bottom() - plot.height() * value / top; };
  if (bars) {
    for (std::size_t i = 0; i < v.size(); ++i)
      p.fillRect(QRectF(plot.left() + i * dx + dx * 0.15, y(v[i]), dx * 0.7, plot.bottom() - y(v[i])), colour);
  } else {
    QPainterPath path(QPointF(plot.left(), y(v[0])));
    for (std::size_t i = 0; i < v.size(); ++i) path.lineTo(plot.left() + (i + 1) * dx, y(v[i]));
    p.setPen(QPen(colour, 2));
    p.drawPath(path);
  }
}

}  // namespace

CutPlot::CutPlot(QWidget* parent) : QWidget(parent) { setMinimumHeight(140); }

void CutPlot::setData(std::vector<double> cumulativeMm3, std::vector<double> cutMs) {
  cumulative_ = std::move(cumulativeMm3);
  cutMs_ = std::move(cutMs);
  update();
}

void CutPlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), palette().base());
  const QRectF r = QRectF(rect()).adjusted(2, 2, -2, -2);
  const double h = (r.height() - 4) / 2;
  drawChart(p, QRectF(r.left(), r.top(), r.width(), h), tr("cumulative removed mm³"), cumulative_, false,
            QColor(200, 60, 40));
  drawChart(p, QRectF(r.left(), r.top() + h + 4, r.width(), h), tr("cut ms per step"), cutMs_, true,
            QColor(40, 100, 200));
}

}  // namespace reamsim::ui
