"""spsc: soft pneumatic sensing chambers — parametric CAD, the membrane and wall models, the 3D
FEM check and the pipeline that runs them (Duretto et al., Sensors and Actuators A, 2026).

The subpackages stack from low to high: ``core`` (units, the Curve, the load case), ``cad``
(geometry and manufacturing), ``membrane`` (fast physics), ``fem`` (the wall model and the 3D
FEM), ``pipeline`` (the ``spsc`` command line, runs, reports). Imports only go down that list.
"""
