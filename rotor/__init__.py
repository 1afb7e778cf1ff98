"""Multi-support rotor with a loose support: model, linear analyses, time integration."""
