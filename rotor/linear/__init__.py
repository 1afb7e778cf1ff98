"""Linear rotor analyses: modes, Campbell diagram, critical speeds, unbalance response."""
