"""Surgical operations from Python (thesis 6.4): the basket punch's bite at
the meniscus's inner border, made by vtkInstrumentBladeSource and given to
vtkThinTissueCutFilter with free pieces dropped, takes a piece out; with a
jagged cut surface the bitten rim is rough (field data RimRoughness) and
contouring passes at the bite smooth it, removing nothing (6.4.4); shaving
passes remove the collision triangles the window holds and the cut surface
closes the opening (6.4.3); the probe hook makes no blade."""
import math
import unittest

import vtk
import thintissue


def collision_area(polydata):
    """Area of the collision triangles (a dropped piece leaves the output)."""
    mass = vtk.vtkMassProperties()
    mass.SetInputData(polydata)
    mass.Update()
    return mass.GetSurfaceArea()


def punch_pose(monitors, instrument_bite_centre, where=0.5):
    """Tool frame to world: the punch's working side up (+z), its shaft
    toward the meniscus's open centre, its bite centred on the inner
    border at fraction `where` along it, the fixed jaw 0.6 mm below it."""
    middle = int(where * (monitors.GetNumberOfPoints() - 1))
    rim = monitors.GetPoint(middle)
    region = monitors.GetPointData().GetArray("RegionPoint").GetTuple3(middle)
    inward = [region[0] - rim[0], region[1] - rim[1], 0.0]
    length = math.hypot(inward[0], inward[1])
    handle = [-inward[0] / length, -inward[1] / length, 0.0]  # to the centre
    up = [0.0, 0.0, 1.0]
    side = [handle[1] * up[2] - handle[2] * up[1],
            handle[2] * up[0] - handle[0] * up[2],
            handle[0] * up[1] - handle[1] * up[0]]
    columns = (up, side, handle)  # tool x, y, z in the world
    target = (rim[0], rim[1], rim[2] - 0.6)
    pose = vtk.vtkMatrix4x4()
    for r in range(3):
        for c in range(3):
            pose.SetElement(r, c, columns[c][r])
        moved = sum(columns[c][r] * instrument_bite_centre[c] for c in range(3))
        pose.SetElement(r, 3, target[r] - moved)
    return pose


class OperationsTest(unittest.TestCase):
    def setUp(self):
        self.meniscus = thintissue.vtkMeniscusSource()
        self.meniscus.SetExaminationResolution()
        self.meniscus.Update()
        binding = thintissue.vtkVisualCollisionBindingFilter()
        binding.SetInputConnection(0, self.meniscus.GetOutputPort(0))
        binding.SetCollisionConnection(self.meniscus.GetOutputPort(1))
        self.cut = thintissue.vtkThinTissueCutFilter()
        self.cut.SetInputConnection(0, binding.GetOutputPort(0))
        self.cut.SetCollisionConnection(self.meniscus.GetOutputPort(1))
        self.cut.SetSimulationConnection(self.meniscus.GetOutputPort(2))
        self.cut.SetFreePieces(thintissue.vtkThinTissueCutFilter.DROP_FREE_PIECES)
        self.blade = thintissue.vtkInstrumentBladeSource()
        self.cut.SetBladeConnection(self.blade.GetOutputPort())

    def test_a_punch_bite_takes_a_piece_out(self):
        monitors = self.meniscus.GetMonitorPointsOutput()
        # The punch's bite outline is centred 1.9 mm up its shaft from the
        # tip (biteLength 3.5 mm from the jaw's end, SurgicalInstruments.h).
        self.blade.SetInstrument(1)
        self.blade.Update()
        bounds = self.blade.GetOutput().GetBounds()
        self.assertGreater(self.blade.GetOutput().GetNumberOfCells(), 0)
        centre_z = 0.5 * (bounds[4] + bounds[5])  # tool frame at identity
        centre_y = 0.5 * (bounds[2] + bounds[3])
        self.blade.SetPose(punch_pose(monitors, (0.0, centre_y, centre_z)))
        before = collision_area(self.meniscus.GetCollisionOutput())
        self.cut.Update()
        self.assertEqual(self.cut.GetLastErrorMessage(), "")
        self.assertTrue(self.cut.GetLastCutChangedTissue())
        after = collision_area(self.cut.GetCollisionOutput())
        self.assertLess(after, before - 1.0)  # mm^2 went with the piece

    def bite_in_the_middle_of_the_border(self, where=0.5):
        monitors = self.meniscus.GetMonitorPointsOutput()
        self.blade.SetInstrument(1)
        self.blade.Update()
        bounds = self.blade.GetOutput().GetBounds()
        centre = (0.0, 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]))
        self.blade.SetPose(punch_pose(monitors, centre, where))
        self.cut.Update()
        self.assertEqual(self.cut.GetLastErrorMessage(), "")
        self.assertTrue(self.cut.GetLastCutChangedTissue())
        return monitors.GetPoint(int(where * (monitors.GetNumberOfPoints() - 1)))

    def test_settings_changed_between_bites_apply_to_the_next(self):
        self.bite_in_the_middle_of_the_border()
        self.assertEqual(self.rim_roughness(), 0.0)
        self.cut.SetJaggedAmplitude(0.3)
        self.bite_in_the_middle_of_the_border(0.3)
        self.assertEqual(self.cut.GetNumberOfCuts(), 2)
        self.assertGreater(self.rim_roughness(), 0.0)
        # A new row count once cut is an error; the tissue stays as it was.
        cells = self.cut.GetVisualOutput().GetNumberOfCells()
        self.cut.SetCutSurfaceRows(3)
        self.cut.GlobalWarningDisplayOff()
        self.cut.Update()
        self.assertIn("rows", self.cut.GetLastErrorMessage())
        self.assertEqual(self.cut.GetVisualOutput().GetNumberOfCells(), cells)
        self.assertEqual(self.cut.GetNumberOfCuts(), 2)

    def rim_roughness(self):
        field = self.cut.GetVisualOutput().GetFieldData()
        self.assertEqual(field.GetArray("RimRoughness").GetValue(0),
                         self.cut.GetRimRoughness())
        return self.cut.GetRimRoughness()

    def test_a_jagged_bite_is_smoothed_by_contouring_passes(self):
        self.cut.SetJaggedAmplitude(0.3)
        self.cut.SetJaggedSeed(5)
        rim = self.bite_in_the_middle_of_the_border()
        jagged = self.rim_roughness()
        self.assertGreater(jagged, 0.03)  # mm
        self.assertGreaterEqual(self.cut.GetRimRoughnessMaximum(), jagged)
        area = collision_area(self.cut.GetCollisionOutput())
        cells = self.cut.GetVisualOutput().GetNumberOfCells()
        # Passes of a tool held on the bitten rim (a 3 mm sphere about the
        # bite's centre, full strength): the jaggedness goes, nothing else.
        for _ in range(3):
            self.cut.AddContourPass(rim[0], rim[1], rim[2], 3.0, 1.0)
        self.cut.Update()
        self.assertEqual(self.cut.GetLastErrorMessage(), "")
        self.assertEqual(self.cut.GetNumberOfContourPasses(), 3)
        moved = self.cut.GetVisualOutput().GetFieldData().GetArray("ContouredVertices")
        self.assertGreater(moved.GetValue(0), 0)
        self.assertLess(self.rim_roughness(), 0.5 * jagged)
        self.assertEqual(self.cut.GetNumberOfCuts(), 1)
        self.assertAlmostEqual(collision_area(self.cut.GetCollisionOutput()), area, places=9)
        self.assertEqual(self.cut.GetVisualOutput().GetNumberOfCells(), cells)

    def test_a_smooth_bite_has_no_roughness_and_a_bad_pass_is_reported(self):
        rim = self.bite_in_the_middle_of_the_border()
        self.assertEqual(self.rim_roughness(), 0.0)
        self.cut.AddContourPass(rim[0], rim[1], rim[2], -1.0, 0.5)
        self.cut.GlobalWarningDisplayOff()
        self.cut.Update()
        self.assertIn("radius", self.cut.GetLastErrorMessage())

    def open_edges(self):
        """Boundary and non-manifold edges of the visual output."""
        edges = vtk.vtkFeatureEdges()
        edges.SetInputData(self.cut.GetVisualOutput())
        edges.FeatureEdgesOff()
        edges.ManifoldEdgesOff()
        edges.BoundaryEdgesOn()
        edges.NonManifoldEdgesOn()
        edges.Update()
        return edges.GetOutput().GetNumberOfCells()

    def test_shaving_passes_remove_what_the_window_holds_and_close_the_surface(self):
        self.cut.Update()  # the tissue, uncut
        self.assertEqual(self.open_edges(), 0)
        area = collision_area(self.cut.GetCollisionOutput())
        monitors = self.meniscus.GetMonitorPointsOutput()
        count = monitors.GetNumberOfPoints()
        # A running shaver along the inner border: five windows 0.5 mm apart.
        first = count // 2
        for k in range(5):
            p = monitors.GetPoint(first + k)
            self.cut.AddShavingPass(p[0], p[1], p[2], 1.7)
        self.cut.Update()
        self.assertEqual(self.cut.GetLastErrorMessage(), "")
        shaved = self.cut.GetLastShavedTriangles()
        self.assertGreater(shaved, 0)
        self.assertGreater(self.cut.GetNumberOfShavingPasses(), 0)
        self.assertLess(collision_area(self.cut.GetCollisionOutput()), area - 0.5)
        self.assertEqual(self.open_edges(), 0)  # the cut surface closes it
        material = self.cut.GetVisualOutput().GetCellData().GetArray("Material")
        self.assertGreater(material.GetRange()[1], 0)  # cut-surface triangles
        # The same windows again hold nothing: nothing more goes.
        cells = self.cut.GetVisualOutput().GetNumberOfCells()
        p = monitors.GetPoint(first)
        self.cut.AddShavingPass(p[0], p[1], p[2], 1.7)
        self.cut.Update()
        self.assertEqual(self.cut.GetLastShavedTriangles(), 0)
        self.assertEqual(self.cut.GetVisualOutput().GetNumberOfCells(), cells)
        # A window of no size is reported; the tissue stays as it was.
        self.cut.AddShavingPass(p[0], p[1], p[2], -1.0)
        self.cut.GlobalWarningDisplayOff()
        self.cut.Update()
        self.assertIn("radius", self.cut.GetLastErrorMessage())
        self.assertEqual(self.cut.GetVisualOutput().GetNumberOfCells(), cells)

    def test_the_probe_makes_no_blade(self):
        self.blade.SetInstrument(0)
        self.blade.Update()
        self.assertEqual(self.blade.GetOutput().GetNumberOfCells(), 0)


if __name__ == "__main__":
    unittest.main()
