"""Reading a config: validation errors as one line per problem (file, key, unit,
did-you-mean), and paths resolved relative to the file."""

from __future__ import annotations

import difflib
import tomllib
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import InputError
from .run import RunConfig


def _field_names(model: type[BaseModel], loc: tuple) -> list[str]:
    """Valid keys at the location of an error (for did-you-mean)."""
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        field = model.model_fields.get(part)
        if field is None:
            return []
        ann = field.annotation
        for cand in getattr(ann, "__args__", (ann,)):
            if isinstance(cand, type) and issubclass(cand, BaseModel):
                model = cand
                break
        else:
            return []
    return list(model.model_fields)


def _format_error(err: dict, source: str) -> str:
    loc = tuple(err["loc"])
    key = ".".join(str(p) for p in loc) or "(top level)"
    if err["type"] == "extra_forbidden":
        names = _field_names(RunConfig, loc)
        guess = difflib.get_close_matches(str(loc[-1]), names, n=1)
        hint = f"; did you mean '{guess[0]}'?" if guess else (
            f"; allowed: {', '.join(names)}" if names else "")
        return f"{source}: unknown key '{key}'{hint}"
    msg = err["msg"].removeprefix("Value error, ")
    field_desc = ""
    try:
        names = RunConfig
        for part in loc:
            if isinstance(part, int):
                continue
            f = names.model_fields[part]
            field_desc = f.description or ""
            ann = f.annotation
            nxt = [c for c in getattr(ann, "__args__", (ann,))
                   if isinstance(c, type) and issubclass(c, BaseModel)]
            names = nxt[0] if nxt else names
    except (KeyError, AttributeError):
        field_desc = ""
    unit = f" ({field_desc})" if field_desc else ""
    got = f", got {err['input']!r}" if "input" in err and not isinstance(err["input"], dict) else ""
    return f"{source}: key '{key}'{unit}: {msg}{got}"


def _resolve_paths(cfg: RunConfig, base: Path) -> RunConfig:
    def fix(p: Path | None) -> Path | None:
        return None if p is None else (p if p.is_absolute() else (base / p).resolve())

    def fix_profiles(prof, where: str):
        prof = prof.model_copy(update={"files": [fix(f) for f in prof.files]})
        missing = [str(f) for f in prof.files if not f.is_file()]
        if missing:
            raise InputError(f"{where}.files: file(s) not found: {', '.join(missing)}")
        return prof

    upd: dict[str, Any] = {}
    if cfg.surface.profiles is not None:
        prof = fix_profiles(cfg.surface.profiles, "surface.profiles")
        upd["surface"] = cfg.surface.model_copy(update={"profiles": prof})
    synthetic = cfg.surface.map.synthetic if cfg.surface.map is not None else None
    if synthetic is not None and synthetic.profiles is not None:
        prof = fix_profiles(synthetic.profiles, "surface.map.synthetic.profiles")
        syn = synthetic.model_copy(update={"profiles": prof})
        upd["surface"] = cfg.surface.model_copy(
            update={"map": cfg.surface.map.model_copy(update={"synthetic": syn})})
    if cfg.surface.map is not None and cfg.surface.map.file is not None:
        path = fix(cfg.surface.map.file)
        if not path.is_file():
            raise InputError(f"surface.map.file: not found: {path}")
        upd["surface"] = cfg.surface.model_copy(
            update={"map": cfg.surface.map.model_copy(update={"file": path})})
    for key in ("file", "dma"):
        path = getattr(cfg.material, key)
        if path is not None:
            if not fix(path).is_file():
                raise InputError(f"material.{key}: not found: {fix(path)}")
            upd["material"] = upd.get("material", cfg.material).model_copy(
                update={key: fix(path)})
    if cfg.law.file is not None:
        if not fix(cfg.law.file).is_file():
            raise InputError(f"law.file: not found: {fix(cfg.law.file)}")
        upd["law"] = cfg.law.model_copy(update={"file": fix(cfg.law.file)})
    upd["output"] = cfg.output.model_copy(update={"directory": fix(cfg.output.directory)})
    if cfg.execution.cache is not None:
        upd["execution"] = cfg.execution.model_copy(update={"cache": fix(cfg.execution.cache)})
    return cfg.model_copy(update=upd)


def parse_config(data: dict, source: str = "<config>", base_dir: Path | None = None) -> RunConfig:
    """Validate a config mapping; raise :class:`InputError` with one line per problem."""
    if not isinstance(data, dict):
        raise InputError(f"{source}: expected a table of keys, got {type(data).__name__}")
    try:
        cfg = RunConfig.model_validate(data)
    except ValidationError as exc:
        lines = [_format_error(e, source) for e in exc.errors()]
        raise InputError("; ".join(lines)) from None
    return _resolve_paths(cfg, base_dir or Path.cwd())


def load_config(path: str | Path) -> RunConfig:
    """Read and validate a TOML run configuration."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"config file {path}: not found")
    try:
        text = path.read_text(encoding="utf-8")
        data = tomllib.loads(text)
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a UTF-8 text file") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: invalid TOML: {exc}") from None
    return parse_config(data, source=str(path), base_dir=path.resolve().parent)

