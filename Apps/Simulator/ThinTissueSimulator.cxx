// ThinTissueSimulator: the training simulator (issue 17). A scenario file
// and a recording of the two styluses (the arthroscope's and the
// instrument's) drive the training scene in lock-step; in a window when
// there is a display, otherwise offscreen, writing the arthroscope's
// picture at the asked times, the metrics and the timings.
//
//   ThinTissueSimulator [--scenario S.json] [--replay R.json] [--offscreen]
//                       [--snapshots T1,T2,...] [--output DIR]
//                       [--compare DIR] [--size WxH]
//                       [--devices replay|mouse|touch|auto] [--hd-library PATH]
//                       [--scope-device NAME] [--instrument-device NAME]
//                       [--record R.json] [--tissue FILE] [--tissue-thickness T]
//
// Defaults: the shipped meniscus examination and its recording; without a
// display the program re-runs itself under xvfb-run, offscreen. With
// --devices mouse the mouse and keyboard drive the instrument (with Shift
// the arthroscope): left drag across, right drag in and out, [ ] roll;
// --record writes what they did as a recording (up to 5 minutes) that
// --replay plays back bit for bit (in lock-step: the window's threads take
// the poses as they come, so the replay is the run as recorded, not as
// the window's physics thread happened to sample it). --devices touch: two
// 3D Systems Touch devices named "Arthroscope" and "Instrument" (or
// --scope-device / --instrument-device) through the OpenHaptics library
// (libHD.so, or --hd-library), in the window; --devices auto: the Touch
// devices when they open, else the mouse. --tissue FILE puts your own tissue in the
// scenario: a bundle made by ThinTissuePrepare (.ttbundle) or a mesh file
// prepared as it loads (--tissue-thickness T: an open sheet, such as a
// segmented cartilage, given T mm of thickness first).
#include "SimulatorView.h"
#include "SimulatorWindow.h"
#include "TouchDevices.h"
#include "VirtualDisplay.h"

#include "MouseHapticDevice.h"
#include "OpenHapticsSystem.h"
#include "ScriptedHapticDevice.h"
#include "ThinTissueError.h"
#include "TrainingScene.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkTesting.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using namespace thintissue;

struct Options
{
  std::string scenario;
  std::string replay = std::string(THINTISSUE_DATA_DIR) + "/Recordings/meniscus-examination.json";
  bool offscreen = false;
  std::vector<double> snapshots;
  std::string output = "simulator-output";
  std::string compare;
  int width = 640;
  int height = 480;
  /// replay, mouse, touch (two Touch devices) or auto (Touch if there, else
  /// the mouse).
  std::string devices = "replay";
  std::string hdLibrary = "libHD.so";
  std::string scopeDevice = "Arthroscope";
  std::string instrumentDevice = "Instrument";
  std::string record;
  std::string tissue;
  double tissueThickness = 0.0;
};

void printUsage()
{
  std::cerr
    << "usage: ThinTissueSimulator [--scenario S.json] [--replay R.json] [--offscreen]\n"
       "                           [--snapshots T1,T2,...] [--output DIR] [--compare DIR]\n"
       "                           [--size WxH] [--devices replay|mouse|touch|auto]\n"
       "                           [--hd-library PATH] [--scope-device NAME]\n"
       "                           [--instrument-device NAME] [--record R.json]\n"
       "                           [--tissue BUNDLE.ttbundle|MESH] [--tissue-thickness T]\n";
}

/// The scenario with its tissue replaced by the user's: a bundle made by
/// ThinTissuePrepare or a mesh file prepared as it loads.
void useTissueFile(ScenarioDescription& scenario, const std::string& path)
{
  const bool bundle = path.size() > 9 && path.compare(path.size() - 9, 9, ".ttbundle") == 0;
  scenario.tissueModel = bundle ? "bundle" : "file";
  scenario.tissueFile = path;
  scenario.wrinkles = false;
  if (scenario.fixedNodes == "model")
  {
    scenario.fixedNodes = "bottom";
  }
}

bool parseTimes(const std::string& text, std::vector<double>& times)
{
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    char* end = nullptr;
    const double t = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !(t >= 0.0))
    {
      return false;
    }
    times.push_back(t);
  }
  std::sort(times.begin(), times.end());
  return !times.empty();
}

bool validDevices(const std::string& devices)
{
  return devices == "replay" || devices == "mouse" || devices == "touch" || devices == "auto";
}

bool parseArguments(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--offscreen")
    {
      o.offscreen = true;
    }
    else if (a == "--scenario" && hasValue)
    {
      o.scenario = argv[++i];
    }
    else if (a == "--replay" && hasValue)
    {
      o.replay = argv[++i];
    }
    else if (a == "--snapshots" && hasValue && parseTimes(argv[++i], o.snapshots))
    {
    }
    else if (a == "--output" && hasValue)
    {
      o.output = argv[++i];
    }
    else if (a == "--devices" && hasValue && validDevices(argv[i + 1]))
    {
      o.devices = argv[++i];
    }
    else if (a == "--hd-library" && hasValue)
    {
      o.hdLibrary = argv[++i];
    }
    else if (a == "--scope-device" && hasValue)
    {
      o.scopeDevice = argv[++i];
    }
    else if (a == "--instrument-device" && hasValue)
    {
      o.instrumentDevice = argv[++i];
    }
    else if (a == "--record" && hasValue)
    {
      o.record = argv[++i];
    }
    else if (a == "--tissue" && hasValue)
    {
      o.tissue = argv[++i];
    }
    else if (a == "--tissue-thickness" && hasValue &&
             std::sscanf(argv[++i], "%lf", &o.tissueThickness) == 1 && o.tissueThickness > 0.0 &&
             std::isfinite(o.tissueThickness))
    {
    }
    else if (a == "--compare" && hasValue)
    {
      o.compare = argv[++i];
    }
    else if (a == "--size" && hasValue &&
             std::sscanf(argv[++i], "%dx%d", &o.width, &o.height) == 2 && o.width > 0 &&
             o.height > 0)
    {
    }
    else
    {
      std::cerr << "ThinTissueSimulator: bad argument '" << a << "'\n";
      printUsage();
      return false;
    }
  }
  return true;
}

std::string snapshotName(const std::string& scenario, double t)
{
  std::ostringstream name;
  name << std::filesystem::path(scenario).stem().string() << "-" << std::fixed;
  name.precision(2);
  name << t << "s.png";
  return name.str();
}

double percentile(std::vector<double> values, double fraction)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(fraction * values.size()))];
}

/// Compares the window with DIR/name; false (and the picture kept in the
/// output) when it differs.
bool compareWithBaseline(vtkRenderWindow* window, const Options& o, const std::string& name)
{
  vtkNew<vtkTesting> testing;
  testing->AddArgument("-T");
  testing->AddArgument(o.output.c_str());
  testing->AddArgument("-V");
  testing->AddArgument((std::filesystem::path(o.compare) / name).string().c_str());
  testing->SetRenderWindow(window);
  return testing->RegressionTest(0.15) == vtkTesting::PASSED;
}

int runOffscreen(TrainingScene& scene, const Options& o)
{
  std::filesystem::create_directories(o.output);
  SimulatorView view(scene);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(o.width, o.height);
  window->AddRenderer(view.renderer());
  std::vector<double> steps, frames;
  SceneSnapshot snapshot;
  bool matches = true;
  std::vector<double> times = o.snapshots;
  times.push_back(scene.scenario().duration);
  for (std::size_t k = 0; k < times.size(); ++k)
  {
    while (scene.time() + 0.5 * scene.scenario().timeStep < times[k])
    {
      const auto start = std::chrono::steady_clock::now();
      if (!scene.step())
      {
        std::cerr << "ThinTissueSimulator: " << scene.lastError() << "\n";
        return 1;
      }
      steps.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (k + 1 == times.size())
    {
      break; // the end of the run: metrics only
    }
    const auto start = std::chrono::steady_clock::now();
    scene.snapshot(snapshot);
    view.update(snapshot);
    window->Render();
    frames.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const std::string name = snapshotName(scene.scenario().source, times[k]);
    SimulatorView::writePicture(window, (std::filesystem::path(o.output) / name).string());
    std::cout << "picture at " << times[k]
              << " s: " << (std::filesystem::path(o.output) / name).string() << "\n";
    if (!o.compare.empty() && !compareWithBaseline(window, o, name))
    {
      std::cerr << "ThinTissueSimulator: " << name << " differs from the baseline in " << o.compare
                << "\n";
      matches = false;
    }
  }
  std::ofstream(std::filesystem::path(o.output) / "metrics.json") << scene.metricsJson() << "\n";
  const nlohmann::ordered_json timings = { { "scenario", scene.scenario().name },
    { "physics_steps", steps.size() },
    { "physics_step_median_ms", percentile(steps, 0.5) * 1e3 },
    { "physics_step_p99_ms", percentile(steps, 0.99) * 1e3 },
    { "frame_median_ms", percentile(frames, 0.5) * 1e3 } };
  std::ofstream(std::filesystem::path(o.output) / "timings.json") << timings.dump(2) << "\n";
  std::cout << scene.metricsJson() << "\n"
            << timings.dump(2) << "\n"
            << "metrics and timings written to " << o.output << "\n";
  return matches ? 0 : 1;
}

/// The session's two styluses: the recording's, the mouse's or two Touch
/// devices (OpenHaptics, loaded at run time). With --record they are
/// wrapped in recorders (and only then: a recorder hands the run the
/// orientation as it stores it, so that its replay is exact).
class SessionDevices
{
public:
  SessionDevices(const SceneRecording& recording, const Options& options)
    : ScriptedScope(recording.scope)
    , ScriptedInstrument(recording.instrument)
  {
    Scope = &ScriptedScope;
    Instrument = &ScriptedInstrument;
    Description = "the recording " + options.replay;
    if (options.devices == "touch" || options.devices == "auto")
    {
      openTouch(options);
    }
    if (options.devices == "mouse" || (options.devices == "auto" && !Touch))
    {
      Scope = &MouseScope;
      Instrument = &MouseInstrument;
      Description = "mouse and keyboard (Shift: arthroscope; left drag across, right drag in "
                    "and out, [ ] roll)" +
                    (TouchProblem.empty() ? "" : "; no Touch: " + TouchProblem);
    }
    if (!options.record.empty())
    {
      ScopeRecorder = std::make_unique<RecordingHapticDevice>(*Scope, FiveMinutes);
      InstrumentRecorder = std::make_unique<RecordingHapticDevice>(*Instrument, FiveMinutes);
      Scope = ScopeRecorder.get();
      Instrument = InstrumentRecorder.get();
    }
  }
  HapticDevice& scope() { return *Scope; }
  HapticDevice& instrument() { return *Instrument; }
  bool touch() const { return Touch != nullptr; }
  bool mouse() const { return !Touch && Description.rfind("mouse", 0) == 0; }
  /// What the window shows and controls.
  WindowDevices forWindow()
  {
    if (Touch)
    {
      return touchWindowDevices(*Touch, Description);
    }
    WindowDevices w;
    w.description = Description;
    if (mouse())
    {
      w.mouseScope = &MouseScope;
      w.mouseInstrument = &MouseInstrument;
    }
    return w;
  }
  const std::string& description() const { return Description; }
  SceneRecording recorded(const std::string& scenario) const
  {
    return SceneRecording{ std::filesystem::absolute(scenario).string(),
      0,
      ScopeRecorder->trajectory(),
      InstrumentRecorder->trajectory() };
  }

private:
  static constexpr std::size_t FiveMinutes = 300000; // samples at 1 kHz

  /// Two Touch devices by name; with "auto" a failure leaves the mouse.
  void openTouch(const Options& options)
  {
    try
    {
      OpenHapticsSettings settings;
      settings.library = options.hdLibrary;
      settings.deviceNames = { options.scopeDevice, options.instrumentDevice };
      Touch = std::make_unique<OpenHapticsSystem>(settings);
      Scope = &Touch->device(0);
      Instrument = &Touch->device(1);
      Description = "Touch '" + options.scopeDevice + "' (arthroscope) and '" +
                    options.instrumentDevice + "' (instrument)";
    }
    catch (const HapticDeviceError& error)
    {
      if (options.devices == "touch")
        throw;
      TouchProblem = error.what();
    }
  }

  ScriptedHapticDevice ScriptedScope;
  ScriptedHapticDevice ScriptedInstrument;
  MouseHapticDevice MouseScope;
  MouseHapticDevice MouseInstrument;
  std::unique_ptr<OpenHapticsSystem> Touch;
  std::unique_ptr<RecordingHapticDevice> ScopeRecorder;
  std::unique_ptr<RecordingHapticDevice> InstrumentRecorder;
  HapticDevice* Scope = nullptr;
  HapticDevice* Instrument = nullptr;
  std::string Description;
  std::string TouchProblem;
};

int runWindow(TrainingScene& scene,
  SessionDevices& devices,
  const SimulatorWindow::SceneFactory& factory,
  int argc,
  char* argv[])
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  SimulatorWindow window(scene, devices.forWindow());
  window.setScenarios(std::string(THINTISSUE_DATA_DIR) + "/Scenarios", factory);
  window.show();
  return application.exec();
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!parseArguments(argc, argv, options))
  {
    return 2;
  }
  if (!thintissue::apps::haveDisplayOrRerun(argc, argv, "ThinTissueSimulator"))
  {
    return 3;
  }
  try
  {
    const SceneRecording recording = readSceneRecording(options.replay);
    ScenarioDescription scenario =
      readScenario(options.scenario.empty() ? recording.scenario : options.scenario);
    if (!options.tissue.empty())
    {
      useTissueFile(scenario, options.tissue);
      scenario.tissueThickness = options.tissueThickness;
    }
    SessionDevices devices(recording, options);
    if (options.offscreen && devices.touch())
    {
      std::cerr << "ThinTissueSimulator: Touch devices need the window (not --offscreen)\n";
      return 2;
    }
    TrainingScene scene(scenario, devices.scope(), devices.instrument());
    std::cout << "ThinTissue simulator: " << scenario.name << " (" << scenario.source << "), "
              << devices.description() << "\n";
    // Another scenario, chosen in the window, with the same devices.
    const SimulatorWindow::SceneFactory factory = [&](const ScenarioDescription& next)
    { return std::make_unique<TrainingScene>(next, devices.scope(), devices.instrument()); };
    const int status = options.offscreen ? runOffscreen(scene, options)
                                         : runWindow(scene, devices, factory, argc, argv);
    if (!options.record.empty())
    {
      writeSceneRecording(options.record, devices.recorded(scenario.source));
      std::cout << "recording written to " << options.record << "\n";
    }
    return status;
  }
  catch (const Error& error)
  {
    std::cerr << "ThinTissueSimulator: " << error.what() << "\n";
    return 1;
  }
  catch (const std::filesystem::filesystem_error& error)
  {
    // e.g. an --output that is a file, not a directory
    std::cerr << "ThinTissueSimulator: " << error.what() << "\n";
    return 1;
  }
}
