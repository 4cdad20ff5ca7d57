// VTK adapter of the co-rotational FEM: cantilever statics, dynamics,
// errors and PrintSelf.
#include "vtkCorotationalHexFemFilter.h"

#include "HexahedralMesh.h"
#include "vtkThinTissueConversion.h"

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include "ThinTissueVtkErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace
{
using thintissue::testing::ErrorCounter;

/// Counts progress events.
class ProgressCounter : public vtkCommand
{
public:
  static ProgressCounter* New() { return new ProgressCounter; }
  void Execute(vtkObject*, unsigned long, void* progress) override
  {
    ++count;
    last = *static_cast<double*>(progress);
  }
  int count = 0;
  double last = -1.0;
};

constexpr double Length = 10.0;
constexpr double TipForce = 0.01;

/// A 10 x 1 x 1 beam along x, clamped at x = 0 ("FixedNode"), with a total
/// force TipForce along -z spread over the nodes at x = 10 ("ExternalForce").
vtkSmartPointer<vtkUnstructuredGrid> cantilever(int nx, int nyz)
{
  auto grid = thintissue::toUnstructuredGrid(
    thintissue::HexahedralMesh::makeRegularGrid(thintissue::Vector3::Zero(),
      thintissue::Vector3(Length / nx, 1.0 / nyz, 1.0 / nyz),
      nx,
      nyz,
      nyz));
  const vtkIdType count = grid->GetNumberOfPoints();
  vtkNew<vtkUnsignedCharArray> fixed;
  fixed->SetName("FixedNode");
  fixed->SetNumberOfTuples(count);
  vtkNew<vtkDoubleArray> force;
  force->SetName("ExternalForce");
  force->SetNumberOfComponents(3);
  force->SetNumberOfTuples(count);
  const double tipNodes = (nyz + 1) * (nyz + 1);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double x = grid->GetPoint(i)[0];
    fixed->SetValue(i, x < 1e-12 ? 1 : 0);
    const bool tip = std::abs(x - Length) < 1e-9;
    force->SetTuple3(i, 0.0, 0.0, tip ? -TipForce / tipNodes : 0.0);
  }
  grid->GetPointData()->AddArray(fixed);
  grid->GetPointData()->AddArray(force);
  return grid;
}

/// 20 dynamic steps of `rest` swinging down under a light gravity.
void swingUnderGravity(vtkCorotationalHexFemFilter* fem, vtkUnstructuredGrid* rest)
{
  fem->SetInputData(rest);
  fem->SetYoungModulus(1.0e5);
  fem->SetDensity(1.0);
  fem->SetTimeStep(0.01);
  fem->SetNumberOfSteps(20);
  fem->SetGravity(0.0, 0.0, -0.001);
}

double meanTipDeflection(vtkUnstructuredGrid* rest, vtkUnstructuredGrid* deformed)
{
  double sum = 0.0;
  int count = 0;
  for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
  {
    if (std::abs(rest->GetPoint(i)[0] - Length) < 1e-9)
    {
      sum += deformed->GetPoint(i)[2] - rest->GetPoint(i)[2];
      ++count;
    }
  }
  return sum / count;
}

/// Observes errors on the filter and its executive; returns the counter.
vtkSmartPointer<ErrorCounter> observeErrors(vtkCorotationalHexFemFilter* filter)
{
  auto errors = vtkSmartPointer<ErrorCounter>::New();
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  return errors;
}
} // namespace

TEST(vtkCorotationalHexFemFilter, StaticCantileverMatchesEulerBernoulli)
{
  const double E = 1.0e5;
  const double exact = TipForce * Length * Length * Length / (3.0 * E * (1.0 / 12.0));
  auto rest = cantilever(40, 3);
  vtkNew<vtkCorotationalHexFemFilter> fem;
  fem->SetInputData(rest);
  fem->SetYoungModulus(E);
  fem->SetPoissonRatio(0.0);
  fem->SetNumberOfSteps(0);
  auto errors = observeErrors(fem);
  vtkNew<ProgressCounter> progress;
  fem->AddObserver(vtkCommand::ProgressEvent, progress);
  fem->Update();
  EXPECT_EQ(errors->count, 0) << errors->all;
  EXPECT_TRUE(fem->GetLastSolveSucceeded());
  EXPECT_EQ(fem->GetNumberOfFixedNodes(), 16);
  EXPECT_GE(fem->GetLastIterations(), 1);
  EXPECT_GT(progress->count, 0);
  EXPECT_DOUBLE_EQ(progress->last, 1.0);

  vtkUnstructuredGrid* deformed = fem->GetOutput();
  ASSERT_EQ(deformed->GetNumberOfPoints(), rest->GetNumberOfPoints());
  ASSERT_EQ(deformed->GetNumberOfCells(), rest->GetNumberOfCells());
  EXPECT_EQ(deformed->GetCellType(0), VTK_HEXAHEDRON);
  const double deflection = -meanTipDeflection(rest, deformed);
  EXPECT_GT(deflection, 0.0);
  EXPECT_LT(std::abs(deflection - exact) / exact, 0.10) << deflection << " vs " << exact;
  // Fixed nodes stay; input arrays are passed; velocity is zero.
  for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
  {
    if (rest->GetPoint(i)[0] < 1e-12)
    {
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(deformed->GetPoint(i)[a], rest->GetPoint(i)[a]);
      }
    }
  }
  EXPECT_NE(deformed->GetPointData()->GetArray("FixedNode"), nullptr);
  EXPECT_NE(deformed->GetPointData()->GetArray("ExternalForce"), nullptr);
  vtkDataArray* velocity = deformed->GetPointData()->GetArray("Velocity");
  ASSERT_NE(velocity, nullptr);
  EXPECT_EQ(velocity->GetNumberOfComponents(), 3);
  EXPECT_EQ(velocity->GetRange(-1)[1], 0.0);
  // The input is untouched.
  EXPECT_EQ(rest->GetPointData()->GetArray("Displacement"), nullptr);
  EXPECT_EQ(rest->GetPoint(rest->GetNumberOfPoints() - 1)[2], 1.0);

  // Plain linear FEM agrees for this small deflection.
  fem->CorotationalOff();
  fem->SetLinearSolverToConjugateGradient();
  fem->Update();
  EXPECT_EQ(errors->count, 0) << errors->all;
  EXPECT_NEAR(-meanTipDeflection(rest, fem->GetOutput()), deflection, 1e-3 * deflection);
}

TEST(vtkCorotationalHexFemFilter, DynamicStepsMoveDownAndReportDisplacement)
{
  auto rest = cantilever(20, 2);
  vtkNew<vtkCorotationalHexFemFilter> fem;
  swingUnderGravity(fem, rest);
  auto errors = observeErrors(fem);
  vtkNew<ProgressCounter> progress;
  fem->AddObserver(vtkCommand::ProgressEvent, progress);
  fem->Update();
  EXPECT_EQ(errors->count, 0) << errors->all;
  EXPECT_TRUE(fem->GetLastSolveSucceeded());
  EXPECT_EQ(fem->GetNumberOfCompletedSteps(), 20);
  EXPECT_EQ(fem->GetNumberOfFixedNodes(), 9);
  EXPECT_GE(progress->count, 20);
  EXPECT_DOUBLE_EQ(progress->last, 1.0);

  vtkUnstructuredGrid* deformed = fem->GetOutput();
  ASSERT_EQ(deformed->GetNumberOfPoints(), rest->GetNumberOfPoints());
  EXPECT_LT(meanTipDeflection(rest, deformed), 0.0);
  vtkDataArray* displacement = deformed->GetPointData()->GetArray("Displacement");
  vtkDataArray* velocity = deformed->GetPointData()->GetArray("Velocity");
  ASSERT_NE(displacement, nullptr);
  ASSERT_NE(velocity, nullptr);
  ASSERT_EQ(displacement->GetNumberOfComponents(), 3);
  ASSERT_EQ(displacement->GetNumberOfTuples(), rest->GetNumberOfPoints());
  double largestSpeed = 0.0;
  for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(
        displacement->GetComponent(i, a), deformed->GetPoint(i)[a] - rest->GetPoint(i)[a], 1e-12);
    }
    largestSpeed = std::max(largestSpeed, std::abs(velocity->GetComponent(i, 2)));
  }
  EXPECT_GT(largestSpeed, 0.0);

  // Each update starts again from rest: the same result twice.
  const double first = meanTipDeflection(rest, deformed);
  fem->Modified();
  fem->Update();
  EXPECT_DOUBLE_EQ(meanTipDeflection(rest, fem->GetOutput()), first);
}

TEST(vtkCorotationalHexFemFilter, EverySolverGivesTheMotionOfCholmod)
{
  // The same 20 dynamic steps with each linear solver: the same tip
  // motion within the solve tolerance (the multigrid one included, which
  // Automatic takes only for huge meshes).
  auto rest = cantilever(20, 2);
  auto tipAfterSteps = [&](void (vtkCorotationalHexFemFilter::*choose)())
  {
    vtkNew<vtkCorotationalHexFemFilter> fem;
    swingUnderGravity(fem, rest);
    (fem.GetPointer()->*choose)();
    auto errors = observeErrors(fem);
    fem->Update();
    EXPECT_EQ(errors->count, 0) << errors->all;
    EXPECT_TRUE(fem->GetLastSolveSucceeded()) << fem->GetLinearSolverAsString();
    return meanTipDeflection(rest, fem->GetOutput());
  };
  const double reference = tipAfterSteps(&vtkCorotationalHexFemFilter::SetLinearSolverToCholmod);
  ASSERT_LT(reference, 0.0);
  for (auto choose : { &vtkCorotationalHexFemFilter::SetLinearSolverToConjugateGradient,
         &vtkCorotationalHexFemFilter::SetLinearSolverToStaleFactorConjugateGradient,
         &vtkCorotationalHexFemFilter::SetLinearSolverToMultigridConjugateGradient,
         &vtkCorotationalHexFemFilter::SetLinearSolverToAutomatic })
  {
    EXPECT_NEAR(tipAfterSteps(choose), reference, 1e-6 * std::abs(reference));
  }
}

TEST(vtkCorotationalHexFemFilter, BadParametersGiveAnErrorAndAnEmptyOutput)
{
  auto rest = cantilever(4, 1);
  const auto expectError = [&](vtkCorotationalHexFemFilter* fem, const std::string& words)
  {
    auto errors = observeErrors(fem);
    fem->Update();
    EXPECT_GE(errors->count, 1);
    EXPECT_NE(errors->all.find(words), std::string::npos) << errors->all;
    EXPECT_EQ(fem->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(fem->GetOutput()->GetNumberOfCells(), 0);
  };
  {
    vtkNew<vtkCorotationalHexFemFilter> fem;
    fem->SetInputData(rest);
    fem->SetPoissonRatio(0.5);
    expectError(fem, "Poisson");
  }
  {
    vtkNew<vtkCorotationalHexFemFilter> fem;
    fem->SetInputData(rest);
    fem->SetYoungModulus(0.0);
    expectError(fem, "oung");
  }
  {
    vtkNew<vtkCorotationalHexFemFilter> fem;
    fem->SetInputData(rest);
    fem->SetNumberOfSteps(3);
    fem->SetTimeStep(0.0);
    expectError(fem, "time step");
  }
  {
    // A good grid first, then a tetrahedron appended: the old output goes.
    auto mixed = vtkSmartPointer<vtkUnstructuredGrid>::New();
    mixed->DeepCopy(rest);
    const vtkIdType tetra[4] = { 0, 1, 2, 5 };
    vtkNew<vtkCorotationalHexFemFilter> fem;
    fem->SetInputData(mixed);
    fem->Update();
    EXPECT_GT(fem->GetOutput()->GetNumberOfPoints(), 0);
    mixed->InsertNextCell(VTK_TETRA, 4, tetra);
    mixed->Modified();
    expectError(fem, "not a hexahedron");
  }
  {
    // A malformed force array.
    auto bad = vtkSmartPointer<vtkUnstructuredGrid>::New();
    bad->DeepCopy(rest);
    vtkNew<vtkDoubleArray> force;
    force->SetName("ExternalForce");
    force->SetNumberOfTuples(bad->GetNumberOfPoints());
    force->FillValue(1.0);
    bad->GetPointData()->AddArray(force);
    vtkNew<vtkCorotationalHexFemFilter> fem;
    fem->SetInputData(bad);
    expectError(fem, "ExternalForce");
  }
}

TEST(vtkCorotationalHexFemFilter, FailedSolveReportsAndKeepsTheLastGoodState)
{
  // No fixed node: no unique static equilibrium. The rest state is output.
  auto rest = cantilever(4, 1);
  rest->GetPointData()->RemoveArray("FixedNode");
  vtkNew<vtkCorotationalHexFemFilter> fem;
  fem->SetInputData(rest);
  auto errors = observeErrors(fem);
  fem->Update();
  EXPECT_EQ(errors->count, 1) << errors->all;
  EXPECT_NE(errors->all.find("no fixed node"), std::string::npos) << errors->all;
  EXPECT_FALSE(fem->GetLastSolveSucceeded());
  EXPECT_EQ(fem->GetNumberOfFixedNodes(), 0);
  vtkUnstructuredGrid* output = fem->GetOutput();
  ASSERT_EQ(output->GetNumberOfPoints(), rest->GetNumberOfPoints());
  for (vtkIdType i = 0; i < rest->GetNumberOfPoints(); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(output->GetPoint(i)[a], rest->GetPoint(i)[a]);
    }
  }
  // A free body is legal for time steps.
  fem->SetNumberOfSteps(5);
  fem->Update();
  EXPECT_EQ(errors->count, 1) << errors->all;
  EXPECT_TRUE(fem->GetLastSolveSucceeded());
}

TEST(vtkCorotationalHexFemFilter, PrintSelfNamesTheParameters)
{
  vtkNew<vtkCorotationalHexFemFilter> fem;
  fem->SetYoungModulus(150.0);
  fem->SetPoissonRatio(0.45);
  fem->SetGravity(0.0, 0.0, -9.81);
  fem->SetLinearSolverToStaleFactorConjugateGradient();
  fem->SetNumberOfSteps(12);
  std::ostringstream print;
  fem->Print(print);
  const std::string text = print.str();
  for (const char* expected : { "YoungModulus: 150",
         "PoissonRatio: 0.45",
         "Density: 1000",
         "TimeStep: 0.01",
         "NumberOfSteps: 12",
         "RayleighMass: 0.1",
         "RayleighStiffness: 0.01",
         "Gravity: 0 0 -9.81",
         "Corotational: On",
         "LinearSolver: StaleFactorConjugateGradient",
         "NumberOfFixedNodes: 0" })
  {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
  fem->SetLinearSolver(7); // clamped
  EXPECT_EQ(fem->GetLinearSolver(), vtkCorotationalHexFemFilter::MULTIGRID_CONJUGATE_GRADIENT);
  fem->SetLinearSolverToMultigridConjugateGradient();
  EXPECT_STREQ(fem->GetLinearSolverAsString(), "MultigridConjugateGradient");
  fem->SetNumberOfSteps(-3);
  EXPECT_EQ(fem->GetNumberOfSteps(), 0);
}
