#include "SimulatorWindow.h"

#include "MouseHapticDevice.h"
#include "SettingsPanel.h"

#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
#include <QTabWidget>
#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>

#include "vtkHapticInteractorStyle.h"

#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderWindowInteractor.h>

namespace thintissue
{

SimulatorWindow::SimulatorWindow(TrainingScene& scene, WindowDevices devices)
  : Scene(&scene)
  , Devices(std::move(devices))
  , FreePlay(Devices.mouseScope != nullptr && Devices.mouseInstrument != nullptr)
{
  Widget = new QVTKOpenGLNativeWidget(this);
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  window->SetNumberOfLayers(2);
  // Anti-aliasing by FXAA (the arthroscope renderer's), not multisampling:
  // 8 samples cost several times the frame on a software renderer (bench
  // simulator).
  window->SetMultiSamples(0);
  Widget->setRenderWindow(window);
  setCentralWidget(Widget);
  if (FreePlay)
  {
    vtkNew<vtkHapticInteractorStyle> style;
    style->SetExternalMouseDevices(Devices.mouseScope, Devices.mouseInstrument);
    style->DriveCameraOff();
    Widget->interactor()->SetInteractorStyle(style);
  }
  auto* dock = new QDockWidget("Session", this);
  dock->setWidget(makePanel());
  addDockWidget(Qt::RightDockWidgetArea, dock);
  resize(1280, 720);

  connect(&Frames, &QTimer::timeout, this, &SimulatorWindow::advance);
  showScene();
  startLoop();
  Frames.start(16);
}

SimulatorWindow::~SimulatorWindow()
{
  stopLoop();
}

QWidget* SimulatorWindow::makePanel()
{
  auto* tabs = new QTabWidget(this);
  auto* panel = new QWidget(tabs);
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
  DeviceText = new QLabel(panel);
  DeviceText->setWordWrap(true);
  layout->addWidget(DeviceText);
  Metrics = new QLabel(panel);
  layout->addWidget(Metrics);
  layout->addStretch();
  tabs->addTab(panel, "Session");
  Settings = new SettingsPanel(
    [this](const ScenarioDescription& changed) { return changeSettings(changed); }, tabs);
  tabs->addTab(Settings, "Settings");
  return tabs;
}

void SimulatorWindow::startLoop()
{
  RealTimeLoopSettings settings;
  settings.servo = Devices.startServo ? LoopServo::External : LoopServo::Thread;
  // A replay stops at the scenario's end; live devices play on.
  const bool replay = !FreePlay && !Devices.startServo;
  if (replay)
  {
    settings.endTime = Scene->scenario().duration;
  }
  Loop = std::make_unique<RealTimeLoop>(*Scene, settings);
  Loop->start();
  DeviceError.clear();
  if (Devices.startServo)
  {
    try
    {
      Devices.startServo(Scene->servo());
    }
    catch (const std::exception& error)
    {
      // Shown with the device status; the scene runs on, without forces.
      DeviceError = QString::fromStdString(error.what());
    }
  }
}

void SimulatorWindow::stopLoop()
{
  if (Devices.stopServo)
  {
    Devices.stopServo();
  }
  Loop.reset();
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
  View->renderer()->UseFXAAOn();
  window->AddRenderer(View->renderer());
  // The overview in a corner, over the arthroscope's black surround.
  vtkRenderer* overview = View->overview();
  overview->SetViewport(0.74, 0.0, 1.0, 0.34);
  overview->SetLayer(1);
  window->AddRenderer(overview);
  // Before the loop runs, the GUI may read the scene itself.
  Scene->snapshot(Shown);
  View->update(Shown);
  const ScenarioDescription& s = Scene->scenario();
  Instruments->setCurrentIndex(
    Instruments->findData(QString::fromStdString(instrumentTypeName(s.instrument))));
  setWindowTitle(QString("ThinTissue simulator - %1").arg(QString::fromStdString(s.name)));
  ScenarioText->setText(
    QString("<b>%1</b><br>%2")
      .arg(QString::fromStdString(s.name), QString::fromStdString(s.description)));
  Settings->show(s);
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
  try
  {
    ScenarioDescription scenario = readScenario(path);
    if (!instrument.empty())
      scenario.instrument = parseSurgicalInstrumentType(instrument);
    return startScenario(scenario);
  }
  catch (const std::exception& error)
  {
    return failToLoad(error.what());
  }
}

bool SimulatorWindow::startScenario(const ScenarioDescription& scenario)
{
  if (!Factory)
  {
    return false;
  }
  // The devices serve one scene at a time: the running one pauses while
  // the next is built, and goes on if it cannot be.
  stopLoop();
  try
  {
    std::unique_ptr<TrainingScene> next = Factory(scenario);
    Owned.swap(next); // the old one (if owned) goes after the view is rebuilt
    Scene = Owned.get();
    showScene();
    startLoop();
    return true;
  }
  catch (const std::exception& error)
  {
    startLoop();
    return failToLoad(error.what());
  }
}

bool SimulatorWindow::changeSettings(const ScenarioDescription& changed)
{
  // The physics thread paused for the change: the scene is ours meanwhile.
  stopLoop();
  const bool live = Scene->applySettings(changed);
  if (!live)
  {
    return startScenario(changed);
  }
  Settings->show(Scene->scenario());
  startLoop();
  return true;
}

bool SimulatorWindow::failToLoad(const std::string& message)
{
  // Not modal: the running scenario goes on behind the message.
  auto* box = new QMessageBox(QMessageBox::Warning,
    "Scenario not loaded",
    QString::fromStdString(message),
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

void SimulatorWindow::advance()
{
  Shown = Loop->latest();
  if (Loop->finished() && !Loop->error().empty())
  {
    Frames.stop();
    QMessageBox::warning(this, "Simulation stopped", QString::fromStdString(Loop->error()));
  }
  View->update(Shown);
  Widget->renderWindow()->Render();
  showMetrics();
  showDevices();
}

QString SimulatorWindow::deviceStatus() const
{
  QString text = "<b>Devices:</b> " + QString::fromStdString(Devices.description);
  const char* names[2] = { "arthroscope", "instrument" };
  for (int slot = 0; slot < 2; ++slot)
  {
    const SceneDeviceStatus& d = Shown.devices[slot];
    text += QString("<br>%1: %2, buttons %3, force %4 N")
              .arg(names[slot])
              .arg(d.calibrated ? "calibrated" : "<b>not calibrated</b>")
              .arg(d.buttons)
              .arg(d.force.norm(), 0, 'f', 2);
  }
  if (!DeviceError.isEmpty())
  {
    text += "<br><b>" + DeviceError.toHtmlEscaped() + "</b>";
  }
  if (Devices.problems)
  {
    for (const std::string& problem : Devices.problems())
    {
      text += "<br><b>" + QString::fromStdString(problem).toHtmlEscaped() + "</b>";
    }
  }
  return text;
}

void SimulatorWindow::showDevices()
{
  DeviceText->setText(deviceStatus());
}

void SimulatorWindow::showMetrics()
{
  const SceneMetrics& m = Shown.metrics;
  Metrics->setText(QString("time %1 s<br>instrument path %2 mm<br>camera path %3 mm<br>"
                           "peak force %4 N<br>cartilage contacts %5 steps<br>"
                           "cuts and bites %7, removed %8 mm&sup3;<br>%6")
                     .arg(m.time, 0, 'f', 2)
                     .arg(m.instrumentPathLength, 0, 'f', 1)
                     .arg(m.cameraPathLength, 0, 'f', 1)
                     .arg(m.peakForce, 0, 'f', 2)
                     .arg(m.cartilageContactSteps)
                     .arg(Shown.wrinkling ? "<b>wrinkling</b>" : "")
                     .arg(m.operations)
                     .arg(m.removedVolume, 0, 'f', 1));
  if (m.contourPasses > 0 || m.rimRoughnessAtStart > 0.0)
  {
    // Contouring (6.4.4): how even the rim is now against the start.
    Metrics->setText(Metrics->text() + QString("<br>rim roughness %1 mm (start %2 mm), %3 passes")
                                         .arg(m.rimRoughness, 0, 'f', 3)
                                         .arg(m.rimRoughnessAtStart, 0, 'f', 3)
                                         .arg(m.contourPasses));
  }
}

} // namespace thintissue
