#pragma once
// Colours, material and lights of the 3D view (the thesis's ambient, directional and point lights),
// kept in QSettings under "render/".
#include <QColor>

class QSettings;

namespace reamsim::ui {

struct RenderSettings {
  QColor background{32, 36, 44};
  QColor background2{78, 88, 104};  // gradient top
  QColor bone{233, 222, 196};
  QColor reamer{150, 160, 175};
  QColor freshCut{220, 70, 50};     // the surface made by the last cut
  double reamerOpacity = 1.0;
  QColor ambientLight{255, 255, 255};  // colour of the ambient light (the renderers' ambient)
  double ambient = 0.15;            // how much of the ambient light the materials reflect
  double diffuse = 0.85;
  double specular = 0.15;
  double specularPower = 20;
  double directionalIntensity = 0.75;  // light along the view direction (camera light)
  double pointIntensity = 0.45;        // positional light, placed around the bone:
  double pointAzimuthDeg = 0;          //   about the bone's +Y (superior) axis, 0 = lateral (+Z)
  double pointElevationDeg = 45;       //   above the XZ plane; one bone diagonal from its centre
  bool smoothShading = true;

  static RenderSettings load(QSettings& settings);
  void save(QSettings& settings) const;
};

}  // namespace reamsim::ui
