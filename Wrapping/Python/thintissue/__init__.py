"""ThinTissue: VTK filters and sources for thin deformable tissues.

Use next to VTK:  import vtk; import thintissue; thintissue.vtkThinSlabSource()
"""
# The wrapped modules derive from these VTK classes: load them first.
from vtkmodules import vtkCommonCore, vtkCommonDataModel, vtkCommonExecutionModel  # noqa: F401
from vtkmodules import vtkRenderingCore  # noqa: F401  (vtkInteractorStyle3D)

from .ThinTissueVTKCore import *  # noqa: F401,F403
from .ThinTissueVTKModels import *  # noqa: F401,F403
from .ThinTissueVTKSolver import *  # noqa: F401,F403
from .ThinTissueVTKBinding import *  # noqa: F401,F403
from .ThinTissueVTKCutting import *  # noqa: F401,F403
from .ThinTissueVTKWrinkles import *  # noqa: F401,F403
from .ThinTissueVTKHaptics import *  # noqa: F401,F403
from .ThinTissueVTKOperations import *  # noqa: F401,F403
