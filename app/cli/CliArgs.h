#pragma once
// Minimal, strict command-line parsing: --name value pairs, --flag switches and positionals.
// Unknown options are errors (a typo must not silently run something else).
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace reamsim::cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CliArgs {
 public:
  // `valueOptions` take one value, `flags` take none; both without the leading "--".
  CliArgs(const std::vector<std::string>& args, const std::set<std::string>& valueOptions,
          const std::set<std::string>& flags);

  bool has(const std::string& name) const { return values_.count(name) || flags_.count(name); }
  std::string value(const std::string& name, const std::string& fallback = "") const;
  std::string required(const std::string& name) const;
  double number(const std::string& name, double fallback) const;
  const std::vector<std::string>& positionals() const { return positionals_; }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
  std::vector<std::string> positionals_;
};

}  // namespace reamsim::cli
