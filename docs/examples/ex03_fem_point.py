"""One 2D FEM contact point on a coarse mesh

The straight ring pressed into its support, solved by the 2D reference FEM (gmsh P2 triangles,
scikit-fem, frictionless mortar contact) on the ``clamped`` scene: the paper's Table 1 rings, the
support's outer surface clamped, the bearing's inner surface moved rigidly by ``t = δ0 + Δr``.

The committed reference (``fem_reference/data/fem2d-reference.json``) solved each point on four
contact element sizes (4, 2, 1, 0.5 mm) and extrapolated (Richardson). Here we solve one point on
the two coarse levels only, in a few seconds. The test checks that the 2 mm force is the committed
2 mm level (same mesh family) and within the published discretisation trend of the reference value.
Same as ``ringcontact fem-point 0.01 --h-mm 2``.
"""
from __future__ import annotations

from fem_reference.plane.solve import ContactModel
from fem_reference.plane.sweep import arc_zone_rad, spec_for
from fem_reference.scenes import by_name

PENETRATION_M = 0.01e-3
LEVELS_M = (4e-3, 2e-3)


def solve(h_contact_m: float, penetration_m: float = PENETRATION_M, scene_name: str = "clamped"):
    """:class:`fem_reference.plane.solve.ContactSolution` on one level of the reference's mesh family."""
    scene = by_name(scene_name)
    zone = arc_zone_rad(scene.rings, penetration_m)          # meshes graded toward this point's arc
    model = ContactModel.build(scene, spec_for(scene, h_contact_m, 2, zone))
    return model.solve(penetration_m)


def main():
    """Print each level's result; return the figure (force against contact element size)."""
    import matplotlib.pyplot as plt
    forces = []
    for h in LEVELS_M:
        s = solve(h)
        forces.append(s.force_n)
        print(f"h = {h * 1e3:g} mm: force {s.force_n / 1e3:.3f} kN, contact half-angle {s.half_angle_rad * 57.29578:.2f}°, "
              f"{s.ndofs} DOFs, {s.iterations} active-set iterations")
    fig, ax = plt.subplots(figsize=(6, 3.6), layout="constrained")
    ax.plot([h * 1e3 for h in LEVELS_M], [f / 1e3 for f in forces], "o-")
    ax.invert_xaxis()
    ax.set(xlabel="contact element size h (mm)", ylabel="contact force (kN)",
           title=f"2D FEM, clamped scene, Δr = {PENETRATION_M * 1e3:g} mm")
    return fig


if __name__ == "__main__":
    main()
