#include "reamsim/tools/ReamerPresets.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {

namespace {
using nlohmann::json;

// Thrown inside the parser, turned into InputError with the source name at the boundary.
struct PresetProblem : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string label(const ReamerSpec& spec, std::size_t index) {
  return "preset #" + std::to_string(index + 1) + (spec.name.empty() ? "" : " '" + spec.name + "'");
}

double number(const json& obj, const char* key, double fallback, const std::string& where) {
  if (!obj.contains(key)) return fallback;
  const json& v = obj.at(key);
  if (!v.is_number()) throw PresetProblem(where + ": \"" + key + "\" must be a number");
  return v.get<double>();
}

int integer(const json& obj, const char* key, int fallback, const std::string& where) {
  if (!obj.contains(key)) return fallback;
  const json& v = obj.at(key);
  if (!v.is_number_integer()) throw PresetProblem(where + ": \"" + key + "\" must be an integer");
  const auto i = v.get<long long>();
  if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
    throw PresetProblem(where + ": \"" + key + "\" is out of range");
  return static_cast<int>(i);
}

ReamerSpec specFromJson(const json& obj, std::size_t index, const std::string& baseDir) {
  static const std::set<std::string> kKeys = {
      "name",         "diameterMm",    "sphereRadiusMm", "bodyLengthMm", "guidePinDiameterMm",
      "guidePinLengthMm", "shaftDiameterMm", "shaftLengthMm", "segments", "rings",
      "meshFile",     "source"};
  const std::string where0 = "preset #" + std::to_string(index + 1);
  if (!obj.is_object()) throw PresetProblem(where0 + ": expected an object");
  ReamerSpec spec;
  if (!obj.contains("name") || !obj.at("name").is_string() || obj.at("name").get<std::string>().empty())
    throw PresetProblem(where0 + ": \"name\" (non-empty string) is required");
  spec.name = obj.at("name").get<std::string>();
  const std::string where = label(spec, index);
  for (const auto& item : obj.items())
    if (!kKeys.count(item.key())) throw PresetProblem(where + ": unknown key \"" + item.key() + "\"");

  const bool hasMesh = obj.contains("meshFile");
  if (hasMesh) {
    if (!obj.at("meshFile").is_string()) throw PresetProblem(where + ": \"meshFile\" must be a string");
    std::filesystem::path p = obj.at("meshFile").get<std::string>();
    if (p.is_relative() && !baseDir.empty()) p = std::filesystem::path(baseDir) / p;
    spec.meshFile = p.string();
  }
  if (!obj.contains("diameterMm") && !hasMesh) throw PresetProblem(where + ": \"diameterMm\" is required");
  spec.diameterMm = number(obj, "diameterMm", spec.diameterMm, where);
  if (obj.contains("sphereRadiusMm")) {
    const json& r = obj.at("sphereRadiusMm");
    if (r.is_string() && (r == "flat" || r == "infinity"))
      spec.sphereRadiusMm = std::numeric_limits<double>::infinity();
    else if (r.is_number())
      spec.sphereRadiusMm = r.get<double>();
    else
      throw PresetProblem(where + ": \"sphereRadiusMm\" must be a number or \"flat\"");
  } else if (!hasMesh) {
    throw PresetProblem(where + ": \"sphereRadiusMm\" is required (a number, or \"flat\")");
  }
  spec.bodyLengthMm = number(obj, "bodyLengthMm", spec.bodyLengthMm, where);
  spec.guidePinDiameterMm = number(obj, "guidePinDiameterMm", spec.guidePinDiameterMm, where);
  spec.guidePinLengthMm = number(obj, "guidePinLengthMm", spec.guidePinLengthMm, where);
  spec.shaftDiameterMm = number(obj, "shaftDiameterMm", spec.shaftDiameterMm, where);
  spec.shaftLengthMm = number(obj, "shaftLengthMm", spec.shaftLengthMm, where);
  spec.segments = integer(obj, "segments", spec.segments, where);
  spec.rings = integer(obj, "rings", spec.rings, where);
  if (obj.contains("source") && !obj.at("source").is_string())
    throw PresetProblem(where + ": \"source\" must be a string");
  try {
    validateReamerSpec(spec);
  } catch (const std::invalid_argument& e) {
    throw PresetProblem(where + ": " + e.what());
  }
  return spec;
}

long lineOfByte(const std::string& text, std::size_t byte) {
  byte = std::min(byte, text.size());
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(byte), '\n'));
}

json parseText(const std::string& text, const std::string& sourceName) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character.
    throw InputError(sourceName, lineOfByte(text, e.byte > 0 ? e.byte - 1 : 0),
                     std::string("malformed JSON: ") + e.what());
  } catch (const json::exception& e) {  // out_of_range: a number beyond double (found by fuzzing)
    throw InputError(sourceName, std::string("malformed JSON: ") + e.what());
  }
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open reamer presets file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

std::vector<ReamerSpec> parsePresets(const std::string& jsonText, const std::string& sourceName,
                                     const std::string& baseDir) {
  const json doc = parseText(jsonText, sourceName);
  const json* list = &doc;
  if (doc.is_object()) {
    if (!doc.contains("presets")) throw InputError(sourceName, "expected a \"presets\" array");
    list = &doc.at("presets");
  }
  if (!list->is_array()) throw InputError(sourceName, "\"presets\" must be an array of preset objects");
  std::vector<ReamerSpec> specs;
  std::set<std::string> names;
  try {
    for (std::size_t i = 0; i < list->size(); ++i) {
      specs.push_back(specFromJson((*list)[i], i, baseDir));
      if (!names.insert(specs.back().name).second)
        throw PresetProblem("preset name '" + specs.back().name + "' is used twice");
    }
  } catch (const PresetProblem& e) {
    throw InputError(sourceName, e.what());
  }
  return specs;
}

std::vector<ReamerSpec> loadPresets(const std::string& presetsJsonPath) {
  const std::string dir = std::filesystem::path(presetsJsonPath).parent_path().string();
  return parsePresets(readFile(presetsJsonPath), presetsJsonPath, dir);
}

ReamerSpec loadPreset(const std::string& name, const std::string& presetsJsonPath) {
  const std::vector<ReamerSpec> specs = loadPresets(presetsJsonPath);
  std::string known;
  for (const ReamerSpec& s : specs) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw std::invalid_argument("unknown reamer preset '" + name + "' in " + presetsJsonPath +
                              "; known presets: " + (known.empty() ? "(none)" : known));
}

ReamerSpec reamerSpecFromJsonText(const std::string& jsonObjectText) {
  const json obj = parseText(jsonObjectText, "<json>");
  try {
    return specFromJson(obj, 0, "");
  } catch (const PresetProblem& e) {
    throw InputError("<json>", e.what());
  }
}

}  // namespace reamsim
