// ThinTissueBind: the pre-processing step of thesis 5.2 from the command
// line. Binds a closed visual surface to its collision mid-surface (with a
// per-point radius array) and writes the re-meshed visual surface with the
// binding arrays (and, optionally, the geodesic paths) as VTK XML polydata.
//
//   ThinTissueBind VISUAL_MESH COLLISION_MESH OUTPUT.vtp [--paths PATHS.vtp]
//                  [--cache FILE] [--radius-array NAME] [--serial]
//
// Exit codes: 0 done, 1 failed (unreadable mesh, bad input, write error),
// 2 bad command line.
#include "ThinTissueAppSupport.h"
#include "vtkThinTissueMeshReader.h"
#include "vtkVisualCollisionBindingFilter.h"

#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

namespace
{

using namespace thintissue::apps;

const char* const Program = "ThinTissueBind";

struct Options
{
  std::string visual;
  std::string collision;
  std::string output;
  std::string paths;
  std::string cache;
  std::string radiusArray = "Radius";
  bool serial = false;
};

void printUsage(std::ostream& out)
{
  out << "usage: ThinTissueBind VISUAL_MESH COLLISION_MESH OUTPUT.vtp [--paths PATHS.vtp]\n"
         "                      [--cache FILE] [--radius-array NAME] [--serial]\n"
         "\n"
         "Binds every vertex of the closed visual surface to the collision mid-surface\n"
         "(thesis 5.2): geodesic paths between paired vertices, the visual mesh\n"
         "re-meshed along them, and per-vertex binding arrays. Writes the re-meshed\n"
         "visual surface (point arrays BindingKind, BindingElement, BindingSide,\n"
         "BindingParameters; cell arrays CollisionTriangle, CollisionSide) as VTK XML\n"
         "polydata.\n"
         "\n"
         "  VISUAL_MESH          closed, thin visual surface (OBJ, STL, PLY, OFF, glTF,\n"
         "                       FBX, VTP, VTK, VTU)\n"
         "  COLLISION_MESH       collision mid-surface with a per-point radius array\n"
         "                       (VTP, VTK or VTU keep point arrays)\n"
         "  OUTPUT.vtp           the bound visual surface\n"
         "  --paths PATHS.vtp    also write the geodesic paths (one polyline per path)\n"
         "  --cache FILE         binding cache: read when current, else built and written\n"
         "  --radius-array NAME  name of the radius array (default Radius)\n"
         "  --serial             compute the paths on one thread\n"
         "  --help               this text\n";
}

/// 0: parsed; 2: bad command line; -1: --help printed.
int parseArguments(int argc, char* argv[], Options& options)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    const bool hasValue = i + 1 < argc;
    if (argument == "--help" || argument == "-h")
    {
      printUsage(std::cout);
      return -1;
    }
    if ((argument == "--paths" || argument == "--cache" || argument == "--radius-array") &&
        !hasValue)
    {
      std::cerr << Program << ": " << argument << " expects a value\n";
      return 2;
    }
    if (argument == "--paths")
    {
      options.paths = argv[++i];
    }
    else if (argument == "--cache")
    {
      options.cache = argv[++i];
    }
    else if (argument == "--radius-array")
    {
      options.radiusArray = argv[++i];
      if (options.radiusArray.empty())
      {
        std::cerr << Program << ": --radius-array expects a name\n";
        return 2;
      }
    }
    else if (argument == "--serial")
    {
      options.serial = true;
    }
    else if (argument.size() > 1 && argument[0] == '-')
    {
      std::cerr << Program << ": unknown option '" << argument << "'\n";
      return 2;
    }
    else
    {
      positional.push_back(argument);
    }
  }
  if (positional.size() != 3)
  {
    std::cerr << Program << ": expected VISUAL_MESH COLLISION_MESH OUTPUT.vtp, got "
              << positional.size() << " file name" << (positional.size() == 1 ? "" : "s")
              << " (--help for usage)\n";
    return 2;
  }
  options.visual = positional[0];
  options.collision = positional[1];
  options.output = positional[2];
  if (!options.paths.empty() && options.paths == options.output)
  {
    std::cerr << Program << ": --paths must name another file than OUTPUT.vtp\n";
    return 2;
  }
  return 0;
}

int fail(const std::string& message)
{
  std::cerr << Program << ": " << message << "\n";
  return 1;
}

/// Writes `data` to `fileName` + ".writing"; empty string on success.
std::string writeTemporary(vtkPolyData* data, const std::string& fileName)
{
  const std::string temporary = fileName + ".writing";
  vtkNew<vtkXMLPolyDataWriter> writer;
  vtkNew<MessageCollector> messages;
  collectMessages(writer, messages);
  vtkNew<MessageCollector> pipelineMessages;
  collectMessages(writer->GetExecutive(), pipelineMessages);
  writer->SetInputData(data);
  writer->SetFileName(temporary.c_str());
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1 || !messages->errors.empty())
  {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    std::string why = messages->errors.empty() ? "write failed" : messages->errors.front();
    // VTK's messages carry the source location first; keep the reason.
    const std::size_t cut = why.find("): ");
    if (cut != std::string::npos)
    {
      why = why.substr(cut + 3);
    }
    while (!why.empty() && (why.back() == '\n' || why.back() == ' '))
    {
      why.pop_back();
    }
    return "cannot write '" + fileName + "': " + why;
  }
  return {};
}

} // namespace

int main(int argc, char* argv[])
{
  Options options;
  const int parsed = parseArguments(argc, argv, options);
  if (parsed != 0)
  {
    return parsed < 0 ? 0 : parsed;
  }

  // Fail before the work when an output cannot be written.
  for (const std::string& output : { options.output, options.paths })
  {
    if (output.empty())
    {
      continue;
    }
    const std::filesystem::path directory =
      std::filesystem::absolute(std::filesystem::path(output)).parent_path();
    std::error_code status;
    if (!std::filesystem::is_directory(directory, status))
    {
      return fail("cannot write '" + output + "': no directory '" + directory.string() + "'");
    }
    if (std::filesystem::is_directory(output, status))
    {
      return fail("cannot write '" + output + "': it is a directory");
    }
  }

  std::string error;
  vtkSmartPointer<vtkPolyData> visual = readMesh(options.visual, error);
  if (visual == nullptr)
  {
    return fail(error);
  }
  vtkSmartPointer<vtkPolyData> collision = readMesh(options.collision, error);
  if (collision == nullptr)
  {
    return fail(error);
  }
  if (collision->GetPointData()->GetArray(options.radiusArray.c_str()) == nullptr)
  {
    return fail("collision mesh '" + options.collision + "' has no point array '" +
                options.radiusArray +
                "' (the collision radii; save it as VTP, VTK or VTU to keep point arrays, or "
                "name the array with --radius-array)");
  }
  std::cout << "visual mesh '" << options.visual << "': " << visual->GetNumberOfPoints()
            << " vertices, " << visual->GetNumberOfPolys() << " triangles\n"
            << "collision mesh '" << options.collision << "': " << collision->GetNumberOfPoints()
            << " vertices, " << collision->GetNumberOfPolys() << " triangles\n"
            << std::flush;

  vtkNew<vtkVisualCollisionBindingFilter> binding;
  binding->SetInputData(0, visual);
  binding->SetCollisionData(collision);
  binding->SetRadiusArrayName(options.radiusArray.c_str());
  binding->SetParallel(!options.serial);
  if (!options.cache.empty())
  {
    binding->SetCacheFileName(options.cache.c_str());
  }
  vtkNew<MessageCollector> messages;
  collectMessages(binding, messages);
  vtkNew<MessageCollector> pipelineMessages;
  collectMessages(binding->GetExecutive(), pipelineMessages);
  vtkNew<ProgressBarObserver> progress;
  binding->AddObserver(vtkCommand::ProgressEvent, progress);
  binding->Update();
  progress->finish();
  if (binding->GetLastErrorMessage()[0] != '\0')
  {
    return fail(binding->GetLastErrorMessage());
  }
  if (!messages->errors.empty())
  {
    return fail(messages->errors.front());
  }
  if (!options.cache.empty())
  {
    std::cout << "binding cache '" << options.cache << "': ";
    if (binding->GetCacheWasRebuilt())
    {
      std::cout << "built and written (" << binding->GetLastCacheMessage() << ")\n";
    }
    else
    {
      std::cout << "current, loaded\n";
    }
  }
  vtkPolyData* bound = binding->GetVisualOutput();
  vtkPolyData* paths = binding->GetPathsOutput();
  std::cout << "bound visual mesh: " << bound->GetNumberOfPoints() << " vertices, "
            << bound->GetNumberOfPolys() << " triangles; " << paths->GetNumberOfLines()
            << " geodesic paths\n";

  // Both files are written under temporary names first and renamed only
  // when both are complete: a failure never leaves a half-written file.
  std::vector<std::pair<vtkPolyData*, std::string>> files = { { bound, options.output } };
  if (!options.paths.empty())
  {
    files.emplace_back(paths, options.paths);
  }
  for (std::size_t f = 0; f < files.size(); ++f)
  {
    error = writeTemporary(files[f].first, files[f].second);
    if (!error.empty())
    {
      for (std::size_t g = 0; g < f; ++g)
      {
        std::error_code ignored;
        std::filesystem::remove(files[g].second + ".writing", ignored);
      }
      return fail(error);
    }
  }
  for (const auto& file : files)
  {
    std::error_code renameError;
    std::filesystem::rename(file.second + ".writing", file.second, renameError);
    if (renameError)
    {
      std::error_code ignored;
      std::filesystem::remove(file.second + ".writing", ignored);
      return fail("cannot write '" + file.second + "': " + renameError.message());
    }
    std::cout << "wrote '" << file.second << "'\n";
  }
  return 0;
}
