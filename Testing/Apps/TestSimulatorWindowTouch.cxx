// The simulator's window with two Touch devices through the OpenHaptics
// backend, on the stand-in HD library (Testing/Haptics/StandInHD.cxx): the
// HD scheduler (stepped here, on the GUI thread, as the HD runtime would on
// its own) ticks the scene's servo while the physics thread runs the scene;
// moving the instrument's stylus moves the instrument; the device status
// shows the uncalibrated arthroscope stylus and the backend's message
// about it; loading another scenario hands the scheduler to its servo.
#include "OpenHapticsSystem.h"
#include "SimulatorWindow.h"
#include "TouchDevices.h"
#include "TrainingScene.h"

#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <dlfcn.h>

#include <cstdlib>
#include <iostream>

using namespace thintissue;

namespace
{

/// The stand-in's test controls.
struct StandIn
{
  void* handle = dlopen(THINTISSUE_STANDIN_HD, RTLD_NOW | RTLD_LOCAL);
  template <typename F>
  F get(const char* name)
  {
    return reinterpret_cast<F>(dlsym(handle, name));
  }
  void stylusAt(const char* name, double x)
  {
    const double m[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, 0, 0, 1 };
    get<void (*)(const char*, const double*, int)>("standin_set_stylus")(name, m, 0);
  }
  int tick(int n) { return get<int (*)(int)>("standin_tick")(n); }
};

} // namespace

int main(int argc, char* argv[])
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  StandIn hd;
  if (hd.handle == nullptr)
  {
    std::cerr << "cannot load the stand-in HD library " << THINTISSUE_STANDIN_HD << "\n";
    return EXIT_FAILURE;
  }
  hd.get<void (*)()>("standin_reset")();
  const auto add = hd.get<void (*)(const char*, int, double, double)>("standin_add_device");
  add("Arthroscope", 0, 0.88, 3.3); // not calibrated
  add("Instrument", 1, 0.88, 3.3);
  OpenHapticsSettings settings;
  settings.library = THINTISSUE_STANDIN_HD;
  settings.deviceNames = { "Arthroscope", "Instrument" };
  OpenHapticsSystem touch(settings);
  const ScenarioDescription scenario =
    readScenario(std::string(THINTISSUE_DATA_DIR) + "/Scenarios/meniscus-examination.json");
  TrainingScene scene(scenario, touch.device(0), touch.device(1));
  SimulatorWindow window(scene, touchWindowDevices(touch, "Touch (stand-in)"));
  window.setScenarios(std::string(THINTISSUE_DATA_DIR) + "/Scenarios",
    [&](const ScenarioDescription& next)
    { return std::make_unique<TrainingScene>(next, touch.device(0), touch.device(1)); });
  window.show();
  const Vector3 start = window.snapshot().instrument.translation;
  bool moved = false, reloaded = false, ticking = false;
  QString status;
  int stage = 0;
  QTimer scheduler; // the HD scheduler's 1 kHz, 16 ticks at a time
  QObject::connect(&scheduler, &QTimer::timeout, [&] { ticking = hd.tick(16) > 0 || ticking; });
  QTimer watch;
  QObject::connect(&watch,
    &QTimer::timeout,
    [&]
    {
      const double now = window.snapshot().time;
      if (stage == 0 && now > 0.1)
      {
        hd.stylusAt("Instrument", 10.0);
        stage = 1;
      }
      else if (stage == 1 && (window.snapshot().instrument.translation - start).norm() > 9.0)
      {
        moved = true;
        status = window.deviceStatus();
        reloaded = window.loadScenario(
          std::string(THINTISSUE_DATA_DIR) + "/Scenarios/ligament-firmness.json");
        stage = 2;
      }
      else if (stage == 2 && now > 0.1)
      {
        application.quit();
      }
    });
  scheduler.start(16);
  watch.start(50);
  QTimer::singleShot(90000, &application, &QApplication::quit);
  application.exec();
  std::cout << "status: " << status.toStdString() << "\n";
  std::cout << "scheduler ticking " << ticking << ", instrument followed the stylus " << moved
            << ", other scenario loaded and running " << reloaded << " (at "
            << window.snapshot().time << " s)\n";
  const bool shown = status.contains("arthroscope: <b>not calibrated</b>") &&
                     status.contains("instrument: calibrated") &&
                     status.contains("'Arthroscope' is not calibrated");
  return ticking && moved && reloaded && shown && window.snapshot().time > 0.1 ? EXIT_SUCCESS
                                                                               : EXIT_FAILURE;
}
