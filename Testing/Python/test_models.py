"""Procedural models from Python: generate the medial meniscus (intact and
torn), check it with the validation filter, write its meshes to .vtp and read
them back; bad parameters are reported, not crashed on."""
import os
import tempfile
import unittest

import vtk
import thintissue


class MeniscusTest(unittest.TestCase):
    def test_meniscus_to_vtp(self):
        meniscus = thintissue.vtkMeniscusSource()
        meniscus.SetTearType(thintissue.vtkMeniscusSource.FlapTear)
        validation = thintissue.vtkTriangleMeshValidationFilter()
        validation.SetInputConnection(meniscus.GetOutputPort(0))
        validation.Update()
        self.assertTrue(validation.GetClosedOutwardSingleSurface(), validation.GetReport())

        with tempfile.TemporaryDirectory() as directory:
            paths = {}
            for port, name in ((0, "visual"), (1, "collision"), (4, "monitor")):
                path = os.path.join(directory, "meniscus-%s.vtp" % name)
                writer = vtk.vtkXMLPolyDataWriter()
                writer.SetInputConnection(meniscus.GetOutputPort(port))
                writer.SetFileName(path)
                self.assertEqual(writer.Write(), 1)
                paths[name] = path
            reader = vtk.vtkXMLPolyDataReader()
            reader.SetFileName(paths["collision"])
            reader.Update()
            collision = reader.GetOutput()
            self.assertGreater(collision.GetNumberOfPoints(), 105)  # the flap doubles lip nodes
            radius = collision.GetPointData().GetArray("Radius")
            self.assertIsNotNone(radius)
            low, high = radius.GetRange()
            self.assertGreater(low, 0.0)
            self.assertLess(high, 4.0)  # half of a rim of at most 7 mm, plus margin
            visual = thintissue.vtkThinTissueMeshReader()
            visual.SetFileName(paths["visual"])
            visual.Update()
            self.assertEqual(visual.GetOutput().GetNumberOfPolys(),
                             meniscus.GetVisualOutput().GetNumberOfPolys())

        hexahedra = meniscus.GetSimulationOutput()
        self.assertEqual(hexahedra.GetCellType(0), vtk.VTK_HEXAHEDRON)
        self.assertEqual(meniscus.GetAllMeshesOutput().GetNumberOfBlocks(), 4)

    def test_segmented_meniscus(self):
        # The segmentation-like test bed: voxelized at MRI spacing, blurred,
        # iso-surfaced, in metres.
        meniscus = thintissue.vtkMeniscusSource()
        segmentation = thintissue.vtkSimulatedSegmentationFilter()
        segmentation.SetInputConnection(meniscus.GetOutputPort(0))
        segmentation.SetVoxelSpacing(0.3, 0.3, 0.9)
        segmentation.SetOutputScale(0.001)
        validation = thintissue.vtkTriangleMeshValidationFilter()
        validation.SetInputConnection(segmentation.GetOutputPort())
        validation.Update()
        self.assertTrue(validation.GetClosedOutwardSingleSurface(), validation.GetReport())
        bounds = segmentation.GetOutput().GetBounds()
        self.assertLess(bounds[1] - bounds[0], 0.1)  # metres: a meniscus is a few cm
        self.assertGreater(segmentation.GetOutput().GetNumberOfPoints(),
                           meniscus.GetVisualOutput().GetNumberOfPoints())

    def test_bad_parameters_are_reported(self):
        sheet = thintissue.vtkThinSheetSource()
        sheet.SetWidth(-1.0)
        messages = []
        sheet.AddObserver("ErrorEvent", lambda caller, event: messages.append(event))
        sheet.Update()
        self.assertEqual(sheet.GetVisualOutput().GetNumberOfPoints(), 0)
        self.assertTrue(messages)


if __name__ == "__main__":
    unittest.main()
