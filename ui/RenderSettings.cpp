#include "RenderSettings.h"

#include <QSettings>

namespace reamsim::ui {

RenderSettings RenderSettings::load(QSettings& s) {
  RenderSettings r;
  s.beginGroup("render");
  auto colour = [&](const char* key, QColor& c) { c = s.value(key, c).value<QColor>(); };
  auto number = [&](const char* key, double& v) { v = s.value(key, v).toDouble(); };
  colour("background", r.background);
  colour("background2", r.background2);
  colour("bone", r.bone);
  colour("reamer", r.reamer);
  colour("fresh_cut", r.freshCut);
  number("reamer_opacity", r.reamerOpacity);
  colour("ambient_light", r.ambientLight);
  number("ambient", r.ambient);
  number("diffuse", r.diffuse);
  number("specular", r.specular);
  number("specular_power", r.specularPower);
  number("directional_intensity", r.directionalIntensity);
  number("point_intensity", r.pointIntensity);
  number("point_azimuth_deg", r.pointAzimuthDeg);
  number("point_elevation_deg", r.pointElevationDeg);
  r.smoothShading = s.value("smooth_shading", r.smoothShading).toBool();
  s.endGroup();
  return r;
}

void RenderSettings::save(QSettings& s) const {
  s.beginGroup("render");
  s.setValue("background", background);
  s.setValue("background2", background2);
  s.setValue("bone", bone);
  s.setValue("reamer", reamer);
  s.setValue("fresh_cut", freshCut);
  s.setValue("reamer_opacity", reamerOpacity);
  s.setValue("ambient_light", ambientLight);
  s.setValue("ambient", ambient);
  s.setValue("diffuse", diffuse);
  s.setValue("specular", specular);
  s.setValue("specular_power", specularPower);
  s.setValue("directional_intensity", directionalIntensity);
  s.setValue("point_intensity", pointIntensity);
  s.setValue("point_azimuth_deg", pointAzimuthDeg);
  s.setValue("point_elevation_deg", pointElevationDeg);
  s.setValue("smooth_shading", smoothShading);
  s.endGroup();
}

}  // namespace reamsim::ui
