"""Sweep files: reading, strict validation and expansion into runs.

A sweep file (YAML, config/sweeps/*.yaml; every key is described in docs/sweeps.md) names a base
scene, fixed overrides, a grid of parameter values (a product of axes, optionally crossed with
one group of zipped lists), the stopping rule, what to record and the plots to draw. Every
problem is a SweepError whose message names the key (as a path, e.g. `grid.product.Ca_E[2]`),
the value and what is accepted.

Expansion is deterministic: the runs come in the order of the grid (product keys in the order
written, the zip group last, the last key varying fastest) and each run's name is built from its
values alone (`Ca=0.04+Ca_E=0.3+case=A`), so a name does not change when the grid is extended.
"""
import copy
import itertools
import math
import os
import re

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES_DIR = os.path.join(REPO, "config", "scenes")

# Grid keys starting with this prefix are labels (carried into names, the table and plots), not
# scene keys: `tag.case: [A, B, C]` next to `sigma_r: [1.75, 3.25, 4.75]` in a zip group.
TAG_PREFIX = "tag."

# Quantities a plot can show. Time series: CSV columns of `ehd_sim run` (theta is the
# inclination in units of pi). Final values: columns of the summary table.
SERIES_QUANTITIES = {
    "dxy": "D_xy",
    "theta": "theta / pi",
    "tt_phase": "tank-treading phase (rad)",
    "area_drift": "area drift",
    "area": "area / (pi a^2)",
    "gmres_iterations": "GMRES iterations",
}
FINAL_QUANTITIES = {
    "dxy": "final D_xy",
    "theta": "final theta / pi",
    "tt_frequency": "tank-treading frequency f = 4 pi / (k T)",
    "steady_time": "steady-state time (1/k)",
    "wall_s": "wall time (s)",
    "area_drift": "final area drift",
}
NAME_VALUE = re.compile(r"^[A-Za-z0-9._-]+$")

# A grid key that is not a scene key but chooses each run's base scene (a shipped scene name or
# a .yaml path): `grid.product.scene: [shear_field, drop_shear]`; the top-level `scene` is then
# not needed.
SCENE_KEY = "scene"
# The grid key of grid.variants: each entry's name (a tag, shown as "variant").
VARIANT_KEY = TAG_PREFIX + "variant"


class SweepError(Exception):
    """A sweep file problem; the message names the key."""


class _Loader(yaml.SafeLoader):
    """SafeLoader that also reads 1e-3 and 5E+2 as floats (YAML 1.1 wants a dot in the
    mantissa, so PyYAML would read them as strings; yaml-cpp, which reads the scenes, takes
    them as numbers)."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
                 |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
                 |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
                 |[-+]?\.(?:inf|Inf|INF)
                 |\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


def load_yaml(path):
    with open(path) as f:
        return yaml.load(f, Loader=_Loader)


def load_yaml_text(text):
    return yaml.load(text, Loader=_Loader)


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _type_name(v):
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "a boolean"
    if _is_number(v):
        return "a number"
    if isinstance(v, str):
        return "a string"
    if isinstance(v, list):
        return "a list"
    if isinstance(v, dict):
        return "a mapping"
    return type(v).__name__


def _check_keys(where, mapping, allowed, required=()):
    if not isinstance(mapping, dict):
        raise SweepError("%s: must be a mapping, got %s" % (where or "sweep file",
                                                            _type_name(mapping)))
    for k in mapping:
        if k not in allowed:
            raise SweepError("%s: unknown key '%s'; accepted keys: %s" % (
                where or "sweep file", k, ", ".join(sorted(allowed))))
    for k in required:
        if k not in mapping:
            raise SweepError("%s: missing key '%s'" % (where or "sweep file", k))


def _path(where, key):
    return "%s.%s" % (where, key) if where else key


def _number(where, v, low=None, high=None, integer=False, low_open=False):
    """A number (an integer if asked) in [low, high] (low excluded when low_open)."""
    if not _is_number(v) or (integer and not isinstance(v, int)):
        raise SweepError("%s: must be %s, got %s (%r)" % (
            where, "an integer" if integer else "a number", _type_name(v), v))
    if isinstance(v, float) and not math.isfinite(v):
        raise SweepError("%s: must be finite, got %r" % (where, v))
    if low is not None and (v < low or (low_open and v == low)):
        raise SweepError("%s: %r is out of range: accepted %s%s, %s]" % (
            where, v, "(" if low_open else "[", low, "inf" if high is None else high))
    if high is not None and v > high:
        raise SweepError("%s: %r is out of range: accepted [%s, %s]" % (where, v, low, high))
    return v


def _string(where, v):
    if not isinstance(v, str) or not v:
        raise SweepError("%s: must be a non-empty string, got %s (%r)" % (where, _type_name(v), v))
    return v


def _scalar(where, v):
    if not (_is_number(v) or isinstance(v, (str, bool))):
        raise SweepError("%s: must be a number, a string or a boolean, got %s" % (
            where, _type_name(v)))
    if isinstance(v, float) and not math.isfinite(v):
        raise SweepError("%s: must be finite, got %r" % (where, v))
    return v


def format_value(v):
    """The text of a value in run names and tables: shortest round-trip for floats; "" for
    None (a key removed from the base scene)."""
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v) if not isinstance(v, float) else repr(v)


def _key_name(where, key):
    if not isinstance(key, str) or not re.match(r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$",
                                                key):
        raise SweepError("%s: '%s' is not a scene key (letters, digits and _, nested keys "
                         "joined by '.', e.g. geometry.shape)" % (where, key))
    return key


def _value_list(where, values):
    if not isinstance(values, list):
        raise SweepError("%s: must be a list of values, got %s" % (where, _type_name(values)))
    if not values:
        raise SweepError("%s: empty list (a grid axis needs at least one value)" % where)
    seen = set()
    for i, v in enumerate(values):
        _scalar("%s[%d]" % (where, i), v)
        text = format_value(v)
        if not NAME_VALUE.match(text):
            raise SweepError("%s[%d]: %r cannot be part of a run name (letters, digits, '.', "
                             "'_' and '-' only)" % (where, i, v))
        if text in seen:
            raise SweepError("%s[%d]: %r appears twice" % (where, i, v))
        seen.add(text)
    return values


def _flatten(where, mapping, prefix=""):
    """{'geometry': {'shape': 'x'}, 'N': 64} -> {'geometry.shape': 'x', 'N': 64}."""
    out = {}
    for k, v in mapping.items():
        key = _key_name(where, prefix + str(k))
        if isinstance(v, dict) and v:
            out.update(_flatten(where, v, key + "."))
        elif v is None:
            out[key] = None  # `law: ~`: removes the key from the base scene (ehd_sim's law=)
        else:
            out[key] = v if isinstance(v, dict) else _scalar(_path(where, key), v)
    return out


def apply_overrides(scene, overrides):
    """A copy of the scene mapping with dotted-key overrides applied (intermediate mappings are
    created as needed; a scalar in the way is an error naming the key). A None value removes
    the key, as an empty value does in `ehd_sim run --set key=`."""
    out = copy.deepcopy(scene)
    for key, value in overrides.items():
        node = out
        parts = key.split(".")
        if value is None:
            for part in parts[:-1]:
                node = node.get(part) if isinstance(node, dict) else None
            if isinstance(node, dict):
                node.pop(parts[-1], None)
            continue
        for i, part in enumerate(parts[:-1]):
            if part not in node or node[part] is None:
                node[part] = {}
            if not isinstance(node[part], dict):
                raise SweepError("override %s: '%s' in the base scene is %s, not a mapping" % (
                    key, ".".join(parts[:i + 1]), _type_name(node[part])))
            node = node[part]
        node[parts[-1]] = copy.deepcopy(value)
    return out


def resolve_scene(name, base_dir):
    """Path of a base scene: a name in config/scenes, or a .yaml path (relative to the sweep
    file's folder)."""
    if name.endswith(".yaml") or "/" in name:
        path = name if os.path.isabs(name) else os.path.join(base_dir, name)
    else:
        path = os.path.join(SCENES_DIR, name + ".yaml")
    if not os.path.isfile(path):
        raise SweepError("scene: '%s' not found (looked for %s; shipped scenes: %s)" % (
            name, path, ", ".join(sorted(f[:-5] for f in os.listdir(SCENES_DIR)
                                         if f.endswith(".yaml")))))
    return os.path.abspath(path)


class Run:
    """One point of the grid."""

    def __init__(self, index, values, sweep, variant_set=None, t_end=None):
        self.index = index
        self.values = values  # grid key -> value (tags included), in grid order
        self.name = "+".join("%s=%s" % (k[len(TAG_PREFIX):] if k.startswith(TAG_PREFIX) else k,
                                        format_value(v)) for k, v in values.items())
        overrides = dict(sweep.fixed)
        overrides.update({k: v for k, v in values.items()
                          if not k.startswith(TAG_PREFIX) and k != SCENE_KEY})
        overrides.update(variant_set or {})  # the overrides of this run's grid.variants entry
        self.overrides = overrides
        # Its end time: its grid.variants entry's t_end, else stop.t_end (--t-end replaces both).
        self.t_end = sweep.t_end if t_end is None else t_end
        if SCENE_KEY in values:
            self.scene_path = sweep.scene_paths[values[SCENE_KEY]]
            base = sweep.base_scenes[values[SCENE_KEY]]
        else:
            self.scene_path, base = sweep.scene_path, sweep.base_scene
        self.scene = apply_overrides(base, overrides)

    def scene_yaml(self, sweep):
        header = ("# Written by scripts/sweep: sweep %s, run %s\n# base scene %s with %s\n" % (
            sweep.name, self.name, os.path.relpath(self.scene_path, REPO),
            ", ".join("%s=%s" % (k, format_value(v)) for k, v in self.overrides.items())
            or "no overrides"))
        return header + yaml.safe_dump(self.scene, sort_keys=False, default_flow_style=False)


class Plot:
    def __init__(self, where, spec, grid_keys):
        _check_keys(where, spec, {"file", "type", "y", "x", "curves", "for_each", "where",
                                  "title", "logy"}, required=("file", "type", "y"))
        self.file = _string(_path(where, "file"), spec["file"])
        if not self.file.endswith(".png"):
            raise SweepError("%s: '%s' must end in .png" % (_path(where, "file"), self.file))
        self.type = spec["type"]
        if self.type not in ("series", "final"):
            raise SweepError("%s: '%s' is not a plot type; accepted: series (a quantity against "
                             "t, one curve per run), final (a final value against a grid key)" % (
                                 _path(where, "type"), self.type))
        quantities = SERIES_QUANTITIES if self.type == "series" else FINAL_QUANTITIES
        ys = spec["y"] if isinstance(spec["y"], list) else [spec["y"]]
        if not ys:
            raise SweepError("%s: empty list" % _path(where, "y"))
        for i, y in enumerate(ys):
            if y not in quantities:
                raise SweepError("%s: '%s' is not a %s quantity; accepted: %s" % (
                    _path(where, "y") + ("[%d]" % i if isinstance(spec["y"], list) else ""), y,
                    self.type, ", ".join(quantities)))
        self.y = ys

        def grid_key(key_where, k):
            if k not in grid_keys:
                raise SweepError("%s: '%s' is not a grid key; grid keys: %s" % (
                    key_where, k, ", ".join(grid_keys)))
            return k

        self.x = None
        if self.type == "final":
            if "x" not in spec:
                raise SweepError("%s: missing key 'x' (the grid key on the horizontal axis)"
                                 % where)
            self.x = grid_key(_path(where, "x"), spec["x"])
        elif "x" in spec:
            raise SweepError("%s: a series plot is against t; 'x' is for type final" % (
                _path(where, "x")))
        self.curves = grid_key(_path(where, "curves"), spec["curves"]) if "curves" in spec \
            else None
        fe = spec.get("for_each", [])
        if isinstance(fe, str):
            fe = [fe]
        if not isinstance(fe, list):
            raise SweepError("%s: must be a list of grid keys" % _path(where, "for_each"))
        self.for_each = [grid_key("%s[%d]" % (_path(where, "for_each"), i), k)
                         for i, k in enumerate(fe)]
        w = spec.get("where", {})
        _check_keys(_path(where, "where"), w, set(grid_keys))
        self.where = {k: _scalar(_path(_path(where, "where"), k), v) for k, v in w.items()}
        self.title = _string(_path(where, "title"), spec["title"]) if "title" in spec else ""
        self.logy = bool(spec.get("logy", False))
        used = [k for k in [self.x, self.curves] + self.for_each if k]
        if len(set(used)) != len(used):
            raise SweepError("%s: x, curves and for_each must be different keys (got %s)" % (
                where, ", ".join(used)))
        for k in used:
            if k in self.where:
                raise SweepError("%s: '%s' is both selected by where and plotted" % (
                    _path(where, "where"), k))
        for template in (self.file, self.title):
            for field in re.findall(r"\{([^}]*)\}", template):
                if field not in self.for_each and TAG_PREFIX + field not in self.for_each:
                    raise SweepError("%s: {%s} in '%s' is not a for_each key (for_each: %s)" % (
                        where, field, template, ", ".join(self.for_each) or "none"))


def fill_template(template, values):
    """'dxy_{case}_{Ca}.png' with {'tag.case': 'A', 'Ca': 0.04} -> 'dxy_A_0.04.png' (a field
    is a grid key, a tag without its prefix, or a nested key such as geometry.shape)."""
    def field(m):
        name = m.group(1)
        key = name if name in values else TAG_PREFIX + name
        return format_value(values[key])
    return re.sub(r"\{([^}]*)\}", field, template)


class Sweep:
    """A validated sweep file and its runs."""

    TOP_KEYS = {"name", "description", "reference", "scene", "set", "grid", "stop", "record",
                "plots", "table", "jobs"}

    def __init__(self, path, extra_set=None, t_end=None, only=None):
        """extra_set: overrides from the command line (`--set N=64`), added to the file's `set`
        (and replacing its values); t_end: replaces stop.t_end (`--t-end`); only: {grid key:
        [values]} keeps the runs with those values (`--only scene=a,b`)."""
        self.path = os.path.abspath(path)
        if not os.path.isfile(self.path):
            raise SweepError("sweep file %s not found" % path)
        try:
            data = load_yaml(self.path)
        except yaml.YAMLError as e:
            raise SweepError("sweep file %s is not valid YAML: %s" % (path, e))
        self.text = open(self.path).read()
        _check_keys("", data, self.TOP_KEYS, required=("grid", "stop"))
        stem = os.path.splitext(os.path.basename(self.path))[0]
        self.name = _string("name", data.get("name", stem))
        if not NAME_VALUE.match(self.name):
            raise SweepError("name: '%s' must be letters, digits, '.', '_' and '-' only" %
                             self.name)
        self.description = _string("description", data["description"]) \
            if "description" in data else ""
        self.reference = _string("reference", data["reference"]) if "reference" in data else ""
        self.scene_path, self.base_scene = None, None
        if "scene" in data:
            self.scene_path = resolve_scene(_string("scene", data["scene"]),
                                            os.path.dirname(self.path))
            self.base_scene = _load_scene(self.scene_path)
        self.jobs = _number("jobs", data["jobs"], low=1, integer=True) if "jobs" in data \
            else None

        fixed = data.get("set", {}) or {}
        _check_keys("set", fixed, set(fixed) if isinstance(fixed, dict) else set())
        self.fixed = _flatten("set", fixed)
        self.variant = []  # the command-line changes, in the default output folder's name
        for key, value in (extra_set or {}).items():
            _key_name("--set", key)
            # KEY= (None) removes the key from the base scene, as in ehd_sim run --set.
            self.fixed[key] = None if value is None else _scalar("--set %s" % key, value)
            self.variant.append("%s=%s" % (key, format_value(value)))
        self.t_end_replaced = t_end is not None  # --t-end: also replaces the variants' t_end
        if t_end is not None:
            stop = data.get("stop")
            if isinstance(stop, dict):
                stop = dict(stop, t_end=t_end)
                data["stop"] = stop
            self.variant.append("t_end=%s" % format_value(t_end))

        self._read_grid(data["grid"])
        if self.base_scene is None and SCENE_KEY not in self.grid_keys:
            raise SweepError("sweep file: missing key 'scene' (the base scene; or give a grid "
                             "key 'scene' with a base scene per run)")
        if self.base_scene is not None and SCENE_KEY in self.grid_keys:
            raise SweepError("scene: given both at the top and as a grid key; keep one")
        self.scene_paths, self.base_scenes = {}, {}
        for i, name in enumerate(self._grid_values(SCENE_KEY)):
            where = self._grid_where[SCENE_KEY] + "[%d]" % i
            try:
                self.scene_paths[name] = resolve_scene(_string(where, name),
                                                       os.path.dirname(self.path))
            except SweepError as e:
                raise SweepError("%s: %s" % (where, e))
            self.base_scenes[name] = _load_scene(self.scene_paths[name])
        self._read_stop(data["stop"])
        self._read_record(data.get("record", {}))
        plots = data.get("plots", [])
        if not isinstance(plots, list):
            raise SweepError("plots: must be a list, got %s" % _type_name(plots))
        self.plots = [Plot("plots[%d]" % i, p, self.grid_keys) for i, p in enumerate(plots)]
        files = [p.file for p in self.plots]
        for f in files:
            if files.count(f) > 1:
                raise SweepError("plots: file '%s' appears twice" % f)

        self.table = None
        if "table" in data:
            self.table = _load_table(_string("table", data["table"]), os.path.dirname(self.path))

        self.runs = []
        for index, combo in enumerate(itertools.product(*self.axes)):
            values, variant_set, run_t_end = {}, {}, None
            for part in combo:
                part = dict(part)
                variant_set.update(part.pop("__set__", {}))
                run_t_end = part.pop("__t_end__", run_t_end)
                values.update(part)
            if self.t_end_replaced:
                run_t_end = None
            self.runs.append(Run(index, values, self, variant_set, run_t_end))
        for key, wanted in (only or {}).items():
            self._select(key, wanted)
        names = [r.name for r in self.runs]
        if len(set(names)) != len(names):  # cannot happen with distinct values; kept as a guard
            raise SweepError("grid: two runs have the same name")

    def _select(self, key, wanted):
        """Keeps the runs whose grid value of key (a tag with or without its prefix) is one of
        wanted (texts, as in run names); the runs are numbered again (--task follows)."""
        full = key if key in self.grid_keys else TAG_PREFIX + key
        if full not in self.grid_keys:
            raise SweepError("--only %s: not a grid key; grid keys: %s" % (
                key, ", ".join(k[len(TAG_PREFIX):] if k.startswith(TAG_PREFIX) else k
                               for k in self.grid_keys)))
        values = [format_value(r.values[full]) for r in self.runs]
        for w in wanted:
            if w not in values:
                raise SweepError("--only %s: '%s' is not one of its values (%s)" % (
                    key, w, ", ".join(dict.fromkeys(values))))
        self.runs = [r for r in self.runs if format_value(r.values[full]) in wanted]
        for i, r in enumerate(self.runs):
            r.index = i
        self.variant.append("%s=%s" % (key, "-".join(wanted)))

    def _read_grid(self, grid):
        _check_keys("grid", grid, {"product", "zip", "variants"})
        if not grid:
            raise SweepError("grid: empty (give 'product', 'zip' and/or 'variants')")
        self.axes = []  # each axis: a list of {key: value} mappings (one per point)
        self.grid_keys = []
        self._grid_where = {}  # grid key -> where it is written (for messages)
        self.variant_labels = {}  # grid.variants name -> its label (the name if none)
        variant_keys = set()
        for section in grid:  # the axes in the order written (the last varies fastest)
            if section == "product":
                self._read_product(grid["product"])
            elif section == "zip":
                self._read_zip(grid["zip"])
            else:
                variant_keys = self._read_variants(grid["variants"])
        for key in self.grid_keys:
            if key in self.fixed:
                raise SweepError("grid: '%s' is also fixed in 'set'" % key)
            if key in variant_keys:
                raise SweepError("grid.variants: '%s' is also a grid key of %s" % (
                    key, self._grid_where[key]))
            if key.startswith(TAG_PREFIX) and key.count(".") != 1:
                raise SweepError("grid: tag '%s' must be one word after '%s'" % (key, TAG_PREFIX))
        for key in variant_keys:
            if key in self.fixed:
                raise SweepError("grid.variants: '%s' is also fixed in 'set' (a variant's "
                                 "overrides must not replace the common ones silently)" % key)
        for key in self.fixed:
            if key.startswith(TAG_PREFIX):
                raise SweepError("set.%s: tags belong in the grid" % key)
            if key == SCENE_KEY:
                raise SweepError("set.scene: the base scene is the top-level key 'scene'")

    def _add_key(self, where, key):
        if key in self.grid_keys:
            raise SweepError("%s: '%s' is also in %s" % (where, key, self._grid_where[key]))
        self.grid_keys.append(key)
        self._grid_where[key] = where

    def _grid_values(self, key):
        return [point[key] for axis in self.axes for point in axis if key in point]

    def _read_product(self, product):
        if not isinstance(product, dict):
            _bad_mapping("grid.product", product)
        if not product:
            raise SweepError("grid.product: empty (give at least one key with its values)")
        for key, values in product.items():
            _key_name("grid.product", key)
            _value_list("grid.product.%s" % key, values)
            self._add_key("grid.product.%s" % key, key)
            self.axes.append([{key: v} for v in values])

    def _read_zip(self, z):
        if not isinstance(z, dict):
            _bad_mapping("grid.zip", z)
        if not z:
            raise SweepError("grid.zip: empty (give at least one key with its values)")
        length = None
        first = None
        for key, values in z.items():
            _key_name("grid.zip", key)
            _value_list("grid.zip.%s" % key, values)
            if length is None:
                length, first = len(values), key
            elif len(values) != length:
                raise SweepError("grid.zip.%s: %d values, but grid.zip.%s has %d (zipped "
                                 "lists go together and must have the same length)" % (
                                     key, len(values), first, length))
            self._add_key("grid.zip.%s" % key, key)
        self.axes.append([{k: z[k][i] for k in z} for i in range(length)])

    def _read_variants(self, variants):
        """grid.variants: a list of named override sets, one axis (grid key `variant`); an
        entry's t_end replaces stop.t_end for its runs."""
        if not isinstance(variants, list):
            raise SweepError("grid.variants: must be a list of {name, label, set, t_end}, got %s" %
                             _type_name(variants))
        if not variants:
            raise SweepError("grid.variants: empty list")
        self._add_key("grid.variants", VARIANT_KEY)
        axis, keys = [], set()
        for i, v in enumerate(variants):
            where = "grid.variants[%d]" % i
            _check_keys(where, v, {"name", "label", "set", "t_end"}, required=("name",))
            name = _string(where + ".name", v["name"])
            if not NAME_VALUE.match(name):
                raise SweepError("%s.name: '%s' must be letters, digits, '.', '_' and '-' only "
                                 "(it is part of the run name)" % (where, name))
            if name in self.variant_labels:
                raise SweepError("%s.name: '%s' appears twice" % (where, name))
            self.variant_labels[name] = _string(where + ".label", v["label"]) \
                if "label" in v else name
            overrides = v.get("set", {}) or {}
            _check_keys(where + ".set", overrides, set(overrides)
                        if isinstance(overrides, dict) else set())
            overrides = _flatten(where + ".set", overrides)
            for key in overrides:
                if key.startswith(TAG_PREFIX) or key == SCENE_KEY:
                    raise SweepError("%s.set.%s: a variant sets scene keys only" % (where, key))
            keys.update(overrides)
            point = {VARIANT_KEY: name, "__set__": overrides}
            if "t_end" in v:
                point["__t_end__"] = float(_number(where + ".t_end", v["t_end"], low=0,
                                                   low_open=True))
            axis.append(point)
        self.axes.append(axis)
        return keys

    def _read_stop(self, stop):
        _check_keys("stop", stop, {"t_end", "steady"}, required=("t_end",))
        self.t_end = float(_number("stop.t_end", stop["t_end"], low=0, low_open=True))
        self.steady = float(_number("stop.steady", stop["steady"], low=0, high=1,
                                    low_open=True)) if "steady" in stop else None

    def _read_record(self, record):
        record = record or {}
        _check_keys("record", record, {"csv_every", "checkpoint_every", "vtk_final",
                                       "keep_checkpoint", "steady_tolerance", "sections_every"})
        self.csv_every = _number("record.csv_every", record.get("csv_every", 100), low=1,
                                 integer=True)
        # A chunk is one ehd_sim process; the steady rule is checked at chunk ends, so a sweep
        # that stops at the steady state uses short chunks by default.
        self.checkpoint_given = "checkpoint_every" in record
        self.checkpoint_every = float(_number(
            "record.checkpoint_every", record.get("checkpoint_every", self._default_chunk(
                self.t_end)), low=0, low_open=True))
        self.vtk_final = record.get("vtk_final", False)
        if not isinstance(self.vtk_final, bool):
            raise SweepError("record.vtk_final: must be true or false, got %r" % self.vtk_final)
        # The membrane's section in the shear plane every this many steps (ehd_sim run
        # --sections): sections.csv in the run's folder; 0 or absent: none.
        self.sections_every = _number("record.sections_every", record.get("sections_every", 0),
                                      low=0, integer=True)
        self.keep_checkpoint = record.get("keep_checkpoint", False)
        if not isinstance(self.keep_checkpoint, bool):
            raise SweepError("record.keep_checkpoint: must be true or false, got %r" %
                             self.keep_checkpoint)
        default_tol = self.steady if self.steady is not None else 1e-3
        self.steady_tolerance = float(_number("record.steady_tolerance",
                                              record.get("steady_tolerance", default_tol), low=0,
                                              high=1, low_open=True))

    def _default_chunk(self, t_end):
        return min(t_end, 1.0 if self.steady is not None else 10.0)

    def t_end_of(self, run=None):
        """The end time of a run (its variant's t_end or stop.t_end; stop.t_end without one)."""
        return self.t_end if run is None else run.t_end

    def checkpoint_every_of(self, run=None):
        """A run's chunk length: record.checkpoint_every, else the default of its own t_end."""
        if self.checkpoint_given:
            return self.checkpoint_every
        return self._default_chunk(self.t_end_of(run))

    def chunk_ends(self, run=None):
        """The simulation times at which each chunk (one ehd_sim process) of a run ends and
        writes a checkpoint: checkpoint_every, 2 checkpoint_every, ..., its t_end."""
        t_end, every = self.t_end_of(run), self.checkpoint_every_of(run)
        ends = []
        k = 1
        while k * every < t_end * (1 - 1e-12):
            ends.append(round(k * every, 12))
            k += 1
        ends.append(t_end)
        return ends

    def run_settings(self, run=None):
        """What, besides the scene, decides a run's result (compared on resume)."""
        settings = {"t_end": self.t_end_of(run), "steady": self.steady,
                    "csv_every": self.csv_every, "checkpoint_every": self.checkpoint_every_of(run),
                    "steady_tolerance": self.steady_tolerance}
        if self.sections_every:
            settings["sections_every"] = self.sections_every
        return settings


def _load_scene(path):
    try:
        scene = load_yaml(path)
    except yaml.YAMLError as e:
        raise SweepError("scene %s is not valid YAML: %s" % (path, e))
    if not isinstance(scene, dict):
        raise SweepError("scene %s: not a mapping" % path)
    return scene


def _load_table(name, base_dir):
    """The campaign table of `table: FILE.py` (relative to the sweep file): a Python file
    defining table(runs) -> (header, rows[, notes[, after]]) (docs/campaigns.md)."""
    import importlib.util
    path = name if os.path.isabs(name) else os.path.join(base_dir, name)
    if not name.endswith(".py") or not os.path.isfile(path):
        raise SweepError("table: '%s' is not a Python file (looked for %s)" % (name, path))
    module_name = "campaign_table_" + re.sub(r"[^A-Za-z0-9_]", "_", os.path.basename(path)[:-3])
    spec = importlib.util.spec_from_file_location(module_name, path)
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except Exception as e:  # noqa: BLE001 - any error of the file is the file's
        raise SweepError("table: %s does not load: %s: %s" % (name, type(e).__name__, e))
    if not callable(getattr(module, "table", None)):
        raise SweepError("table: %s defines no function table(runs)" % name)
    return module


def _bad_mapping(where, v):
    raise SweepError("%s: must be a mapping of key: [values], got %s" % (where, _type_name(v)))
