// The simulator's Qt window: the arthroscope view (QVTKOpenGLNativeWidget)
// and a panel with the scenario, the devices and the live metrics; the
// scene advances with the wall clock on a 60 Hz timer.
#ifndef SimulatorWindow_h
#define SimulatorWindow_h

#include "SimulatorView.h"

#include <QElapsedTimer>
#include <QMainWindow>
#include <QTimer>

#include <memory>

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

private:
  void advance();
  void showMetrics();

  TrainingScene& Scene;
  std::unique_ptr<SimulatorView> View;
  QVTKOpenGLNativeWidget* Widget = nullptr;
  QLabel* Metrics = nullptr;
  QTimer Frames;
  QElapsedTimer Clock;
  bool FreePlay = false;
};

} // namespace thintissue

#endif
