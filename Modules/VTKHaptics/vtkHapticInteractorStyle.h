/**
 * @class vtkHapticInteractorStyle
 * @brief Two haptic devices drive a VTK scene as in arthroscopy (thesis
 * 4.1): one stylus holds the arthroscope (the active camera), the other the
 * instrument (a prop), each through its portal into the joint, and the
 * instrument renders the tissue's force (thintissue::HapticServo at 1 kHz).
 *
 * Backends: MOUSE (default; the mouse drives the instrument, with Shift the
 * arthroscope: left drag moves across, right drag in and out, keys q / e
 * roll, 1 / 2 toggle the stylus buttons), SCRIPTED (two recorded
 * trajectories, files of thintissue::writeHapticTrajectory), OPENHAPTICS
 * (two Touch devices by name, the HD library loaded at run time).
 *
 * StartDevices() builds the backend and the servo; with RealTime on (the
 * default) the servo runs on its own 1 kHz thread and a repeating
 * interactor timer (TimerPeriod ms) polls the latest state; with RealTime
 * off the servo is ticked by AdvanceTo(seconds) at 1 ms steps
 * (deterministic replays, tests, offscreen pictures). Each update moves the
 * instrument prop (its user matrix: the instrument frame of
 * SurgicalInstruments.h), places the camera as an arthroscope (eye at the
 * scope tip, looking down the shaft turned by ViewingAngle toward the
 * scope's working side, a headlight at the tip), and invokes on the
 * interactor a Move3DEvent per device (vtkEventDataDevice3D: LeftController
 * the arthroscope, RightController the instrument) and a Button3DEvent
 * (Trigger: button 1, Grip: button 2) when a button changes.
 *
 * Errors (no trajectory file, a device not found, ...) make StartDevices()
 * return false with the message in GetLastErrorMessage() and vtkErrorMacro.
 */
#ifndef vtkHapticInteractorStyle_h
#define vtkHapticInteractorStyle_h

#include "ThinTissueVTKHapticsModule.h"
#include "vtkInteractorStyle3D.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkProp3D;
class vtkLight;
namespace thintissue
{
class MouseHapticDevice;
}

class THINTISSUEVTKHAPTICS_EXPORT vtkHapticInteractorStyle : public vtkInteractorStyle3D
{
public:
  static vtkHapticInteractorStyle* New();
  vtkTypeMacro(vtkHapticInteractorStyle, vtkInteractorStyle3D);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Backends
  {
    MOUSE = 0,
    SCRIPTED = 1,
    OPENHAPTICS = 2
  };
  ///@{
  /// The devices (take effect at StartDevices()).
  vtkSetClampMacro(Backend, int, MOUSE, OPENHAPTICS);
  vtkGetMacro(Backend, int);
  void SetBackendToMouse() { this->SetBackend(MOUSE); }
  void SetBackendToScripted() { this->SetBackend(SCRIPTED); }
  void SetBackendToOpenHaptics() { this->SetBackend(OPENHAPTICS); }
  vtkSetStringMacro(ScopeTrajectoryFileName);
  vtkGetStringMacro(ScopeTrajectoryFileName);
  vtkSetStringMacro(InstrumentTrajectoryFileName);
  vtkGetStringMacro(InstrumentTrajectoryFileName);
  vtkSetStringMacro(HDLibrary);
  vtkGetStringMacro(HDLibrary);
  vtkSetStringMacro(ScopeDeviceName);
  vtkGetStringMacro(ScopeDeviceName);
  vtkSetStringMacro(InstrumentDeviceName);
  vtkGetStringMacro(InstrumentDeviceName);
  ///@}

  ///@{
  /// The portals (world, mm): the fulcrum point and the direction into the
  /// joint; device mm to world mm scale (take effect at StartDevices()).
  vtkSetVector3Macro(ScopePortal, double);
  vtkGetVector3Macro(ScopePortal, double);
  vtkSetVector3Macro(ScopeInward, double);
  vtkGetVector3Macro(ScopeInward, double);
  vtkSetVector3Macro(InstrumentPortal, double);
  vtkGetVector3Macro(InstrumentPortal, double);
  vtkSetVector3Macro(InstrumentInward, double);
  vtkGetVector3Macro(InstrumentInward, double);
  vtkSetMacro(WorkspaceScale, double);
  vtkGetMacro(WorkspaceScale, double);
  ///@}

  ///@{
  /// The arthroscope's viewing angle (degrees off the shaft, default 30),
  /// its field of view (degrees, default 70) and whether it drives the
  /// active camera (default on).
  vtkSetClampMacro(ViewingAngle, double, 0.0, 90.0);
  vtkGetMacro(ViewingAngle, double);
  vtkSetClampMacro(FieldOfView, double, 1.0, 170.0);
  vtkGetMacro(FieldOfView, double);
  vtkSetMacro(DriveCamera, bool);
  vtkGetMacro(DriveCamera, bool);
  vtkBooleanMacro(DriveCamera, bool);
  ///@}

  ///@{
  /// RealTime on: a servo thread and a repeating timer of TimerPeriod ms.
  /// Off: AdvanceTo() ticks the servo.
  vtkSetMacro(RealTime, bool);
  vtkGetMacro(RealTime, bool);
  vtkBooleanMacro(RealTime, bool);
  vtkSetClampMacro(TimerPeriod, int, 1, 1000);
  vtkGetMacro(TimerPeriod, int);
  ///@}

  /// The prop the instrument moves (its user matrix); may be null.
  void SetInstrumentProp(vtkProp3D* prop);
  vtkProp3D* GetInstrumentProp();

  /// Builds the backend and the servo (and starts its thread when
  /// RealTime). False on error (see GetLastErrorMessage()).
  bool StartDevices();
  void StopDevices();
  bool GetDevicesRunning();
  const char* GetLastErrorMessage() { return this->LastError.c_str(); }

  /// RealTime off: ticks the servo at 1 ms steps up to `seconds`, then
  /// updates the scene once (no render).
  void AdvanceTo(double seconds);
  /// Moves the prop and camera to the latest device state and invokes the
  /// 3D events (the timer calls it, then renders).
  void UpdateFromDevices();

  ///@{
  /// The latest poses (world): instrument tip, arthroscope tip, and the
  /// buttons of each stylus.
  void GetInstrumentTip(double tip[3]);
  void GetScopeTip(double tip[3]);
  int GetInstrumentButtons();
  int GetScopeButtons();
  ///@}

  void OnTimer() override;
  void OnMouseMove() override;
  void OnLeftButtonDown() override;
  void OnLeftButtonUp() override;
  void OnRightButtonDown() override;
  void OnRightButtonUp() override;
  void OnChar() override;
  void OnMove3D(vtkEventData*) override {}
  void OnButton3D(vtkEventData*) override {}
  void SetInteractor(vtkRenderWindowInteractor* interactor) override;

  struct Internals;
  /// C++ only: the kernel objects (servo, devices), null when stopped.
  Internals* GetInternals() { return this->State.get(); }
  /// C++ only: the mouse and keyboard drive these two devices (the
  /// arthroscope's, the instrument's) of an application that runs its own
  /// servo (e.g. a TrainingScene), instead of the style's. Null: the style's.
  void SetExternalMouseDevices(thintissue::MouseHapticDevice* scope,
    thintissue::MouseHapticDevice* instrument);

protected:
  vtkHapticInteractorStyle();
  ~vtkHapticInteractorStyle() override;

  int Backend = MOUSE;
  char* ScopeTrajectoryFileName = nullptr;
  char* InstrumentTrajectoryFileName = nullptr;
  char* HDLibrary = nullptr;
  char* ScopeDeviceName = nullptr;
  char* InstrumentDeviceName = nullptr;
  double ScopePortal[3] = { 0.0, 0.0, 0.0 };
  double ScopeInward[3] = { 0.0, 0.0, -1.0 };
  double InstrumentPortal[3] = { 0.0, 0.0, 0.0 };
  double InstrumentInward[3] = { 0.0, 0.0, -1.0 };
  double WorkspaceScale = 1.0;
  double ViewingAngle = 30.0;
  double FieldOfView = 70.0;
  bool DriveCamera = true;
  bool RealTime = true;
  int TimerPeriod = 16;
  std::string LastError;

private:
  vtkHapticInteractorStyle(const vtkHapticInteractorStyle&) = delete;
  void operator=(const vtkHapticInteractorStyle&) = delete;

  bool BuildBackend();
  void MouseDrag(int mode);
  void InvokeDeviceEvents(int slot, unsigned previousButtons);

  std::unique_ptr<Internals> State;
  int Dragging = 0; ///< 0 none, 1 across (left), 2 in and out (right)
  int TimerId = -1;
};

#endif
