// A smoke test of the simulator's window under Xvfb, its three threads
// running (servo, physics, GUI): the meniscus examination with mouse
// devices; a left drag in the arthroscope view moves the instrument while
// the physics thread runs the scene and the GUI draws its snapshots; the
// live metrics and the device status follow; a scenario that fails to load
// leaves the running one, another one starts; the settings panel refuses a
// bad value naming its key and restarts the scenario with a good one. (The
// window's classes are compiled in from Apps/Simulator.)
#include "MouseHapticDevice.h"
#include "SettingsPanel.h"
#include "SimulatorWindow.h"
#include "TrainingScene.h"

#include <QApplication>
#include <QFileInfo>
#include <QLabel>
#include <QLineEdit>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkCommand.h>
#include <vtkRenderWindowInteractor.h>

#include <cstdlib>
#include <iostream>

using namespace thintissue;

namespace
{

/// A left drag of 50 pixels to the right in the view: 10 mm of stylus.
void dragRight(SimulatorWindow& window)
{
  auto* widget = window.findChild<QVTKOpenGLNativeWidget*>();
  vtkRenderWindowInteractor* interactor = widget->interactor();
  interactor->SetEventInformation(100, 100);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  interactor->SetEventInformation(150, 100);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
}

/// The settings panel: a Poisson's ratio of 0.7 is refused (its key named,
/// the scene kept); a softer tissue reaches the running scene (no restart);
/// so do the cut-surface rows of the running punch scenario before a bite.
bool settingsWork(SimulatorWindow& window)
{
  SettingsPanel& panel = window.settings();
  const TrainingScene* before = &window.scene();
  panel.field("tissue.material.poissonRatio")->setText("0.7");
  const bool refused = !panel.apply() && &window.scene() == before &&
                       panel.error().contains("tissue.material.poissonRatio");
  std::cout << "settings refusal: " << panel.error().toStdString() << "\n";
  panel.field("tissue.material.poissonRatio")->setText("0.3");
  panel.field("tissue.material.youngModulus")->setText("12.5");
  const bool live = panel.apply() && &window.scene() == before &&
                    window.scene().scenario().material.youngModulus == 12.5;
  std::cout << "material applied live: " << live << "\n";
  // The punch scenario (loaded before, no bite yet): its running cutter
  // takes the rows for the cuts to come (TissueCutter::setSettings; only a
  // row change once a cut surface exists needs the scene built again).
  panel.field("cutting.cutSurfaceRows")->setText("2");
  const bool rowsLive = panel.apply() && &window.scene() == before &&
                        window.scene().scenario().cutSurfaceRows == 2 &&
                        window.scene().scenario().material.youngModulus == 12.5;
  std::cout << "cut-surface rows applied live: " << rowsLive << "\n";
  return refused && live && rowsLive;
}

} // namespace

int main(int argc, char* argv[])
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  const ScenarioDescription scenario =
    readScenario(std::string(THINTISSUE_DATA_DIR) + "/Scenarios/meniscus-examination.json");
  MouseHapticDevice scope, instrument;
  TrainingScene scene(scenario, scope, instrument);
  WindowDevices devices;
  devices.mouseScope = &scope;
  devices.mouseInstrument = &instrument;
  devices.description = "mouse and keyboard";
  SimulatorWindow window(scene, devices);
  window.show();
  const Vector3 start = window.snapshot().instrument.translation;
  window.setScenarios(std::string(THINTISSUE_DATA_DIR) + "/Scenarios",
    [&](const ScenarioDescription& next)
    { return std::make_unique<TrainingScene>(next, scope, instrument); });
  bool badRefused = false, tornLoaded = false, punchLoaded = false, pictured = false;
  bool settings = false, status = false;
  Vector3 moved = Vector3::Zero();
  double ran = 0.0;
  // Each stage waits for the scene to have run (a loaded machine delays
  // Qt's timers; stages on fixed times could run back to back).
  int stage = 0;
  double dragTime = 0.0;
  QTimer watch;
  QObject::connect(&watch,
    &QTimer::timeout,
    [&]
    {
      const double now = window.snapshot().time;
      if (stage == 0 && now > 0.2)
      {
        dragRight(window);
        dragTime = now;
        stage = 1;
      }
      else if (stage == 1 && ((window.snapshot().instrument.translation - start).norm() > 5.0 ||
                               now > dragTime + 5.0))
      {
        // (The drag reaches the picture through the servo and physics
        // threads: waited for, up to 5 s of scene time.)
        moved = window.snapshot().instrument.translation - start;
        ran = now;
        status = window.deviceStatus().contains("instrument: calibrated");
        // A scenario that cannot load leaves the running one; a good one
        // starts.
        badRefused = !window.loadScenario(std::string(THINTISSUE_DATA_DIR) + "/no-such.json") &&
                     &window.scene() == &scene;
        tornLoaded = window.loadScenario(
          std::string(THINTISSUE_DATA_DIR) + "/Scenarios/meniscus-examination-radial.json");
        stage = 2;
      }
      else if (stage == 2)
      {
        // The same scenario with the punch instead of the hook: it can cut.
        const std::string radial = window.scene().scenario().source;
        punchLoaded = window.loadScenario(radial, "punch") &&
                      window.scene().instrumentModel().type == SurgicalInstrumentType::Punch &&
                      window.scene().cutter() != nullptr;
        const std::string picture = "simulator-window-screenshot.png";
        pictured = window.screenshot(picture) && QFileInfo(picture.c_str()).size() > 1000;
        stage = 3;
      }
      else if (stage == 3 && now > 0.1)
      {
        settings = settingsWork(window);
        stage = 4;
      }
      else if (stage == 4 && now > 0.1)
      {
        application.quit();
      }
    });
  watch.start(50);
  QTimer::singleShot(90000, &application, &QApplication::quit);
  application.exec();
  std::cout << "punch loaded " << punchLoaded << ", screenshot " << pictured << ", settings "
            << settings << ", device status " << status << "\n";
  std::cout << "bad scenario refused " << badRefused << ", torn scenario loaded " << tornLoaded
            << " (now " << window.scene().scenario().name << ", at " << window.snapshot().time
            << " s)\n";
  std::cout << "first scene ran to " << ran << " s, instrument moved " << moved.transpose()
            << " mm\n";
  const bool followed = moved.norm() > 5.0;
  const bool switched = badRefused && tornLoaded && punchLoaded && pictured &&
                        window.scene().scenario().tear == MeniscusTearType::Radial &&
                        window.snapshot().time > 0.0;
  return ran > 0.2 && followed && switched && settings && status ? EXIT_SUCCESS : EXIT_FAILURE;
}
