// ThinTissuePrepare: a ready tissue from a thin visual mesh alone (the
// thesis built its collision meshes by hand, 7.2): collision mid-surface
// with radii, simulation hexahedra and the visual-collision binding (5.2),
// saved as one bundle that the simulator and the VTK filters load.
//
//   ThinTissuePrepare VISUAL_MESH -o BUNDLE [--collision-vertices N | --collision-triangles N]
//                     [--hexahedra N] [--collision-output FILE.vtp]
//                     [--hexahedra-output FILE.vtu] [--max-thickness-ratio R] [--repair]
//
// With --repair the visual mesh is repaired first (MeshRepair.h: non-manifold
// vertices split, small holes filled, degenerate and duplicate triangles
// removed, triangles oriented); what changed and where is printed and kept
// in the bundle's metadata under "repair". Without it, a mesh refused for a
// defect that repair fixes gets an error that says so.
//
// Exit codes: 0 done, 1 failed (unreadable mesh, bad input, write error),
// 2 bad command line.
#include "MeshRepair.h"
#include "MeshValidation.h"
#include "ThinTissueAppSupport.h"
#include "ThinTissueError.h"
#include "TissueBundle.h"
#include "vtkThinTissueConversion.h"

#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{

using namespace thintissue::apps;

const char* const Program = "ThinTissuePrepare";

struct Options
{
  std::string visual;
  std::string bundle;
  std::string collisionOutput;
  std::string hexahedraOutput;
  int collisionVertices = 85;
  int collisionTriangles = 0;
  int hexahedra = 76;
  double maximumThicknessRatio = 0.35;
  bool repair = false;
};

void printUsage(std::ostream& out)
{
  out << "usage: ThinTissuePrepare VISUAL_MESH -o BUNDLE [--collision-vertices N] [--hexahedra N]\n"
         "                         [--collision-output FILE.vtp] [--hexahedra-output FILE.vtu]\n"
         "                         [--max-thickness-ratio R] [--repair]\n"
         "\n"
         "Makes a ready tissue from a closed, thin visual surface: a collision mid-surface\n"
         "with per-vertex radii (half the local thickness), hexahedra for the simulation,\n"
         "and the visual-collision binding (thesis 5.2), saved as one bundle file.\n"
         "\n"
         "  VISUAL_MESH                  closed thin surface (OBJ, STL, PLY, OFF, glTF, FBX,\n"
         "                               VTP, VTK, VTU)\n"
         "  -o, --output BUNDLE          the bundle to write\n"
         "  --collision-vertices N       vertices of the collision mesh (default 85)\n"
         "  --collision-triangles N      or the triangles of the collision mesh (at least N)\n"
         "  --hexahedra N                hexahedra of the simulation mesh (default 76)\n"
         "  --collision-output FILE.vtp  also write the collision mesh (with Radius)\n"
         "  --hexahedra-output FILE.vtu  also write the hexahedra\n"
         "  --max-thickness-ratio R      thickness over extent allowed (default 0.35)\n"
         "  --repair                     repair the visual mesh first: split non-manifold\n"
         "                               vertices, fill small holes, remove degenerate and\n"
         "                               duplicate triangles, orient the triangles; prints\n"
         "                               what changed and where, and keeps it in the bundle\n"
         "  --help                       this text\n";
}

bool parsePositive(const std::string& text, int& value)
{
  char* end = nullptr;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || parsed < 1 || parsed > 100000000)
  {
    return false;
  }
  value = static_cast<int>(parsed);
  return true;
}

/// 0: parsed; 2: bad command line; -1: --help printed.
int parseArguments(int argc, char* argv[], Options& options)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--help" || argument == "-h")
    {
      printUsage(std::cout);
      return -1;
    }
    if (argument == "--repair")
    {
      options.repair = true;
      continue;
    }
    const bool takesValue = argument == "-o" || argument == "--output" ||
                            argument == "--collision-vertices" || argument == "--hexahedra" ||
                            argument == "--collision-triangles" ||
                            argument == "--collision-output" || argument == "--hexahedra-output" ||
                            argument == "--max-thickness-ratio";
    if (takesValue && i + 1 >= argc)
    {
      std::cerr << Program << ": " << argument << " expects a value\n";
      return 2;
    }
    if (argument == "-o" || argument == "--output")
    {
      options.bundle = argv[++i];
    }
    else if (argument == "--collision-vertices" || argument == "--hexahedra" ||
             argument == "--collision-triangles")
    {
      int& target = argument == "--hexahedra"             ? options.hexahedra
                    : argument == "--collision-triangles" ? options.collisionTriangles
                                                          : options.collisionVertices;
      if (!parsePositive(argv[++i], target))
      {
        std::cerr << Program << ": " << argument << " expects a positive whole number, not '"
                  << argv[i] << "'\n";
        return 2;
      }
    }
    else if (argument == "--collision-output")
    {
      options.collisionOutput = argv[++i];
    }
    else if (argument == "--hexahedra-output")
    {
      options.hexahedraOutput = argv[++i];
    }
    else if (argument == "--max-thickness-ratio")
    {
      char* end = nullptr;
      options.maximumThicknessRatio = std::strtod(argv[++i], &end);
      if (end == argv[i] || *end != '\0' || !(options.maximumThicknessRatio > 0.0))
      {
        std::cerr << Program << ": --max-thickness-ratio expects a positive number\n";
        return 2;
      }
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
  if (positional.size() != 1 || options.bundle.empty())
  {
    std::cerr << Program << ": expected VISUAL_MESH and -o BUNDLE (--help for usage)\n";
    return 2;
  }
  options.visual = positional[0];
  return 0;
}

int fail(const std::string& message)
{
  std::cerr << Program << ": " << message << "\n";
  return 1;
}

/// What --repair would do to `visual`, as the end of the error message:
/// said only when the repaired mesh would pass the closed-surface checks
/// that refused it, so that the advice is never wrong.
std::string repairAdvice(const thintissue::TriangleMesh& visual)
{
  thintissue::MeshRepairReport report;
  thintissue::MeshValidationReport validation;
  try
  {
    validation =
      thintissue::validateTriangleMesh(thintissue::repairTriangleMesh(visual, {}, &report));
  }
  catch (const thintissue::Error&)
  {
    return {}; // beyond repair: the original message says enough
  }
  if (!report.changed() || !validation.isClosedManifold() || validation.signedVolume <= 0.0)
  {
    return report.openBorders == 0
             ? std::string()
             : " (--repair fills only small holes; this mesh has " +
                 std::to_string(report.openBorders) + " open border" +
                 (report.openBorders == 1 ? "" : "s") + " longer than a hole)";
  }
  std::vector<std::string> actions;
  const auto add = [&actions](int count, const std::string& action)
  {
    if (count > 0)
    {
      actions.push_back(action);
    }
  };
  add(report.nonManifoldVertices + report.nonManifoldEdges, "split non-manifold vertices");
  add(report.filledHoles, "fill small holes");
  add(report.removedDegenerateTriangles, "remove degenerate triangles");
  add(report.removedDuplicateTriangles, "remove duplicate triangles");
  add(report.flippedTriangles, "orient the triangles consistently and outward");
  add(report.mergedCoincidentVertices, "merge coincident vertices");
  std::string text;
  for (std::size_t i = 0; i < actions.size(); ++i)
  {
    text += (i == 0 ? "" : i + 1 == actions.size() ? " and " : ", ") + actions[i];
  }
  return " (run with --repair to " + text + ")";
}

/// Writes --collision-output and --hexahedra-output if asked; returns the
/// file that could not be written ("" when all were).
std::string writeOptionalOutputs(const Options& options, const thintissue::TissueBundle& bundle)
{
  if (!options.collisionOutput.empty())
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(thintissue::toPolyData(bundle.collision));
    writer->SetFileName(options.collisionOutput.c_str());
    if (writer->Write() != 1)
    {
      return options.collisionOutput;
    }
  }
  if (!options.hexahedraOutput.empty())
  {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(thintissue::toUnstructuredGrid(bundle.simulation));
    writer->SetFileName(options.hexahedraOutput.c_str());
    if (writer->Write() != 1)
    {
      return options.hexahedraOutput;
    }
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
  std::string error;
  vtkSmartPointer<vtkPolyData> visualData = readMesh(options.visual, error);
  if (!visualData)
  {
    return fail(error);
  }
  TextProgressBar bar;
  thintissue::TriangleMesh visual;
  try
  {
    visual = thintissue::fromPolyData(visualData, options.visual);
    visual.name = options.visual;
    thintissue::MeshRepairReport repair;
    if (options.repair)
    {
      visual = thintissue::repairTriangleMesh(visual, {}, &repair);
      std::cout << repair.summary() << std::flush;
    }
    thintissue::TissuePreparationSettings settings;
    settings.collision.vertexCount = options.collisionVertices;
    settings.collision.triangleCount = options.collisionTriangles;
    settings.collision.maximumThicknessRatio = options.maximumThicknessRatio;
    settings.hexahedronCount = options.hexahedra;
    thintissue::TissueBundle bundle = thintissue::prepareTissue(visual,
      settings,
      [&bar](double fraction, const char* stage)
      {
        bar.draw(fraction, stage);
        return true;
      });
    bar.finish();
    if (options.repair)
    {
      thintissue::addBundleMetadata(bundle, "repair", repair.toJson());
    }
    thintissue::writeTissueBundle(options.bundle, bundle);
    const std::string unwritten = writeOptionalOutputs(options, bundle);
    if (!unwritten.empty())
    {
      return fail("cannot write '" + unwritten + "'");
    }
    std::cout << bundle.metadata << "\n"
              << "wrote '" << options.bundle << "': " << bundle.collision.vertexCount()
              << " collision vertices, " << bundle.simulation.hexahedronCount() << " hexahedra, "
              << bundle.visual.vertexCount() << " bound visual vertices\n";
  }
  catch (const thintissue::InvalidInputError& e)
  {
    bar.finish();
    const bool read = !visual.triangles.empty();
    return fail(e.what() + (options.repair || !read ? std::string() : repairAdvice(visual)));
  }
  catch (const std::exception& e)
  {
    bar.finish();
    return fail(e.what());
  }
  return 0;
}
