#include "SimulatorWindow.h"

#include <QDockWidget>
#include <QLabel>
#include <QMessageBox>
#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>

#include "vtkHapticInteractorStyle.h"

#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderWindowInteractor.h>

namespace thintissue
{

SimulatorWindow::SimulatorWindow(TrainingScene& scene,
  MouseHapticDevice* scope,
  MouseHapticDevice* instrument)
  : Scene(scene)
  , View(std::make_unique<SimulatorView>(scene))
  , FreePlay(scope != nullptr && instrument != nullptr)
{
  const QString devices = FreePlay ? "mouse and keyboard (Shift: arthroscope; left drag across, "
                                     "right drag in and out, [ ] roll)"
                                   : "the recording";
  setWindowTitle(
    QString("ThinTissue simulator - %1").arg(QString::fromStdString(scene.scenario().name)));
  Widget = new QVTKOpenGLNativeWidget(this);
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  Widget->setRenderWindow(window);
  window->AddRenderer(View->renderer());
  // The overview in a corner, over the arthroscope's black surround.
  vtkRenderer* overview = View->overview();
  overview->SetViewport(0.74, 0.0, 1.0, 0.34);
  overview->SetLayer(1);
  window->SetNumberOfLayers(2);
  window->AddRenderer(overview);
  setCentralWidget(Widget);
  if (FreePlay)
  {
    vtkNew<vtkHapticInteractorStyle> style;
    style->SetExternalMouseDevices(scope, instrument);
    style->DriveCameraOff();
    Widget->interactor()->SetInteractorStyle(style);
  }

  auto* panel = new QWidget(this);
  auto* layout = new QVBoxLayout(panel);
  auto* scenario = new QLabel(QString("<b>%1</b><br>%2")
                                .arg(QString::fromStdString(scene.scenario().name),
                                  QString::fromStdString(scene.scenario().description)),
    panel);
  scenario->setWordWrap(true);
  layout->addWidget(scenario);
  layout->addWidget(new QLabel("Devices: " + devices, panel));
  Metrics = new QLabel(panel);
  layout->addWidget(Metrics);
  layout->addStretch();
  auto* dock = new QDockWidget("Session", this);
  dock->setWidget(panel);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  resize(1280, 720);

  connect(&Frames, &QTimer::timeout, this, &SimulatorWindow::advance);
  Frames.start(16);
  Clock.start();
}

void SimulatorWindow::advance()
{
  const double elapsed = Clock.elapsed() / 1000.0;
  const double now = FreePlay ? elapsed : std::min(elapsed, Scene.scenario().duration);
  if (!Scene.runTo(now))
  {
    Frames.stop();
    QMessageBox::warning(this, "Simulation stopped", QString::fromStdString(Scene.lastError()));
    return;
  }
  View->update();
  Widget->renderWindow()->Render();
  showMetrics();
}

void SimulatorWindow::showMetrics()
{
  const SceneMetrics& m = Scene.metrics();
  Metrics->setText(QString("time %1 s<br>instrument path %2 mm<br>camera path %3 mm<br>"
                           "peak force %4 N<br>cartilage contacts %5 steps<br>%6")
                     .arg(m.time, 0, 'f', 2)
                     .arg(m.instrumentPathLength, 0, 'f', 1)
                     .arg(m.cameraPathLength, 0, 'f', 1)
                     .arg(m.peakForce, 0, 'f', 2)
                     .arg(m.cartilageContactSteps)
                     .arg(Scene.wrinkling() ? "<b>wrinkling</b>" : ""));
}

} // namespace thintissue
