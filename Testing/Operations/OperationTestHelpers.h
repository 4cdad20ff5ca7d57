// Shared by the operations tests: the bound meniscus, tool poses and
// instrument commands.
#ifndef OperationTestHelpers_h
#define OperationTestHelpers_h

#include "InstrumentAction.h"
#include "MeniscusModel.h"
#include "VisualCollisionBinding.h"

#include <vector>

namespace thintissue
{
namespace operations_test
{

struct BoundMeniscus
{
  MeniscusModel model = makeMeniscus(examinationMeniscusParameters());
  VisualCollisionBinding binding = bindVisualToCollision(model.visual, model.collision);
};

inline const BoundMeniscus& boundMeniscus()
{
  static const BoundMeniscus meniscus;
  return meniscus;
}

inline TissueCutterSettings handOverPieces()
{
  TissueCutterSettings settings;
  settings.freePieces = FreePieceHandling::HandOver;
  return settings;
}

/// A pose with the tool's working side `up` and its handle toward `handle`,
/// placing tool point `local` at world point `at`.
inline RigidPose poseAt(const Vector3& local,
  const Vector3& at,
  const Vector3& up,
  const Vector3& handle)
{
  ToolFrame frame;
  frame.handleAxis = handle.normalized();
  frame.up = (up - up.dot(frame.handleAxis) * frame.handleAxis).normalized();
  RigidPose pose;
  pose.rotation = frame.rotation();
  pose.translation = at - pose.rotation * local;
  return pose;
}

inline Vector3 centroid(const std::vector<Vector3>& points)
{
  Vector3 sum = Vector3::Zero();
  for (const Vector3& p : points)
    sum += p;
  return sum / static_cast<double>(points.size());
}

/// The punch over monitor point `i` of a border curve: its jaws around the
/// border (fixed jaw 0.6 mm below it, opening upward), the shaft toward the
/// open side turned by `turn` radians about z, the bite outline's centre
/// `inward` mm into the tissue from the border.
inline RigidPose punchOverBorder(const SurgicalInstrumentModel& punch,
  const MonitorCurve& curve,
  std::size_t i,
  double inward = 0.0,
  double turn = 0.0)
{
  const Vector3 rim = curve.monitorPoints[i];
  Vector3 into = curve.regionPoints[i] - rim;
  into.z() = 0.0;
  into = Eigen::AngleAxisd(turn, Vector3::UnitZ()) * into.normalized();
  return poseAt(
    centroid(punch.biteOutline), rim + inward * into - Vector3(0, 0, 0.6), Vector3::UnitZ(), -into);
}

/// Rest area of the collision triangles still in the tissue (mm^2).
inline double activeArea(const TissueCutter& cutter)
{
  const auto& mesh = cutter.collision();
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    if (!cutter.isActive(static_cast<int>(t)))
      continue;
    const Triangle& tri = mesh.triangles()[t];
    const auto& x = mesh.restPositions();
    area += 0.5 * (x[tri[1]] - x[tri[0]]).cross(x[tri[2]] - x[tri[0]]).norm();
  }
  return area;
}

inline InstrumentCommand command(double time,
  const RigidPose& pose,
  double jaw,
  bool working = false)
{
  InstrumentCommand c;
  c.time = time;
  c.pose = pose;
  c.jawOpening = jaw;
  c.working = working;
  return c;
}

} // namespace operations_test
} // namespace thintissue

#endif
