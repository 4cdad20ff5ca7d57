#include "SimulatorWindow.h"

#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
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
  : Scene(&scene)
  , FreePlay(scope != nullptr && instrument != nullptr)
{
  const QString devices = FreePlay ? "mouse and keyboard (Shift: arthroscope; left drag across, "
                                     "right drag in and out, [ ] roll)"
                                   : "the recording";
  Widget = new QVTKOpenGLNativeWidget(this);
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  window->SetNumberOfLayers(2);
  Widget->setRenderWindow(window);
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
  Scenarios = new QComboBox(panel);
  Scenarios->setEnabled(false);
  layout->addWidget(Scenarios);
  Instruments = new QComboBox(panel);
  for (SurgicalInstrumentType type : allSurgicalInstrumentTypes())
  {
    const QString name = QString::fromStdString(instrumentTypeName(type));
    Instruments->addItem(name, name);
  }
  Instruments->setEnabled(false);
  layout->addWidget(Instruments);
  auto* shot = new QPushButton("Screenshot", panel);
  layout->addWidget(shot);
  connect(shot,
    &QPushButton::clicked,
    this,
    [this]
    {
      const QString name =
        QString("thintissue-%1.png").arg(QDateTime::currentDateTime().toString("yyyyMMdd-hhmmss"));
      if (screenshot(name.toStdString()))
        statusBar()->showMessage("picture written to " + name, 5000);
    });
  ScenarioText = new QLabel(panel);
  ScenarioText->setWordWrap(true);
  layout->addWidget(ScenarioText);
  layout->addWidget(new QLabel("Devices: " + devices, panel));
  Metrics = new QLabel(panel);
  layout->addWidget(Metrics);
  layout->addStretch();
  auto* dock = new QDockWidget("Session", this);
  dock->setWidget(panel);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  resize(1280, 720);

  connect(&Frames, &QTimer::timeout, this, &SimulatorWindow::advance);
  showScene();
  Frames.start(16);
}

void SimulatorWindow::showScene()
{
  vtkRenderWindow* window = Widget->renderWindow();
  if (View)
  {
    window->RemoveRenderer(View->renderer());
    window->RemoveRenderer(View->overview());
  }
  View = std::make_unique<SimulatorView>(*Scene);
  window->AddRenderer(View->renderer());
  // The overview in a corner, over the arthroscope's black surround.
  vtkRenderer* overview = View->overview();
  overview->SetViewport(0.74, 0.0, 1.0, 0.34);
  overview->SetLayer(1);
  window->AddRenderer(overview);
  const ScenarioDescription& s = Scene->scenario();
  Instruments->setCurrentIndex(
    Instruments->findData(QString::fromStdString(instrumentTypeName(s.instrument))));
  setWindowTitle(QString("ThinTissue simulator - %1").arg(QString::fromStdString(s.name)));
  ScenarioText->setText(
    QString("<b>%1</b><br>%2")
      .arg(QString::fromStdString(s.name), QString::fromStdString(s.description)));
  Clock.restart();
}

void SimulatorWindow::setScenarios(const std::string& directory, SceneFactory factory)
{
  Factory = std::move(factory);
  const QDir folder(QString::fromStdString(directory));
  Scenarios->clear();
  for (const QString& file : folder.entryList({ "*.json" }, QDir::Files, QDir::Name))
  {
    Scenarios->addItem(file, folder.absoluteFilePath(file));
  }
  const int current = Scenarios->findData(
    QFileInfo(QString::fromStdString(Scene->scenario().source)).absoluteFilePath());
  Scenarios->setCurrentIndex(current);
  Scenarios->setEnabled(true);
  connect(Scenarios,
    QOverload<int>::of(&QComboBox::activated),
    this,
    [this](int index) { loadScenario(Scenarios->itemData(index).toString().toStdString()); });
  Instruments->setEnabled(true);
  connect(Instruments,
    QOverload<int>::of(&QComboBox::activated),
    this,
    [this](int index) {
      loadScenario(Scene->scenario().source, Instruments->itemData(index).toString().toStdString());
    });
}

bool SimulatorWindow::screenshot(const std::string& path)
{
  try
  {
    SimulatorView::writePicture(Widget->renderWindow(), path);
    return true;
  }
  catch (const std::exception& error)
  {
    QMessageBox::warning(this, "Screenshot", QString::fromStdString(error.what()));
    return false;
  }
}

bool SimulatorWindow::loadScenario(const std::string& path, const std::string& instrument)
{
  if (!Factory)
  {
    return false;
  }
  try
  {
    std::unique_ptr<TrainingScene> next = Factory(path, instrument);
    Owned.swap(next); // the old one (if owned) goes after the view is rebuilt
    Scene = Owned.get();
    showScene();
    return true;
  }
  catch (const std::exception& error)
  {
    // Not modal: the running scenario goes on behind the message.
    auto* box = new QMessageBox(QMessageBox::Warning,
      "Scenario not loaded",
      QString::fromStdString(error.what()),
      QMessageBox::Ok,
      this);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->show();
    const int current = Scenarios->findData(
      QFileInfo(QString::fromStdString(Scene->scenario().source)).absoluteFilePath());
    Scenarios->setCurrentIndex(current);
    Instruments->setCurrentIndex(Instruments->findData(
      QString::fromStdString(instrumentTypeName(Scene->scenario().instrument))));
    return false;
  }
}

void SimulatorWindow::advance()
{
  const double elapsed = Clock.elapsed() / 1000.0;
  const double now = FreePlay ? elapsed : std::min(elapsed, Scene->scenario().duration);
  if (!Scene->runTo(now))
  {
    Frames.stop();
    QMessageBox::warning(this, "Simulation stopped", QString::fromStdString(Scene->lastError()));
    return;
  }
  View->update();
  Widget->renderWindow()->Render();
  showMetrics();
}

void SimulatorWindow::showMetrics()
{
  const SceneMetrics& m = Scene->metrics();
  Metrics->setText(QString("time %1 s<br>instrument path %2 mm<br>camera path %3 mm<br>"
                           "peak force %4 N<br>cartilage contacts %5 steps<br>"
                           "cuts and bites %7, removed %8 mm&sup3;<br>%6")
                     .arg(m.time, 0, 'f', 2)
                     .arg(m.instrumentPathLength, 0, 'f', 1)
                     .arg(m.cameraPathLength, 0, 'f', 1)
                     .arg(m.peakForce, 0, 'f', 2)
                     .arg(m.cartilageContactSteps)
                     .arg(Scene->wrinkling() ? "<b>wrinkling</b>" : "")
                     .arg(m.operations)
                     .arg(m.removedVolume, 0, 'f', 1));
}

} // namespace thintissue
