"""Rotor model: elements, scenes (TOML), assembly of the global matrices."""
