"""The wall model's surrogate: learnt maps of the chamber, the gas law applied exactly."""
