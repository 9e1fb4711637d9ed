#pragma once
#include <stdexcept>
#include <string>

namespace reamsim {

// Every problem with user input is reported as "FILE[:LINE]: problem" so the user knows what to fix.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, long line, const std::string& problem)
      : std::runtime_error(format(file, line, problem)), file_(std::move(file)), line_(line), problem_(problem) {}
  InputError(std::string file, const std::string& problem) : InputError(std::move(file), 0, problem) {}

  const std::string& file() const { return file_; }
  long line() const { return line_; }  // 0 when not applicable (binary formats)
  const std::string& problem() const { return problem_; }

 private:
  static std::string format(const std::string& file, long line, const std::string& problem) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem;
  }
  std::string file_;
  long line_;
  std::string problem_;
};

}  // namespace reamsim
