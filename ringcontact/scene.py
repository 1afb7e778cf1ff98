"""Rotor scenes from Python: load a file or a bundled scene, build one from elements, write it back as TOML.

A scene is the frozen dataclass of :mod:`rotor.model.scene` (SI units inside) with a few methods:
:meth:`Scene.to_toml` (the file an engineer can edit, :func:`rotor.model.scene_toml.scene_to_toml`),
:meth:`Scene.save`, :meth:`Scene.checked` (every check a scene file gets, by reading the scene's own TOML) and
:meth:`Scene.with_loose_bearing` (one bearing of a linear rotor made loose: the bearing ring in a support
through a radial clearance, Dai et al. 2025). The element constructors are the dataclasses of
:mod:`rotor.model.scene` (``Material``, ``Station``, ``Shaft``, ``Disk``, ``Bearing`` …) plus
:func:`disk_from_geometry` and :func:`loose_support`.
"""
from __future__ import annotations

import dataclasses
import os
import tomllib
from pathlib import Path

from contact.files import atomic_write_text
from rotor.model import scene as rotor_scene
from rotor.model.loose_support_scene import FROM_LAW, LooseSupport, complete_loose_support
from rotor.model.scene import Disk, Material, SupportNode, bundled_scenes, parse_scene
from rotor.model.scene_toml import scene_to_toml


@dataclasses.dataclass(frozen=True)
class Scene(rotor_scene.Scene):
    """A rotor scene (SI units): every field of :class:`rotor.model.scene.Scene`, plus the methods below.

    Build one from the element dataclasses (``ringcontact.Material``, ``Station``, ``Shaft``, ``Disk``,
    ``Bearing``, ``SupportNode``, :func:`loose_support`), read one with :func:`load_scene`, and pass it,
    or a scene file's path or a bundled scene's name, to any analysis of :mod:`ringcontact`.
    """

    def to_toml(self) -> str:
        """The scene as a TOML scene file (engineer units in the keys: ``x_mm``, ``stiffness_n_per_m`` …)."""
        return scene_to_toml(self)

    def save(self, path: str | os.PathLike) -> Path:
        """Write :meth:`to_toml` to ``path`` (written to a temporary name, then renamed); returns the path."""
        return atomic_write_text(Path(path), self.to_toml())

    def checked(self) -> "Scene":
        """This scene read back from its own TOML: every check of a scene file (ranges, units, names that
        must exist, stations in increasing x, a calibrated law's geometry) applies.

        Raises
        ------
        contact.errors.InputError
            One line naming the table entry, the field, its value with its unit and what is allowed.
        """
        return Scene.from_toml(self.to_toml(), origin=f"scene {self.name!r}", path=self.path)

    @classmethod
    def from_toml(cls, text: str, *, origin: str = "<string>", base_dir=None, path: str = "") -> "Scene":
        """A scene from TOML text; ``base_dir``: the folder a relative law-file path is taken from."""
        from contact.errors import DatasetError
        try:
            doc = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise DatasetError(f"{origin}: not valid TOML: {exc}") from None
        parsed = parse_scene(doc, origin=origin, base_dir=base_dir)
        return cls.of(dataclasses.replace(parsed, path=path or parsed.path))

    @classmethod
    def of(cls, scene: rotor_scene.Scene) -> "Scene":
        """The same scene as a :class:`Scene` (with its methods)."""
        if type(scene) is cls:
            return scene
        return cls(**{f.name: getattr(scene, f.name) for f in dataclasses.fields(rotor_scene.Scene)})

    def replace(self, **changes) -> "Scene":
        """A copy with ``changes`` (field name -> value), checked (:meth:`checked`)."""
        return dataclasses.replace(self, **changes).checked()

    def with_loose_bearing(self, bearing: str, *, support_mass_kg: float, support_inertia_kg_m2: float,
                           support_angular_stiffness_n_m_rad: float, support_angular_damping_n_m_s_rad: float = 0.0,
                           support_name: str = "support", **loose) -> "Scene":
        """This rotor with the linear bearing ``bearing`` made loose (Dai et al. 2025, Eq. 52).

        The bearing's spring and damper now hold a support node of mass ``support_mass_kg`` (kg) and tilt
        inertia ``support_inertia_kg_m2`` (kg m^2) to ground, with the angular stiffness and damping given
        (N m/rad, N m s/rad); the rotor station touches the support only through the clearance of
        ``loose`` (the keyword arguments of :func:`loose_support`: ``clearance_m``, ``ring_width_m``, moduli,
        ``friction_coefficient``, ``preload_n``, ``collision_factor_s_m``, ``law``).
        """
        from contact.errors import InputError
        match = [b for b in self.bearings if b.name == bearing]
        if not match:
            raise InputError(f"bearing = {bearing!r}: no such bearing in scene {self.name!r} "
                             f"(have {', '.join(b.name for b in self.bearings) or 'none'})")
        b = match[0]
        node = SupportNode(support_name, b.station, support_mass_kg, support_inertia_kg_m2, b.stiffness_n_m,
                           b.damping_n_s_m, support_angular_stiffness_n_m_rad, support_angular_damping_n_m_s_rad)
        return dataclasses.replace(
            self, bearings=tuple(x for x in self.bearings if x is not b), supports=self.supports + (node,),
            loose_support=loose_support(b.station, support_name, **loose)).checked()


    def with_law(self, law: str) -> "Scene":
        """This scene with its loose support's contact law replaced by ``law`` (as :func:`loose_support` takes
        it), the clearance, ring width and materials kept (a calibrated law must hold for them)."""
        from contact.errors import InputError
        ls = self.loose_support
        if ls is None:
            raise InputError(f"law = {law!r}: scene {self.name!r} has no loose support to apply it to")
        new = loose_support(ls.bearing_station, ls.support, clearance_m=ls.clearance_m, ring_width_m=ls.ring_width_m,
                            bearing_modulus_pa=ls.bearing_modulus_pa, bearing_poisson=ls.bearing_poisson,
                            support_modulus_pa=ls.support_modulus_pa, support_poisson=ls.support_poisson,
                            collision_factor_s_m=ls.collision_factor_s_m,
                            friction_coefficient=ls.friction_coefficient, preload_n=ls.preload_n, law=law)
        return dataclasses.replace(self, loose_support=new).checked()


def load_scene(name_or_path: str | os.PathLike) -> Scene:
    """A scene file (``.toml``) or a bundled scene by name (:func:`list_scenes`), in SI units.

    Raises
    ------
    contact.errors.DatasetError
        The file is missing, unreadable or not TOML.
    contact.errors.InputError
        A field is missing, out of range, has an unknown unit or name.
    """
    return Scene.of(rotor_scene.load_scene(name_or_path))


def list_scenes() -> list[str]:
    """Names of the scenes shipped with the package (``rotor/scenes/*.toml``)."""
    return bundled_scenes()


def as_scene(scene) -> Scene:
    """``scene`` as a checked :class:`Scene`: a path or a bundled name is read, a dataclass checked."""
    if isinstance(scene, rotor_scene.Scene):
        return scene.checked() if isinstance(scene, Scene) else Scene.of(scene).checked()
    from ringcontact._checks import scene_argument
    scene_argument(scene)             # None, a number …: refused in one line before a path is made of it
    return load_scene(scene)


def disk_from_geometry(name: str, station: str, material: Material, *, outer_diameter_m: float, width_m: float,
                       inner_diameter_m: float = 0.0, unbalance_kg_m: float = 0.0,
                       unbalance_phase_rad: float = 0.0) -> Disk:
    """A rigid disk of uniform ``material``: an annulus (bore ``inner_diameter_m``, m) of axial ``width_m`` (m).

    Mass, polar and diametral inertia from :func:`rotor.model.elements.disk_properties` (the same as a scene
    file's disk given by ``outer_diameter_mm``, ``inner_diameter_mm``, ``thickness_mm`` and ``material``).
    """
    from rotor.model.elements import disk_properties
    mass, ip, idd = disk_properties(material.density_kg_m3, float(outer_diameter_m), float(inner_diameter_m),
                                    float(width_m))
    return Disk(name, station, mass, ip, idd, float(unbalance_kg_m), float(unbalance_phase_rad))


def loose_support(bearing_station: str, support: str, *, clearance_m: float | None = None,
                  ring_width_m: float | None = None, bearing_modulus_pa: float | None = None,
                  bearing_poisson: float | None = None, support_modulus_pa: float | None = None,
                  support_poisson: float | None = None, collision_factor_s_m: float = 0.0,
                  friction_coefficient: float = 0.0, preload_n: float = 0.0, law: str = "conformal") -> LooseSupport:
    """The ``[loose_support]`` of a scene: the bearing at ``bearing_station`` in the support node ``support``.

    ``law``: ``"conformal"`` (Dai et al. 2025, as published), ``"pereira"``, ``"calibrated:<name>"`` (a shipped
    law) or the path of a law file (``ringcontact bearing`` writes one; :func:`ringcontact.bearing`). The
    geometry (clearance and ring width, m; moduli, Pa; Poisson ratios) is required with an analytic law and
    may be left out with a calibrated one, which then supplies it (a value given must agree with the law's).
    Friction coefficient of the end faces (–), nut preload per face (N) and the collision damping factor
    (s/m) default to 0. Ranges are checked with the scene (:meth:`Scene.checked`).
    """
    given = {"clearance_m": clearance_m, "ring_width_m": ring_width_m, "bearing_modulus_pa": bearing_modulus_pa,
             "bearing_poisson": bearing_poisson, "support_modulus_pa": support_modulus_pa,
             "support_poisson": support_poisson}
    kw = {k: (FROM_LAW if v is None else float(v)) for k, v in given.items()}
    kw.update(bearing_station=bearing_station, support=support, collision_factor_s_m=float(collision_factor_s_m),
              friction_coefficient=float(friction_coefficient), preload_n=float(preload_n), law=law)
    done = complete_loose_support(kw, "loose_support()", None)
    if done.get("law_file") and not law.startswith("calibrated:"):
        done["law"] = str(done["law_file"])          # a law file by its resolved path: the scene reads anywhere
    return LooseSupport(**done)
