"""Surface and material inputs: one parser for the config, the pipeline and the CLI.

A **surface** is one of

* a preset, by name (:data:`rubbercontact.roughness.presets.PRESETS`: ``section3``,
  ``asphalt_ac8``, ``high_slope_wave``);
* a sine table: ``wavelengths`` and ``amplitudes`` [mm] (and, on the command line,
  ``phases`` [rad]; a run draws its own random phases);
* measured profiles (``[surface.profiles]``), fitted with a sine series (paper §2.2);
* an areal height map (``[surface.map]``: a file or a synthetic self-affine map), run by
  :mod:`rubbercontact.pipeline.maprun`.

A **material** is the ``[material]`` table of :func:`rubbercontact.materials.load_material`
(``preset = "sbr"``, a Prony ``file``, a ``dma`` file to fit, or inline
``equilibrium_modulus``/``moduli``/``relaxation_times`` [MPa, s]; optional
``reference_temperature`` [°C] and a ``shift`` law) plus Poisson's ratio ``nu`` of the
half-space; with no source it is the SBR of Table 1. On the command line ``--material``
takes a preset name, ``elastic`` (with ``--modulus`` [MPa]) or a Prony file.

The config (:mod:`rubbercontact.config`) validates these tables with the models below, the
pipeline builds them with :func:`build_surface` and :func:`build_material`, and the CLI
commands parse their options with :func:`surface_from_value` and
:func:`material_from_value`: the same names, the same presets, the same errors.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    field_validator,
    model_validator,
)

from .errors import InputError
from .roughness.presets import PRESETS

PositiveFloat = Annotated[float, Field(gt=0)]
#: Names of the surface presets (for ``Literal`` types and help texts).
SURFACE_PRESETS = tuple(PRESETS)
#: Names of the material presets (:func:`rubbercontact.materials.load_material`).
MATERIAL_PRESETS = ("sbr",)


class Strict(BaseModel):
    """Base of the config tables: unknown keys are errors, values are frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class ProfileInput(Strict):
    """Measured profiles to fit a sine series to (paper §2.2)."""

    files: list[Path] = Field(min_length=1, description="profile files (relative to the config)")
    format: Literal["auto", "text", "captif", "topography"] = "auto"
    unit: Literal["mm", "um", "m"] = Field(
        "mm", description="unit of heights and distances in the files")
    dx: PositiveFloat | None = Field(
        None, description="sampling interval [mm] if the file has no x column")
    waves: int | None = Field(None, ge=1, le=40, description="number of sine waves M (octaves)")
    lower_cutoff: PositiveFloat | None = Field(None, description="shortest wavelength [mm]")
    upper_cutoff: PositiveFloat | None = Field(None, description="longest wavelength [mm]")
    method: Literal["wellconditioned", "paper"] = "wellconditioned"
    window: PositiveFloat | None = Field(None, description="NaN-free window length [mm]")
    despike: bool = False


class SyntheticMapInput(Strict):
    """A synthetic periodic map: self-affine (:func:`rubbercontact.roughness.self_affine_map`)
    or with the isotropic spectrum of measured line scans
    (:func:`rubbercontact.roughness.synthetic_map` on the scans' periodogram, which assumes
    the road has no lay)."""

    kind: Literal["self-affine", "from-profiles"] = "self-affine"
    size: PositiveFloat = Field(description="side of the square map Lx = Ly [mm]")
    points: int = Field(ge=16, le=4096, description="points per side")
    hurst: float | None = Field(None, gt=0, lt=1, description="self-affine: Hurst exponent H")
    rms_gradient: PositiveFloat | None = Field(
        None, description="self-affine: rms gradient of the map [-]")
    profiles: ProfileInput | None = Field(
        None, description="from-profiles: the line scans whose spectrum the map takes "
                          "(read as [surface.profiles]; lower/upper_cutoff bound the map's "
                          "wavelengths; waves and method do not apply)")
    seed: int = Field(0, ge=0, description="seed of the phases")

    @model_validator(mode="after")
    def _kind_fields(self) -> SyntheticMapInput:
        own = {"self-affine": ("hurst", "rms_gradient"), "from-profiles": ("profiles",)}
        missing = [k for k in own[self.kind] if getattr(self, k) is None]
        if missing:
            raise ValueError(f"kind = {self.kind!r} needs {', '.join(missing)}")
        other = [k for kind, keys in own.items() if kind != self.kind for k in keys
                 if getattr(self, k) is not None]
        if other:
            raise ValueError(f"{', '.join(other)} do not apply to kind = {self.kind!r}")
        return self


class MapInput(Strict):
    """An areal height map: a file (:func:`rubbercontact.io.read_map`) or a synthetic one."""

    file: Path | None = Field(None, description="map file (relative to the config)")
    format: Literal["auto", "text", "npy", "topography"] = "auto"
    unit: Literal["mm", "um", "nm", "m"] | None = Field(
        None, description="unit of heights and dx when the file does not state it")
    dx: PositiveFloat | None = Field(None, description="pixel size (in unit) of a .npy map")
    nan: Literal["error", "fill"] = "error"
    detrend: Literal["plane", "mean", "none"] | None = Field(
        None, description="default: plane when mirrored, mean for a periodic map")
    periodize: Literal["mirror", "none"] = Field(
        "mirror", description="mirror a measured map, or take it as one period (none)")
    synthetic: SyntheticMapInput | None = None

    @model_validator(mode="after")
    def _one_map(self) -> MapInput:
        if (self.file is None) == (self.synthetic is None):
            raise ValueError("give exactly one of 'file' and 'synthetic'")
        npy = self.format == "npy" or (self.format == "auto" and self.file is not None
                                       and self.file.suffix.lower() == ".npy")
        if npy and self.dx is None:
            raise ValueError("a .npy map carries no pixel size: give dx (in unit, default mm)")
        if self.synthetic is not None:
            given = [k for k in ("unit", "dx", "detrend") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"{', '.join(given)} apply to a map 'file' only")
        return self


class SurfaceSpec(Strict):
    """Rough rigid surface: a preset, an explicit sine table, measured profiles, or a map."""

    preset: Literal[SURFACE_PRESETS] | None = None
    wavelengths: list[PositiveFloat] | None = Field(None, description="[mm]")
    amplitudes: list[Annotated[float, Field(ge=0)]] | None = Field(None, description="[mm]")
    profiles: ProfileInput | None = None
    map: MapInput | None = None
    m2_threshold: PositiveFloat = Field(
        1.0, description="rms slope above which a wave is high-slope [-]")

    @model_validator(mode="after")
    def _one_source(self) -> SurfaceSpec:
        table = self.wavelengths is not None or self.amplitudes is not None
        given = [self.preset is not None, table, self.profiles is not None,
                 self.map is not None]
        if sum(given) != 1:
            raise ValueError("give exactly one of 'preset', 'wavelengths'+'amplitudes', "
                             "'profiles', 'map'")
        if (self.wavelengths is None) != (self.amplitudes is None):
            raise ValueError("'wavelengths' and 'amplitudes' go together")
        if self.wavelengths is not None and len(self.wavelengths) != len(self.amplitudes):
            raise ValueError(f"'wavelengths' ({len(self.wavelengths)}) and 'amplitudes' "
                             f"({len(self.amplitudes)}) differ in length")
        return self


class SineTable(Strict):
    """A sine series given as a table (command line and ``--config`` files)."""

    wavelengths: list[PositiveFloat] = Field(min_length=1, description="[mm]")
    amplitudes: list[Annotated[float, Field(ge=0)]] = Field(min_length=1, description="[mm]")
    phases: list[float] | None = Field(None, description="[rad]")


_MATERIAL_SOURCES = ("preset", "file", "dma", "equilibrium_modulus")
_DMA_ONLY = ("frequency_unit", "modulus_unit", "terms", "tolerance")


class MaterialSpec(Strict):
    """Generalized Maxwell material (MPa, s): a preset, a Prony file, a DMA file to fit, or
    inline values; with no source, the SBR of Table 1. Keys as
    :func:`rubbercontact.materials.load_material`, plus ``nu``."""

    preset: Literal[MATERIAL_PRESETS] | None = None
    file: Path | None = Field(None, description="Prony table, TOML or CSV")
    dma: Path | None = Field(None, description="DMA master curve or isothermal sweeps (CSV)")
    equilibrium_modulus: PositiveFloat | None = Field(None, description="[MPa]")
    moduli: list[PositiveFloat] = Field(default_factory=list, description="[MPa]")
    relaxation_times: list[PositiveFloat] = Field(default_factory=list, description="[s]")
    name: str | None = None
    frequency_unit: str | None = Field(None, description="Hz or rad/s, if the header has none")
    modulus_unit: str | None = Field(None, description="Pa, kPa, MPa or GPa, if the header "
                                                       "has none")
    terms: int | None = Field(None, ge=1, le=200, description="Prony terms of the DMA fit")
    tolerance: PositiveFloat | None = Field(None, description="DMA fit tolerance [-]")
    reference_temperature: float | None = Field(
        None, gt=-273.15, description="temperature the series describes [°C]")
    shift: dict[str, Any] | None = Field(
        None, description="time-temperature shift law: law = 'WLF', c1, c2 [K] (t_ref [°C]) "
                          "or law = 'Arrhenius', activation_energy [J/mol]")
    nu: float = Field(0.5, ge=0.0, le=0.5, description="Poisson's ratio of the half-space [-]")
    thermal: dict[str, Any] | None = Field(
        None, description="the compound's conductivity [W/(m·K)], density [kg/m³], "
                          "specific_heat [J/(kg·K)] (and source); default: a filled SBR")

    @field_validator("thermal")
    @classmethod
    def _thermal(cls, value: dict | None) -> dict | None:
        from .materials.spec import load_thermal

        try:
            load_thermal({"thermal": value})
        except InputError as exc:
            raise ValueError(str(exc).removeprefix("material.thermal: ")
                             .removeprefix("thermal.")) from None
        return value

    @model_validator(mode="after")
    def _one_source(self) -> MaterialSpec:
        given = [k for k in _MATERIAL_SOURCES if getattr(self, k) is not None]
        if len(given) > 1:
            raise ValueError(f"give one of {', '.join(_MATERIAL_SOURCES)}, got {given}")
        if self.equilibrium_modulus is None and (self.moduli or self.relaxation_times):
            raise ValueError("'moduli' and 'relaxation_times' need 'equilibrium_modulus'")
        if self.dma is None:
            extra = [k for k in _DMA_ONLY if getattr(self, k) is not None]
            if extra:
                raise ValueError(f"{', '.join(extra)} apply to 'dma' only")
        if self.shift is not None and "law" not in self.shift:
            raise ValueError("shift: needs law = 'WLF' or 'Arrhenius'")
        return self

    def load_spec(self) -> dict:
        """The plain-data table :func:`rubbercontact.materials.load_material` reads."""
        keys = (*_MATERIAL_SOURCES, "name", *_DMA_ONLY, "reference_temperature", "shift",
                "thermal")
        spec = {k: getattr(self, k) for k in keys if getattr(self, k) is not None}
        if self.equilibrium_modulus is not None:
            spec.update(moduli=list(self.moduli), relaxation_times=list(self.relaxation_times))
        if not any(k in spec for k in _MATERIAL_SOURCES):
            spec["preset"] = "sbr"
        for k in ("file", "dma"):
            if k in spec:
                spec[k] = str(spec[k])
        return spec


@dataclass(frozen=True)
class SurfaceInput:
    """A built surface: the base sine series and where it came from.

    Attributes
    ----------
    series
        The sine series (zero phases for presets and tables; the fit's for profiles).
    info
        Provenance (plain data): ``source`` and, for a profile fit, the files, their
        hashes, the fit method and its error.
    profiles
        The measured scans the fit read (:class:`rubbercontact.io.Profiles`), else None.
    """

    series: Any
    info: dict = field(default_factory=dict)
    profiles: Any = None


def read_profile_input(p: ProfileInput):
    """The scans a ``[surface.profiles]`` table names (:class:`rubbercontact.io.Profiles`):
    read, cut into gap-free windows (``window``, default 16 mm) and despiked if asked."""
    from .io.profiles import read_profiles

    return read_profiles(p.files, format=p.format, unit=p.unit, dx=p.dx,
                         window=p.window or 16.0, despike=p.despike)


def build_surface(spec: SurfaceSpec) -> SurfaceInput:
    """The sine series a ``[surface]`` table describes (profiles are read and fitted)."""
    from .roughness import SineSeries
    from .roughness.presets import preset

    if spec.preset is not None:
        return SurfaceInput(preset(spec.preset), {"source": f"preset:{spec.preset}"})
    if spec.wavelengths is not None:
        return SurfaceInput(SineSeries(spec.wavelengths, spec.amplitudes),
                            {"source": "sine table"})
    from .roughness.fit import default_wavelengths, fit_hdc_details

    p = spec.profiles
    profiles = read_profile_input(p)
    shortest = min(z.size for z in profiles.profiles) * profiles.dx
    wavelengths = default_wavelengths(profiles.dx, shortest, n_waves=p.waves,
                                      lower_cutoff=p.lower_cutoff, upper_cutoff=p.upper_cutoff)
    fit = fit_hdc_details(profiles, wavelengths=wavelengths, method=p.method)
    info = {"source": "fit of measured profiles", "files": [str(f) for f in p.files],
            "sources": [dict(src) for src in profiles.sources], "fit_method": p.method,
            "n_scans": len(profiles.profiles), "dx_mm": profiles.dx,
            "log10_rms_error": float(fit.log10_rms_error)}
    return SurfaceInput(fit.series, info, profiles)


def build_material(spec: MaterialSpec, base_dir: str | Path | None = None):
    """The :class:`~rubbercontact.materials.GeneralizedMaxwell` of a ``[material]`` table
    (paths relative to ``base_dir``; the config resolves them to absolute ones)."""
    from .materials import load_material

    return load_material(spec.load_spec(), base_dir=base_dir)


def _validation_message(exc: ValidationError, where: str) -> str:
    parts = []
    for err in exc.errors():
        loc = ".".join(str(p) for p in err["loc"])
        key = f"{where}.{loc}" if loc else where
        if err["type"] == "extra_forbidden":
            parts.append(f"{key}: unknown key")
        else:
            parts.append(f"{key}: {err['msg'].removeprefix('Value error, ')}")
    return "; ".join(parts)


def surface_from_value(value, *, default: str = "section3", phases=None,
                       where: str = "surface"):
    """A sine series from a CLI value: ``None`` (the ``default`` preset), a preset name, or
    a table ``{wavelengths, amplitudes, phases}`` [mm, mm, rad]. ``phases`` [rad], when
    given, replace the surface's."""
    from .roughness import SineSeries
    from .roughness.presets import preset

    if value is None:
        value = default
    if isinstance(value, str):
        surf = preset(value)
    elif isinstance(value, Mapping):
        try:
            table = SineTable.model_validate(dict(value))
        except ValidationError as exc:
            raise InputError(_validation_message(exc, where)) from None
        if len(table.wavelengths) != len(table.amplitudes):
            raise InputError(f"{where}: wavelengths ({len(table.wavelengths)}) and amplitudes "
                             f"({len(table.amplitudes)}) differ in length")
        surf = SineSeries(table.wavelengths, table.amplitudes, table.phases)
    else:
        raise InputError(f"{where}: expected a preset name ({', '.join(SURFACE_PRESETS)}) or "
                         f"a table of wavelengths/amplitudes, got {value!r}")
    return surf.with_phases(phases) if phases is not None else surf


def material_from_value(value, *, modulus: float | None = None, base_dir=None,
                        where: str = "material"):
    """A material from a CLI value: ``None`` (SBR), a preset name, ``"elastic"`` (with
    ``modulus`` [MPa]), a Prony file path (TOML/CSV), or a ``[material]`` table."""
    from .materials import GeneralizedMaxwell

    if value is None:
        value = "sbr"
    if isinstance(value, Mapping):
        table = dict(value)
        table.pop("nu", None)
        try:
            spec = MaterialSpec.model_validate(table)
        except ValidationError as exc:
            raise InputError(_validation_message(exc, where)) from None
        return build_material(spec, base_dir)
    if not isinstance(value, str | Path):
        raise InputError(f"{where}: expected a preset name, 'elastic', a file or a table, "
                         f"got {value!r}")
    text = str(value)
    if text in MATERIAL_PRESETS:
        return build_material(MaterialSpec(preset=text))
    if text == "elastic":
        if modulus is None:
            raise InputError("modulus: an elastic material needs --modulus E (MPa)")
        return GeneralizedMaxwell.elastic(modulus)
    path = Path(text) if base_dir is None or Path(text).is_absolute() else Path(base_dir) / text
    if path.suffix.lower() in (".toml", ".csv") or path.exists():
        return GeneralizedMaxwell.from_file(path)
    raise InputError(f"{where}: expected {', '.join(MATERIAL_PRESETS)}, 'elastic' or a Prony "
                     f"file (.toml/.csv), got {text!r}")
