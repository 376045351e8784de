"""Parameter dataclasses of the scenes: field checks and command-line options from one description.

A scene's parameter field says what it means and which rule it obeys in its metadata::

    crank_length: float = field(metadata=param("crank length r [m]", positive))

:func:`check_fields` applies the rules (``ValueError`` naming the field and the rule,
nothing clamped), and :func:`add_param_options` makes one command-line option per field
(``crank_length`` -> ``--crank-length``, its type from the annotation, its help from the
metadata, its default from the scene's named constructor).  The numeric rules are the
library's public checks (:mod:`exuclear.checks`).
"""
from __future__ import annotations

import argparse
import math
import re
import types
import typing
from collections.abc import Callable, Iterable
from dataclasses import Field, fields
from typing import Any

from exuclear.checks import check_nonnegative, check_positive, check_real
from exuclear.columns import Column

#: A field's rule: takes the field's name and value, returns the value (a float for the
#: numeric rules) or raises ``ValueError`` naming the field.
Check = Callable[[str, Any], Any]


#: The numeric rules are the library's own checks (exuclear.checks), so that a scene's
#: field and the library's argument refuse a bad value with the same words.
real, positive, nonnegative = check_real, check_positive, check_nonnegative


def nonzero(rule: str) -> Check:
    """A real number other than 0; ``rule`` says what its sign means."""

    def check(name: str, value: object) -> float:
        if real(name, value) == 0.0:
            raise ValueError(f"`{name}` must be non-zero ({rule}), got 0")
        return float(value)

    return check


def crank_speed_from_rpm(name: str, rpm: object) -> float:
    """A crank speed given in rpm (command lines, studies) in rad/s; ``ValueError`` naming
    ``name`` unless it is a real number other than 0 (negative: a clockwise crank)."""
    return nonzero("negative for a clockwise crank")(name, rpm) * math.pi / 30.0


def optional(rule: Check) -> Check:
    """None, or a value that obeys ``rule``."""

    def check(name: str, value: object) -> object:
        return None if value is None else rule(name, value)

    return check


def boolean(name: str, value: object) -> bool:
    if not isinstance(value, bool):
        raise ValueError(f"`{name}` must be True or False, got {value!r}")
    return value


def count(name: str, value: object) -> int:
    """A positive whole number."""
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"`{name}` must be a positive whole number, got {value!r}")
    return value


def one_of(known: Iterable[str]) -> Check:
    """One of the names ``known`` (listed in this order in the error)."""
    known = tuple(known)

    def check(name: str, value: object) -> str:
        if not isinstance(value, str) or value not in known:
            raise ValueError(f"unknown `{name}` {value!r}; known: {', '.join(known)}")
        return value

    return check


def param(help: str, check: Check | None = None, *, option: str | None = None, cli: bool = True,
          choices: Iterable[str] | None = None) -> dict[str, Any]:
    """The metadata of a parameter field.

    Parameters
    ----------
    help : str
        What the field means, with its unit: the option's help text.
    check : callable, optional
        Its rule (:func:`positive`, :func:`one_of`, ...), applied by :func:`check_fields`.
    option : str, optional
        A second, shorter option name kept from earlier command lines (``"journal"`` for
        ``journal_material``).
    cli : bool
        False: no generated option (the scene gives the value its own way, e.g. the crank
        speed in rpm).
    choices : iterable of str, optional
        The values the option accepts (argparse refuses others).
    """
    return {"help": help, "check": check, "option": option, "cli": cli,
            "choices": None if choices is None else tuple(choices)}


def check_fields(params: object) -> None:
    """Apply every field's rule (:func:`param`), in field order."""
    for f in fields(params):
        rule = f.metadata.get("check")
        if rule is not None:
            rule(f.name, getattr(params, f.name))


def option_name(name: str) -> str:
    """``"crank_length"`` -> ``"--crank-length"``."""
    return "--" + name.replace("_", "-")


#: What an option's value is called in ``--help``, by its type.
METAVARS = {float: "X", int: "N", str: "NAME"}


def _option_type(hint: object) -> type:
    """The type an option converts its text to: that of the annotation, without ``None``."""
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        hint = next(arg for arg in typing.get_args(hint) if arg is not type(None))
    return hint


def _option_fields(cls: type) -> list[Field]:
    """The fields of the dataclass ``cls`` that have a :func:`param` with ``cli`` true."""
    return [f for f in fields(cls) if f.metadata.get("cli", False)]


def add_param_options(ap: argparse.ArgumentParser, defaults: object) -> None:
    """Add one option per field of the dataclass instance ``defaults`` that has a
    :func:`param` with ``cli`` true, defaulting to that instance's value (its ``dest`` is
    the field's name; :func:`changes_from_args` reads them back)."""
    hints = typing.get_type_hints(type(defaults))
    for f in _option_fields(type(defaults)):
        default = getattr(defaults, f.name)
        flags = [option_name(f.name)] + ([option_name(f.metadata["option"])] if f.metadata["option"] else [])
        kind = _option_type(hints[f.name])
        if kind not in (bool, *METAVARS):
            raise TypeError(f"field `{f.name}` of type {kind} has no generated option: give it cli=False and an "
                            "option of the scene's own")
        if kind is bool:  # a flag; --no-NAME as well where it defaults to True
            action = argparse.BooleanOptionalAction if default else "store_true"
            ap.add_argument(*flags, dest=f.name, action=action, default=default, help=f.metadata["help"])
        else:
            shown = "" if default is None else " (default %(default)s)"
            ap.add_argument(*flags, dest=f.name, type=kind, default=default, choices=f.metadata["choices"],
                            metavar=None if f.metadata["choices"] else METAVARS.get(kind, "VALUE"),
                            help=f.metadata["help"].replace("%", "%%") + shown)


def changes_from_args(args: argparse.Namespace, cls: type) -> dict[str, Any]:
    """The fields of ``cls`` that :func:`add_param_options` made options of, as parsed."""
    return {f.name: getattr(args, f.name) for f in _option_fields(cls)}


#: A unit in a field's help text: ``"crank length r [m]"``.
_UNIT = re.compile(r"\s*\[([^\]]+)\]")


def column(f: Field, label: str | None = None) -> Column:
    """The study :class:`~exuclear.columns.Column` of a parameter field: its help text (up to
    a colon, semicolon or parenthesis) as the label, the unit in its brackets, its short
    option (:func:`param`'s ``option``) as the other spelling.  ``label`` replaces the
    label where the help does not read as one."""
    text = f.metadata["help"]
    unit = _UNIT.search(text)
    if label is None:
        label = re.split(r":|;| \(", _UNIT.sub("", text, count=1), maxsplit=1)[0].strip()
    aliases = (f.metadata["option"],) if f.metadata.get("option") else ()
    return Column(label, unit.group(1) if unit else "", aliases)


def study_columns(cls: type, names: Iterable[str], labels: dict[str, str] | None = None) -> dict[str, Column]:
    """:func:`column` of each field of the dataclass ``cls`` among ``names`` (the others are
    left out), with the labels ``labels`` where given."""
    by_name = {f.name: f for f in fields(cls)}
    return {name: column(by_name[name], (labels or {}).get(name)) for name in names if name in by_name}
