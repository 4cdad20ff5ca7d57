// Collects the messages of vtkErrorMacro (ErrorEvent) instead of printing
// them, so tests can check that bad input is reported. Header-only.
#ifndef ThinTissueVtkErrorObserver_h
#define ThinTissueVtkErrorObserver_h

#include <vtkCommand.h>

#include <string>

namespace thintissue::testing
{

class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* message) override
  {
    ++count;
    all += static_cast<const char*>(message);
    all += "\n";
  }
  int count = 0;
  /// Every message, one per line.
  std::string all;
};

} // namespace thintissue::testing

#endif
