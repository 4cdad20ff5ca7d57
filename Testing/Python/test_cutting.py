"""Cutting from Python: bind the thesis's sheet (visual model 1, collision
model 1), cut it in two with a scalpel's swept quad, and check the pieces,
the cut surface and that a bad blade is reported, not crashed on."""
import unittest

import vtk
import thintissue


def scalpel(x, y0, y1):
    """The quad a vertical scalpel sweeps at x from y0 to y1 (two triangles)."""
    points = vtk.vtkPoints()
    for y, z in ((y0, -5.0), (y0, 5.0), (y1, 5.0), (y1, -5.0)):
        points.InsertNextPoint(x, y, z)
    triangles = vtk.vtkCellArray()
    for cell in ((0, 1, 2), (0, 2, 3)):
        triangles.InsertNextCell(3, cell)
    blade = vtk.vtkPolyData()
    blade.SetPoints(points)
    blade.SetPolys(triangles)
    return blade


def pieces(surface):
    connectivity = vtk.vtkPolyDataConnectivityFilter()
    connectivity.SetInputData(surface)
    connectivity.SetExtractionModeToAllRegions()
    connectivity.Update()
    return connectivity.GetNumberOfExtractedRegions()


class CuttingTest(unittest.TestCase):
    def setUp(self):
        self.sheet = thintissue.vtkThinSheetSource()
        self.sheet.SetThesisVisualModel(1)
        self.sheet.SetThesisCollisionModel(1)
        binding = thintissue.vtkVisualCollisionBindingFilter()
        binding.SetInputConnection(0, self.sheet.GetOutputPort(0))
        binding.SetCollisionConnection(self.sheet.GetOutputPort(1))
        self.cut = thintissue.vtkThinTissueCutFilter()
        self.cut.SetInputConnection(0, binding.GetOutputPort(0))
        self.cut.SetCollisionConnection(self.sheet.GetOutputPort(1))
        self.cut.SetSimulationConnection(self.sheet.GetOutputPort(2))
        self.cut.SetCutSurfaceRows(2)

    def test_cut_in_two(self):
        self.cut.SetBladeData(scalpel(3.0, -80.0, 80.0))
        self.cut.Update()
        self.assertEqual(self.cut.GetLastErrorMessage(), "")
        self.assertEqual(self.cut.GetNumberOfCuts(), 1)
        visual = self.cut.GetVisualOutput()
        self.assertEqual(pieces(visual), 2)
        self.assertEqual(pieces(self.cut.GetCollisionOutput()), 2)
        material = visual.GetCellData().GetArray("Material")
        cut_surface = sum(1 for c in range(material.GetNumberOfTuples()) if material.GetValue(c) == 1)
        self.assertGreater(cut_surface, 0)
        # Closed: every edge of the visual surface has two triangles.
        edges = vtk.vtkFeatureEdges()
        edges.SetInputData(visual)
        edges.BoundaryEdgesOn()
        edges.NonManifoldEdgesOn()
        edges.FeatureEdgesOff()
        edges.ManifoldEdgesOff()
        edges.Update()
        self.assertEqual(edges.GetOutput().GetNumberOfCells(), 0)
        self.assertGreater(self.cut.GetSimulationOutput().GetNumberOfCells(),
                           self.sheet.GetSimulationOutput().GetNumberOfCells())

    def test_bad_blade_is_reported(self):
        self.cut.SetBladeData(scalpel(3.0, 5.0, 5.0))
        self.cut.GlobalWarningDisplayOff()
        self.cut.Update()
        self.assertIn("degenerate", self.cut.GetLastErrorMessage())
        self.assertEqual(self.cut.GetNumberOfCuts(), 0)
        self.assertEqual(pieces(self.cut.GetVisualOutput()), 1)


if __name__ == "__main__":
    unittest.main()
