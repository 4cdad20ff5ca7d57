/**
 * @class vtkTissueModelSource
 * @brief Base of the sources of procedural tissues: outputs the three meshes
 * of a tissue (thesis fig. 5-1) and all of them as one multiblock.
 *
 * Output ports: 0 the visual surface (vtkPolyData: normals, texture
 * coordinates), 1 the collision mid-surface (vtkPolyData with the point
 * array "Radius"), 2 the hexahedra (vtkUnstructuredGrid of VTK_HEXAHEDRON
 * with the point array "FixedNode"), 3 a vtkMultiBlockDataSet whose blocks
 * "Visual", "Collision" and "Simulation" are those three (subclasses may
 * add blocks and ports after these).
 */
#ifndef vtkTissueModelSource_h
#define vtkTissueModelSource_h

#include "ThinTissueVTKModelsModule.h"
#include "vtkAlgorithm.h"

class vtkMultiBlockDataSet;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace thintissue
{
struct TissueModel;
}

class THINTISSUEVTKMODELS_EXPORT vtkTissueModelSource : public vtkAlgorithm
{
public:
  vtkTypeMacro(vtkTissueModelSource, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputPort
  {
    VisualPort = 0,
    CollisionPort = 1,
    SimulationPort = 2,
    AllMeshesPort = 3
  };

  ///@{
  /// The outputs (valid after Update()).
  vtkPolyData* GetVisualOutput();
  vtkPolyData* GetCollisionOutput();
  vtkUnstructuredGrid* GetSimulationOutput();
  vtkMultiBlockDataSet* GetAllMeshesOutput();
  ///@}

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputs,
    vtkInformationVector* outputs) override;

protected:
  vtkTissueModelSource();
  ~vtkTissueModelSource() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;

  /// The kernel model for the current parameters; throws thintissue::Error
  /// on bad parameters (reported with vtkErrorMacro, outputs left empty).
  virtual thintissue::TissueModel BuildTissueModel() = 0;

  /// Subclasses with more ports fill them (and may add blocks to `all`).
  virtual void FillExtraOutputs(vtkInformationVector* outputs, vtkMultiBlockDataSet* all);

  /// Number of ports of the subclass (at least 4).
  void SetNumberOfTissueOutputPorts(int count);

private:
  vtkTissueModelSource(const vtkTissueModelSource&) = delete;
  void operator=(const vtkTissueModelSource&) = delete;
};

#endif
