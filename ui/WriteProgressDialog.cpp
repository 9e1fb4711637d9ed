#include "WriteProgressDialog.h"

#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>
#include <cmath>

namespace reamsim::ui {

WriteProgressDialog::WriteProgressDialog(const QString& what, QWidget* parent, const QString& title)
    : QDialog(parent), what_(what) {
  setObjectName("WriteProgressDialog");
  setWindowTitle(title.isEmpty() ? tr("Saving") : title);
  setWindowModality(Qt::WindowModal);
  label_ = new QLabel(what_, this);
  bar_ = new QProgressBar(this);
  bar_->setRange(0, 1000);
  bar_->setValue(0);
  cancel_ = new QPushButton(tr("Cancel"), this);
  cancel_->setObjectName("WriteCancelButton");
  connect(cancel_, &QPushButton::clicked, this, &WriteProgressDialog::reject);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(label_);
  layout->addWidget(bar_);
  layout->addWidget(cancel_, 0, Qt::AlignRight);
}

void WriteProgressDialog::showProgress(double fraction, const QString& stage) {
  if (cancelRequested()) return;
  bar_->setValue(int(std::lround(fraction * 1000)));
  label_->setText(tr("%1: %2").arg(what_, stage));
}

void WriteProgressDialog::reject() {
  if (stop_->exchange(true)) return;
  label_->setText(tr("Cancelling…"));  // a write past its last check still ends; the caller says how it ended
  cancel_->setEnabled(false);
}

}  // namespace reamsim::ui
