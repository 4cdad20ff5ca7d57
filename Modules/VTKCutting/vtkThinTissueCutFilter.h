/**
 * @class vtkThinTissueCutFilter
 * @brief Cuts a bound thin tissue with blade surfaces, cut after cut
 * (thesis 5.3): the collision mesh is split and opened along the blade,
 * the hexahedra holding more than one branch of it are duplicated, and the
 * fine visual surface is cut consistently through its binding, with a cut
 * surface closing it.
 *
 * Input port 0: the bound visual surface (vtkPolyData with the arrays of
 * vtkVisualCollisionBindingFilter: point BindingKind, BindingElement,
 * BindingSide, BindingParameters; cell CollisionTriangle, CollisionSide),
 * e.g. that filter's output 0 or vtkTissueBundleReader's. Port 1: the
 * collision mid-surface with the point array "Radius". Port 2: the
 * hexahedra (vtkUnstructuredGrid). Port 3 (optional): the blade, a
 * vtkPolyData of triangles in the tissue's coordinates -- the surface the
 * tool's edge swept since the last cut.
 *
 * The filter keeps the cut tissue between updates. It is built from ports
 * 0-2 at the first update and again whenever one of them is modified (or
 * after ResetTissue()); each update whose blade input was modified since
 * the last cut applies that blade once (a blade present when the tissue
 * is built cuts it). SnapFraction, FreePieces, FragmentAreaFraction and
 * the jagged cut surface (JaggedAmplitude, JaggedWavelength, JaggedSeed;
 * thesis 6.4.4) apply to the cuts of the updates after they are set;
 * CutSurfaceRows too until the first cut makes a cut surface, after which
 * a change is an error that leaves the tissue as it is (ResetTissue()
 * builds it again).
 *
 * Contouring (6.4.4): AddContourPass() asks for a pass of a tool held on
 * the cut rim (a sphere and a strength, as TissueCutter::contour); the
 * next update applies the passes asked for since the last, after the cut.
 * The output's field data carry the rim's roughness (TissueCutter::
 * cutRimRoughness): "RimRoughness" (RMS, mm), "RimRoughnessMaximum" (mm)
 * and "ContouredVertices" (cut-surface vertices the last update's passes
 * moved).
 *
 * Shaving (6.4.3): AddShavingPass() asks for a pass of a running shaver
 * whose window is a ball: the next update removes the collision triangles
 * still in the tissue whose centroid (rest) it holds, with the visual
 * triangles bound to them, and closes the opening with cut surface
 * (TissueCutter::removeTriangles); passes apply after the blade and before
 * the contouring passes.
 *
 * Output port 0: the visual surface with its cut surfaces (rest
 * positions), with the binding arrays of the input (the binding after the
 * cuts) and the cell array "Material" (unsigned char: 0 the tissue's
 * surface, 1 cut surface). Port 1: the collision mesh with "Radius". Port
 * 2: the hexahedra with their copies. Cut-surface triangles have
 * CollisionSide 0 (they lie on a collision edge, between the sides); edge
 * bindings refer to the sorted edges of the cut collision mesh, as those of
 * vtkVisualCollisionBindingFilter do.
 *
 * Errors (missing or inconsistent binding arrays, no radius, a cell that is
 * not a hexahedron, a degenerate blade) are reported with vtkErrorMacro and
 * kept in GetLastErrorMessage(); a bad blade leaves the tissue as it was, a
 * bad tissue input gives empty outputs.
 */
#ifndef vtkThinTissueCutFilter_h
#define vtkThinTissueCutFilter_h

#include "ThinTissueVTKCuttingModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkUnstructuredGrid;

class THINTISSUEVTKCUTTING_EXPORT vtkThinTissueCutFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkThinTissueCutFilter* New();
  vtkTypeMacro(vtkThinTissueCutFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum InputPort
  {
    VisualInputPort = 0,
    CollisionInputPort = 1,
    SimulationInputPort = 2,
    BladeInputPort = 3
  };
  enum OutputPort
  {
    VisualPort = 0,
    CollisionPort = 1,
    SimulationPort = 2
  };

  ///@{
  /// The tissue's collision mesh, hexahedra and the blade (ports 1-3).
  void SetCollisionConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetCollisionData(vtkPolyData* collision);
  void SetSimulationConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetSimulationData(vtkUnstructuredGrid* simulation);
  void SetBladeConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(3, output); }
  void SetBladeData(vtkPolyData* blade);
  ///@}

  ///@{
  /// Rows of cut-surface vertices between the two sides (fig. 5-12c).
  /// Default 1.
  vtkSetClampMacro(CutSurfaceRows, int, 0, 64);
  vtkGetMacro(CutSurfaceRows, int);
  ///@}

  ///@{
  /// A blade crossing a collision edge nearer than this fraction of it to
  /// an end cuts through the end instead. Default 0.15.
  vtkSetClampMacro(SnapFraction, double, 0.0, 0.49);
  vtkGetMacro(SnapFraction, double);
  ///@}

  /// What becomes of a piece cut free of every fixed node (or, when none
  /// is fixed, of the largest piece).
  enum FreePieceHandlings
  {
    KEEP_FREE_PIECES = 0,
    DROP_FREE_PIECES = 1
  };

  ///@{
  /// KEEP_FREE_PIECES (the default) or DROP_FREE_PIECES: a dropped piece
  /// leaves the outputs.
  vtkSetClampMacro(FreePieces, int, KEEP_FREE_PIECES, DROP_FREE_PIECES);
  vtkGetMacro(FreePieces, int);
  ///@}

  ///@{
  /// Free pieces whose collision area is below this fraction of the
  /// tissue's leave the outputs whatever FreePieces says. Default 0.
  vtkSetClampMacro(FragmentAreaFraction, double, 0.0, 1.0);
  vtkGetMacro(FragmentAreaFraction, double);
  ///@}

  ///@{
  /// Jagged cut surface (6.4.4): amplitude (mm; 0, the default, a smooth
  /// cut), wavelength (mm, default 0.5) and seed of the noise that moves
  /// the cut surface across the cut. Needs CutSurfaceRows >= 1.
  vtkSetClampMacro(JaggedAmplitude, double, 0.0, 100.0);
  vtkGetMacro(JaggedAmplitude, double);
  vtkSetClampMacro(JaggedWavelength, double, 1e-3, 1e3);
  vtkGetMacro(JaggedWavelength, double);
  vtkSetMacro(JaggedSeed, vtkTypeUInt32);
  vtkGetMacro(JaggedSeed, vtkTypeUInt32);
  ///@}

  /// Asks for a contouring pass at the next update: the cut surface within
  /// `radius` of `centre` (world) is smoothed by `strength` in [0, 1] where
  /// the tool is (TissueCutter::contour). Bad values are reported by that
  /// update. Marks the filter modified.
  void AddContourPass(double centreX,
    double centreY,
    double centreZ,
    double radius,
    double strength);

  /// Asks for a shaving pass at the next update: the collision triangles
  /// whose centroid lies within `radius` of `centre` (rest) are removed
  /// (TissueCutter::removeTriangles). Bad values are reported by that
  /// update. Marks the filter modified.
  void AddShavingPass(double centreX, double centreY, double centreZ, double radius);

  ///@{
  /// Shaving passes that removed something since the tissue was built, and
  /// the collision triangles the last update's passes removed.
  vtkGetMacro(NumberOfShavingPasses, int);
  vtkGetMacro(LastShavedTriangles, int);
  ///@}

  ///@{
  /// The rim's roughness after the last update (as the field data), and
  /// the contouring passes applied since the tissue was built.
  vtkGetMacro(RimRoughness, double);
  vtkGetMacro(RimRoughnessMaximum, double);
  vtkGetMacro(NumberOfContourPasses, int);
  ///@}

  /// Forgets the cuts: the next update builds the tissue from the inputs.
  void ResetTissue();

  ///@{
  /// Cuts applied since the tissue was built; the last one's time (ms) and
  /// whether it changed the tissue (a blade that crosses nothing does not).
  vtkGetMacro(NumberOfCuts, int);
  vtkGetMacro(LastCutMilliseconds, double);
  vtkGetMacro(LastCutChangedTissue, vtkTypeBool);
  ///@}

  ///@{
  /// The outputs (valid after Update()).
  vtkPolyData* GetVisualOutput();
  vtkPolyData* GetCollisionOutput();
  vtkUnstructuredGrid* GetSimulationOutput();
  ///@}

  /// Empty when the last update went well.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

protected:
  vtkThinTissueCutFilter();
  ~vtkThinTissueCutFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int CutSurfaceRows = 1;
  double SnapFraction = 0.15;
  int FreePieces = KEEP_FREE_PIECES;
  double FragmentAreaFraction = 0.0;
  double JaggedAmplitude = 0.0;
  double JaggedWavelength = 0.5;
  vtkTypeUInt32 JaggedSeed = 0;
  double RimRoughness = 0.0;
  double RimRoughnessMaximum = 0.0;
  int NumberOfContourPasses = 0;
  int NumberOfShavingPasses = 0;
  int LastShavedTriangles = 0;
  int NumberOfCuts = 0;
  double LastCutMilliseconds = 0.0;
  vtkTypeBool LastCutChangedTissue = 0;
  std::string LastErrorMessage;

private:
  vtkThinTissueCutFilter(const vtkThinTissueCutFilter&) = delete;
  void operator=(const vtkThinTissueCutFilter&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Tissue;
  void ApplyContourPasses();
  void ApplyShavingPasses();
  void WriteRoughness(vtkPolyData* output);
};

#endif
