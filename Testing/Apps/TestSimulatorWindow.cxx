// A smoke test of the simulator's window under Xvfb: the meniscus
// examination with mouse devices; a left drag in the arthroscope view moves
// the instrument while Qt's event loop runs the scene; the live metrics
// follow; a scenario that fails to load leaves the running one, another
// one starts. (The window's classes are compiled in from Apps/Simulator.)
#include "MouseHapticDevice.h"
#include "SimulatorWindow.h"
#include "TrainingScene.h"

#include <QApplication>
#include <QFileInfo>
#include <QLabel>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkCommand.h>
#include <vtkRenderWindowInteractor.h>

#include <cstdlib>
#include <iostream>

using namespace thintissue;

int main(int argc, char* argv[])
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  const ScenarioDescription scenario =
    readScenario(std::string(THINTISSUE_DATA_DIR) + "/Scenarios/meniscus-examination.json");
  MouseHapticDevice scope, instrument;
  TrainingScene scene(scenario, scope, instrument);
  SimulatorWindow window(scene, &scope, &instrument);
  window.show();
  const Vector3 start = scene.instrumentPose().translation;
  window.setScenarios(std::string(THINTISSUE_DATA_DIR) + "/Scenarios",
    [&](const std::string& path, const std::string& tool)
    {
      ScenarioDescription next = readScenario(path);
      if (!tool.empty())
        next.instrument = parseSurgicalInstrumentType(tool);
      return std::make_unique<TrainingScene>(next, scope, instrument);
    });
  bool badRefused = false, tornLoaded = false, punchLoaded = false, pictured = false;
  // Each stage waits for the scene to have run (a loaded machine delays
  // Qt's timers; stages on fixed times could run back to back).
  int stage = 0;
  double dragTime = 0.0;
  QTimer watch;
  QObject::connect(&watch,
    &QTimer::timeout,
    [&]
    {
      if (stage == 0 && scene.time() > 0.2)
      {
        // A left drag of 50 pixels to the right: 10 mm of stylus.
        auto* widget = window.findChild<QVTKOpenGLNativeWidget*>();
        vtkRenderWindowInteractor* interactor = widget->interactor();
        interactor->SetEventInformation(100, 100);
        interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
        interactor->SetEventInformation(150, 100);
        interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
        interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
        dragTime = scene.time();
        stage = 1;
      }
      else if (stage == 1 && scene.time() > dragTime + 0.3)
      {
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
      else if (stage == 3 && window.scene().time() > 0.1)
      {
        application.quit();
      }
    });
  watch.start(50);
  QTimer::singleShot(60000, &application, &QApplication::quit);
  application.exec();
  std::cout << "punch loaded " << punchLoaded << ", screenshot " << pictured << "\n";
  std::cout << "bad scenario refused " << badRefused << ", torn scenario loaded " << tornLoaded
            << " (" << window.scene().scenario().name << ", at " << window.scene().time()
            << " s)\n";
  const Vector3 moved = scene.instrumentPose().translation - start;
  std::cout << "scene time " << scene.time() << " s, instrument moved " << moved.transpose()
            << " mm\n";
  const bool ran = scene.time() > 0.3;
  const bool followed = moved.norm() > 5.0;
  const bool switched = badRefused && tornLoaded && punchLoaded && pictured &&
                        window.scene().scenario().tear == MeniscusTearType::Radial &&
                        window.scene().time() > 0.0;
  return ran && followed && switched ? EXIT_SUCCESS : EXIT_FAILURE;
}
