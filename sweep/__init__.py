"""Resumable sweeps of independent tasks: checksummed result store, executors, progress, provenance."""
