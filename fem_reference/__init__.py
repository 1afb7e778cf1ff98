"""FEM reference: gmsh meshes + scikit-fem frictionless contact of ring in ring."""
