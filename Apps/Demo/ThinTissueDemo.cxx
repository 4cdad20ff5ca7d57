// ThinTissueDemo: by default the simulator's knee scene (medial meniscus,
// tibia, femur, cartilage, cruciate ligaments, a probe hook) seen through a
// 30-degree arthroscope; or a tissue surface loaded from a file. Prints the
// tissue's validation report and timings, and renders it -- in a window when
// there is a display, otherwise offscreen into a PNG.
//
//   ThinTissueDemo [mesh-file] [--offscreen] [--screenshot out.png]
//                  [--timings out.json] [--size WxH]
#include "MeniscusModel.h"
#include "SurgicalInstruments.h"
#include "VirtualDisplay.h"
#include "vtkKneeSceneSource.h"
#include "vtkMeniscusSource.h"
#include "vtkSurgicalInstrumentSource.h"
#include "vtkThinTissueMeshReader.h"
#include "vtkTriangleMeshValidationFilter.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{

struct Options
{
  std::string meshFile;
  std::string screenshot;
  std::string timings;
  bool offscreen = false;
  int width = 1024;
  int height = 768;
};

void printUsage()
{
  std::cout << "usage: ThinTissueDemo [mesh-file] [--offscreen] [--screenshot out.png]\n"
               "                      [--timings out.json] [--size WxH]\n"
               "Shows the knee scene through a 30-degree arthroscope, or loads a mesh (OBJ,\n"
               "STL, PLY, OFF, glTF, FBX, VTP, VTK, VTU), prints the tissue's validation\n"
               "report and renders it.\n"
               "Without a display it renders offscreen and writes a PNG.\n";
}

bool parseArguments(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    const bool hasValue = i + 1 < argc;
    if (argument == "--help" || argument == "-h")
    {
      printUsage();
      std::exit(0);
    }
    else if (argument == "--offscreen")
    {
      options.offscreen = true;
    }
    else if (argument == "--screenshot" && hasValue)
    {
      options.screenshot = argv[++i];
    }
    else if (argument == "--timings" && hasValue)
    {
      options.timings = argv[++i];
    }
    else if (argument == "--size" && hasValue)
    {
      if (std::sscanf(argv[++i], "%dx%d", &options.width, &options.height) != 2 ||
          options.width < 16 || options.height < 16)
      {
        std::cerr << "ThinTissueDemo: --size expects WxH, e.g. 1024x768\n";
        return false;
      }
    }
    else if (!argument.empty() && argument[0] != '-' && options.meshFile.empty())
    {
      options.meshFile = argument;
    }
    else
    {
      std::cerr << "ThinTissueDemo: unknown or incomplete argument '" << argument << "'\n";
      printUsage();
      return false;
    }
  }
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || display[0] == '\0')
  {
    options.offscreen = true;
  }
  if (options.offscreen && options.screenshot.empty())
  {
    options.screenshot = "thintissue-demo.png";
  }
  if (!options.screenshot.empty() && options.timings.empty())
  {
    options.timings = options.screenshot.substr(0, options.screenshot.rfind('.')) + "-timings.json";
  }
  return true;
}

/// An opaque surface actor with a soft specular highlight.
vtkSmartPointer<vtkActor> makeSurfaceActor(vtkPolyData* surface, double r, double g, double b)
{
  vtkNew<vtkPolyDataNormals> normals; // shading only: sharp edges split
  normals->SetInputData(surface);
  normals->SetFeatureAngle(60.0);
  normals->ConsistencyOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetSpecular(0.35);
  actor->GetProperty()->SetSpecularPower(25.0);
  return actor;
}

/// The knee surroundings (everything but the meniscus) and a probe hook
/// touching the meniscus's inner edge, into `renderer`; the camera is a
/// 30-degree arthroscope in the anterolateral portal looking at the medial
/// compartment.
void addKneeSurroundings(vtkRenderer* renderer)
{
  vtkNew<vtkKneeSceneSource> knee;
  knee->Update();
  vtkMultiBlockDataSet* scene = knee->GetOutput();
  const double colours[5][3] = { { 0.93, 0.85, 0.62 },
    { 0.93, 0.85, 0.62 },
    { 0.82, 0.86, 0.95 },
    { 0.92, 0.62, 0.60 },
    { 0.86, 0.55, 0.56 } };
  for (unsigned int b = 0; b < 5; ++b) // tibia, femur, cartilage, ACL, PCL
  {
    auto* meshes = vtkMultiBlockDataSet::SafeDownCast(scene->GetBlock(b));
    renderer->AddActor(makeSurfaceActor(
      vtkPolyData::SafeDownCast(meshes->GetBlock(0)), colours[b][0], colours[b][1], colours[b][2]));
  }

  // Probe hook from the anteromedial portal, hook resting on the inner edge.
  const auto solid = thintissue::makeMeniscusSolid(thintissue::MeniscusParameters{});
  const thintissue::Vector3 tip = solid.point(thintissue::ParameterPoint(0.55, 0.15, 1.0));
  const thintissue::Vector3 portal(-40.0, 45.0, 22.0);
  const thintissue::Vector3 handle = (portal - tip).normalized();
  const thintissue::Vector3 hook =
    (-thintissue::Vector3::UnitZ() + thintissue::Vector3::UnitZ().dot(handle) * handle)
      .normalized();
  vtkNew<vtkMatrix4x4> pose;
  for (int row = 0; row < 3; ++row)
  {
    pose->SetElement(row, 0, hook[row]);
    pose->SetElement(row, 1, handle.cross(hook)[row]);
    pose->SetElement(row, 2, handle[row]);
    pose->SetElement(row, 3, tip[row]);
  }
  vtkNew<vtkSurgicalInstrumentSource> probe;
  probe->SetInstrumentType(vtkSurgicalInstrumentSource::ProbeHook);
  probe->Update();
  auto probeActor = makeSurfaceActor(probe->GetOutput(0), 0.78, 0.80, 0.84);
  probeActor->SetUserMatrix(pose);
  renderer->AddActor(probeActor);

  // The arthroscope: 30-degree optics turned to look down at the meniscus.
  thintissue::ArthroscopeCamera scope = thintissue::defaultArthroscopeCamera();
  scope.tip = thintissue::Vector3(-6.0, 22.0, 9.0);
  const thintissue::Vector3 aim(-24.0, -6.0, 11.0);
  scope.handleAxis = (scope.tip - aim).normalized();
  scope.imageUp = thintissue::Vector3::UnitZ();
  scope.opticsRotationDegrees = 180.0;
  const thintissue::Vector3 focal = scope.focalPoint(25.0);
  const thintissue::Vector3 up = scope.viewUp();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(scope.tip.data());
  camera->SetFocalPoint(focal.data());
  camera->SetViewUp(up.data());
  camera->SetViewAngle(75.0);
  camera->SetClippingRange(scope.nearClipDistance, scope.farClipDistance);
}

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!parseArguments(argc, argv, options))
  {
    return 2;
  }
  if (!thintissue::apps::haveDisplayOrRerun(argc, argv, "ThinTissueDemo"))
  {
    return 3;
  }

  // Load.
  auto start = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkAlgorithm> source;
  std::string meshLabel;
  const bool kneeScene = options.meshFile.empty();
  if (kneeScene)
  {
    source = vtkSmartPointer<vtkMeniscusSource>::New();
    meshLabel = "knee scene: medial meniscus";
  }
  else
  {
    auto reader = vtkSmartPointer<vtkThinTissueMeshReader>::New();
    reader->SetFileName(options.meshFile.c_str());
    source = reader;
    meshLabel = options.meshFile;
  }
  vtkNew<vtkTriangleMeshValidationFilter> validation;
  validation->SetInputConnection(source->GetOutputPort());
  source->Update();
  const double loadMilliseconds = millisecondsSince(start);
  if (auto* reader = vtkThinTissueMeshReader::SafeDownCast(source))
  {
    if (reader->GetLastErrorMessage()[0] != '\0')
    {
      std::cerr << "ThinTissueDemo: " << reader->GetLastErrorMessage() << "\n";
      return 1;
    }
  }

  // Validate.
  start = std::chrono::steady_clock::now();
  validation->Update();
  const double validateMilliseconds = millisecondsSince(start);
  vtkPolyData* surface = validation->GetOutput();
  std::cout << "ThinTissue demo: " << meshLabel << "\n" << validation->GetReport() << "\n";

  // Render.
  start = std::chrono::steady_clock::now();
  // Shading normals for the picture only: sharp edges split, input untouched.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surface);
  normals->SetFeatureAngle(40.0);
  normals->SplittingOn();
  normals->ConsistencyOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.93, 0.62, 0.58); // soft-tissue pink
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20.0);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.55, 0.30, 0.28);
  if (validation->GetSignedVolume() < 0.0)
  {
    actor->GetProperty()->BackfaceCullingOff(); // inward-facing files still show
  }

  std::ostringstream caption;
  caption << meshLabel << "\n"
          << surface->GetNumberOfPoints() << " vertices, " << surface->GetNumberOfPolys()
          << " triangles\n"
          << (validation->GetClosedOutwardSingleSurface()
                 ? "closed outward 2-manifold"
                 : (validation->GetClosedManifold() ? "closed 2-manifold (see report)"
                                                    : "NOT a closed 2-manifold (see report)"));
  vtkNew<vtkTextActor> text;
  text->SetInput(caption.str().c_str());
  text->GetTextProperty()->SetFontSize(16);
  text->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  text->SetDisplayPosition(12, 12);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->AddViewProp(text);
  renderer->GradientBackgroundOn();
  if (kneeScene)
  {
    actor->GetProperty()->SetColor(0.97, 0.95, 0.92); // meniscus white
    actor->GetProperty()->EdgeVisibilityOff();
    addKneeSurroundings(renderer);
    renderer->SetBackground(0.25, 0.08, 0.07); // synovial red-brown
    renderer->SetBackground2(0.45, 0.20, 0.16);
  }
  else
  {
    renderer->SetBackground(0.10, 0.12, 0.16);
    renderer->SetBackground2(0.30, 0.34, 0.42);
    renderer->GetActiveCamera()->Elevation(-55.0);
    renderer->GetActiveCamera()->Azimuth(25.0);
    renderer->ResetCamera();
    renderer->GetActiveCamera()->Zoom(1.3);
  }

  vtkNew<vtkRenderWindow> window;
  window->SetSize(options.width, options.height);
  window->SetWindowName("ThinTissue");
  window->AddRenderer(renderer);
  window->SetOffScreenRendering(options.offscreen ? 1 : 0);
  window->Render();
  const double firstFrameMilliseconds = millisecondsSince(start);

  std::cout << "timings: load " << loadMilliseconds << " ms, validate " << validateMilliseconds
            << " ms, first frame " << firstFrameMilliseconds << " ms\n";
  if (!options.screenshot.empty())
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(options.screenshot.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    std::cout << "picture written to " << options.screenshot << "\n";
  }
  if (!options.timings.empty())
  {
    const nlohmann::ordered_json timings = { { "mesh", meshLabel },
      { "vertices", surface->GetNumberOfPoints() },
      { "triangles", surface->GetNumberOfPolys() },
      { "load_ms", loadMilliseconds },
      { "validate_ms", validateMilliseconds },
      { "first_frame_ms", firstFrameMilliseconds } };
    std::ofstream(options.timings) << timings.dump(2) << "\n";
    std::cout << "timings written to " << options.timings << "\n";
  }
  if (!options.offscreen)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Initialize();
    interactor->Start();
  }
  return 0;
}
