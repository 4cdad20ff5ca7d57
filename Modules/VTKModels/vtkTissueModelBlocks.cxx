#include "vtkTissueModelBlocks.h"

#include "KneeModels.h"
#include "TissueModel.h"
#include "vtkThinTissueConversion.h"

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

namespace thintissue
{

void appendNamedBlock(vtkMultiBlockDataSet* blocks, vtkDataObject* block, const char* name)
{
  const unsigned int index = blocks->GetNumberOfBlocks();
  blocks->SetBlock(index, block);
  blocks->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), name);
}

vtkSmartPointer<vtkMultiBlockDataSet> toMultiBlock(const TissueModel& model)
{
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  appendNamedBlock(blocks, toPolyData(model.visual), "Visual");
  appendNamedBlock(blocks, toPolyData(model.collision), "Collision");
  appendNamedBlock(blocks, toUnstructuredGrid(model.simulation), "Simulation");
  return blocks;
}

vtkSmartPointer<vtkMultiBlockDataSet> toMultiBlock(const BoneModel& model)
{
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  appendNamedBlock(blocks, toPolyData(model.visual), "Visual");
  appendNamedBlock(blocks, toPolyData(model.collision), "Collision");
  return blocks;
}

} // namespace thintissue
