// Support shared by ThinTissue's command-line tools (header-only): VTK
// error and warning messages collected instead of VTK's output window, mesh
// files read through vtkThinTissueMeshReader, and a text progress bar.
#ifndef ThinTissueAppSupport_h
#define ThinTissueAppSupport_h

#include "vtkThinTissueMeshReader.h"

#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace thintissue::apps
{

/// Keeps the messages of VTK error and warning events (instead of VTK's
/// output window) so that they are printed once, plainly.
class MessageCollector : public vtkCommand
{
public:
  static MessageCollector* New() { return new MessageCollector; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    if (data != nullptr)
    {
      (event == vtkCommand::ErrorEvent ? errors : warnings)
        .emplace_back(static_cast<const char*>(data));
    }
  }
  std::vector<std::string> errors;
  std::vector<std::string> warnings;
};

inline void collectMessages(vtkObject* object, MessageCollector* collector)
{
  object->AddObserver(vtkCommand::ErrorEvent, collector);
  object->AddObserver(vtkCommand::WarningEvent, collector);
}

/// "[#####     ]  52% computing geodesic paths" on stderr, redrawn in place
/// on a terminal. Where stderr is not one (a log file, a pipe, a CI job),
/// one plain line per stage instead ("[ 52%] computing geodesic paths"):
/// a redrawn bar there is one endless line of carriage returns.
class TextProgressBar
{
public:
  TextProgressBar()
    : Interactive(isatty(fileno(stderr)) != 0)
  {
  }
  void draw(double fraction, const std::string& stage)
  {
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (stage.empty())
    {
      return; // a pipeline's own start, before the first stage
    }
    const int percent = static_cast<int>(fraction * 100.0 + 0.5);
    if (percent == LastPercent && stage == LastStage)
    {
      return;
    }
    const bool newStage = stage != LastStage;
    LastPercent = percent;
    LastStage = stage;
    if (!Interactive)
    {
      if (newStage)
      {
        char number[8];
        std::snprintf(number, sizeof(number), "[%3d%%]", percent);
        std::cerr << number << ' ' << stage << '\n' << std::flush;
      }
      return;
    }
    constexpr int Width = 30;
    const int filled = static_cast<int>(fraction * Width + 0.5);
    std::string line = "[" + std::string(filled, '#') + std::string(Width - filled, ' ') + "] ";
    char number[8];
    std::snprintf(number, sizeof(number), "%3d%%", percent);
    line += number;
    line += " " + stage;
    // Pad to blank out a longer previous line.
    const std::size_t length = line.size();
    line.resize(std::max(length, LastLength), ' ');
    LastLength = length;
    std::cerr << '\r' << line << std::flush;
    Drawn = true;
  }
  /// Ends the bar's line (before other output).
  void finish()
  {
    if (Drawn)
    {
      std::cerr << '\n';
      Drawn = false;
    }
  }

private:
  bool Interactive;
  int LastPercent = -1;
  std::string LastStage;
  std::size_t LastLength = 0;
  bool Drawn = false;
};

/// The bar drawn from an algorithm's progress events (with its progress text).
class ProgressBarObserver : public vtkCommand
{
public:
  static ProgressBarObserver* New() { return new ProgressBarObserver; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const char* text = static_cast<vtkAlgorithm*>(caller)->GetProgressText();
    Bar.draw(*static_cast<double*>(data), text != nullptr ? text : "");
  }
  void finish() { Bar.finish(); }

private:
  TextProgressBar Bar;
};

/// Reads a mesh; empty on failure with the reader's message (naming the
/// file) in `error`.
inline vtkSmartPointer<vtkPolyData> readMesh(const std::string& fileName, std::string& error)
{
  vtkNew<vtkThinTissueMeshReader> reader;
  vtkNew<MessageCollector> messages;
  collectMessages(reader, messages);
  vtkNew<MessageCollector> pipelineMessages;
  collectMessages(reader->GetExecutive(), pipelineMessages);
  reader->SetFileName(fileName.c_str());
  reader->Update();
  if (reader->GetLastErrorMessage()[0] != '\0' || !messages->errors.empty())
  {
    error = reader->GetLastErrorMessage()[0] != '\0' ? reader->GetLastErrorMessage()
                                                     : messages->errors.front();
    return nullptr;
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(reader->GetOutput());
  return mesh;
}

} // namespace thintissue::apps

#endif
