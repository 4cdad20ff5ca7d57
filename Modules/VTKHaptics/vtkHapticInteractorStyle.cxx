#include "vtkHapticInteractorStyle.h"

#include "HapticServo.h"
#include "MouseHapticDevice.h"
#include "OpenHapticsSystem.h"
#include "PortalMapping.h"
#include "ScriptedHapticDevice.h"
#include "ServoThread.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkEventData.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkProp3D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cmath>
#include <exception>

vtkStandardNewMacro(vtkHapticInteractorStyle);

using thintissue::Vector3;

namespace
{
constexpr int ScopeSlot = 0;
constexpr int InstrumentSlot = 1;
/// Stylus millimetres per mouse pixel, roll per key press (radians).
constexpr double MillimetresPerPixel = 0.2;
constexpr double RollStep = 5.0 * M_PI / 180.0;
} // namespace

struct vtkHapticInteractorStyle::Internals
{
  // Kept across StartDevices / StopDevices.
  vtkSmartPointer<vtkProp3D> prop;
  // The running devices.
  std::unique_ptr<thintissue::OpenHapticsSystem> hd;
  std::array<std::unique_ptr<thintissue::HapticDevice>, 2> owned;
  std::array<thintissue::MouseHapticDevice*, 2> mouse{ { nullptr, nullptr } };
  std::array<thintissue::HapticDeviceState, 2> mouseState;
  std::unique_ptr<thintissue::HapticServo> servo;
  std::unique_ptr<thintissue::ServoThread> thread;
  double time = 0.0; ///< AdvanceTo's clock
  std::array<thintissue::HapticToolState, 2> latest;
  std::array<unsigned, 2> buttons{ { 0, 0 } };
  int lastX = 0;
  int lastY = 0;

  void stop()
  {
    if (thread)
    {
      thread->stop();
    }
    if (hd)
    {
      hd->stop();
    }
    thread.reset();
    servo.reset();
    hd.reset();
    owned[0].reset();
    owned[1].reset();
    mouse = { nullptr, nullptr };
  }
};

vtkHapticInteractorStyle::vtkHapticInteractorStyle()
  : State(std::make_unique<Internals>())
{
  this->SetHDLibrary("libHD.so");
  this->SetScopeDeviceName("Left Device");
  this->SetInstrumentDeviceName("Right Device");
}

vtkHapticInteractorStyle::~vtkHapticInteractorStyle()
{
  this->StopDevices();
  this->SetScopeTrajectoryFileName(nullptr);
  this->SetInstrumentTrajectoryFileName(nullptr);
  this->SetHDLibrary(nullptr);
  this->SetScopeDeviceName(nullptr);
  this->SetInstrumentDeviceName(nullptr);
}

void vtkHapticInteractorStyle::SetExternalMouseDevices(thintissue::MouseHapticDevice* scope,
  thintissue::MouseHapticDevice* instrument)
{
  this->StopDevices();
  this->State->mouse = { scope, instrument };
}

void vtkHapticInteractorStyle::SetInstrumentProp(vtkProp3D* prop)
{
  this->State->prop = prop;
  this->Modified();
}

vtkProp3D* vtkHapticInteractorStyle::GetInstrumentProp()
{
  return this->State->prop;
}

bool vtkHapticInteractorStyle::BuildBackend()
{
  Internals& s = *this->State;
  if (this->Backend == SCRIPTED)
  {
    if (!this->ScopeTrajectoryFileName || !this->InstrumentTrajectoryFileName)
    {
      throw thintissue::InvalidInputError(
        "scripted devices need ScopeTrajectoryFileName and InstrumentTrajectoryFileName");
    }
    s.owned[ScopeSlot] = std::make_unique<thintissue::ScriptedHapticDevice>(
      thintissue::readHapticTrajectory(this->ScopeTrajectoryFileName));
    s.owned[InstrumentSlot] = std::make_unique<thintissue::ScriptedHapticDevice>(
      thintissue::readHapticTrajectory(this->InstrumentTrajectoryFileName));
  }
  else if (this->Backend == OPENHAPTICS)
  {
    thintissue::OpenHapticsSettings settings;
    settings.library = this->HDLibrary ? this->HDLibrary : "libHD.so";
    settings.deviceNames = { this->ScopeDeviceName ? this->ScopeDeviceName : "Left Device",
      this->InstrumentDeviceName ? this->InstrumentDeviceName : "Right Device" };
    s.hd = std::make_unique<thintissue::OpenHapticsSystem>(settings);
    return true;
  }
  else
  {
    for (int slot = 0; slot < 2; ++slot)
    {
      auto device = std::make_unique<thintissue::MouseHapticDevice>();
      s.mouse[slot] = device.get();
      device->setState(s.mouseState[slot]);
      s.owned[slot] = std::move(device);
    }
  }
  return true;
}

bool vtkHapticInteractorStyle::StartDevices()
{
  this->StopDevices();
  this->LastError.clear();
  Internals& s = *this->State;
  try
  {
    this->BuildBackend();
    std::array<thintissue::PortalSettings, 2> portals;
    const double* portal[2] = { this->ScopePortal, this->InstrumentPortal };
    const double* inward[2] = { this->ScopeInward, this->InstrumentInward };
    std::vector<thintissue::HapticSlot> slots;
    for (int slot = 0; slot < 2; ++slot)
    {
      portals[slot].portal = Vector3(portal[slot][0], portal[slot][1], portal[slot][2]);
      portals[slot].inward = Vector3(inward[slot][0], inward[slot][1], inward[slot][2]);
      portals[slot].scale = this->WorkspaceScale;
      thintissue::HapticDevice* device =
        s.hd ? &s.hd->device(static_cast<std::size_t>(slot)) : s.owned[slot].get();
      slots.push_back(thintissue::HapticSlot{ device, portals[slot], slot == InstrumentSlot });
    }
    s.servo = std::make_unique<thintissue::HapticServo>(slots);
    s.time = 0.0;
    if (s.hd)
    {
      s.hd->start(*s.servo);
    }
    else if (this->RealTime)
    {
      s.thread = std::make_unique<thintissue::ServoThread>(*s.servo);
      s.thread->start();
    }
    if (!s.hd && !this->RealTime)
    {
      s.servo->tick(0.0);
    }
  }
  catch (const std::exception& error)
  {
    s.stop();
    this->LastError = error.what();
    vtkErrorMacro(<< this->LastError);
    return false;
  }
  if (this->RealTime && this->Interactor && this->TimerId < 0)
  {
    this->TimerId =
      this->Interactor->CreateRepeatingTimer(static_cast<unsigned long>(this->TimerPeriod));
  }
  return true;
}

void vtkHapticInteractorStyle::StopDevices()
{
  if (this->Interactor && this->TimerId >= 0)
  {
    this->Interactor->DestroyTimer(this->TimerId);
  }
  this->TimerId = -1;
  this->State->stop();
}

bool vtkHapticInteractorStyle::GetDevicesRunning()
{
  return this->State->servo != nullptr;
}

void vtkHapticInteractorStyle::AdvanceTo(double seconds)
{
  Internals& s = *this->State;
  if (!s.servo || this->RealTime || s.hd)
  {
    return;
  }
  while (s.time + 0.0005 < seconds)
  {
    s.time = std::min(seconds, s.time + 0.001);
    s.servo->tick(s.time);
  }
  this->UpdateFromDevices();
}

void vtkHapticInteractorStyle::UpdateFromDevices()
{
  Internals& s = *this->State;
  if (!s.servo)
  {
    return;
  }
  for (int slot = 0; slot < 2; ++slot)
  {
    const unsigned previous = s.latest[slot].stylus.buttons;
    s.latest[slot] = s.servo->latestToolState(static_cast<std::size_t>(slot));
    this->InvokeDeviceEvents(slot, previous);
  }
  const thintissue::RigidPose& instrument = s.latest[InstrumentSlot].pose;
  if (s.prop)
  {
    vtkNew<vtkMatrix4x4> matrix;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        matrix->SetElement(r, c, instrument.rotation(r, c));
      }
      matrix->SetElement(r, 3, instrument.translation[r]);
    }
    s.prop->SetUserMatrix(matrix);
  }
  vtkRenderer* renderer = this->GetDefaultRenderer();
  if (!renderer && this->Interactor && this->Interactor->GetRenderWindow())
  {
    renderer = this->Interactor->GetRenderWindow()->GetRenderers()->GetFirstRenderer();
  }
  if (this->DriveCamera && renderer)
  {
    // The camera's headlight (VTK's default light) is then at the scope tip.
    const thintissue::ArthroscopeView view =
      thintissue::arthroscopeView(s.latest[ScopeSlot].pose, this->ViewingAngle);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(view.eye.data());
    camera->SetFocalPoint(view.focalPoint.data());
    camera->SetViewUp(view.viewUp.data());
    camera->SetViewAngle(this->FieldOfView);
    renderer->ResetCameraClippingRange();
  }
}

void vtkHapticInteractorStyle::InvokeDeviceEvents(int slot, unsigned previousButtons)
{
  if (!this->Interactor)
  {
    return;
  }
  const thintissue::HapticToolState& state = this->State->latest[slot];
  const vtkEventDataDevice device =
    slot == ScopeSlot ? vtkEventDataDevice::LeftController : vtkEventDataDevice::RightController;
  vtkNew<vtkEventDataDevice3D> move;
  move->SetDevice(device);
  move->SetWorldPosition(state.pose.translation.data());
  const Vector3 direction = -state.pose.rotation.col(2);
  move->SetWorldDirection(direction.data());
  const Eigen::AngleAxisd turn(state.pose.rotation);
  const double orientation[4] = {
    turn.angle() * 180.0 / M_PI, turn.axis().x(), turn.axis().y(), turn.axis().z()
  };
  move->SetWorldOrientation(orientation);
  this->Interactor->InvokeEvent(vtkCommand::Move3DEvent, move);
  const unsigned changed = previousButtons ^ state.stylus.buttons;
  for (unsigned bit = 0; bit < 2; ++bit)
  {
    if (changed & (1u << bit))
    {
      vtkNew<vtkEventDataDevice3D> button;
      button->SetDevice(device);
      button->SetInput(bit == 0 ? vtkEventDataDeviceInput::Trigger : vtkEventDataDeviceInput::Grip);
      button->SetAction((state.stylus.buttons & (1u << bit)) ? vtkEventDataAction::Press
                                                             : vtkEventDataAction::Release);
      button->SetWorldPosition(state.pose.translation.data());
      this->Interactor->InvokeEvent(vtkCommand::Button3DEvent, button);
    }
  }
}

void vtkHapticInteractorStyle::OnTimer()
{
  if (this->State->servo && this->RealTime)
  {
    this->UpdateFromDevices();
    if (this->Interactor)
    {
      this->Interactor->Render();
    }
  }
}

void vtkHapticInteractorStyle::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  if (interactor == this->Interactor)
  {
    return;
  }
  if (this->Interactor && this->TimerId >= 0)
  {
    this->Interactor->DestroyTimer(this->TimerId);
    this->TimerId = -1;
  }
  this->Superclass::SetInteractor(interactor);
  if (interactor && this->State->servo && this->RealTime)
  {
    this->TimerId = interactor->CreateRepeatingTimer(static_cast<unsigned long>(this->TimerPeriod));
  }
}

// --- Mouse and keyboard (the MOUSE backend) -----------------------------------

void vtkHapticInteractorStyle::MouseDrag(int mode)
{
  Internals& s = *this->State;
  if (!this->Interactor || !s.mouse[0])
  {
    return;
  }
  const int* position = this->Interactor->GetEventPosition();
  if (mode != 0)
  {
    this->Dragging = mode;
    s.lastX = position[0];
    s.lastY = position[1];
    return;
  }
  const int slot = this->Interactor->GetShiftKey() ? ScopeSlot : InstrumentSlot;
  thintissue::HapticDeviceState& stylus = s.mouseState[slot];
  const double dx = MillimetresPerPixel * (position[0] - s.lastX);
  const double dy = MillimetresPerPixel * (position[1] - s.lastY);
  if (this->Dragging == 1)
  {
    stylus.position += Vector3(dx, dy, 0.0);
  }
  else
  {
    stylus.position.z() -= dy;
  }
  s.lastX = position[0];
  s.lastY = position[1];
  s.mouse[slot]->setState(stylus);
}

void vtkHapticInteractorStyle::OnMouseMove()
{
  if (this->Dragging != 0 && this->State->mouse[0])
  {
    this->MouseDrag(0);
  }
}

void vtkHapticInteractorStyle::OnLeftButtonDown()
{
  this->MouseDrag(1);
}

void vtkHapticInteractorStyle::OnLeftButtonUp()
{
  this->Dragging = 0;
}

void vtkHapticInteractorStyle::OnRightButtonDown()
{
  this->MouseDrag(2);
}

void vtkHapticInteractorStyle::OnRightButtonUp()
{
  this->Dragging = 0;
}

void vtkHapticInteractorStyle::OnChar()
{
  Internals& s = *this->State;
  if (!this->Interactor || !s.mouse[0])
  {
    this->Superclass::OnChar();
    return;
  }
  const int slot = this->Interactor->GetShiftKey() ? ScopeSlot : InstrumentSlot;
  thintissue::HapticDeviceState& stylus = s.mouseState[slot];
  switch (this->Interactor->GetKeyCode())
  {
    case '[':
    case ']':
    {
      const double angle = this->Interactor->GetKeyCode() == '[' ? -RollStep : RollStep;
      stylus.orientation =
        stylus.orientation * Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix();
      break;
    }
    case '1':
      stylus.buttons ^= 1u;
      break;
    case '2':
      stylus.buttons ^= 2u;
      break;
    default:
      this->Superclass::OnChar();
      return;
  }
  s.mouse[slot]->setState(stylus);
}

// --- Latest state --------------------------------------------------------------

void vtkHapticInteractorStyle::GetInstrumentTip(double tip[3])
{
  const Vector3& x = this->State->latest[InstrumentSlot].pose.translation;
  tip[0] = x[0];
  tip[1] = x[1];
  tip[2] = x[2];
}

void vtkHapticInteractorStyle::GetScopeTip(double tip[3])
{
  const Vector3& x = this->State->latest[ScopeSlot].pose.translation;
  tip[0] = x[0];
  tip[1] = x[1];
  tip[2] = x[2];
}

int vtkHapticInteractorStyle::GetInstrumentButtons()
{
  return static_cast<int>(this->State->latest[InstrumentSlot].stylus.buttons);
}

int vtkHapticInteractorStyle::GetScopeButtons()
{
  return static_cast<int>(this->State->latest[ScopeSlot].stylus.buttons);
}

void vtkHapticInteractorStyle::PrintSelf(ostream& os, vtkIndent indent)
{
  static const char* const backends[] = { "Mouse", "Scripted", "OpenHaptics" };
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << backends[this->Backend] << "\n"
     << indent << "ScopeTrajectoryFileName: "
     << (this->ScopeTrajectoryFileName ? this->ScopeTrajectoryFileName : "(none)") << "\n"
     << indent << "InstrumentTrajectoryFileName: "
     << (this->InstrumentTrajectoryFileName ? this->InstrumentTrajectoryFileName : "(none)") << "\n"
     << indent << "HDLibrary: " << (this->HDLibrary ? this->HDLibrary : "(none)") << "\n"
     << indent << "ScopeDeviceName: " << (this->ScopeDeviceName ? this->ScopeDeviceName : "")
     << "\n"
     << indent
     << "InstrumentDeviceName: " << (this->InstrumentDeviceName ? this->InstrumentDeviceName : "")
     << "\n"
     << indent << "ScopePortal: " << this->ScopePortal[0] << " " << this->ScopePortal[1] << " "
     << this->ScopePortal[2] << "\n"
     << indent << "InstrumentPortal: " << this->InstrumentPortal[0] << " "
     << this->InstrumentPortal[1] << " " << this->InstrumentPortal[2] << "\n"
     << indent << "WorkspaceScale: " << this->WorkspaceScale << "\n"
     << indent << "ViewingAngle: " << this->ViewingAngle << "\n"
     << indent << "FieldOfView: " << this->FieldOfView << "\n"
     << indent << "DriveCamera: " << (this->DriveCamera ? "On" : "Off") << "\n"
     << indent << "RealTime: " << (this->RealTime ? "On" : "Off") << "\n"
     << indent << "TimerPeriod: " << this->TimerPeriod << "\n"
     << indent << "DevicesRunning: " << (this->State->servo ? "yes" : "no") << "\n";
}
