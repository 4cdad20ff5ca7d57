// ThinTissuePrepare: a ready tissue from a thin visual mesh alone (the
// thesis built its collision meshes by hand, 7.2): collision mid-surface
// with radii, simulation hexahedra and the visual-collision binding (5.2),
// saved as one bundle that the simulator and the VTK filters load.
//
//   ThinTissuePrepare VISUAL_MESH -o BUNDLE [--collision-vertices N | --collision-triangles N]
//                     [--hexahedra N] [--collision-output FILE.vtp]
//                     [--hexahedra-output FILE.vtu] [--max-thickness-ratio R] [--repair]
//                     [--units mm|cm|m|um | --scale S] [--minimum-piece-fraction F]
//                     [--bundle-per-piece] [--thicken T]
//
// Units: the mesh is never rescaled (every tolerance is relative to it);
// its units, given or detected from its size (LengthUnits.h), are printed
// and recorded in the bundle. Pieces: each large piece of the visual mesh
// becomes a tissue of its own; fragments (area below F of the largest
// piece's) are dropped with a warning naming each. Several tissues go in
// one bundle file (TissueBundle.h), or with --bundle-per-piece in
// BUNDLE-1.ttbundle, BUNDLE-2.ttbundle, ... (the optional outputs too).
// Each tissue's quality report (TissueQuality.h) is printed, with its
// warnings, and kept in the metadata under "quality".
//
// With --repair the visual mesh is repaired first (MeshRepair.h: non-manifold
// vertices split, small holes filled, degenerate and duplicate triangles
// removed, triangles oriented); what changed and where is printed and kept
// in the bundle's metadata under "repair". Without it, a mesh refused for a
// defect that repair fixes gets an error that says so.
//
// With --thicken T (millimetres) every open piece, a tissue segmented as one
// surface (a cartilage's articular sheet), becomes the closed slab of that
// thickness it stands for (SheetThickening.h), after the repair; what was
// done is printed and kept in the metadata under "thicken".
//
// Exit codes: 0 done, 1 failed (unreadable mesh, bad input, write error),
// 2 bad command line.
#include "LengthUnits.h"
#include "MeshRepair.h"
#include "MeshValidation.h"
#include "SheetThickening.h"
#include "ThinTissueAppSupport.h"
#include "ThinTissueError.h"
#include "TissueBundle.h"
#include "vtkThinTissueConversion.h"

#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
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
  std::optional<thintissue::LengthUnits> units;
  double minimumPieceFraction = 0.05;
  bool bundlePerPiece = false;
  /// --thicken: the thickness (mm) given to open pieces; 0: none.
  double thickness = 0.0;
};

void printUsage(std::ostream& out)
{
  out << "usage: ThinTissuePrepare VISUAL_MESH -o BUNDLE [--collision-vertices N] [--hexahedra N]\n"
         "                         [--collision-output FILE.vtp] [--hexahedra-output FILE.vtu]\n"
         "                         [--max-thickness-ratio R] [--repair]\n"
         "                         [--units mm|cm|m|um | --scale S] [--minimum-piece-fraction F]\n"
         "                         [--bundle-per-piece] [--thicken T]\n"
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
         "  --units mm|cm|m|um           units of VISUAL_MESH (default: detected from its size,\n"
         "                               a tissue of 5 mm to 0.5 m; trying mm, m, cm, um)\n"
         "  --scale S                    or: one unit of VISUAL_MESH is S metres\n"
         "  --minimum-piece-fraction F   pieces smaller than F times the largest piece's area\n"
         "                               are fragments, dropped (default 0.05); each other\n"
         "                               piece is a tissue of its own\n"
         "  --bundle-per-piece           several tissues: one bundle each, BUNDLE-1, BUNDLE-2...\n"
         "                               (default: all in BUNDLE)\n"
         "  --thicken T                  give each open piece (a tissue segmented as one\n"
         "                               surface, such as a cartilage sheet) a thickness of\n"
         "                               T mm: the closed slab with that sheet as mid-surface\n"
         "  --help                       this text\n"
         "\n"
         "Prints the units, the dropped fragments and each tissue's quality: the distance\n"
         "between the visual and the thick collision surface relative to the local\n"
         "thickness, visual vertices per collision triangle, the worst binding region, and\n"
         "a warning when the collision mesh represents the tissue poorly.\n";
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

bool parsePositiveNumber(const std::string& text, double& value)
{
  char* end = nullptr;
  const double parsed = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(parsed > 0.0) || !std::isfinite(parsed))
  {
    return false;
  }
  value = parsed;
  return true;
}

/// Options that take a value; returns false with the message printed.
bool parseValue(const std::string& option, const std::string& value, Options& options)
{
  auto refuse = [&](const std::string& expected)
  {
    std::cerr << Program << ": " << option << " expects " << expected << ", not '" << value
              << "'\n";
    return false;
  };
  if (option == "-o" || option == "--output")
  {
    options.bundle = value;
  }
  else if (option == "--collision-vertices" || option == "--hexahedra" ||
           option == "--collision-triangles")
  {
    int& target = option == "--hexahedra"             ? options.hexahedra
                  : option == "--collision-triangles" ? options.collisionTriangles
                                                      : options.collisionVertices;
    return parsePositive(value, target) || refuse("a positive whole number");
  }
  else if (option == "--collision-output")
  {
    options.collisionOutput = value;
  }
  else if (option == "--hexahedra-output")
  {
    options.hexahedraOutput = value;
  }
  else if (option == "--max-thickness-ratio")
  {
    return parsePositiveNumber(value, options.maximumThicknessRatio) || refuse("a positive number");
  }
  else if (option == "--units")
  {
    options.units = thintissue::lengthUnitsNamed(value);
    return options.units.has_value() || refuse("mm, cm, m or um");
  }
  else if (option == "--scale")
  {
    double scale = 0.0;
    if (!parsePositiveNumber(value, scale))
    {
      return refuse("a positive number of metres per unit");
    }
    options.units = thintissue::lengthUnitsOfScale(scale);
  }
  else if (option == "--thicken")
  {
    return parsePositiveNumber(value, options.thickness) || refuse("a positive thickness in mm");
  }
  else if (option == "--minimum-piece-fraction")
  {
    double& fraction = options.minimumPieceFraction;
    char* end = nullptr;
    fraction = std::strtod(value.c_str(), &end);
    return (end != value.c_str() && *end == '\0' && fraction >= 0.0 && fraction <= 1.0) ||
           refuse("a fraction from 0 to 1");
  }
  return true;
}

/// 0: parsed; 2: bad command line; -1: --help printed.
int parseArguments(int argc, char* argv[], Options& options)
{
  static const std::vector<std::string> valued = { "-o",
    "--output",
    "--collision-vertices",
    "--collision-triangles",
    "--hexahedra",
    "--collision-output",
    "--hexahedra-output",
    "--max-thickness-ratio",
    "--units",
    "--scale",
    "--minimum-piece-fraction",
    "--thicken" };
  std::vector<std::string> positional;
  bool unitsGiven = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--help" || argument == "-h")
    {
      printUsage(std::cout);
      return -1;
    }
    if (argument == "--repair" || argument == "--bundle-per-piece")
    {
      (argument == "--repair" ? options.repair : options.bundlePerPiece) = true;
    }
    else if (std::find(valued.begin(), valued.end(), argument) != valued.end())
    {
      if (i + 1 >= argc)
      {
        std::cerr << Program << ": " << argument << " expects a value\n";
        return 2;
      }
      if ((argument == "--units" || argument == "--scale") && std::exchange(unitsGiven, true))
      {
        std::cerr << Program << ": give the units once (--units or --scale)\n";
        return 2;
      }
      if (!parseValue(argument, argv[++i], options))
      {
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
                 (report.openBorders == 1 ? "" : "s") +
                 " longer than a hole; a tissue segmented as one surface gets a thickness "
                 "with --thicken T)";
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

/// `path` with "-N" before its extension: "knee.ttbundle" -> "knee-2.ttbundle".
std::string numbered(const std::string& path, std::size_t number)
{
  const std::filesystem::path p(path);
  return (
    p.parent_path() / (p.stem().string() + "-" + std::to_string(number) + p.extension().string()))
    .string();
}

/// Writes --collision-output and --hexahedra-output if asked, numbered when
/// there are several tissues; returns the file that could not be written
/// ("" when all were).
std::string writeOptionalOutputs(const Options& options,
  const thintissue::TissueBundle& bundle,
  std::size_t number,
  std::size_t count)
{
  auto name = [&](const std::string& path) { return count > 1 ? numbered(path, number) : path; };
  if (!options.collisionOutput.empty())
  {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(thintissue::toPolyData(bundle.collision));
    writer->SetFileName(name(options.collisionOutput).c_str());
    if (writer->Write() != 1)
    {
      return name(options.collisionOutput);
    }
  }
  if (!options.hexahedraOutput.empty())
  {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(thintissue::toUnstructuredGrid(bundle.simulation));
    writer->SetFileName(name(options.hexahedraOutput).c_str());
    if (writer->Write() != 1)
    {
      return name(options.hexahedraOutput);
    }
  }
  return {};
}

thintissue::TissuePreparationSettings preparationSettings(const Options& options)
{
  thintissue::TissuePreparationSettings settings;
  settings.collision.vertexCount = options.collisionVertices;
  settings.collision.triangleCount = options.collisionTriangles;
  settings.collision.maximumThicknessRatio = options.maximumThicknessRatio;
  settings.hexahedronCount = options.hexahedra;
  settings.units = options.units;
  settings.minimumPieceFraction = options.minimumPieceFraction;
  return settings;
}

std::string tissueCounts(const thintissue::TissueBundle& bundle)
{
  return std::to_string(bundle.collision.vertexCount()) + " collision vertices, " +
         std::to_string(bundle.simulation.hexahedronCount()) + " hexahedra, " +
         std::to_string(bundle.visual.vertexCount()) + " bound visual vertices";
}

/// Units, fragments, each tissue's metadata and quality, on the console.
void printReport(const thintissue::PreparedTissues& prepared)
{
  std::cout << "units: " << prepared.units.description() << " ("
            << (prepared.unitsDetected ? "detected from the size: " + prepared.unitsReason +
                                           "; --units or --scale to say otherwise"
                                       : std::string("given"))
            << ")\n";
  for (const std::string& warning : prepared.warnings)
  {
    std::cout << "warning: " << warning << "\n";
  }
  const std::size_t count = prepared.tissues.size();
  for (std::size_t i = 0; i < count; ++i)
  {
    const thintissue::TissueBundle& bundle = prepared.tissues[i];
    std::cout << bundle.metadata << "\n";
    if (count > 1)
    {
      std::cout << "tissue " << i + 1 << " of " << count << " (" << bundle.visual.name << "):\n";
    }
    std::cout << bundle.quality.summary(prepared.units.name);
  }
}

/// The bundle file(s); returns the file that could not be written.
std::string writeTissues(const Options& options, const thintissue::PreparedTissues& prepared)
{
  const auto& tissues = prepared.tissues;
  if (options.bundlePerPiece && tissues.size() > 1)
  {
    for (std::size_t i = 0; i < tissues.size(); ++i)
    {
      const std::string path = numbered(options.bundle, i + 1);
      thintissue::writeTissueBundle(path, tissues[i]);
      std::cout << "wrote '" << path << "': " << tissueCounts(tissues[i]) << "\n";
    }
  }
  else
  {
    thintissue::writeTissueBundles(options.bundle, tissues);
    std::cout << "wrote '" << options.bundle << "': ";
    for (std::size_t i = 0; i < tissues.size(); ++i)
    {
      std::cout << (tissues.size() == 1 ? ""
                     : i == 0           ? std::to_string(tissues.size()) + " tissues: 1: "
                                        : "; " + std::to_string(i + 1) + ": ")
                << tissueCounts(tissues[i]);
    }
    std::cout << "\n";
  }
  for (std::size_t i = 0; i < tissues.size(); ++i)
  {
    const std::string unwritten = writeOptionalOutputs(options, tissues[i], i + 1, tissues.size());
    if (!unwritten.empty())
    {
      return unwritten;
    }
  }
  return {};
}

/// --thicken: the open pieces given the thickness (mm, in the mesh's units,
/// given or detected as the preparation will).
thintissue::SheetThickeningReport thicken(const Options& options, thintissue::TriangleMesh& visual)
{
  const thintissue::LengthUnits units =
    options.units ? *options.units
                  : thintissue::detectLengthUnits(visual.boundingBox().sizes().maxCoeff()).units;
  thintissue::SheetThickeningReport report;
  visual =
    thintissue::thickenOpenSheets(visual, options.thickness * 0.001 / units.metresPerUnit, &report);
  std::cout << report.summary(units.name.empty() ? "units" : units.name) << std::flush;
  return report;
}

/// Repair (if asked), thickening (if asked), preparation of every piece,
/// report and files.
int prepareAndWrite(const Options& options, thintissue::TriangleMesh& visual)
{
  thintissue::MeshRepairReport repair;
  if (options.repair)
  {
    visual = thintissue::repairTriangleMesh(visual, {}, &repair);
    std::cout << repair.summary() << std::flush;
  }
  thintissue::SheetThickeningReport thickening;
  if (options.thickness > 0.0)
  {
    thickening = thicken(options, visual);
  }
  TextProgressBar bar;
  thintissue::PreparedTissues prepared;
  try
  {
    prepared = thintissue::prepareTissues(visual,
      preparationSettings(options),
      [&bar](double fraction, const char* stage)
      {
        bar.draw(fraction, stage);
        return true;
      });
  }
  catch (...)
  {
    bar.finish();
    throw;
  }
  bar.finish();
  for (thintissue::TissueBundle& bundle : prepared.tissues)
  {
    if (options.repair)
    {
      thintissue::addBundleMetadata(bundle, "repair", repair.toJson());
    }
    if (options.thickness > 0.0)
    {
      thintissue::addBundleMetadata(bundle, "thicken", thickening.toJson());
    }
  }
  printReport(prepared);
  const std::string unwritten = writeTissues(options, prepared);
  return unwritten.empty() ? 0 : fail("cannot write '" + unwritten + "'");
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
  thintissue::TriangleMesh visual;
  try
  {
    visual = thintissue::fromPolyData(visualData, options.visual);
    visual.name = options.visual;
    return prepareAndWrite(options, visual);
  }
  catch (const thintissue::InvalidInputError& e)
  {
    const bool read = !visual.triangles.empty();
    const bool advise = read && !options.repair && options.thickness == 0.0;
    return fail(e.what() + (advise ? repairAdvice(visual) : std::string()));
  }
  catch (const std::exception& e)
  {
    return fail(e.what());
  }
}
