#pragma once
#include <nlohmann/json.hpp>

#include "reamsim/mesh/Validation.h"

namespace reamsim {
nlohmann::json toJsonValue(const ValidationReport& report);
}
