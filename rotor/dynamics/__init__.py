"""Time integration of the loose-support rotor: constraints, the paper's scheme, the compiled scheme, energy."""
