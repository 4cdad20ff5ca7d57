// What the simulator draws of a TrainingScene: the knee (bones, cartilage,
// ligaments), the tissue's visual surface as the scene moves it (wrinkles
// included), the instrument, and the arthroscope's view (30 degree scope,
// round field of view, headlight at the scope tip). Only the GUI thread
// touches it: what moves comes from SceneSnapshots (the physics thread's,
// or TrainingScene::snapshot in lock-step); of the scene itself it reads
// only what never changes once built (scenario, knee, instrument model).
#ifndef SimulatorView_h
#define SimulatorView_h

#include "TrainingScene.h"

#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <string>

class vtkRenderWindow;

namespace thintissue
{

class SimulatorView
{
public:
  /// Draws nothing that moves until the first update().
  explicit SimulatorView(const TrainingScene& scene);
  vtkRenderer* renderer() const { return Renderer; }
  /// The overview: the same knee, tissue and instrument seen from outside
  /// the joint (femur hidden), with the arthroscope's shaft; its camera is
  /// fixed. Made on first call (before an update()).
  vtkRenderer* overview();
  /// Follows the scene: tissue points and normals, instrument, camera.
  void update(const SceneSnapshot& snapshot);
  /// Writes the window's picture (PNG).
  static void writePicture(vtkRenderWindow* window, const std::string& path);

private:
  void addKnee();
  void rebuildTissue(const SceneTopology& topology);
  void showJaws(double jawOpening);
  void placeInstrumentAndCamera(const SceneSnapshot& snapshot);
  /// The cut surfaces' normals from `positions` (their own triangles only).
  void updateCutSurfaceNormals(const std::vector<Vector3>& positions);
  void addRoundFieldOfView();
  void placeRing(double aspect);
  static constexpr int RingSegments = 96;

  const TrainingScene& Scene;
  vtkSmartPointer<vtkRenderer> Renderer;
  /// The tissue's outer surface and its cut surfaces (one point set), as
  /// of the scene's topology version.
  vtkSmartPointer<vtkPolyData> Tissue = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkPolyData> CutSurface = vtkSmartPointer<vtkPolyData>::New();
  int TopologyVersion = -1;
  /// The drawn triangles of the outer surface, for its normals each frame.
  TriangleMesh Shading;
  /// The cut surfaces' triangles and vertices, and their normals (one per
  /// visual vertex, set on the cut-surface vertices only). Each surface has
  /// its own normal array: a lip vertex both share is smooth on each side
  /// of the crease, not averaged across it (that showed as light and dark
  /// streaks at the lips).
  std::vector<Triangle> CutTriangles;
  std::vector<int> CutVertices;
  std::vector<Vector3> CutNormals;
  /// Per visual vertex: its rest normal (the mesh's) and the normal
  /// computed from its rest positions on the outer surface.
  std::vector<Vector3> RestNormals;
  std::vector<Vector3> ComputedRestNormals;
  vtkSmartPointer<vtkActor> Instrument;
  vtkSmartPointer<vtkActor> Femur;
  double JawsShown = 1.0; ///< jaw opening of the instrument drawn
  vtkSmartPointer<vtkPolyData> Ring;
  vtkSmartPointer<vtkRenderer> Overview;
  vtkSmartPointer<vtkPolyData> ScopeShaft;
  double RingAspect = 0.0;
};

} // namespace thintissue

#endif
