"""The visual-collision binding from Python: bind the thesis's sheet (visual
model 1, collision model 1), check the binding arrays, write the result to
.vtp and read it back; bad input is reported, not crashed on."""
import os
import tempfile
import unittest

import vtk
import thintissue


def sheet_source():
    sheet = thintissue.vtkThinSheetSource()
    sheet.SetThesisVisualModel(1)
    sheet.SetThesisCollisionModel(1)
    return sheet


class BindingTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sheet = sheet_source()
        cls.binding = thintissue.vtkVisualCollisionBindingFilter()
        cls.binding.SetInputConnection(0, cls.sheet.GetOutputPort(0))
        cls.binding.SetCollisionConnection(cls.sheet.GetOutputPort(1))
        cls.binding.Update()

    def test_arrays_and_parameters(self):
        self.assertEqual(self.binding.GetLastErrorMessage(), "")
        visual = self.binding.GetOutputDataObject(0)
        points = visual.GetNumberOfPoints()
        cells = visual.GetNumberOfCells()
        self.assertGreaterEqual(points, self.sheet.GetVisualOutput().GetNumberOfPoints())
        point_data = visual.GetPointData()
        for name, components, type_name in (("BindingKind", 1, "vtkUnsignedCharArray"),
                                            ("BindingElement", 1, "vtkIntArray"),
                                            ("BindingSide", 1, "vtkSignedCharArray"),
                                            ("BindingParameters", 3, "vtkDoubleArray")):
            array = point_data.GetArray(name)
            self.assertIsNotNone(array, name)
            self.assertEqual(array.GetClassName(), type_name)
            self.assertEqual(array.GetNumberOfTuples(), points, name)
            self.assertEqual(array.GetNumberOfComponents(), components, name)
        for name in ("CollisionTriangle", "CollisionSide"):
            array = visual.GetCellData().GetArray(name)
            self.assertIsNotNone(array, name)
            self.assertEqual(array.GetNumberOfTuples(), cells, name)

        parameters = point_data.GetArray("BindingParameters")
        for v in range(points):
            a, b, c = parameters.GetTuple3(v)
            self.assertAlmostEqual(a + b + c, 1.0, places=9, msg="vertex %d" % v)

        paths = self.binding.GetOutputDataObject(1)
        self.assertGreater(paths.GetNumberOfLines(), 0)
        self.assertEqual(paths.GetCellData().GetArray("CollisionEdge").GetNumberOfTuples(),
                         paths.GetNumberOfLines())
        self.assertEqual(paths.GetCellData().GetArray("Side").GetNumberOfTuples(),
                         paths.GetNumberOfLines())

    def test_labelled_rim_paths(self):
        # The labelled equator binds the sheet too; the rim points move onto
        # the border between its halves, so the paths differ from the
        # geodesic ones, and the output is as complete.
        labelled = thintissue.vtkVisualCollisionBindingFilter()
        labelled.SetInputConnection(0, self.sheet.GetOutputPort(0))
        labelled.SetCollisionConnection(self.sheet.GetOutputPort(1))
        labelled.SetRimPathMethodToLabelled()
        self.assertEqual(labelled.GetRimPathMethod(), labelled.RIM_PATHS_LABELLED)
        labelled.Update()
        self.assertEqual(labelled.GetLastErrorMessage(), "")
        paths = labelled.GetOutputDataObject(1)
        self.assertEqual(paths.GetNumberOfLines(),
                         self.binding.GetOutputDataObject(1).GetNumberOfLines())
        kinds = labelled.GetOutputDataObject(0).GetPointData().GetArray("BindingKind")
        self.assertEqual(kinds.GetNumberOfTuples(),
                         labelled.GetOutputDataObject(0).GetNumberOfPoints())

    def test_vtp_round_trip(self):
        visual = self.binding.GetOutputDataObject(0)
        with tempfile.TemporaryDirectory() as directory:
            written = {}
            for port, name in ((0, "bound-visual"), (1, "paths")):
                path = os.path.join(directory, name + ".vtp")
                writer = vtk.vtkXMLPolyDataWriter()
                writer.SetInputConnection(self.binding.GetOutputPort(port))
                writer.SetFileName(path)
                self.assertEqual(writer.Write(), 1)
                written[name] = path
            reader = vtk.vtkXMLPolyDataReader()
            reader.SetFileName(written["bound-visual"])
            reader.Update()
            back = reader.GetOutput()
            self.assertEqual(back.GetNumberOfPoints(), visual.GetNumberOfPoints())
            self.assertEqual(back.GetNumberOfPolys(), visual.GetNumberOfPolys())
            for name in ("BindingKind", "BindingElement", "BindingSide", "BindingParameters"):
                original = visual.GetPointData().GetArray(name)
                read = back.GetPointData().GetArray(name)
                self.assertIsNotNone(read, name)
                self.assertEqual(read.GetDataType(), original.GetDataType(), name)
                for i in range(0, original.GetNumberOfTuples(), 17):
                    self.assertEqual(read.GetTuple(i), original.GetTuple(i), name)
            self.assertEqual(back.GetCellData().GetArray("CollisionTriangle").GetRange(),
                             visual.GetCellData().GetArray("CollisionTriangle").GetRange())

            reader = vtk.vtkXMLPolyDataReader()
            reader.SetFileName(written["paths"])
            reader.Update()
            self.assertEqual(reader.GetOutput().GetNumberOfLines(),
                             self.binding.GetOutputDataObject(1).GetNumberOfLines())

    def test_missing_radius_is_reported(self):
        collision = vtk.vtkPolyData()
        collision.DeepCopy(self.sheet.GetCollisionOutput())
        collision.GetPointData().RemoveArray("Radius")
        binding = thintissue.vtkVisualCollisionBindingFilter()
        binding.SetInputConnection(0, self.sheet.GetOutputPort(0))
        binding.SetCollisionData(collision)
        messages = []
        binding.AddObserver("ErrorEvent", lambda caller, event: messages.append(event))
        binding.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)
        binding.Update()
        self.assertTrue(messages)
        self.assertIn("'Radius'", binding.GetLastErrorMessage())
        self.assertEqual(binding.GetOutputDataObject(0).GetNumberOfPoints(), 0)

    def test_horizontal_cleavage_binds_its_crease(self):
        # The cleaved meniscus's collision mesh has junction edges of three
        # triangles: three paths each (sides 1, -1 and 0, the crease), and a
        # crease vertex (bound to its junction vertex with side 0) beside
        # the top and the bottom ones of every inner junction vertex.
        meniscus = thintissue.vtkMeniscusSource()
        meniscus.SetTearType(thintissue.vtkMeniscusSource.HorizontalCleavageTear)
        binding = thintissue.vtkVisualCollisionBindingFilter()
        binding.SetInputConnection(0, meniscus.GetOutputPort(0))
        binding.SetCollisionConnection(meniscus.GetOutputPort(1))
        binding.Update()
        self.assertEqual(binding.GetLastErrorMessage(), "")
        paths = binding.GetOutputDataObject(1)
        edge = paths.GetCellData().GetArray("CollisionEdge")
        side = paths.GetCellData().GetArray("Side")
        sides_per_edge = {}
        for line in range(paths.GetNumberOfLines()):
            sides_per_edge.setdefault(int(edge.GetTuple1(line)), set()).add(int(side.GetTuple1(line)))
        junctions = [e for e, s in sides_per_edge.items() if s == {-1, 0, 1}]
        self.assertGreaterEqual(len(junctions), 3)

        visual = binding.GetOutputDataObject(0)
        kind = visual.GetPointData().GetArray("BindingKind")
        element = visual.GetPointData().GetArray("BindingElement")
        point_side = visual.GetPointData().GetArray("BindingSide")
        sides_of_vertex = {}
        for v in range(visual.GetNumberOfPoints()):
            if int(kind.GetTuple1(v)) == 0:  # bound to a collision vertex
                sides_of_vertex.setdefault(int(element.GetTuple1(v)), []).append(
                    int(point_side.GetTuple1(v)))
        three_sided = [c for c, s in sides_of_vertex.items() if sorted(s) == [-1, 0, 1]]
        self.assertGreaterEqual(len(three_sided), 2)

    def test_print_self_names_settings(self):
        binding = thintissue.vtkVisualCollisionBindingFilter()
        self.assertIn("RadiusArrayName: Radius", str(binding))
        self.assertTrue(binding.GetParallel())


if __name__ == "__main__":
    unittest.main()
