// How well a prepared tissue's collision mesh and binding represent its
// visual surface (issue 14, item 6): reported with every preparation, in
// the bundle's metadata under "quality" and on ThinTissuePrepare's console.
//
// Measures:
//  - Deviation relative to the local thickness. The thick collision surface
//    is the mid-surface swept by its radii (Spillmann's reduced triangles
//    with radii). Both ways, as the generator's Hausdorff distance: each
//    visual vertex to the thick surface (nearest point of the mid-surface,
//    less the radius there), and points of the thick surface (every
//    collision vertex and triangle centre, one radius along the normal on
//    both sides, those on its outside) to the visual surface. Each distance
//    is divided by the local thickness there: twice the radius interpolated
//    at the nearest mid-surface point (resp. at the sample), but at least
//    `minimumThicknessFraction` of the largest thickness, because the
//    thickness goes to zero at a sharp rim, where any distance would be
//    "infinitely" bad. Reported: the largest (the Hausdorff distance
//    relative to the local thickness) with its absolute distance, local
//    thickness and place; and the 95th percentile over all samples, which
//    says how much of the surface is off rather than one spot. The sharp
//    inner rim of a meniscus, which spheres cannot reach, keeps the largest
//    value near 0.6-1.0 whatever the resolution (measured: the procedural
//    and the two MRI menisci at 85-200 collision vertices); the percentile
//    falls with the resolution: 0.7-0.9 at 12 vertices, 0.45-0.55 at 20,
//    0.2-0.3 at 85-200.
//  - Visual vertices per collision triangle: distinct vertices of the visual
//    triangles bound to it, both sides (the three paired corners included);
//    fewest, mean and most.
//  - Worst binding region (collision triangle and side). Each visual
//    triangle of a region is mapped into the collision triangle by its
//    binding parameters (formula 5-1); stretch = mapped area / visual area.
//    A region's area distortion is exp(RMS of ln(stretch / region's mean
//    stretch)), area-weighted: 1 for a map that scales all triangles alike,
//    2 when triangles typically shrink or grow by a factor of 2 relative to
//    each other (1.5-2.3 measured on the menisci above at 20-200 vertices,
//    3-6 at 12). A visual triangle whose image has the opposite orientation
//    of its region's (the parameterisation folds) counts as folded. The
//    worst region is the one with the most folded triangles, then the
//    largest distortion.
// Warnings (each a sentence for the console) when the collision mesh
// represents the tissue poorly: the 95th percentile of the relative
// deviation above maximumRelativeDeviation95 or its largest value above
// maximumRelativeDeviation; a region that folds or whose distortion
// exceeds maximumAreaDistortion; a collision triangle that binds fewer
// than minimumVisualVerticesPerTriangle visual vertices (the collision
// mesh nearly as fine as the visual mesh).
#ifndef TissueQuality_h
#define TissueQuality_h

#include "ThinTissueBindingModule.h"
#include "VisualCollisionBinding.h"

#include <string>
#include <vector>

namespace thintissue
{

struct TissueQualitySettings
{
  /// The local thickness is at least this fraction of the largest.
  double minimumThicknessFraction = 0.25;
  /// Warning thresholds (see above).
  double maximumRelativeDeviation95 = 0.4;
  double maximumRelativeDeviation = 1.5;
  double maximumAreaDistortion = 4.0;
  int minimumVisualVerticesPerTriangle = 4;
};

/// A distance between the visual and the thick collision surface.
struct SurfaceDeviation
{
  double distance = 0.0;
  /// Twice the radius there (at least the floor, see above).
  double localThickness = 0.0;
  /// distance / localThickness.
  double relative = 0.0;
  /// The visual vertex, or the point of the thick surface.
  Vector3 point = Vector3::Zero();
  /// The collision triangle nearest to it.
  int collisionTriangle = -1;
  /// True: a visual vertex away from the thick surface; false: a point of
  /// the thick surface away from the visual surface.
  bool fromVisual = true;
};

struct BindingRegionQuality
{
  int collisionTriangle = -1;
  int side = 0;
  int visualVertices = 0;
  int visualTriangles = 0;
  int foldedTriangles = 0;
  double areaDistortion = 1.0;
  /// Centre of the region's visual triangles (area-weighted).
  Vector3 centre = Vector3::Zero();
};

struct THINTISSUEBINDING_EXPORT TissueQuality
{
  /// Largest distance either way (absolute) and the largest thickness.
  double hausdorffDistance = 0.0;
  double largestThickness = 0.0;
  /// Where the deviation relative to the local thickness is largest.
  SurfaceDeviation worstDeviation;
  /// 95th percentile of the relative deviation over all samples.
  double relativeDeviation95 = 0.0;
  int fewestVisualVerticesPerTriangle = 0;
  double meanVisualVerticesPerTriangle = 0.0;
  int mostVisualVerticesPerTriangle = 0;
  /// The collision triangle with the fewest.
  int sparsestCollisionTriangle = -1;
  BindingRegionQuality worstRegion;
  /// Empty when the collision mesh represents the tissue well.
  std::vector<std::string> warnings;

  /// The report as a JSON object (text).
  std::string toJson() const;
  /// The report read back from toJson's text (a bundle's metadata
  /// "quality"); false, and the report untouched, when the text is not such
  /// a report.
  bool fromJson(const std::string& json);
  /// Lines for the console; `unit` (e.g. "mm") follows lengths.
  std::string summary(const std::string& unit = {}) const;
};

/// Measures the binding's visual mesh against its collision mesh with
/// radii. Throws InvalidInputError for a binding without collision
/// triangles or radii.
THINTISSUEBINDING_EXPORT TissueQuality measureTissueQuality(const VisualCollisionBinding& binding,
  const TissueQualitySettings& settings = {});

} // namespace thintissue

#endif
