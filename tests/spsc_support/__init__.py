"""What the tests and the benchmarks share, outside the installed package: independent models
that verify the solvers (:mod:`.verify`; FElupe is a test extra), the table of invalid
invocations of every verb (:mod:`.fuzz_cases`), closed test solids (:mod:`.check_shapes`,
:mod:`.part_shapes`), generated sensing traces (:mod:`.sense_traces`) and the gate-against-sweep
comparison of printability verdicts (:mod:`.printability_agreement`). The tests find it on
``pytest``'s ``pythonpath`` (``tests``), the benchmarks on the Makefile environment's path (a
``.pth`` file the install writes). What Dask workers import (the sweep's and the design's
stand-ins) stays in :mod:`spsc.testing`.
"""
