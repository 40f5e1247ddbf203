"""The mold of a bladder's wall for casting or compression molding (sec. 2.2): the pieces
(:mod:`.build`: halves, lost core, pins, the pull test), their specification
(:mod:`.spec`), the solid kernels that cut them (:mod:`.kernel`: B-rep or mesh), the mold
gate (:mod:`.gate`) and the files (:mod:`.export`: STL, 3MF, STEP, mold.json).

The package imports nothing itself: :mod:`.spec` is read to check a command line before the
CAD kernel loads.
"""
