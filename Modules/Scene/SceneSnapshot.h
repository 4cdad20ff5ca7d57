// What the physics thread hands the GUI thread after a step (DESIGN.md:
// real-time loop): everything the view and the panels draw, copied out of
// the scene so that the GUI never reads the scene while physics writes it.
// Exchanged through a LatestValue triple buffer (RealTimeLoop); in
// lock-step the GUI fills one itself (TrainingScene::snapshot).
#ifndef SceneSnapshot_h
#define SceneSnapshot_h

#include "RigidTool.h"
#include "TriangleMesh.h"
#include "VisualMeshCut.h"

#include <array>
#include <memory>
#include <vector>

namespace thintissue
{

/// What a run measured (issue: metrics and assessment).
struct SceneMetrics
{
  double time = 0.0;                 ///< s
  double instrumentPathLength = 0.0; ///< mm, of the instrument tip
  double cameraPathLength = 0.0;     ///< mm, of the arthroscope tip
  int cartilageContactSteps = 0;     ///< steps the instrument touched cartilage
  double peakForce = 0.0;            ///< N, on the instrument
  int wrinklingSteps = 0;
  int steps = 0;
  /// Bites, strokes and shaver bites that changed the tissue, and the rest
  /// volume they removed (mm^3).
  int operations = 0;
  double removedVolume = 0.0;
  /// Of it, the pieces whose centre lies in the task's target region (and
  /// the rest: tissue that should have stayed).
  double removedInTarget = 0.0;
  double removedOutsideTarget = 0.0;
  /// Contouring (6.4.4): passes that moved the cut rim, and the rim's
  /// roughness (TissueCutter::cutRimRoughness, RMS and largest, mm) when
  /// the run started (after the scenario's preparation) and now.
  int contourPasses = 0;
  double rimRoughnessAtStart = 0.0;
  double rimRoughness = 0.0;
  double rimRoughnessMaximum = 0.0;
};

/// The tissue's visual surface as cut so far: made again only when a cut
/// changes it (shared, never changed once made).
struct SceneTopology
{
  int version = 0;
  /// Rest positions, triangles and rest normals (no texture, no attributes).
  TriangleMesh mesh;
  /// Per triangle: still part of the tissue (removed pieces are not drawn).
  std::vector<char> active;
  /// Per triangle (empty before any cutting instrument: all outer surface).
  std::vector<VisualMaterial> materials;
};

/// A stylus as the servo last saw it (device status in the window).
struct SceneDeviceStatus
{
  bool calibrated = true;
  unsigned buttons = 0;
  /// The force sent to the device (N, device frame).
  Vector3 force = Vector3::Zero();
};

struct SceneSnapshot
{
  double time = -1.0; ///< scene seconds; < 0: nothing published yet
  std::shared_ptr<const SceneTopology> topology;
  /// One per topology->mesh vertex, wrinkles added.
  std::vector<Vector3> visualPositions;
  RigidPose instrument;
  RigidPose scope;
  double jawOpening = 1.0;
  bool wrinkling = false;
  SceneMetrics metrics;
  /// 0: the arthroscope's stylus, 1: the instrument's.
  std::array<SceneDeviceStatus, 2> devices;
};

} // namespace thintissue

#endif
