"""The validation report: built from a study's outcomes (:mod:`.build`), its sections
(:mod:`.sections` and the fingertip, haptic, mold, sweep and bench sections), figures and the
paper's printed numbers (:mod:`.paper`), rendered with Jinja2 templates (:mod:`.render`)."""
