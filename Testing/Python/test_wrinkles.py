"""Procedural wrinkles from Python: the meniscus source's surface embedded in
its hexahedra, the hexahedra pressed and released through
vtkWrinkleDisplacementFilter; wrinkles appear on the release, near the
contact only, with every parameter settable; bad input is reported."""
import math
import unittest

import vtk
import thintissue


class WrinklesTest(unittest.TestCase):
    def setUp(self):
        self.meniscus = thintissue.vtkMeniscusSource()
        self.meniscus.SetExaminationResolution()
        self.meniscus.SetMonitorPointSpacing(0.16)
        self.meniscus.Update()
        self.rest = self.meniscus.GetSimulationOutput()
        self.grid = vtk.vtkUnstructuredGrid()
        self.grid.DeepCopy(self.rest)
        embed = thintissue.vtkHexahedralEmbeddingFilter()
        embed.SetInputConnection(self.meniscus.GetOutputPort(0))
        embed.SetGridConnection(self.meniscus.GetOutputPort(2))
        self.deform = thintissue.vtkEmbeddedSurfaceDeformationFilter()
        self.deform.SetInputConnection(embed.GetOutputPort())
        self.deform.SetGridData(self.grid)
        self.wrinkles = thintissue.vtkWrinkleDisplacementFilter()
        self.wrinkles.SetInputConnection(self.deform.GetOutputPort())
        self.wrinkles.SetMonitorPointsConnection(self.meniscus.GetOutputPort(4))
        self.wrinkles.SetGridData(self.grid)
        monitors = self.meniscus.GetMonitorPointsOutput()
        self.contact = monitors.GetPoint(monitors.GetNumberOfPoints() // 2)
        self.wrinkles.SetLowerSurfaceContacts(5)
        self.wrinkles.InstrumentTouchingOn()
        self.wrinkles.SetInstrumentContactPoint(self.contact)

    def step(self, depth):
        points = vtk.vtkPoints()
        displacement = vtk.vtkDoubleArray()
        displacement.SetName("Displacement")
        displacement.SetNumberOfComponents(3)
        cx, cy = self.contact[0], self.contact[1]
        for i in range(self.rest.GetNumberOfPoints()):
            x, y, z = self.rest.GetPoint(i)
            dz = -depth * math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / 16.0)
            displacement.InsertNextTuple3(0.0, 0.0, dz)
            points.InsertNextPoint(x, y, z + dz)
        self.grid.SetPoints(points)
        self.grid.GetPointData().AddArray(displacement)
        self.grid.Modified()
        self.wrinkles.Update()

    def test_release_wrinkles_the_inner_border(self):
        for k in range(1, 11):
            self.step(0.1 * k)
            self.assertFalse(self.wrinkles.GetWrinkling())
        self.step(0.9)
        self.step(0.8)
        self.assertTrue(self.wrinkles.GetWrinkling())
        output = self.wrinkles.GetOutput()
        wrinkle = output.GetPointData().GetArray("WrinkleDisplacement")
        moved = [i for i in range(output.GetNumberOfPoints())
                 if any(abs(c) > 0.0 for c in wrinkle.GetTuple3(i))]
        self.assertGreater(len(moved), 20)
        self.assertLessEqual(len(moved), self.wrinkles.GetNumberOfDisplacedPoints())
        bound = self.wrinkles.GetMagnitudeBound()
        largest = max(math.sqrt(sum(c * c for c in wrinkle.GetTuple3(i))) for i in moved)
        self.assertGreater(largest, 0.0)
        for i in moved:
            x = output.GetPoint(i)
            self.assertLess(math.hypot(x[0] - self.contact[0], x[1] - self.contact[1]), 12.0)
        self.assertGreater(bound, 0.0)

    def test_automatic_monitor_points_from_the_collision_mesh(self):
        automatic = thintissue.vtkAutomaticMonitorPointsFilter()
        automatic.SetInputConnection(self.meniscus.GetOutputPort(1))
        automatic.Update()
        data = automatic.GetOutput()
        self.assertGreater(data.GetNumberOfPoints(), 10)
        self.assertIsNotNone(data.GetPointData().GetArray("RegionPoint"))
        self.wrinkles.SetMonitorPointsConnection(automatic.GetOutputPort())
        self.wrinkles.SetMonitorPointSpacing(0.16)
        for k in range(1, 11):
            self.step(0.1 * k)
        self.step(0.9)
        self.assertTrue(self.wrinkles.GetWrinkling())

    def test_parameters_round_trip(self):
        f = self.wrinkles
        f.SetFrequency(7 * math.pi)
        f.SetScale(2.0)
        f.SetMagnitudeBound(0.3)
        f.SetCutOffThickness(0.2)
        f.SetWindowSize(40)
        f.SetReversalThreshold(10)
        f.SetStartContacts(2)
        f.SetEndContacts(3)
        f.SetGaussianWidth(1.5)
        f.SetAnchor(thintissue.vtkWrinkleDisplacementFilter.ANCHOR_REFERENCE)
        self.assertEqual(f.GetAnchor(), 1)
        self.assertIn("Anchor: Reference", str(f))
        self.assertAlmostEqual(f.GetFrequency(), 7 * math.pi)
        self.assertEqual((f.GetScale(), f.GetMagnitudeBound(), f.GetCutOffThickness()),
                         (2.0, 0.3, 0.2))
        self.assertEqual((f.GetWindowSize(), f.GetReversalThreshold()), (40, 10))
        self.assertEqual((f.GetStartContacts(), f.GetEndContacts()), (2, 3))
        self.assertEqual(f.GetGaussianWidth(), 1.5)
        self.step(0.1)
        self.assertGreater(f.GetOutput().GetNumberOfPoints(), 0)

    def test_bad_parameter_is_reported(self):
        messages = []

        @vtk.calldata_type(vtk.VTK_STRING)
        def on_error(caller, event, message):
            messages.append(message)

        self.wrinkles.AddObserver("ErrorEvent", on_error)
        self.wrinkles.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)
        self.wrinkles.SetFrequency(-1.0)
        self.step(0.1)
        self.assertEqual(len(messages), 1)
        self.assertIn("frequency", messages[0])
        self.assertEqual(self.wrinkles.GetOutput().GetNumberOfPoints(), 0)


if __name__ == "__main__":
    unittest.main()
