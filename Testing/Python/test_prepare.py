"""Automatic collision mid-surface from Python: the thesis's sheet (visual
model 1) gets a 65-vertex mid-surface with radii that the binding filter
accepts; not-thin and open surfaces are reported, not crashed on; an open
sheet given a thickness (vtkThickenOpenSheetsFilter) gets its mid-surface."""
import unittest

import vtk
import thintissue


class CollisionMidSurfaceTest(unittest.TestCase):
    def test_sheet_mid_surface_binds(self):
        sheet = thintissue.vtkThinSheetSource()
        sheet.SetThesisVisualModel(1)
        generator = thintissue.vtkCollisionMidSurfaceFilter()
        generator.SetInputConnection(sheet.GetOutputPort(0))
        generator.SetVertexCount(65)
        stages = []
        generator.AddObserver(
            "ProgressEvent", lambda caller, event: stages.append(caller.GetProgressText()))
        generator.Update()
        self.assertEqual(generator.GetLastErrorMessage(), "")
        collision = generator.GetOutput()
        self.assertEqual(collision.GetNumberOfPoints(), 65)
        radius = collision.GetPointData().GetArray("Radius")
        self.assertIsNotNone(radius)
        self.assertGreater(radius.GetRange()[0], 0.0)
        hausdorff = collision.GetFieldData().GetArray("HausdorffDistance").GetValue(0)
        self.assertAlmostEqual(hausdorff, generator.GetHausdorffDistance())
        self.assertGreater(hausdorff, 0.0)
        self.assertLess(hausdorff, 1.0)  # half the sheet's thickness of 2 mm
        self.assertIn("triangulating", stages)
        # The sheet's outline has no hole: nothing to join.
        self.assertTrue(generator.GetJoinSeenThroughHoles())
        self.assertEqual(generator.GetJoinedHoles(), 0)
        # The lattice phase moves the inner vertices, not the border.
        self.assertEqual(generator.GetLatticePhase(), 0.0)
        first = [collision.GetPoint(i) for i in range(collision.GetNumberOfPoints())]
        generator.SetLatticePhase(1.0 / 3.0)
        generator.Update()
        self.assertEqual(generator.GetLastErrorMessage(), "")
        moved = generator.GetOutput()
        self.assertEqual(moved.GetNumberOfPoints(), 65)
        changed = sum(1 for i in range(65) if moved.GetPoint(i) != first[i])
        self.assertGreater(changed, 0)
        self.assertLess(changed, 65)
        generator.SetLatticePhase(2.0)  # clamped to [0, 1]
        self.assertEqual(generator.GetLatticePhase(), 1.0)
        generator.SetLatticePhase(0.0)
        generator.Update()

        binding = thintissue.vtkVisualCollisionBindingFilter()
        binding.SetInputConnection(0, sheet.GetOutputPort(0))
        binding.SetInputConnection(1, generator.GetOutputPort())
        binding.Update()
        self.assertEqual(binding.GetLastErrorMessage(), "")
        self.assertGreater(binding.GetOutputDataObject(0).GetNumberOfPoints(), 840)

    def test_bad_input_is_reported(self):
        cube = vtk.vtkCubeSource()
        triangles = vtk.vtkTriangleFilter()
        triangles.SetInputConnection(cube.GetOutputPort())
        cleaned = vtk.vtkCleanPolyData()
        cleaned.SetInputConnection(triangles.GetOutputPort())
        generator = thintissue.vtkCollisionMidSurfaceFilter()
        generator.SetInputConnection(cleaned.GetOutputPort())
        quiet = vtk.vtkObject.GetGlobalWarningDisplay()
        vtk.vtkObject.GlobalWarningDisplayOff()
        try:
            generator.Update()
            self.assertIn("not a thin object", generator.GetLastErrorMessage())
            self.assertEqual(generator.GetOutput().GetNumberOfPoints(), 0)

            plane = vtk.vtkPlaneSource()
            plane_triangles = vtk.vtkTriangleFilter()
            plane_triangles.SetInputConnection(plane.GetOutputPort())
            generator.SetInputConnection(plane_triangles.GetOutputPort())
            generator.Update()
            self.assertIn("open", generator.GetLastErrorMessage())
        finally:
            vtk.vtkObject.SetGlobalWarningDisplay(quiet)

    def test_open_sheet_thickened_gets_its_mid_surface(self):
        plane = vtk.vtkPlaneSource()
        plane.SetOrigin(0.0, 0.0, 0.0)
        plane.SetPoint1(40.0, 0.0, 0.0)
        plane.SetPoint2(0.0, 30.0, 0.0)
        plane.SetResolution(40, 30)
        triangles = vtk.vtkTriangleFilter()
        triangles.SetInputConnection(plane.GetOutputPort())
        thicken = thintissue.vtkThickenOpenSheetsFilter()
        thicken.SetInputConnection(triangles.GetOutputPort())
        thicken.SetThickness(2.0)
        thicken.Update()
        self.assertEqual(thicken.GetLastErrorMessage(), "")
        self.assertEqual(thicken.GetThickenedPieces(), 1)
        self.assertEqual(thicken.GetBorderLoops(), 1)
        slab = thicken.GetOutput()
        self.assertEqual(slab.GetNumberOfPoints(), 2 * 41 * 31)
        bounds = slab.GetBounds()
        self.assertAlmostEqual(bounds[4], -1.0)
        self.assertAlmostEqual(bounds[5], 1.0)
        edges = vtk.vtkFeatureEdges()
        edges.SetInputData(slab)
        edges.BoundaryEdgesOn()
        edges.FeatureEdgesOff()
        edges.NonManifoldEdgesOn()
        edges.ManifoldEdgesOff()
        edges.Update()
        self.assertEqual(edges.GetOutput().GetNumberOfCells(), 0)  # closed

        generator = thintissue.vtkCollisionMidSurfaceFilter()
        generator.SetInputConnection(thicken.GetOutputPort())
        generator.SetVertexCount(40)
        generator.Update()
        self.assertEqual(generator.GetLastErrorMessage(), "")
        collision = generator.GetOutput()
        self.assertEqual(collision.GetNumberOfPoints(), 40)
        z = [collision.GetPoint(i)[2] for i in range(collision.GetNumberOfPoints())]
        self.assertLess(max(abs(value) for value in z), 1e-6)  # the plane itself
        radius = collision.GetPointData().GetArray("Radius")
        self.assertAlmostEqual(radius.GetRange()[1], 1.0, places=6)

        quiet = vtk.vtkObject.GetGlobalWarningDisplay()
        vtk.vtkObject.GlobalWarningDisplayOff()
        try:
            thicken.SetThickness(-1.0)
            thicken.Update()
            self.assertIn("thickness must be positive", thicken.GetLastErrorMessage())
            self.assertEqual(thicken.GetOutput().GetNumberOfPoints(), 0)
        finally:
            vtk.vtkObject.SetGlobalWarningDisplay(quiet)


if __name__ == "__main__":
    unittest.main()
