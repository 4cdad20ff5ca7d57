// Kernel models as VTK multiblocks (blocks named "Visual", "Collision",
// "Simulation"), shared by the sources of this module. Not wrapped.
#ifndef vtkTissueModelBlocks_h
#define vtkTissueModelBlocks_h

#include "ThinTissueVTKModelsModule.h"

#include <vtkSmartPointer.h>

class vtkDataObject;
class vtkMultiBlockDataSet;

namespace thintissue
{
struct TissueModel;
struct BoneModel;

/// Appends `block` to `blocks` under `name`.
THINTISSUEVTKMODELS_EXPORT void appendNamedBlock(vtkMultiBlockDataSet* blocks,
  vtkDataObject* block,
  const char* name);

/// Visual, Collision and Simulation blocks of a tissue.
THINTISSUEVTKMODELS_EXPORT vtkSmartPointer<vtkMultiBlockDataSet> toMultiBlock(
  const TissueModel& model);

/// Visual and Collision blocks of a bone.
THINTISSUEVTKMODELS_EXPORT vtkSmartPointer<vtkMultiBlockDataSet> toMultiBlock(
  const BoneModel& model);

} // namespace thintissue

#endif
