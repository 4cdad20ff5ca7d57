// The simulator's Qt window: the arthroscope view (QVTKOpenGLNativeWidget)
// and a panel with the scenario, the devices and the live metrics; the
// scene advances with the wall clock on a 60 Hz timer.
#ifndef SimulatorWindow_h
#define SimulatorWindow_h

#include "SimulatorView.h"

#include <QElapsedTimer>
#include <QMainWindow>
#include <QTimer>

#include <functional>
#include <memory>
#include <string>

class QComboBox;
class QLabel;
class QVTKOpenGLNativeWidget;

namespace thintissue
{

class MouseHapticDevice;

class SimulatorWindow : public QMainWindow
{
  Q_OBJECT
public:
  /// With mouse devices (both or neither) the mouse and keyboard drive
  /// them and the run has no end; otherwise the scene replays its recording.
  SimulatorWindow(TrainingScene& scene, MouseHapticDevice* scope, MouseHapticDevice* instrument);

  /// Makes a scene from a scenario file with the window's devices, with
  /// another instrument when `instrument` names one ("" : the scenario's);
  /// throws on a scenario it cannot build.
  using SceneFactory = std::function<std::unique_ptr<TrainingScene>(const std::string& path,
    const std::string& instrument)>;
  /// Offers the scenario files of `directory` and the instruments to
  /// choose from.
  void setScenarios(const std::string& directory, SceneFactory factory);
  /// Starts the scenario in `path` (with `instrument`, if not empty); on
  /// failure says why in a dialog, keeps the running one and returns false.
  bool loadScenario(const std::string& path, const std::string& instrument = "");
  /// Writes the window's picture (PNG); false if it could not.
  bool screenshot(const std::string& path);
  const TrainingScene& scene() const { return *Scene; }

private:
  void advance();
  void showMetrics();
  void showScene();

  TrainingScene* Scene;
  std::unique_ptr<TrainingScene> Owned;
  SceneFactory Factory;
  QComboBox* Scenarios = nullptr;
  QComboBox* Instruments = nullptr;
  QLabel* ScenarioText = nullptr;
  std::unique_ptr<SimulatorView> View;
  QVTKOpenGLNativeWidget* Widget = nullptr;
  QLabel* Metrics = nullptr;
  QTimer Frames;
  QElapsedTimer Clock;
  bool FreePlay = false;
};

} // namespace thintissue

#endif
