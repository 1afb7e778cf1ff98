"""Periodic orbits of the loose-support rotor: the period-map adapter (period_flow), shooting, Floquet
multipliers, pseudo-arclength continuation and the Jeffcott verification rotor with its closed form."""
