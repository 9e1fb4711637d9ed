// Help → Plugins: what loaded, from where, and what failed and why.
#include <QDialog>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

#include "MainWindow.h"
#include "PluginHost.h"

namespace reamsim::ui {

void MainWindow::showPluginsDialog() {
  auto* dialog = new QDialog(this);
  dialog->setObjectName("PluginsDialog");
  dialog->setWindowTitle(tr("Plugins"));
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(new QLabel(tr("Plugin folder: %1").arg(plugins_.directory()), dialog));
  const auto& records = plugins_.records();
  auto* table = new QTableWidget(static_cast<int>(records.size()), 4, dialog);
  table->setObjectName("PluginsTable");
  table->setHorizontalHeaderLabels({tr("plugin"), tr("status"), tr("provides"), tr("details")});
  for (int i = 0; i < static_cast<int>(records.size()); ++i) {
    const PluginRecord& r = records[i];
    table->setItem(i, 0, new QTableWidgetItem(r.name));
    table->setItem(i, 1, new QTableWidgetItem(r.loaded ? tr("loaded") : tr("failed")));
    table->setItem(i, 2, new QTableWidgetItem(r.provides));
    auto* detail = new QTableWidgetItem(r.detail);
    detail->setToolTip(r.file.isEmpty() ? r.detail : r.file + "\n" + r.detail);
    table->setItem(i, 3, detail);
  }
  table->horizontalHeader()->setStretchLastSection(true);
  table->resizeColumnsToContents();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  layout->addWidget(table);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  layout->addWidget(buttons);
  dialog->resize(820, 300);
  dialog->open();
}

}  // namespace reamsim::ui
