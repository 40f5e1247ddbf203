"""Independent models used only to verify the solvers.

* :mod:`.axisym_felupe` — an axisymmetric solid model of the l = 0 chamber on FElupe (a
  test-only dependency), against which the 3D FEM is checked;
* :mod:`.membrane_fe` — a 1D finite-element discretisation of the membrane problem,
  against which the box-scheme membrane solver is checked.

Both take the ambient pressure and the gas law from :mod:`spsc.core` and the material law from
:mod:`spsc.materials`, so they check the solvers, not a second copy of the physics.
"""
