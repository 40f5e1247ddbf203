"""Stand-ins the sweep and design tests run on Dask workers (:mod:`.sweep_tasks`,
:mod:`.design_double`): a worker imports them by their module path, so they live in the
installed package. What else the tests and benchmarks share is outside it, in
``tests/spsc_support``. Nothing in ``spsc`` imports this.
"""
