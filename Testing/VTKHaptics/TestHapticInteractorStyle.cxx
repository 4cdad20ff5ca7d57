// vtkHapticInteractorStyle with scripted devices on a manual clock: the
// instrument prop and the arthroscope camera follow the styluses through
// their portals, 3D move and button events reach observers of the
// interactor, the mouse backend moves the instrument, errors are reported.
#include "MouseHapticDevice.h"
#include "PortalMapping.h"
#include "ScriptedHapticDevice.h"
#include "ThinTissueTestSupport.h"
#include "vtkHapticInteractorStyle.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkEventData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <gtest/gtest.h>

using namespace thintissue;

namespace
{

HapticTrajectory line(const Vector3& from, const Vector3& to, unsigned pressedAfterHalf)
{
  HapticTrajectory t;
  for (int k = 0; k <= 10; ++k)
  {
    t.samples.push_back(HapticSample{ 0.1 * k,
      from + 0.1 * k * (to - from),
      Eigen::Quaterniond::Identity(),
      k >= 5 ? pressedAfterHalf : 0u });
  }
  return t;
}

struct Events
{
  int moves[2] = { 0, 0 };
  int presses = 0;
  static void onEvent(vtkObject*, unsigned long event, void* client, void* data)
  {
    auto* self = static_cast<Events*>(client);
    auto* device = static_cast<vtkEventData*>(data)->GetAsEventDataDevice3D();
    const int which = device->GetDevice() == vtkEventDataDevice::LeftController ? 0 : 1;
    if (event == vtkCommand::Move3DEvent)
    {
      ++self->moves[which];
    }
    else if (device->GetAction() == vtkEventDataAction::Press)
    {
      ++self->presses;
    }
  }
};

} // namespace

TEST(HapticInteractorStyle, ScriptedDevicesMoveTheInstrumentAndTheArthroscope)
{
  const auto directory = thintissue::testing::temporaryDirectory();
  const std::string scopePath = (directory / "scope.json").string();
  const std::string toolPath = (directory / "tool.json").string();
  writeHapticTrajectory(scopePath, line(Vector3(0, 0, 0), Vector3(0, 10, 0), 0));
  writeHapticTrajectory(toolPath, line(Vector3(0, 0, 0), Vector3(20, 0, 5), 1));

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  vtkNew<vtkHapticInteractorStyle> style;
  interactor->SetInteractorStyle(style);
  style->SetDefaultRenderer(renderer);
  vtkNew<vtkActor> instrument;
  style->SetInstrumentProp(instrument);
  style->SetBackendToScripted();
  style->SetRealTime(false);
  style->SetScopeTrajectoryFileName(scopePath.c_str());
  style->SetInstrumentTrajectoryFileName(toolPath.c_str());
  style->SetScopePortal(-30.0, 0.0, 40.0);
  style->SetInstrumentPortal(30.0, 0.0, 40.0);
  Events events;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback(&Events::onEvent);
  observer->SetClientData(&events);
  interactor->AddObserver(vtkCommand::Move3DEvent, observer);
  interactor->AddObserver(vtkCommand::Button3DEvent, observer);
  ASSERT_TRUE(style->StartDevices()) << style->GetLastErrorMessage();

  style->AdvanceTo(0.75);
  // The instrument tip is where the portal mapping puts the stylus.
  PortalSettings portal;
  portal.portal = Vector3(30.0, 0.0, 40.0);
  const Vector3 stylus = Vector3(0, 0, 0) + 0.75 * (Vector3(20, 0, 5) - Vector3(0, 0, 0));
  const Vector3 expected = PortalMapping(portal).mappedTip(stylus);
  double tip[3];
  style->GetInstrumentTip(tip);
  EXPECT_LT((Vector3(tip[0], tip[1], tip[2]) - expected).norm(), 1e-9);
  vtkMatrix4x4* matrix = instrument->GetUserMatrix();
  ASSERT_NE(matrix, nullptr);
  EXPECT_NEAR(matrix->GetElement(0, 3), expected.x(), 1e-9);
  EXPECT_NEAR(matrix->GetElement(2, 3), expected.z(), 1e-9);
  EXPECT_EQ(style->GetInstrumentButtons(), 1);
  // The camera is the arthroscope: at its tip, 30 degrees off its shaft.
  double scope[3];
  style->GetScopeTip(scope);
  double eye[3];
  renderer->GetActiveCamera()->GetPosition(eye);
  EXPECT_LT((Vector3(eye[0], eye[1], eye[2]) - Vector3(scope[0], scope[1], scope[2])).norm(), 1e-9);
  // Events: one move per device per update, one press.
  EXPECT_EQ(events.moves[0], 1);
  EXPECT_EQ(events.moves[1], 1);
  EXPECT_EQ(events.presses, 1);
  style->AdvanceTo(0.9);
  EXPECT_EQ(events.presses, 1); // still held: no new press
  style->StopDevices();
  EXPECT_FALSE(style->GetDevicesRunning());

  // A missing file: reported, nothing running.
  style->SetScopeTrajectoryFileName((directory / "missing.json").string().c_str());
  style->GlobalWarningDisplayOff();
  EXPECT_FALSE(style->StartDevices());
  style->GlobalWarningDisplayOn();
  EXPECT_NE(std::string(style->GetLastErrorMessage()).find("missing.json"), std::string::npos)
    << style->GetLastErrorMessage();
  EXPECT_FALSE(style->GetDevicesRunning());
}

TEST(HapticInteractorStyle, TheMouseDrivesTheInstrument)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  vtkNew<vtkHapticInteractorStyle> style;
  interactor->SetInteractorStyle(style);
  style->SetRealTime(false);
  ASSERT_TRUE(style->StartDevices());
  style->AdvanceTo(0.01);
  double before[3];
  style->GetInstrumentTip(before);
  interactor->SetEventInformation(100, 100);
  style->OnLeftButtonDown();
  interactor->SetEventInformation(150, 100); // 50 pixels right: 10 mm
  style->OnMouseMove();
  style->OnLeftButtonUp();
  interactor->SetKeyCode('1');
  style->OnChar();
  style->AdvanceTo(0.02);
  double after[3];
  style->GetInstrumentTip(after);
  EXPECT_NEAR(after[0] - before[0], 10.0, 1e-9);
  EXPECT_NEAR(after[1] - before[1], 0.0, 1e-9);
  EXPECT_EQ(style->GetInstrumentButtons(), 1);
}
