"""TOML input: loading with ``include``, deep merge, dotted overrides.

A file may start with ``include = ["rig/rig.toml", ...]``: the included files (paths relative to
the including file) are loaded first, in order, and the including file's own tables are merged
on top (tables merge key by key, any other value replaces). This is how every paper scenario
shares one rig parameter file.
"""

from __future__ import annotations

import copy
import math
import tomllib
from contextlib import contextmanager
from pathlib import Path

from .errors import InputError
from .readers import read_text

MAX_INCLUDE_DEPTH = 8


def deep_merge(base: dict, top: dict) -> dict:
    """Return ``base`` updated by ``top``; nested tables merge, other values replace."""
    out = copy.deepcopy(base)
    for key, value in top.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def load_toml(path, _depth: int = 0) -> dict:
    """Load a TOML file, resolving ``include``; errors name the file."""
    path = Path(path)
    if _depth > MAX_INCLUDE_DEPTH:
        raise InputError("include", str(path), f"include depth exceeds {MAX_INCLUDE_DEPTH} (circular include?)")
    # the one guard of text input: missing, empty, binary, UTF-16 or non-UTF-8 files (an include too)
    text = read_text(path, field="include" if _depth else "file")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError("(syntax)", str(exc).split("\n")[0], "malformed TOML", file=str(path)) from None
    includes = data.pop("include", [])
    if isinstance(includes, str):
        includes = [includes]
    if not isinstance(includes, list) or not all(isinstance(s, str) for s in includes):
        raise InputError("include", includes, "must be a list of file paths", file=str(path))
    merged: dict = {}
    for inc in includes:
        merged = deep_merge(merged, load_toml(path.parent / inc, _depth + 1))
    return deep_merge(merged, data)


def split_override(item: str) -> tuple[str, str]:
    """``(key, value text)`` of a ``--set key=value`` override; a missing ``=`` or an empty key
    is named as such (not as an unknown field with an empty name)."""
    if not isinstance(item, str) or "=" not in item:
        raise InputError("--set", item, "must look like dotted.key=value")
    key, text = item.split("=", 1)
    key = key.strip()
    if not key or any(not part.strip() for part in key.split(".")):
        raise InputError("--set", item, "the key before '=' is empty or has an empty part; "
                         "must look like dotted.key=value, e.g. contact.mu_rad=0.3")
    return key, text.strip()


def parse_value(text: str):
    """Parse the value of a ``--set key=value`` override as a TOML value (bare words -> strings)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def get_dotted(data: dict, dotted_key: str):
    """``data['a']['b']`` for ``'a.b'`` (a numeric part indexes an array of tables); unknown keys
    are an error."""
    node = data
    for i, part in enumerate(dotted_key.split(".")):
        if isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise InputError(dotted_key, None, f"no such key '{'.'.join(dotted_key.split('.')[: i + 1])}' in the input")
    return node


def set_dotted(data: dict, dotted_key: str, value, *, must_exist: bool = True, create_leaf: bool = False) -> None:
    """Set ``data['a']['b'] = value`` for ``'a.b'``; unknown keys are an error when ``must_exist``
    (with ``create_leaf`` a missing last key inside an existing table is created; the schema
    validation then accepts it if it is a known optional field and names it otherwise).
    A numeric part indexes an array of tables: ``rotor.sections.3.outer_diameter``."""
    parts = dotted_key.split(".")
    node = data
    for i, part in enumerate(parts[:-1]):
        if isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
            continue
        if not isinstance(node, dict) or part not in node:
            if must_exist:
                raise InputError(dotted_key, value, f"no such key '{'.'.join(parts[: i + 1])}' in the input")
            node.setdefault(part, {})
        node = node[part]
    if not isinstance(node, dict) or (must_exist and not create_leaf and parts[-1] not in node):
        raise InputError(dotted_key, value, "no such key in the input")
    node[parts[-1]] = value


class Table:
    """A TOML table being read: tracks the dotted path and rejects unknown keys."""

    def __init__(self, data, path: str):
        if not isinstance(data, dict):
            raise InputError(path, data, "must be a table")
        self.data = data
        self.path = path
        self.used: set[str] = set()

    def _field(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        return key in self.data

    def raw(self, key: str, default=...):
        self.used.add(key)
        if key not in self.data:
            if default is ...:
                raise InputError(self._field(key), None, "missing required field")
            return default
        return self.data[key]

    def number(self, key: str, default=..., *, positive=False, nonnegative=False, upper=None) -> float:
        value = self.raw(key, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(self._field(key), value, "must be a finite number")
        if positive and not value > 0:
            raise InputError(self._field(key), value, "must be > 0")
        if nonnegative and not value >= 0:
            raise InputError(self._field(key), value, "must be >= 0")
        if upper is not None and not value < upper:
            raise InputError(self._field(key), value, f"must be < {upper}")
        return float(value)

    def integer(self, key: str, default=..., *, minimum=1) -> int:
        value = self.raw(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise InputError(self._field(key), value, f"must be an integer >= {minimum}")
        return value

    def string(self, key: str, default=...) -> str:
        value = self.raw(key, default)
        if not isinstance(value, str) or not value:
            raise InputError(self._field(key), value, "must be a non-empty string")
        return value

    def boolean(self, key: str, default=...) -> bool:
        value = self.raw(key, default)
        if not isinstance(value, bool):
            raise InputError(self._field(key), value, "must be true or false")
        return value

    def table(self, key: str, default=...) -> "Table":
        return Table(self.raw(key, default), self._field(key))

    def array_of_tables(self, key: str, default=...) -> list["Table"]:
        value = self.raw(key, default)
        if not isinstance(value, list):
            raise InputError(self._field(key), value, "must be an array of tables ([[...]])")
        return [Table(v, f"{self._field(key)}[{i}]") for i, v in enumerate(value)]

    def finish(self) -> None:
        unknown = sorted(set(self.data) - self.used)
        if unknown:
            raise InputError(self._field(unknown[0]), self.data[unknown[0]],
                             f"unknown field; allowed: {', '.join(sorted(self.used))}")


# ---------------------------------------------------------------------------------------------
# Parts shared by the sweep, calibration and mode-fit space files: one check each, so a space
# file with `fixed = 5` or `{min = "a"}` is one InputError line, not a TypeError traceback


def _is_scalar(v) -> bool:
    return isinstance(v, (bool, str)) or (isinstance(v, (int, float)) and math.isfinite(v))


def _plain_key(key: str, field: str) -> None:
    """A quoted scenario key with spaces around it ("operating.speed_rpm ") named the same value as
    the plain one: a whirl map with both as its axes labelled cells it had run at another speed."""
    if not key.strip() or key != key.strip():
        raise InputError(field, repr(key), 'a scenario key without spaces around it, e.g. "operating.speed_rpm"')


def override_table(value, field: str) -> dict:
    """A table of ``"dotted.key" = value`` overrides (``[fixed]``): scalar values only."""
    if not isinstance(value, dict):
        raise InputError(field, value, 'must be a table of scenario keys = values, e.g. [fixed] "operating.t_end" = 0.5')
    for k, v in value.items():
        _plain_key(k, f"{field}.{k}")
        if not _is_scalar(v):
            raise InputError(f"{field}.{k}", v, "must be a number (finite), true/false or a string")
    return dict(value)


def value_list(value, field: str) -> list:
    """A non-empty list of scalar values (a ``[grid]`` entry; ``field`` = table.key)."""
    _plain_key(field.split(".", 1)[-1], field)
    if not isinstance(value, list) or not value:
        raise InputError(field, value, "must be a non-empty list of values")
    for v in value:
        if not _is_scalar(v):
            raise InputError(field, v, "values must be numbers (finite), true/false or strings")
    return value


def range_spec(value, field: str, *, log: bool = False) -> tuple[float, float, bool]:
    """``{min = a, max = b}`` (with ``log`` allowed: ``{..., log = true}``, then a > 0) ->
    (a, b, log)."""
    _plain_key(field.split(".", 1)[-1], field)
    keys = {"min", "max", "log"} if log else {"min", "max"}
    form = "{min = a, max = b" + (", log = true" if log else "") + "}"
    if not (isinstance(value, dict) and {"min", "max"} <= set(value) <= keys):
        raise InputError(field, value, f"must be {form} with finite numbers a < b")
    lo, hi, lg = value["min"], value["max"], value.get("log", False)
    for name, x in (("min", lo), ("max", hi)):
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
            raise InputError(f"{field}.{name}", x, "must be a finite number")
    if not lo < hi:
        raise InputError(field, value, f"must be {form} with a < b")
    if not isinstance(lg, bool):
        raise InputError(f"{field}.log", lg, "must be true or false")
    if lg and not lo > 0:
        raise InputError(f"{field}.min", lo, "must be > 0 with log = true")
    return float(lo), float(hi), lg


def tied_keys(name: str) -> list[str]:
    """The scenario keys of a calibration range's name: ``"a,b"`` is one unknown set on both (tied)."""
    return [k.strip() for k in name.split(",")]


@contextmanager
def study_file(path):
    """``(path, top table)`` of a study's TOML file (sweep, calibration space, fit-modes space):
    every InputError raised inside the ``with`` block names the file."""
    path = Path(path)
    data = load_toml(path)
    try:
        yield path, Table(data, "")
    except InputError as err:
        raise err.with_file(str(path)) from None


def sample_ranges(ranges: dict, n: int, seed: int) -> list[dict]:
    """``n`` Monte Carlo draws of ``{key: {min, max[, log]}}`` (validated by :func:`range_spec`):
    uniform, or log-uniform with ``log = true``; one generator, the keys in file order per draw,
    so a seed gives the same draws in every study."""
    import numpy as np

    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        d = {}
        for k, r in ranges.items():
            if r.get("log"):
                d[k] = float(10 ** rng.uniform(math.log10(r["min"]), math.log10(r["max"])))
            else:
                d[k] = float(rng.uniform(r["min"], r["max"]))
        out.append(d)
    return out
