#include "SettingsDialogs.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QKeySequenceEdit>
#include <QPushButton>
#include <QVBoxLayout>

namespace reamsim::ui {
namespace {

QDialogButtonBox* okCancel(QDialog* d) {
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, d);
  QObject::connect(buttons, &QDialogButtonBox::accepted, d, &QDialog::accept);
  QObject::connect(buttons, &QDialogButtonBox::rejected, d, &QDialog::reject);
  return buttons;
}

void paintSwatch(QPushButton* b, const QColor& c) {
  b->setStyleSheet(QStringLiteral("QPushButton { background: %1; min-width: 60px; }").arg(c.name()));
}

}  // namespace

RenderSettingsDialog::RenderSettingsDialog(const RenderSettings& initial, QWidget* parent)
    : QDialog(parent), settings_(initial) {
  setWindowTitle(tr("Colours, material and lights"));
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);
  auto colour = [&](const QString& label, QColor RenderSettings::*member) {
    auto* b = new QPushButton(this);
    paintSwatch(b, settings_.*member);
    connect(b, &QPushButton::clicked, this, [this, b, member] {
      const QColor c = QColorDialog::getColor(settings_.*member, this);
      if (!c.isValid()) return;
      settings_.*member = c;
      paintSwatch(b, c);
      Q_EMIT changed(settings_);
    });
    form->addRow(label, b);
  };
  auto number = [&](const QString& label, double RenderSettings::*member, double max, double min = 0) {
    auto* s = new QDoubleSpinBox(this);
    s->setRange(min, max);
    s->setSingleStep(max > 2 ? 1 : 0.05);
    s->setValue(settings_.*member);
    connect(s, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this, member](double v) {
      settings_.*member = v;
      Q_EMIT changed(settings_);
    });
    form->addRow(label, s);
  };
  colour(tr("Bone"), &RenderSettings::bone);
  colour(tr("Freshly cut surface"), &RenderSettings::freshCut);
  colour(tr("Reamer"), &RenderSettings::reamer);
  number(tr("Reamer opacity"), &RenderSettings::reamerOpacity, 1);
  colour(tr("Background (bottom)"), &RenderSettings::background);
  colour(tr("Background (top)"), &RenderSettings::background2);
  colour(tr("Ambient light colour"), &RenderSettings::ambientLight);
  number(tr("Ambient light"), &RenderSettings::ambient, 1);
  number(tr("Diffuse"), &RenderSettings::diffuse, 1);
  number(tr("Specular"), &RenderSettings::specular, 1);
  number(tr("Specular power"), &RenderSettings::specularPower, 128);
  number(tr("Directional light"), &RenderSettings::directionalIntensity, 2);
  number(tr("Point light"), &RenderSettings::pointIntensity, 2);
  number(tr("Point light azimuth (°)"), &RenderSettings::pointAzimuthDeg, 180, -180);
  number(tr("Point light elevation (°)"), &RenderSettings::pointElevationDeg, 90, -90);
  auto* smooth = new QCheckBox(tr("Smooth shading"), this);
  smooth->setChecked(settings_.smoothShading);
  connect(smooth, &QCheckBox::toggled, this, [this](bool on) {
    settings_.smoothShading = on;
    Q_EMIT changed(settings_);
  });
  form->addRow(QString(), smooth);
  layout->addWidget(okCancel(this));
}

KeyBindingsDialog::KeyBindingsDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Reamer key bindings"));
  auto* layout = new QVBoxLayout(this);
  form_ = new QFormLayout;
  layout->addLayout(form_);
  layout->addWidget(okCancel(this));
}

void KeyBindingsDialog::addRow(const QString& id, const QString& label, const QKeySequence& current,
                               const QKeySequence& fallback) {
  auto* row = new QWidget(this);
  auto* h = new QHBoxLayout(row);
  h->setContentsMargins(0, 0, 0, 0);
  auto* edit = new QKeySequenceEdit(current, row);
  auto* reset = new QPushButton(tr("Default (%1)").arg(fallback.toString(QKeySequence::NativeText)), row);
  connect(reset, &QPushButton::clicked, edit, [edit, fallback] { edit->setKeySequence(fallback); });
  h->addWidget(edit, 1);
  h->addWidget(reset);
  form_->addRow(label, row);
  edits_.insert(id, edit);
}

QKeySequence KeyBindingsDialog::keys(const QString& id) const {
  auto* e = edits_.value(id);
  return e ? e->keySequence() : QKeySequence();
}

}  // namespace reamsim::ui
