#include "vtkCorotationalHexFemFilter.h"

#include "CorotationalHexFem.h"
#include "ThinTissueError.h"
#include "vtkThinTissueConversion.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <exception>

vtkStandardNewMacro(vtkCorotationalHexFemFilter);

namespace
{
const char* const ExternalForceArrayName = "ExternalForce";

thintissue::LinearSolverKind linearSolverKind(int solver)
{
  switch (solver)
  {
    case vtkCorotationalHexFemFilter::CHOLMOD:
      return thintissue::LinearSolverKind::Cholmod;
    case vtkCorotationalHexFemFilter::CONJUGATE_GRADIENT:
      return thintissue::LinearSolverKind::ConjugateGradient;
    case vtkCorotationalHexFemFilter::STALE_FACTOR_CONJUGATE_GRADIENT:
      return thintissue::LinearSolverKind::StaleFactorConjugateGradient;
    case vtkCorotationalHexFemFilter::MULTIGRID_CONJUGATE_GRADIENT:
      return thintissue::LinearSolverKind::MultigridConjugateGradient;
    default:
      return thintissue::LinearSolverKind::Automatic;
  }
}

/// The "ExternalForce" point array, if any, applied to the solver.
void applyExternalForces(vtkUnstructuredGrid* input, thintissue::CorotationalHexFem& fem)
{
  vtkDataArray* forces = input->GetPointData()->GetArray(ExternalForceArrayName);
  if (forces == nullptr)
  {
    return;
  }
  if (forces->GetNumberOfComponents() != 3 ||
      forces->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    throw thintissue::InvalidInputError(std::string("point array '") + ExternalForceArrayName +
                                        "' must have 3 components and one tuple per point (got " +
                                        std::to_string(forces->GetNumberOfComponents()) +
                                        " components, " +
                                        std::to_string(forces->GetNumberOfTuples()) + " tuples)");
  }
  for (vtkIdType i = 0; i < forces->GetNumberOfTuples(); ++i)
  {
    thintissue::Vector3 force;
    forces->GetTuple(i, force.data());
    if (force != thintissue::Vector3::Zero())
    {
      fem.setExternalForce(static_cast<std::size_t>(i), force);
    }
  }
}

vtkSmartPointer<vtkDoubleArray> makeVectorArray(const char* name, vtkIdType tuples)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(tuples);
  return array;
}
} // namespace

int vtkCorotationalHexFemFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

int vtkCorotationalHexFemFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  this->NumberOfFixedNodes = 0;
  this->NumberOfCompletedSteps = 0;
  this->LastIterations = 0;
  this->TotalIterations = 0;
  this->LastSolveSucceeded = 0;
  try
  {
    const thintissue::HexahedralMesh mesh =
      thintissue::fromUnstructuredGrid(input, "vtkCorotationalHexFemFilter input");
    this->NumberOfFixedNodes = static_cast<vtkIdType>(
      std::count_if(mesh.fixedNodes.begin(), mesh.fixedNodes.end(), [](auto f) { return f != 0; }));

    thintissue::LinearMaterial material;
    material.youngModulus = this->YoungModulus;
    material.poissonRatio = this->PoissonRatio;
    material.density = this->Density;
    thintissue::CorotationalHexFemSettings settings;
    settings.timeStep = this->TimeStep;
    settings.rayleighMass = this->RayleighMass;
    settings.rayleighStiffness = this->RayleighStiffness;
    settings.gravity = thintissue::Vector3(this->Gravity[0], this->Gravity[1], this->Gravity[2]);
    settings.corotational = this->Corotational != 0;
    settings.solver = linearSolverKind(this->LinearSolver);
    thintissue::CorotationalHexFem fem(mesh, material, settings);
    applyExternalForces(input, fem);
    this->UpdateProgress(0.0);

    thintissue::SolverResult result;
    if (this->NumberOfSteps == 0)
    {
      result = fem.solveStatic(this->MaximumStaticIterations);
      this->LastIterations = result.iterations;
      this->TotalIterations = result.iterations;
    }
    else
    {
      for (int s = 0; s < this->NumberOfSteps && !this->GetAbortExecute(); ++s)
      {
        result = fem.step();
        if (!result.ok)
        {
          break;
        }
        ++this->NumberOfCompletedSteps;
        this->LastIterations = result.iterations;
        this->TotalIterations += result.iterations;
        this->UpdateProgress(static_cast<double>(s + 1) / this->NumberOfSteps);
      }
    }
    if (!result.ok)
    {
      // The solver kept its last good state: report, and output that state.
      vtkErrorMacro(<< result.message);
    }
    this->LastSolveSucceeded = result.ok && !this->GetAbortExecute();

    const vtkIdType count = input->GetNumberOfPoints();
    output->ShallowCopy(input);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(count);
    auto displacement = makeVectorArray("Displacement", count);
    auto velocity = makeVectorArray("Velocity", count);
    const auto& positions = fem.positions();
    const auto& rest = fem.restPositions();
    const auto& velocities = fem.velocities();
    for (vtkIdType i = 0; i < count; ++i)
    {
      const auto n = static_cast<std::size_t>(i);
      points->SetPoint(i, positions[n].data());
      const thintissue::Vector3 moved = positions[n] - rest[n];
      displacement->SetTypedTuple(i, moved.data());
      velocity->SetTypedTuple(i, velocities[n].data());
    }
    output->SetPoints(points);
    output->GetPointData()->AddArray(displacement);
    output->GetPointData()->AddArray(velocity);
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

const char* vtkCorotationalHexFemFilter::GetLinearSolverAsString()
{
  switch (this->LinearSolver)
  {
    case CHOLMOD:
      return "Cholmod";
    case CONJUGATE_GRADIENT:
      return "ConjugateGradient";
    case STALE_FACTOR_CONJUGATE_GRADIENT:
      return "StaleFactorConjugateGradient";
    case MULTIGRID_CONJUGATE_GRADIENT:
      return "MultigridConjugateGradient";
    default:
      return "Automatic";
  }
}

void vtkCorotationalHexFemFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "YoungModulus: " << this->YoungModulus << "\n";
  os << indent << "PoissonRatio: " << this->PoissonRatio << "\n";
  os << indent << "Density: " << this->Density << "\n";
  os << indent << "TimeStep: " << this->TimeStep << "\n";
  os << indent << "NumberOfSteps: " << this->NumberOfSteps << "\n";
  os << indent << "MaximumStaticIterations: " << this->MaximumStaticIterations << "\n";
  os << indent << "RayleighMass: " << this->RayleighMass << "\n";
  os << indent << "RayleighStiffness: " << this->RayleighStiffness << "\n";
  os << indent << "Gravity: " << this->Gravity[0] << " " << this->Gravity[1] << " "
     << this->Gravity[2] << "\n";
  os << indent << "Corotational: " << (this->Corotational ? "On" : "Off") << "\n";
  os << indent << "LinearSolver: " << this->GetLinearSolverAsString() << "\n";
  os << indent << "NumberOfFixedNodes: " << this->NumberOfFixedNodes << "\n";
  os << indent << "NumberOfCompletedSteps: " << this->NumberOfCompletedSteps << "\n";
  os << indent << "LastIterations: " << this->LastIterations << "\n";
  os << indent << "TotalIterations: " << this->TotalIterations << "\n";
  os << indent << "LastSolveSucceeded: " << (this->LastSolveSucceeded ? "Yes" : "No") << "\n";
}
