#pragma once
// Parameters of a glenoid reamer. The cutting volume is a spherical cap of chord diameter D and sphere
// radius R (flat when R is infinite) followed by a cylindrical body of diameter D: everything behind the
// cutting face within the reamer's diameter is removed too when it is fed into bone.
#include <limits>
#include <string>

namespace reamsim {

struct ReamerSpec {
  std::string name = "custom";
  double diameterMm = 44.0;                                     // chord diameter D of the cutting face
  double sphereRadiusMm = std::numeric_limits<double>::infinity();  // R; infinity = flat reamer
  double bodyLengthMm = 12.0;     // length of the cylindrical cutting body behind the cap
  double guidePinDiameterMm = 0;  // 0 = no guide pin (display only)
  double guidePinLengthMm = 0;
  double shaftDiameterMm = 6.0;   // display only
  double shaftLengthMm = 60.0;
  int segments = 96;              // facets around the axis (resolution)
  int rings = 12;                 // rings on the spherical cap (resolution)
  std::string meshFile;           // non-empty: the cutting volume is read from this mesh instead

  bool isFlat() const { return !(sphereRadiusMm < std::numeric_limits<double>::infinity()); }
};

}  // namespace reamsim
