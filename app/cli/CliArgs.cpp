#include "CliArgs.h"

#include <cmath>
#include <cstdlib>

namespace reamsim::cli {

CliArgs::CliArgs(const std::vector<std::string>& args, const std::set<std::string>& valueOptions,
                 const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), inlineValue;
    const bool hasInline = name.find('=') != std::string::npos;
    if (hasInline) {
      inlineValue = name.substr(name.find('=') + 1);
      name = name.substr(0, name.find('='));
    }
    if (flags.count(name)) {
      if (hasInline) throw UsageError("option --" + name + " takes no value");
      flags_.insert(name);
    } else if (valueOptions.count(name)) {
      if (hasInline) values_[name] = inlineValue;
      else if (i + 1 < args.size()) values_[name] = args[++i];
      else throw UsageError("option --" + name + " needs a value");
    } else {
      throw UsageError("unknown option --" + name);
    }
  }
}

std::string CliArgs::value(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

std::string CliArgs::required(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw UsageError("missing required option --" + name);
  return it->second;
}

double CliArgs::number(const std::string& name, double fallback) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v))
    throw UsageError("option --" + name + " needs a number, got '" + it->second + "'");
  return v;
}

}  // namespace reamsim::cli
