// The length unit of a mesh file: metres per unit of its coordinates.
//
// Mesh files carry no unit (STL, OBJ, PLY, VTP have none); segmentations
// come in metres (OpenSim models), millimetres (DICOM, most VTK pipelines),
// centimetres or micrometres (microscopy). ThinTissue never rescales a mesh:
// every tolerance of the preparation is relative to the mesh's own size, so
// the unit only has to be known, recorded with the tissue (its bundle's
// metadata) and used where physics needs SI (stiffness, gravity, forces).
//
// When the user does not say, detectLengthUnits guesses from the size: a
// tissue of the knee (meniscus ~40 mm, ligaments ~35 mm, cartilage ~60 mm)
// is between TissueSizeRange[0] and TissueSizeRange[1] metres across, and
// the units are tried in the order millimetre, metre, centimetre, micrometre
// (the commonest first); the first that gives a tissue-sized object wins.
// Largest extent 40 -> mm, 0.04 -> m, 4 -> cm, 40,000 -> um. A size no unit
// explains (e.g. 2,000) is taken as millimetres, with a reason that says so.
#ifndef LengthUnits_h
#define LengthUnits_h

#include "ThinTissueCoreModule.h"

#include <array>
#include <optional>
#include <string>

namespace thintissue
{

struct LengthUnits
{
  /// "mm", "cm", "m", "um", or "" for a scale that is none of them.
  std::string name = "mm";
  double metresPerUnit = 0.001;

  /// "mm", or "1 unit = 0.0254 m" for an unnamed scale.
  std::string description() const;
};

/// Tissue sizes (largest extent, metres) that detection accepts: 5 mm-0.5 m.
constexpr std::array<double, 2> TissueSizeRange = { 0.005, 0.5 };

/// "mm", "cm", "m", "um" (also "µm", "micrometre(s)", "millimetre(s)",
/// "centimetre(s)", "metre(s)", with -er spellings); nothing for others.
THINTISSUECORE_EXPORT std::optional<LengthUnits> lengthUnitsNamed(const std::string& name);

/// The units where one unit is `metresPerUnit` metres (a named unit when it
/// is one of them, within 1e-9 relative). Throws InvalidInputError unless
/// the scale is positive and finite.
THINTISSUECORE_EXPORT LengthUnits lengthUnitsOfScale(double metresPerUnit);

struct DetectedLengthUnits
{
  LengthUnits units;
  /// Why, for the console: "largest extent 41.2: a tissue of 41.2 mm".
  std::string reason;
  /// False when no unit gives a tissue-sized object (millimetres assumed).
  bool confident = true;
};

/// Guesses the units of a tissue whose largest bounding-box extent is
/// `largestExtent` (in the file's units), as described above.
THINTISSUECORE_EXPORT DetectedLengthUnits detectLengthUnits(double largestExtent);

} // namespace thintissue

#endif
