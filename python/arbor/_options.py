"""The run options as experiments/options/run_options.cc describes them, for the Python side of the API.

arbor.run's and arbor.Filter's keyword signature and per-option docs are built from these at import, and
scripts/generate_python_stub.py writes the typed stub (__init__.pyi) from the same list, so neither can drift
from the command line. A keyword that is not an option is answered here, in Python's terms (`asoc=` -> `assoc=`).
"""

import difflib as _difflib
import inspect as _inspect
import math as _math
import os as _os
import textwrap as _textwrap
import typing as _typing

from . import _arbor

_TYPES = {"bool": bool, "int": int, "float": float, "str": str}


class RunOption(_typing.NamedTuple):
    """One run option: `keyword` is the command line's --name with "_" for "-"."""
    keyword: str
    name: str
    type: type
    default: object  # as the command line's default, typed; None where it has none
    choices: tuple
    help: str


def _typed_default(info):
    text = info["default"]
    if info["type"] == "bool":
        return text.lower() in ("true", "1", "on", "yes")
    if not text:
        return None
    return _TYPES[info["type"]](text)


def _read_options():
    return tuple(RunOption(keyword=info["name"].replace("-", "_"), name=info["name"], type=_TYPES[info["type"]],
                           default=_typed_default(info), choices=tuple(info["choices"]), help=info["help"])
                 for info in _arbor._run_options())


RUN_OPTIONS = _read_options()

# What each call takes as keywords: the scenario is their first argument, and a Filter writes no files.
RUN_KEYWORDS = tuple(o for o in RUN_OPTIONS if o.keyword != "scenario")
FILTER_KEYWORDS = tuple(o for o in RUN_KEYWORDS if o.keyword != "out")


def annotation(option):
    """The keyword's type for a signature: a Literal of the names a named value accepts, a path for paths."""
    if option.choices:
        return _typing.Literal[option.choices]
    if option.keyword in ("out", "prior_map"):
        return _typing.Optional[_typing.Union[str, _os.PathLike]]
    return option.type


def is_plain_default(value):
    """Whether a default can be written as a Python literal (an infinite float cannot)."""
    return not (isinstance(value, float) and not _math.isfinite(value))


def signature(first, options, returns):
    """`first` (positional parameters) then `options` as keyword-only parameters with the CLI's defaults."""
    keywords = [_inspect.Parameter(o.keyword, _inspect.Parameter.KEYWORD_ONLY, annotation=annotation(o),
                                   default=o.default)
                for o in options]
    return _inspect.Signature([*first, *keywords], return_annotation=returns)


def describe(option):
    """One option's entry in a docstring: the keyword, its type or names and default, then --help's text."""
    kind = "{" + ", ".join(repr(c) for c in option.choices) + "}" if option.choices else option.type.__name__
    head = f"{option.keyword} : {kind}" + (f", default {option.default!r}" if option.default is not None else "")
    return head + "\n" + _textwrap.fill(option.help, width=100, initial_indent="    ", subsequent_indent="    ",
                                         break_on_hyphens=False, break_long_words=False)


def options_doc(options):
    """The docstring section listing `options`, in `arbor run --help`'s order."""
    return ("Keyword options (`arbor run`'s, with \"_\" for \"-\": known_gate=0.999 is --known-gate=0.999):\n\n"
            + "\n".join(describe(o) for o in options))


def check_keywords(function, given, options):
    """Refuses a keyword that is not among `options`, naming the closest one as Python spells it. Raises
    arbor.InputError with the keyword as its field, as for a bad value."""
    allowed = [o.keyword for o in options]
    for key in given:
        if key in allowed:
            continue
        close = _difflib.get_close_matches(key, allowed, n=1)
        hint = f" (did you mean {close[0]}=?)" if close else ""
        error = _arbor.InputError(f"{key!r} is not an option of arbor.{function}{hint}; "
                                  f"help(arbor.{function}) lists them")
        error.file, error.line, error.field = "", 0, key
        raise error
