"""Typed, closed TOML tables: the schema check shared by every pair format.

A schema maps a table name (``""`` for the top level, ``"material.pinion"`` for a
nested table) to ``{key: (expected type, required)}``. :func:`check_tables` splits a
parsed TOML document into those tables, converts each value to its type and raises
:class:`~gearcontact.validation.InputRangeError` naming the dotted key for an unknown
table or key, a value of the wrong type, or a missing required key.
"""

from __future__ import annotations

from ..materials import STEEL, Material
from ..validation import InputRangeError

__all__ = ["FLOAT", "INT", "MATERIAL_SCHEMA", "PRINTED", "STR", "check_tables", "materials_of",
           "typed_value"]

FLOAT, INT, STR = "a number (float)", "an integer", "a string"
#: A value as a summary sheet prints it (``[print.gear]``): a text (``"WITH 0.070"``), a
#: number, or a list of texts; kept as typed, its words read by ``geometry.print_words``.
PRINTED = "as printed: a text ('WITH 0.070'), a number or a list of texts"

#: The ``[material.pinion]`` / ``[material.gear]`` tables of every pair format.
MATERIAL_SCHEMA = {f"material.{m}": {"youngs_modulus_gpa": (FLOAT, True),
                                     "poisson_ratio": (FLOAT, True)}
                   for m in ("pinion", "gear")}


def typed_value(key: str, value, kind: str):
    """Return ``value`` converted to the schema type or raise naming the key."""
    if kind == INT:
        if isinstance(value, bool) or not isinstance(value, int):
            raise InputRangeError(key, value, kind)
        return value
    if kind == FLOAT:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputRangeError(key, value, kind)
        return float(value)
    if kind == PRINTED:
        if isinstance(value, list) and all(isinstance(v, str) for v in value):
            return list(value)
        if isinstance(value, bool) or not isinstance(value, (str, int, float)):
            raise InputRangeError(key, value, kind)
        return value
    if not isinstance(value, str):
        raise InputRangeError(key, value, kind)
    return value


def check_tables(doc: dict, schema: dict[str, dict[str, tuple[str, bool]]],
                 required: tuple[str, ...], *, also: tuple[str, ...] = ()) -> dict[str, dict]:
    """Split a parsed TOML document into the tables of ``schema``, typed and checked.

    Tables whose name holds dots (``material.pinion``, ``machine.pinion.drive``) are
    nested as deep in the document; ``required`` names the tables that must be present;
    ``also``: the names of tables the caller reads apart from ``doc`` (``print.gear``),
    listed beside the schema's where an unknown table is named.
    """
    # depth of each nested table family: material.pinion -> 1, machine.pinion.drive -> 2
    nested: dict[str, int] = {}
    for name in schema:
        if "." in name:
            head = name.split(".")[0]
            nested[head] = max(nested.get(head, 0), name.count("."))
    sections: dict[str, dict] = {"": {}}
    for key, value in doc.items():
        if isinstance(value, dict) and key in nested:
            tables = {key: value}
            for _ in range(nested[key]):
                deeper = {}
                for prefix, table in tables.items():
                    for sub, inner in table.items():
                        name = f"{prefix}.{sub}"
                        if not isinstance(inner, dict) or not any(
                                s == name or s.startswith(name + ".") for s in schema):
                            raise InputRangeError(name, inner, "one of the tables " + str(
                                sorted(s for s in schema if s.startswith(key + "."))))
                        deeper[name] = inner
                tables = deeper
            sections.update(tables)
        elif isinstance(value, dict):
            if key not in schema:
                raise InputRangeError(key, "table", "one of the tables "
                                      f"{sorted({*(s for s in schema if s), *also})}")
            sections[key] = value
        else:
            sections[""][key] = value
    out: dict[str, dict] = {}
    for name, table in sections.items():
        fields = schema[name]
        typed = {}
        for key, value in table.items():
            dotted = f"{name}.{key}" if name else key
            if key not in fields:
                raise InputRangeError(dotted, value, f"a known key of [{name or 'top level'}]: "
                                      f"{sorted(fields)}")
            typed[key] = typed_value(dotted, value, fields[key][0])
        for key, (kind, needed) in fields.items():
            if needed and key not in typed:
                raise InputRangeError(f"{name}.{key}" if name else key, None,
                                      f"required: {kind}")
        out[name] = typed
    for name in required:
        if name not in out:
            raise InputRangeError(f"[{name}]", None, "a required table")
    return out


def materials_of(tables: dict[str, dict]) -> dict[str, Material]:
    """``{"pinion": Material, "gear": Material}`` of the checked ``[material.*]``
    tables (steel, :data:`~gearcontact.materials.STEEL`, where a table is absent)."""
    out = {}
    for member in ("pinion", "gear"):
        table = tables.get(f"material.{member}")
        out[member] = STEEL if table is None else Material.from_gpa(
            table["youngs_modulus_gpa"], table["poisson_ratio"], name=f"{member} material")
    return out
