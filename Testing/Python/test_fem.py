"""Co-rotational FEM from Python: a hexahedral grid with fixed nodes and an
external force is deformed by a static solve and by time steps; it moves in
the direction of the load; bad parameters are reported, not crashed on."""
import unittest

import vtk
import thintissue


def sheet_grid():
    """The thesis sheet's 81 hexahedra, fixed along two edges ("FixedNode"
    from the source), with a force along -z on every free node."""
    sheet = thintissue.vtkThinSheetSource()
    sheet.Update()
    grid = vtk.vtkUnstructuredGrid()
    grid.DeepCopy(sheet.GetSimulationOutput())
    fixed = grid.GetPointData().GetArray("FixedNode")
    force = vtk.vtkDoubleArray()
    force.SetName("ExternalForce")
    force.SetNumberOfComponents(3)
    force.SetNumberOfTuples(grid.GetNumberOfPoints())
    for i in range(grid.GetNumberOfPoints()):
        force.SetTuple3(i, 0.0, 0.0, 0.0 if fixed.GetTuple1(i) else -0.05)
    grid.GetPointData().AddArray(force)
    return grid


def slab_grid():
    """A slab voxelized into hexahedra, clamped at its smallest x."""
    slab = thintissue.vtkThinSlabSource()
    slab.SetWidth(8.0)
    slab.SetDepth(2.0)
    slab.SetThickness(1.0)
    voxelize = thintissue.vtkSurfaceToHexahedralGridFilter()
    voxelize.SetInputConnection(slab.GetOutputPort())
    voxelize.SetCellsAlongLongestSide(8)
    voxelize.Update()
    grid = vtk.vtkUnstructuredGrid()
    grid.DeepCopy(voxelize.GetOutput())
    left = grid.GetBounds()[0]
    fixed = grid.GetPointData().GetArray("FixedNode")
    for i in range(grid.GetNumberOfPoints()):
        fixed.SetTuple1(i, 1 if grid.GetPoint(i)[0] < left + 1e-9 else 0)
    return grid


def mean_z_motion(rest, deformed):
    n = rest.GetNumberOfPoints()
    return sum(deformed.GetPoint(i)[2] - rest.GetPoint(i)[2] for i in range(n)) / n


class FemTest(unittest.TestCase):
    def make_filter(self, grid):
        fem = thintissue.vtkCorotationalHexFemFilter()
        fem.SetInputData(grid)
        fem.SetYoungModulus(1.0e3)
        fem.SetPoissonRatio(0.3)
        fem.SetDensity(1.0e-3)
        return fem

    def test_static_solve_moves_along_the_force(self):
        grid = sheet_grid()
        fem = self.make_filter(grid)
        fem.SetNumberOfSteps(0)
        fem.Update()
        self.assertTrue(fem.GetLastSolveSucceeded())
        self.assertGreater(fem.GetNumberOfFixedNodes(), 0)
        self.assertGreaterEqual(fem.GetLastIterations(), 1)
        out = fem.GetOutput()
        self.assertEqual(out.GetNumberOfPoints(), grid.GetNumberOfPoints())
        self.assertEqual(out.GetNumberOfCells(), grid.GetNumberOfCells())
        self.assertEqual(out.GetCellType(0), vtk.VTK_HEXAHEDRON)
        self.assertLess(mean_z_motion(grid, out), 0.0)
        fixed = grid.GetPointData().GetArray("FixedNode")
        displacement = out.GetPointData().GetArray("Displacement")
        self.assertIsNotNone(displacement)
        self.assertIsNotNone(out.GetPointData().GetArray("Velocity"))
        self.assertIsNotNone(out.GetPointData().GetArray("ExternalForce"))
        for i in range(grid.GetNumberOfPoints()):
            p, q = grid.GetPoint(i), out.GetPoint(i)
            d = displacement.GetTuple3(i)
            for a in range(3):
                self.assertAlmostEqual(d[a], q[a] - p[a], places=12)
            if fixed.GetTuple1(i):
                self.assertEqual(p, q)

    def test_time_steps_move_along_the_force(self):
        grid = sheet_grid()
        fem = self.make_filter(grid)
        fem.SetNumberOfSteps(10)
        fem.SetTimeStep(0.01)
        progress = []
        fem.AddObserver("ProgressEvent", lambda caller, event: progress.append(caller.GetProgress()))
        fem.Update()
        self.assertTrue(fem.GetLastSolveSucceeded())
        self.assertEqual(fem.GetNumberOfCompletedSteps(), 10)
        self.assertGreaterEqual(len(progress), 10)
        self.assertEqual(progress[-1], 1.0)
        out = fem.GetOutput()
        self.assertLess(mean_z_motion(grid, out), 0.0)
        velocity = out.GetPointData().GetArray("Velocity")
        self.assertLess(min(velocity.GetComponent(i, 2) for i in range(out.GetNumberOfPoints())), 0.0)

    def test_voxelized_slab_sags_under_gravity(self):
        grid = slab_grid()
        fem = self.make_filter(grid)
        fem.SetGravity(0.0, 0.0, -9.81)
        fem.SetNumberOfSteps(5)
        fem.SetLinearSolver(thintissue.vtkCorotationalHexFemFilter.CHOLMOD)
        fem.Update()
        self.assertTrue(fem.GetLastSolveSucceeded())
        self.assertGreater(fem.GetNumberOfFixedNodes(), 0)
        self.assertLess(mean_z_motion(grid, fem.GetOutput()), 0.0)

    def test_poisson_ratio_one_half_gives_clear_error(self):
        messages = []

        @vtk.calldata_type(vtk.VTK_STRING)
        def on_error(caller, event, message):
            messages.append(message)

        fem = self.make_filter(sheet_grid())
        fem.SetPoissonRatio(0.5)
        fem.AddObserver("ErrorEvent", on_error)
        fem.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)
        fem.Update()
        self.assertEqual(len(messages), 1)
        self.assertIn("Poisson", messages[0])
        self.assertEqual(fem.GetOutput().GetNumberOfPoints(), 0)
        self.assertEqual(fem.GetOutput().GetNumberOfCells(), 0)

    def test_print_self_names_parameters(self):
        text = str(thintissue.vtkCorotationalHexFemFilter())
        for expected in ("YoungModulus: 100000", "PoissonRatio: 0.3", "TimeStep: 0.01",
                         "NumberOfSteps: 0", "LinearSolver: Automatic", "Corotational: On"):
            self.assertIn(expected, text)


if __name__ == "__main__":
    unittest.main()
