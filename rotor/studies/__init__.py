"""Studies on the loose-support rotor: steady state, sweeps of speed and parameters, run-up, sensitivity."""
