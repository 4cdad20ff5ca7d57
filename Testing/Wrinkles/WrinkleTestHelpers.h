// Shared by the wrinkle tests: the examination meniscus with its monitor
// points, and a press of the hexahedra without a solver (a smooth dent).
#ifndef WrinkleTestHelpers_h
#define WrinkleTestHelpers_h

#include "MeniscusModel.h"
#include "MonitorCurves.h"
#include "WrinkleGenerator.h"

#include <cmath>
#include <vector>

namespace thintissue::testing
{

/// The examination meniscus (6.4.1) and its monitor points every 0.16 mm
/// (about the thesis's 296 along the inner border).
struct MeniscusWrinkleCase
{
  MeniscusModel model;
  MonitorPointSet monitors;
};

inline MeniscusWrinkleCase meniscusWrinkleCase(MeniscusTearType tear = MeniscusTearType::None,
  double spacing = 0.16)
{
  MeniscusParameters p = examinationMeniscusParameters();
  if (tear != MeniscusTearType::None)
  {
    p.tear = defaultMeniscusTear(tear);
  }
  MeniscusWrinkleCase c{ makeMeniscus(p), {} };
  c.monitors = resampleMonitorCurves(wrinkleDataCurves(c.model.monitorCurves), spacing);
  return c;
}

/// Node positions of `mesh` pressed down by `depth` around `centre`
/// (Gaussian dent of radius `radius`).
inline std::vector<Vector3> dentedNodes(const HexahedralMesh& mesh,
  const Vector3& centre,
  double depth,
  double radius)
{
  std::vector<Vector3> nodes = mesh.nodes;
  for (Vector3& x : nodes)
  {
    const double r2 = (x - centre).head<2>().squaredNorm();
    x.z() -= depth * std::exp(-r2 / (radius * radius));
  }
  return nodes;
}

/// Contacts of a press: the lower surface on the plateau, the instrument on
/// top at `contact`.
inline WrinkleContactState pressing(const Vector3& contact, int lower = 5)
{
  WrinkleContactState s;
  s.lowerSurfaceContacts = lower;
  s.instrumentTouches = true;
  s.instrumentContact = contact;
  return s;
}

} // namespace thintissue::testing

#endif
