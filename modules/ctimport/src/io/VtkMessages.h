#pragma once
// VTK readers report problems by printing to the output window / raising ErrorEvent, then carry on. This
// guard records both for its lifetime (the output window is process-global, hence a mutex) so that a
// reader's complaint becomes an InputError instead of a console line and garbage data.
#include <functional>
#include <memory>
#include <string>

class vtkObject;

namespace reamsim::ct::io {

class VtkMessageCapture {
 public:
  VtkMessageCapture();
  ~VtkMessageCapture();
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  void observe(vtkObject* o);  // ErrorEvent and WarningEvent of `o`
  // Forwards ProgressEvent of `algorithm` to `tick`; when it returns false the algorithm is asked to abort
  // and cancelled() becomes true.
  void observeProgress(vtkObject* algorithm, std::function<bool(double)> tick);
  bool cancelled() const;
  bool anyError() const;
  std::string firstMessage() const;  // one line, without VTK's "ERROR: In file, line" prefix
  void clear();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reamsim::ct::io
