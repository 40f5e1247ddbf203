"""Studies of particular parts and data: the fused fingertip in the FEM (:mod:`.fingertip`) and
its fast estimate (:mod:`.fused`), the haptic chamber's motor (:mod:`.haptic`), and what a
calibration shows beside the calibrated model (:mod:`.calibration`)."""
