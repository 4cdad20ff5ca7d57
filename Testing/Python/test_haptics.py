"""The haptic interactor style from Python: two scripted styluses (JSON
trajectories written here) drive the instrument prop and the arthroscope
camera on a manual clock; 3D move events reach a Python observer; a missing
trajectory is reported."""
import json
import os
import tempfile
import unittest

import vtk
import thintissue


def write_trajectory(path, start, end):
    samples = []
    for k in range(11):
        s = 0.1 * k
        position = [a + s * (b - a) for a, b in zip(start, end)]
        samples.append({"t": s, "position": position,
                        "orientation": [1.0, 0.0, 0.0, 0.0], "buttons": 1 if k >= 5 else 0})
    with open(path, "w") as f:
        json.dump({"name": os.path.basename(path), "samples": samples}, f)


class HapticsTest(unittest.TestCase):
    def setUp(self):
        self.directory = tempfile.mkdtemp()
        self.scope = os.path.join(self.directory, "scope.json")
        self.tool = os.path.join(self.directory, "tool.json")
        write_trajectory(self.scope, (0, 0, 0), (0, 5, 0))
        write_trajectory(self.tool, (0, 0, 0), (10, 0, 0))
        self.renderer = vtk.vtkRenderer()
        self.window = vtk.vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.AddRenderer(self.renderer)
        self.interactor = vtk.vtkRenderWindowInteractor()
        self.interactor.SetRenderWindow(self.window)
        self.style = thintissue.vtkHapticInteractorStyle()
        self.interactor.SetInteractorStyle(self.style)
        self.style.SetDefaultRenderer(self.renderer)
        self.style.SetBackendToScripted()
        self.style.RealTimeOff()
        self.style.SetScopeTrajectoryFileName(self.scope)
        self.style.SetInstrumentTrajectoryFileName(self.tool)
        self.style.SetInstrumentPortal(20.0, 0.0, 30.0)

    def test_scripted_styluses_move_prop_and_camera(self):
        moves = []
        self.interactor.AddObserver("Move3DEvent", lambda caller, event: moves.append(event))
        prop = vtk.vtkActor()
        self.style.SetInstrumentProp(prop)
        self.assertTrue(self.style.StartDevices(), self.style.GetLastErrorMessage())
        self.style.AdvanceTo(0.5)
        tip = [0.0, 0.0, 0.0]
        self.style.GetInstrumentTip(tip)
        # Portal (20, 0, 30), 20 mm in along -z, stylus 5 mm along +x.
        self.assertAlmostEqual(tip[0], 25.0, places=9)
        self.assertAlmostEqual(tip[2], 10.0, places=9)
        self.assertEqual(self.style.GetInstrumentButtons(), 1)
        self.assertAlmostEqual(prop.GetUserMatrix().GetElement(0, 3), 25.0, places=9)
        scope = [0.0, 0.0, 0.0]
        self.style.GetScopeTip(scope)
        eye = self.renderer.GetActiveCamera().GetPosition()
        for a, b in zip(scope, eye):
            self.assertAlmostEqual(a, b, places=9)
        self.assertEqual(len(moves), 2)  # one per device
        self.style.StopDevices()
        self.assertFalse(self.style.GetDevicesRunning())

    def test_missing_trajectory_is_reported(self):
        self.style.SetScopeTrajectoryFileName(os.path.join(self.directory, "missing.json"))
        messages = []

        @vtk.calldata_type(vtk.VTK_STRING)
        def on_error(caller, event, message):
            messages.append(message)

        self.style.AddObserver("ErrorEvent", on_error)
        self.assertFalse(self.style.StartDevices())
        self.assertIn("missing.json", self.style.GetLastErrorMessage())
        self.assertEqual(len(messages), 1)


if __name__ == "__main__":
    unittest.main()
