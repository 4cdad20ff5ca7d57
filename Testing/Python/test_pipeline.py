"""A VTK pipeline in Python with ThinTissue classes: source -> validation ->
VTK filter -> writer -> ThinTissue reader, plus a clear error on bad input."""
import os
import tempfile
import unittest

import vtk
import thintissue


class PipelineTest(unittest.TestCase):
    def test_slab_pipeline_round_trip(self):
        slab = thintissue.vtkThinSlabSource()
        slab.SetWidth(8.0)
        slab.SetDepth(6.0)
        slab.SetThickness(0.5)
        slab.SetCellsX(8)
        slab.SetCellsY(6)
        validation = thintissue.vtkTriangleMeshValidationFilter()
        validation.SetInputConnection(slab.GetOutputPort())
        normals = vtk.vtkPolyDataNormals()
        normals.SetInputConnection(validation.GetOutputPort())
        normals.SplittingOff()
        normals.Update()
        self.assertTrue(validation.GetClosedOutwardSingleSurface(), validation.GetReport())
        self.assertAlmostEqual(validation.GetSignedVolume(), 8.0 * 6.0 * 0.5, places=9)
        triangles = 4 * (8 * 6 + 8 + 6)
        self.assertEqual(normals.GetOutput().GetNumberOfPolys(), triangles)

        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "slab.vtp")
            writer = vtk.vtkXMLPolyDataWriter()
            writer.SetFileName(path)
            writer.SetInputConnection(normals.GetOutputPort())
            self.assertEqual(writer.Write(), 1)
            reader = thintissue.vtkThinTissueMeshReader()
            reader.SetFileName(path)
            reader.Update()
            self.assertEqual(reader.GetLastErrorMessage(), "")
            self.assertEqual(reader.GetOutput().GetNumberOfPolys(), triangles)

    def test_bad_file_gives_clear_error(self):
        reader = thintissue.vtkThinTissueMeshReader()
        reader.GlobalWarningDisplayOff()
        reader.SetFileName("/no/such/tissue.obj")
        reader.Update()
        reader.GlobalWarningDisplayOn()
        self.assertEqual(reader.GetLastErrorMessage(),
                         "mesh file '/no/such/tissue.obj': no such file")
        self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0)

    def test_print_self_names_parameters(self):
        slab = thintissue.vtkThinSlabSource()
        self.assertIn("Thickness: 0.5", str(slab))


if __name__ == "__main__":
    unittest.main()
