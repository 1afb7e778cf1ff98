"""2D (plane strain/stress) ring-in-ring FEM reference: geometry, mesh, solve, sweep, export."""
