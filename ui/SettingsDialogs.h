#pragma once
// Small dialogs: colours/material/lights of the view, and the reamer key bindings.
#include <QDialog>
#include <QKeySequence>
#include <QMap>

#include "RenderSettings.h"

class QKeySequenceEdit;
class QFormLayout;

namespace reamsim::ui {

class RenderSettingsDialog : public QDialog {
  Q_OBJECT
 public:
  RenderSettingsDialog(const RenderSettings& initial, QWidget* parent);
  const RenderSettings& settings() const { return settings_; }

 Q_SIGNALS:
  void changed(const RenderSettings& settings);  // live preview

 private:
  RenderSettings settings_;
};

class KeyBindingsDialog : public QDialog {
  Q_OBJECT
 public:
  explicit KeyBindingsDialog(QWidget* parent);
  void addRow(const QString& id, const QString& label, const QKeySequence& current, const QKeySequence& fallback);
  QKeySequence keys(const QString& id) const;

 private:
  QFormLayout* form_ = nullptr;
  QMap<QString, QKeySequenceEdit*> edits_;
};

}  // namespace reamsim::ui
