"""3D tilted-ring FEM reference (half model): geometry, mesh, solve, sweep, export."""
