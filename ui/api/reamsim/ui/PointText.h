#pragma once
// A point for the user to read: "x, y, z" in the user's locale, without group separators; where the decimal
// sign is a comma the coordinates are parted by "; ". Shared by the panels (log, planning).
#include <QLocale>
#include <QString>

#include "reamsim/mesh/Vec3.h"

namespace reamsim::ui {

inline QString pointText(const Vec3& p, int decimals) {
  QLocale shown;
  shown.setNumberOptions(QLocale::OmitGroupSeparator);
  const QString sep = shown.decimalPoint() == QChar(',') ? QStringLiteral("; ") : QStringLiteral(", ");
  return shown.toString(p.x, 'f', decimals) + sep + shown.toString(p.y, 'f', decimals) + sep +
         shown.toString(p.z, 'f', decimals);
}

}  // namespace reamsim::ui
