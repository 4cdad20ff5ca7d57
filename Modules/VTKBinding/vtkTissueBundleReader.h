/**
 * @class   vtkTissueBundleReader
 * @brief   reads a tissue bundle (ThinTissuePrepare, writeTissueBundle)
 *
 * A bundle holds a whole tissue prepared from its visual mesh: the
 * re-meshed visual surface bound to the collision mid-surface (thesis 5.2),
 * the collision mid-surface with its radii, and the simulation hexahedra.
 *
 * Output ports: 0 the visual surface with the binding arrays of
 * vtkVisualCollisionBindingFilter (point arrays BindingKind, BindingElement,
 * BindingSide, BindingParameters; cell arrays CollisionTriangle,
 * CollisionSide) and the bundle's JSON metadata as the field data string
 * array "Metadata"; 1 the collision mid-surface with the point array
 * "Radius"; 2 the hexahedra (vtkUnstructuredGrid). A missing, damaged or
 * stale-format file leaves empty outputs and the reason, naming the file,
 * in GetLastErrorMessage().
 *
 * A bundle may hold several tissues (ThinTissuePrepare on a file of several
 * pieces, writeTissueBundles): TissueIndex chooses which one the outputs
 * show (0, the largest, by default); GetNumberOfTissues() says how many
 * there are after an update. When the bundle records its length units,
 * every output carries them as field data: "LengthUnits" (string: "mm",
 * "cm", "m", "um", or "" for another scale) and "MetresPerUnit" (double);
 * the coordinates themselves are as prepared, never rescaled.
 */
#ifndef vtkTissueBundleReader_h
#define vtkTissueBundleReader_h

#include "ThinTissueVTKBindingModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class vtkUnstructuredGrid;

class THINTISSUEVTKBINDING_EXPORT vtkTissueBundleReader : public vtkPolyDataAlgorithm
{
public:
  static vtkTissueBundleReader* New();
  vtkTypeMacro(vtkTissueBundleReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputPort
  {
    VisualPort = 0,
    CollisionPort = 1,
    SimulationPort = 2
  };

  ///@{
  /// The bundle file.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Which tissue of a bundle of several (0-based; default 0).
  vtkSetClampMacro(TissueIndex, int, 0, VTK_INT_MAX);
  vtkGetMacro(TissueIndex, int);
  ///@}

  /// Tissues in the file, after Update() (0 when it could not be read).
  int GetNumberOfTissues() const { return this->NumberOfTissues; }

  ///@{
  /// The outputs (valid after Update()).
  vtkPolyData* GetVisualOutput();
  vtkPolyData* GetCollisionOutput();
  vtkUnstructuredGrid* GetSimulationOutput();
  ///@}

  /// Empty after a successful read.
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

protected:
  vtkTissueBundleReader();
  ~vtkTissueBundleReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  int TissueIndex = 0;
  int NumberOfTissues = 0;
  std::string LastErrorMessage;

private:
  vtkTissueBundleReader(const vtkTissueBundleReader&) = delete;
  void operator=(const vtkTissueBundleReader&) = delete;
};

#endif
