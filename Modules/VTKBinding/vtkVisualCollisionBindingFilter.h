/**
 * @class vtkVisualCollisionBindingFilter
 * @brief Binds a fine closed visual surface to its coarse collision
 * mid-surface (thesis 5.2): geodesic paths between paired vertices, the
 * visual mesh re-meshed along them, and every visual vertex bound to a
 * collision vertex, edge or triangle with local parameters.
 *
 * Input port 0: the visual surface (vtkPolyData; closed, manifold,
 * outward, thin). Input port 1: the collision mid-surface (vtkPolyData with
 * the per-point radius array RadiusArrayName, "Radius" by default); see
 * SetCollisionConnection().
 *
 * Output port 0: the re-meshed visual surface (geometrically the input;
 * normals, texture coordinates -- point "TCoords" when seam-free and cell
 * "CornerTextureCoordinates" -- and other point arrays carried over) with
 *  - point "BindingKind" (unsigned char): 0 bound to a collision vertex,
 *    1 to an edge, 2 to a triangle;
 *  - point "BindingElement" (int): the collision vertex, edge (index into
 *    the collision mesh's edges, each (lower, higher) vertex index, sorted)
 *    or triangle;
 *  - point "BindingSide" (signed char): +1 / -1 side of the collision
 *    surface, 0 on the rim;
 *  - point "BindingParameters" (3 doubles summing to 1): (1, 0, 0) for a
 *    vertex, (1 - t, t, 0) along an edge, barycentric in a triangle;
 *  - cell "CollisionTriangle" (int) and "CollisionSide" (signed char): the
 *    region each visual triangle belongs to.
 *
 * Output port 1: the geodesic paths as polylines, one cell per path from
 * the visual vertex of the edge's first collision vertex to that of its
 * second; its points are the visual vertices the paths pass (point array
 * "VisualVertex": the point id in output 0), with cell arrays
 * "CollisionEdge" (int), "Side" (signed char: +1, -1, 0 for a border edge's
 * rim path) and "Length" (double).
 *
 * With CacheFileName set, the binding is read from that file when it is
 * current (made from the same meshes and settings) and otherwise built and
 * written there (thintissue::loadOrBuildBinding); GetCacheWasRebuilt() and
 * GetLastCacheMessage() say which happened.
 *
 * Progress is reported with the stage as progress text. An observer may
 * abort with SetAbortExecute(1): the run stops at the next progress report,
 * leaves both outputs empty, warns, and keeps the reason in
 * GetLastErrorMessage() (call Modified() to run again). Bad input (open or
 * non-manifold visual surface, collision without radii or outside the
 * visual volume, ...) is reported with vtkErrorMacro naming the problem,
 * kept in GetLastErrorMessage(), and gives empty outputs.
 */
#ifndef vtkVisualCollisionBindingFilter_h
#define vtkVisualCollisionBindingFilter_h

#include "ThinTissueVTKBindingModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string> // for std::string

class THINTISSUEVTKBINDING_EXPORT vtkVisualCollisionBindingFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkVisualCollisionBindingFilter* New();
  vtkTypeMacro(vtkVisualCollisionBindingFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputPort
  {
    VisualPort = 0,
    PathsPort = 1
  };

  /// The collision mid-surface (input port 1).
  void SetCollisionConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetCollisionData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// Outputs (valid after Update()).
  vtkPolyData* GetVisualOutput() { return this->GetOutput(VisualPort); }
  vtkPolyData* GetPathsOutput() { return this->GetOutput(PathsPort); }
  ///@}

  ///@{
  /// Name of the per-point radius array of the collision mesh. Default
  /// "Radius".
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /// A collision vertex counts as inside the visual volume when it lies
  /// within this distance of the surface, relative to the visual bounding
  /// box diagonal (border vertices sit on the rim). Default 1e-3.
  vtkSetClampMacro(InsideTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(InsideTolerance, double);
  ///@}

  ///@{
  /// The visual surface must be met along each inner collision vertex's
  /// normal, on both sides, within this many radii. Default 4.
  vtkSetClampMacro(ThinnessFactor, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ThinnessFactor, double);
  ///@}

  ///@{
  /// Compute the geodesic paths in parallel (the result does not depend on
  /// it). On by default.
  vtkSetMacro(Parallel, bool);
  vtkGetMacro(Parallel, bool);
  vtkBooleanMacro(Parallel, bool);
  ///@}

  ///@{
  /// How the rim paths (the equator between the visual surface's positive
  /// and negative halves) are found: RIM_PATHS_AUTOMATIC (the default:
  /// geodesics between the rim points, the labelled equator where a rough
  /// rim defeats them), RIM_PATHS_GEODESIC, or RIM_PATHS_LABELLED (the
  /// border between the triangles on either side of the collision
  /// mid-surface; no horizontal cleavage).
  enum RimPathMethods
  {
    RIM_PATHS_AUTOMATIC = 0,
    RIM_PATHS_GEODESIC = 1,
    RIM_PATHS_LABELLED = 2
  };
  vtkSetClampMacro(RimPathMethod, int, RIM_PATHS_AUTOMATIC, RIM_PATHS_LABELLED);
  vtkGetMacro(RimPathMethod, int);
  void SetRimPathMethodToAutomatic() { this->SetRimPathMethod(RIM_PATHS_AUTOMATIC); }
  void SetRimPathMethodToGeodesic() { this->SetRimPathMethod(RIM_PATHS_GEODESIC); }
  void SetRimPathMethodToLabelled() { this->SetRimPathMethod(RIM_PATHS_LABELLED); }
  ///@}

  ///@{
  /// Binding cache file; none (null or empty, the default) builds the
  /// binding at every update.
  vtkSetStringMacro(CacheFileName);
  vtkGetStringMacro(CacheFileName);
  ///@}

  /// After an update with CacheFileName: true when the binding was built
  /// (and written), false when it was read from the file.
  vtkGetMacro(CacheWasRebuilt, bool);

  /// After an update with CacheFileName: why the binding was rebuilt (the
  /// file missing, stale, of another version or damaged), or that it was
  /// loaded. "" without a cache file.
  const char* GetLastCacheMessage() const { return this->LastCacheMessage.c_str(); }

  /// The message of the last failed or aborted update, "" after a
  /// successful one.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

protected:
  vtkVisualCollisionBindingFilter();
  ~vtkVisualCollisionBindingFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* RadiusArrayName = nullptr;
  double InsideTolerance = 1e-3;
  double ThinnessFactor = 4.0;
  bool Parallel = true;
  int RimPathMethod = RIM_PATHS_AUTOMATIC;
  char* CacheFileName = nullptr;
  bool CacheWasRebuilt = false;
  std::string LastCacheMessage;
  std::string LastErrorMessage;

private:
  vtkVisualCollisionBindingFilter(const vtkVisualCollisionBindingFilter&) = delete;
  void operator=(const vtkVisualCollisionBindingFilter&) = delete;
};

#endif
