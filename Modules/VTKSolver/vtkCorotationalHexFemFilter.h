/**
 * @class vtkCorotationalHexFemFilter
 * @brief Deforms a hexahedral grid with the co-rotational linear FEM and
 * implicit Euler integration of the thesis (section 4.2): a static solve, or
 * NumberOfSteps time steps from rest.
 *
 * Input: a vtkUnstructuredGrid of VTK_HEXAHEDRON cells (corners in VTK
 * order), its points the rest shape, with optional point arrays
 * "FixedNode" (1 component, nonzero = the node keeps its position) and
 * "ExternalForce" (3 components, a force per node).
 *
 * Output: the same cells and arrays with the points moved, plus the point
 * arrays "Displacement" (output minus input points) and "Velocity" (zero
 * after a static solve), 3 doubles each.
 *
 * Every update starts again from the input at rest: the filter keeps no
 * simulation state between updates (the real-time loop lives in the Scene
 * layer).
 *
 * Errors: a non-hexahedral cell, an inverted or degenerate hexahedron, a bad
 * material or time step (E <= 0, nu outside (-1, 0.5), density <= 0,
 * dt <= 0), a malformed or non-finite "ExternalForce" are reported with
 * vtkErrorMacro and give an empty output. A solver failure during the run
 * (no convergence, non-finite state, a static solve without fixed node) is
 * reported too, and the output then holds the last good state
 * (GetLastSolveSucceeded() is false).
 */
#ifndef vtkCorotationalHexFemFilter_h
#define vtkCorotationalHexFemFilter_h

#include "ThinTissueVTKSolverModule.h"
#include "vtkUnstructuredGridAlgorithm.h"

class THINTISSUEVTKSOLVER_EXPORT vtkCorotationalHexFemFilter : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkCorotationalHexFemFilter* New();
  vtkTypeMacro(vtkCorotationalHexFemFilter, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Linear solvers of the FEM system (see thintissue::LinearSolverKind).
  enum LinearSolvers
  {
    CHOLMOD = 0,
    CONJUGATE_GRADIENT = 1,
    STALE_FACTOR_CONJUGATE_GRADIENT = 2,
    AUTOMATIC = 3,
    MULTIGRID_CONJUGATE_GRADIENT = 4
  };

  ///@{
  /// Isotropic linear material, in consistent units. Defaults: E = 1e5,
  /// nu = 0.3, density = 1e3.
  vtkSetMacro(YoungModulus, double);
  vtkGetMacro(YoungModulus, double);
  vtkSetMacro(PoissonRatio, double);
  vtkGetMacro(PoissonRatio, double);
  vtkSetMacro(Density, double);
  vtkGetMacro(Density, double);
  ///@}

  ///@{
  /// Implicit Euler time step. Default 0.01.
  vtkSetMacro(TimeStep, double);
  vtkGetMacro(TimeStep, double);
  ///@}

  ///@{
  /// Time steps to run from rest; 0 (the default) solves for the static
  /// equilibrium instead, which needs at least one fixed node.
  vtkSetClampMacro(NumberOfSteps, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfSteps, int);
  ///@}

  ///@{
  /// Newton iterations allowed to the static solve. Default 30.
  vtkSetClampMacro(MaximumStaticIterations, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaximumStaticIterations, int);
  ///@}

  ///@{
  /// Rayleigh damping D = RayleighMass M + RayleighStiffness K. Defaults
  /// 0.1 and 0.01.
  vtkSetMacro(RayleighMass, double);
  vtkGetMacro(RayleighMass, double);
  vtkSetMacro(RayleighStiffness, double);
  vtkGetMacro(RayleighStiffness, double);
  ///@}

  ///@{
  /// Gravity acceleration. Default (0, 0, 0).
  vtkSetVector3Macro(Gravity, double);
  vtkGetVector3Macro(Gravity, double);
  ///@}

  ///@{
  /// On (the default): co-rotational FEM. Off: plain linear FEM, for
  /// comparison (it inflates under large rotations).
  vtkSetMacro(Corotational, vtkTypeBool);
  vtkGetMacro(Corotational, vtkTypeBool);
  vtkBooleanMacro(Corotational, vtkTypeBool);
  ///@}

  ///@{
  /// Linear solver: CHOLMOD, CONJUGATE_GRADIENT,
  /// STALE_FACTOR_CONJUGATE_GRADIENT, MULTIGRID_CONJUGATE_GRADIENT (huge
  /// meshes) or AUTOMATIC (the default).
  vtkSetClampMacro(LinearSolver, int, CHOLMOD, MULTIGRID_CONJUGATE_GRADIENT);
  vtkGetMacro(LinearSolver, int);
  void SetLinearSolverToCholmod() { this->SetLinearSolver(CHOLMOD); }
  void SetLinearSolverToConjugateGradient() { this->SetLinearSolver(CONJUGATE_GRADIENT); }
  void SetLinearSolverToStaleFactorConjugateGradient()
  {
    this->SetLinearSolver(STALE_FACTOR_CONJUGATE_GRADIENT);
  }
  void SetLinearSolverToMultigridConjugateGradient()
  {
    this->SetLinearSolver(MULTIGRID_CONJUGATE_GRADIENT);
  }
  void SetLinearSolverToAutomatic() { this->SetLinearSolver(AUTOMATIC); }
  const char* GetLinearSolverAsString();
  ///@}

  ///@{
  /// After Update(): the fixed nodes of the input, the steps completed, the
  /// linear solver iterations of the last step (Newton iterations of a
  /// static solve) and their sum over the run, and whether the whole run
  /// succeeded.
  vtkGetMacro(NumberOfFixedNodes, vtkIdType);
  vtkGetMacro(NumberOfCompletedSteps, int);
  vtkGetMacro(LastIterations, int);
  vtkGetMacro(TotalIterations, vtkIdType);
  vtkGetMacro(LastSolveSucceeded, vtkTypeBool);
  ///@}

protected:
  vtkCorotationalHexFemFilter() = default;
  ~vtkCorotationalHexFemFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double YoungModulus = 1.0e5;
  double PoissonRatio = 0.3;
  double Density = 1.0e3;
  double TimeStep = 0.01;
  int NumberOfSteps = 0;
  int MaximumStaticIterations = 30;
  double RayleighMass = 0.1;
  double RayleighStiffness = 0.01;
  double Gravity[3] = { 0.0, 0.0, 0.0 };
  vtkTypeBool Corotational = 1;
  int LinearSolver = AUTOMATIC;

  vtkIdType NumberOfFixedNodes = 0;
  int NumberOfCompletedSteps = 0;
  int LastIterations = 0;
  vtkIdType TotalIterations = 0;
  vtkTypeBool LastSolveSucceeded = 0;

private:
  vtkCorotationalHexFemFilter(const vtkCorotationalHexFemFilter&) = delete;
  void operator=(const vtkCorotationalHexFemFilter&) = delete;
};

#endif
