// The simulator's Qt window: the arthroscope view (QVTKOpenGLNativeWidget)
// and a panel with the scenario, the devices and their status, the live
// metrics and the settings. Three threads as in DESIGN.md: the servo at
// 1 kHz (the window's RealTimeLoop's own thread, or the OpenHaptics
// scheduler), the physics at the scenario's step on its own thread, and
// this GUI thread, which alone touches VTK and draws the newest snapshot
// on a 60 Hz timer.
#ifndef SimulatorWindow_h
#define SimulatorWindow_h

#include "RealTimeLoop.h"
#include "SimulatorView.h"

#include <QMainWindow>
#include <QTimer>

#include <functional>
#include <memory>
#include <string>
#include <vector>

class QComboBox;
class QLabel;
class QVTKOpenGLNativeWidget;

namespace thintissue
{

class HapticServo;
class MouseHapticDevice;
class SettingsPanel;

/// What drives the styluses, as the window shows and controls it.
struct WindowDevices
{
  /// Both or neither: the mouse and keyboard drive them (free play).
  MouseHapticDevice* mouseScope = nullptr;
  MouseHapticDevice* mouseInstrument = nullptr;
  /// "mouse and keyboard", "the recording", "Touch 'A' and 'B'", ...
  std::string description;
  /// Devices with a scheduler of their own (OpenHaptics): starts ticking a
  /// scene's servo / stops (empty: the window's servo thread ticks it).
  std::function<void(HapticServo&)> startServo;
  std::function<void()> stopServo;
  /// Problems the devices report (not calibrated, over-force shut-down...).
  std::function<std::vector<std::string>()> problems;
};

class SimulatorWindow : public QMainWindow
{
  Q_OBJECT
public:
  /// With mouse devices the run has no end; otherwise it stops at the
  /// scenario's duration (a recording replayed, or real devices: no end).
  SimulatorWindow(TrainingScene& scene, WindowDevices devices);
  ~SimulatorWindow() override;

  /// Makes a scene from a scenario (a file, perhaps changed by the
  /// settings) with the window's devices; throws on one it cannot build.
  using SceneFactory = std::function<std::unique_ptr<TrainingScene>(const ScenarioDescription&)>;
  /// Offers the scenario files of `directory` and the instruments to
  /// choose from.
  void setScenarios(const std::string& directory, SceneFactory factory);
  /// Starts the scenario in `path` (with `instrument`, if not empty); on
  /// failure says why in a dialog, keeps the running one and returns false.
  bool loadScenario(const std::string& path, const std::string& instrument = "");
  /// Starts `scenario` (read already, perhaps changed); as loadScenario.
  bool startScenario(const ScenarioDescription& scenario);
  /// The settings panel's changes: applied to the running scene between
  /// two steps where it can take them (TrainingScene::applySettings),
  /// otherwise the scenario starts again with them; as startScenario.
  bool changeSettings(const ScenarioDescription& changed);
  /// Writes the window's picture (PNG); false if it could not.
  bool screenshot(const std::string& path);
  /// The scene's parts that never change once built (scenario, instrument
  /// model, cutter); what moves is in snapshot().
  const TrainingScene& scene() const { return *Scene; }
  /// The snapshot drawn last (GUI thread).
  const SceneSnapshot& snapshot() const { return Shown; }
  /// The settings panel (material, wrinkles, cut surface).
  SettingsPanel& settings() { return *Settings; }
  /// The device status text as shown.
  QString deviceStatus() const;

private:
  QWidget* makePanel();
  void advance();
  void showMetrics();
  void showDevices();
  void showScene();
  void startLoop();
  void stopLoop();
  bool failToLoad(const std::string& message);

  TrainingScene* Scene;
  std::unique_ptr<TrainingScene> Owned;
  WindowDevices Devices;
  SceneFactory Factory;
  std::unique_ptr<RealTimeLoop> Loop;
  SceneSnapshot Shown;
  QComboBox* Scenarios = nullptr;
  QComboBox* Instruments = nullptr;
  QLabel* ScenarioText = nullptr;
  std::unique_ptr<SimulatorView> View;
  QVTKOpenGLNativeWidget* Widget = nullptr;
  QLabel* Metrics = nullptr;
  QLabel* DeviceText = nullptr;
  SettingsPanel* Settings = nullptr;
  QString DeviceError;
  QTimer Frames;
  bool FreePlay = false;
};

} // namespace thintissue

#endif
