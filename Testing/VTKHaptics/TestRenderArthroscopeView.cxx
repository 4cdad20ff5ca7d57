// The arthroscope's view in the knee scene (thesis 4.1, fig. 4-2), driven
// by a scripted pair of devices through vtkHapticInteractorStyle on its
// manual clock: the scope enters by the anterolateral portal and looks at
// the medial compartment; the probe hook enters by the anteromedial portal
// and reaches toward the medial meniscus. TestRenderArthroscopeView: at
// 0.3 s (the meniscus's anterior body and the plateau's cartilage in view,
// the hook not yet); TestRenderArthroscopeViewLater (THINTISSUE_LATER): at
// 1 s (the hook over the meniscus, the view turned with the scope).
#include "ScriptedHapticDevice.h"
#include "ThinTissueImageTest.h"
#include "ThinTissueTestSupport.h"
#include "vtkHapticInteractorStyle.h"
#include "vtkKneeSceneSource.h"
#include "vtkSurgicalInstrumentSource.h"

#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkRenderWindowInteractor.h>

using namespace thintissue;

namespace
{

void addSurface(vtkRenderer* renderer,
  vtkMultiBlockDataSet* scene,
  unsigned block,
  const std::array<double, 3>& colour)
{
  auto* meshes = vtkMultiBlockDataSet::SafeDownCast(scene->GetBlock(block));
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(vtkPolyData::SafeDownCast(meshes->GetBlock(0)));
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  actor->GetProperty()->SetSpecular(0.3);
  renderer->AddActor(actor);
}

/// The stylus moves from `from` to `to` over one second, held as `held`
/// and turning slowly about its axis.
std::string writeTrajectory(const std::string& name,
  const Vector3& from,
  const Vector3& to,
  const Eigen::Quaterniond& held)
{
  HapticTrajectory t;
  t.name = name;
  for (int k = 0; k <= 20; ++k)
  {
    const double s = 0.05 * k;
    t.samples.push_back(HapticSample{ s,
      from + s * (to - from),
      held * Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * s, Vector3::UnitZ())),
      0u });
  }
  const std::string path = (thintissue::testing::temporaryDirectory() / (name + ".json")).string();
  writeHapticTrajectory(path, t);
  return path;
}

} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkKneeSceneSource> knee;
  knee->SetJointGap(10.0);
  knee->Update();
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.05, 0.03, 0.03);
  addSurface(renderer, knee->GetOutput(), 0, { 0.93, 0.85, 0.55 }); // tibia
  addSurface(renderer, knee->GetOutput(), 1, { 0.93, 0.85, 0.55 }); // femur
  addSurface(renderer, knee->GetOutput(), 2, { 0.80, 0.85, 0.95 }); // tibial cartilage
  addSurface(renderer, knee->GetOutput(), 3, { 0.90, 0.55, 0.55 }); // ACL
  addSurface(renderer, knee->GetOutput(), 4, { 0.80, 0.45, 0.50 }); // PCL
  addSurface(renderer, knee->GetOutput(), 5, { 0.97, 0.93, 0.88 }); // medial meniscus

  vtkNew<vtkSurgicalInstrumentSource> hook;
  hook->SetInstrumentType(vtkSurgicalInstrumentSource::ProbeHook);
  vtkNew<vtkPolyDataMapper> hookMapper;
  hookMapper->SetInputConnection(hook->GetOutputPort());
  vtkNew<vtkActor> instrument;
  instrument->SetMapper(hookMapper);
  instrument->GetProperty()->SetColor(0.75, 0.78, 0.82);
  instrument->GetProperty()->SetSpecular(0.6);
  renderer->AddActor(instrument);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  vtkNew<vtkHapticInteractorStyle> style;
  interactor->SetInteractorStyle(style);
  style->SetDefaultRenderer(renderer);
  style->SetInstrumentProp(instrument);
  style->SetBackendToScripted();
  style->SetRealTime(false);
  // Anterolateral (scope) and anteromedial (instrument) portals, aimed at
  // the medial compartment.
  // The scope held with its lens (the stylus's up) turned down, so that its
  // 30 degrees look down onto the plateau.
  style->SetScopePortal(5.0, 34.0, 9.0);
  style->SetScopeInward(-25.0, -34.0, -5.0);
  style->SetInstrumentPortal(-40.0, 28.0, 9.0);
  style->SetInstrumentInward(15.0, -28.0, -5.0);
  style->SetScopeTrajectoryFileName(writeTrajectory("scope",
    Vector3(0.0, 0.0, 0.0),
    Vector3(-2.0, 0.0, 1.0),
    Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2.0, Vector3::UnitX())))
                                      .c_str());
  style->SetInstrumentTrajectoryFileName(writeTrajectory(
    "hook", Vector3(-8.0, 8.0, 0.0), Vector3(8.0, -6.0, -3.0), Eigen::Quaterniond::Identity())
                                           .c_str());
  if (!style->StartDevices())
  {
    std::cerr << style->GetLastErrorMessage() << "\n";
    return EXIT_FAILURE;
  }
#ifdef THINTISSUE_LATER
  style->AdvanceTo(1.0);
#else
  style->AdvanceTo(0.3);
#endif
  return thintissue::testing::compareWithBaseline(argc, argv, window);
}
