"""What the tests and the benchmarks share (as ``numpy.testing``): independent models that
verify the solvers (:mod:`.verify`, FElupe is a test extra), the table of invalid invocations
of every verb (:mod:`.fuzz_cases`), closed test solids (:mod:`.check_shapes`,
:mod:`.part_shapes`), and stand-ins the sweep and design tests run on Dask workers
(:mod:`.sweep_tasks`, :mod:`.design_double`), and the gate-against-sweep comparison of
printability verdicts (:mod:`.printability_agreement`). Nothing in ``spsc`` imports it.
"""
