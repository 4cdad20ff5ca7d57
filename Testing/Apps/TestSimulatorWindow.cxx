// A smoke test of the simulator's window under Xvfb: the meniscus
// examination with mouse devices; a left drag in the arthroscope view moves
// the instrument while Qt's event loop runs the scene; the live metrics
// follow. (The window's classes are compiled in from Apps/Simulator.)
#include "MouseHapticDevice.h"
#include "SimulatorWindow.h"
#include "TrainingScene.h"

#include <QApplication>
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
  // After 0.3 s a left drag of 50 pixels to the right: 10 mm of stylus.
  QTimer::singleShot(300,
    [&]
    {
      auto* widget = window.findChild<QVTKOpenGLNativeWidget*>();
      vtkRenderWindowInteractor* interactor = widget->interactor();
      interactor->SetEventInformation(100, 100);
      interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
      interactor->SetEventInformation(150, 100);
      interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
      interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
    });
  QTimer::singleShot(900, &application, &QApplication::quit);
  application.exec();
  const Vector3 moved = scene.instrumentPose().translation - start;
  std::cout << "scene time " << scene.time() << " s, instrument moved " << moved.transpose()
            << " mm\n";
  const bool ran = scene.time() > 0.3;
  const bool followed = moved.norm() > 5.0;
  return ran && followed ? EXIT_SUCCESS : EXIT_FAILURE;
}
