"""Embedding in Python: a closed surface is voxelized into a hexahedral grid,
embedded in it, and follows the grid when the grid moves (x = H u)."""
import unittest

import vtk
import thintissue


def make_slab():
    slab = thintissue.vtkThinSlabSource()
    slab.SetWidth(8.0)
    slab.SetDepth(6.0)
    slab.SetThickness(1.0)
    slab.SetCellsX(16)
    slab.SetCellsY(12)
    return slab


class EmbeddingTest(unittest.TestCase):
    def test_surface_follows_translated_grid(self):
        slab = make_slab()
        voxelize = thintissue.vtkSurfaceToHexahedralGridFilter()
        voxelize.SetInputConnection(slab.GetOutputPort())
        voxelize.SetCellsAlongLongestSide(6)
        embed = thintissue.vtkHexahedralEmbeddingFilter()
        embed.SetInputConnection(slab.GetOutputPort())
        embed.SetGridConnection(voxelize.GetOutputPort())
        embed.Update()

        grid = voxelize.GetOutput()
        self.assertGreater(grid.GetNumberOfCells(), 0)
        self.assertEqual(grid.GetCellType(0), vtk.VTK_HEXAHEDRON)
        embedded = embed.GetOutput()
        ids = embedded.GetPointData().GetArray("HexahedronId")
        coordinates = embedded.GetPointData().GetArray("TrilinearCoordinates")
        self.assertIsNotNone(ids)
        self.assertIsNotNone(coordinates)
        self.assertEqual(coordinates.GetNumberOfComponents(), 3)
        self.assertEqual(ids.GetNumberOfTuples(), embedded.GetNumberOfPoints())
        self.assertEqual(embed.GetNumberOfOutsidePoints(), 0)

        translation = vtk.vtkTransform()
        translation.Translate(2.0, -1.0, 0.5)
        move = vtk.vtkTransformFilter()
        move.SetInputConnection(voxelize.GetOutputPort())
        move.SetTransform(translation)
        deform = thintissue.vtkEmbeddedSurfaceDeformationFilter()
        deform.SetInputConnection(embed.GetOutputPort())
        deform.SetGridConnection(move.GetOutputPort())
        deform.Update()

        rest = slab.GetOutput()
        moved = deform.GetOutput()
        self.assertEqual(moved.GetNumberOfPoints(), rest.GetNumberOfPoints())
        self.assertEqual(moved.GetNumberOfPolys(), rest.GetNumberOfPolys())
        for i in range(rest.GetNumberOfPoints()):
            p = rest.GetPoint(i)
            q = moved.GetPoint(i)
            self.assertAlmostEqual(q[0] - p[0], 2.0, places=10)
            self.assertAlmostEqual(q[1] - p[1], -1.0, places=10)
            self.assertAlmostEqual(q[2] - p[2], 0.5, places=10)

    def test_open_surface_gives_clear_error(self):
        messages = []

        @vtk.calldata_type(vtk.VTK_STRING)
        def on_error(caller, event, message):
            messages.append(message)

        plane = vtk.vtkPlaneSource()  # open: not a closed surface
        voxelize = thintissue.vtkSurfaceToHexahedralGridFilter()
        voxelize.SetInputConnection(plane.GetOutputPort())
        voxelize.AddObserver("ErrorEvent", on_error)
        voxelize.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)
        voxelize.Update()
        self.assertEqual(len(messages), 1)
        self.assertIn("not closed", messages[0])
        self.assertEqual(voxelize.GetOutput().GetNumberOfCells(), 0)

    def test_print_self_names_parameters(self):
        self.assertIn("CellsAlongLongestSide: 10", str(thintissue.vtkSurfaceToHexahedralGridFilter()))
        self.assertIn("MaximumExtrapolation: 1", str(thintissue.vtkHexahedralEmbeddingFilter()))


if __name__ == "__main__":
    unittest.main()
