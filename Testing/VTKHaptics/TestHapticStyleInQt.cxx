// vtkHapticInteractorStyle inside a Qt widget (QVTKOpenGLNativeWidget): the
// servo on its 1 kHz thread, the style's repeating interactor timer (a
// QTimer under QVTKInteractor) moving the instrument prop while the Qt event
// loop runs. Runs under Xvfb like the image tests.
#include "ScriptedHapticDevice.h"
#include "ThinTissueTestSupport.h"
#include "vtkHapticInteractorStyle.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkActor.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include <cstdlib>
#include <iostream>

using namespace thintissue;

int main(int argc, char* argv[])
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  HapticTrajectory path;
  for (int k = 0; k <= 10; ++k)
  {
    path.samples.push_back(
      HapticSample{ 0.1 * k, Vector3(2.0 * k, 0.0, 0.0), Eigen::Quaterniond::Identity(), 0u });
  }
  const std::string file = (thintissue::testing::temporaryDirectory() / "qt.json").string();
  writeHapticTrajectory(file, path);

  QVTKOpenGLNativeWidget widget;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  widget.setRenderWindow(window);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  widget.resize(320, 240);
  widget.show();
  vtkNew<vtkActor> instrument;
  vtkNew<vtkHapticInteractorStyle> style;
  widget.interactor()->SetInteractorStyle(style);
  style->SetDefaultRenderer(renderer);
  style->SetInstrumentProp(instrument);
  style->SetBackendToScripted();
  style->SetScopeTrajectoryFileName(file.c_str());
  style->SetInstrumentTrajectoryFileName(file.c_str());
  style->SetTimerPeriod(10);
  if (!style->StartDevices())
  {
    std::cerr << style->GetLastErrorMessage() << "\n";
    return EXIT_FAILURE;
  }
  QTimer::singleShot(600, &application, &QApplication::quit);
  application.exec();
  vtkMatrix4x4* matrix = instrument->GetUserMatrix();
  const double x = matrix ? matrix->GetElement(0, 3) : 0.0;
  style->StopDevices();
  // After 0.6 s the stylus is about 12 mm along +x (the timer updated the
  // prop while Qt ran), wherever the last timer tick fell.
  std::cout << "instrument tip x after 0.6 s of Qt: " << x << "\n";
  return matrix && x > 4.0 && x <= 20.0 + 1e-9 ? EXIT_SUCCESS : EXIT_FAILURE;
}
