#pragma once
// Reamer presets stored as JSON (resources/reamers.json). Format:
//   { "presets": [ { "name": "glenoid-36-R30", "diameterMm": 36, "sphereRadiusMm": 30 | "flat",
//                    "bodyLengthMm": 12, "guidePinDiameterMm": 3.2, "guidePinLengthMm": 20,
//                    "shaftDiameterMm": 8, "shaftLengthMm": 80, "segments": 96, "rings": 12,
//                    "meshFile": "optional/path.stl", "source": "free text" }, ... ] }
// A bare array of preset objects is accepted too. Unknown keys are rejected (they are usually typos).
// A relative meshFile is resolved against the JSON file's directory.
#include <string>
#include <vector>

#include "reamsim/core/ReamerSpec.h"

namespace reamsim {

// Throws reamsim::InputError for unreadable or malformed files (with the line of a JSON syntax error)
// and for invalid presets (naming the preset and the field).
std::vector<ReamerSpec> loadPresets(const std::string& presetsJsonPath);

// Throws std::invalid_argument listing the known names when `name` is not in the file.
ReamerSpec loadPreset(const std::string& name, const std::string& presetsJsonPath);

// Same parsing from text; `sourceName` only labels error messages, `baseDir` resolves relative meshFile.
std::vector<ReamerSpec> parsePresets(const std::string& jsonText, const std::string& sourceName = "<json>",
                                     const std::string& baseDir = "");
// One preset object, e.g. "{\"name\":\"x\",\"diameterMm\":40,\"sphereRadiusMm\":32}".
ReamerSpec reamerSpecFromJsonText(const std::string& jsonObjectText);

}  // namespace reamsim
