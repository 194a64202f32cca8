#!/usr/bin/env python3
"""Rewrites the generated blocks of python/arbor/__init__.pyi, the typed stub of `import arbor`.

    PYTHONPATH=build/python /usr/bin/python3 scripts/generate_python_stub.py          # rewrite the blocks
    PYTHONPATH=build/python /usr/bin/python3 scripts/generate_python_stub.py --check   # exit 1 if one is stale

The stub is written by hand but for the blocks between "# generated: NAME" and "# end generated: NAME": the
package's exports (arbor.__all__), and arbor.run's and arbor.Filter's keywords (their types, defaults and docs,
from the built module's run option descriptors, experiments/options/run_options.cc, through arbor._options), so
a new or changed option changes the stub. tests/python/test_typing.py fails while a block lags; it checks the
hand-written rest against the package.
"""

import argparse
import json
import os
import re
import sys
import textwrap

import arbor
from arbor import _options

STUB = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python", "arbor", "__init__.pyi")
WIDTH = 110  # the stub's line length


def literal(value):
    """A default as the docs write it: a Python literal, or None where it is not one (an infinite float)."""
    if not _options.is_plain_default(value):
        return None
    return json.dumps(value) if isinstance(value, str) else repr(value)


def type_text(option):
    if option.choices:
        return "Literal[" + ", ".join(json.dumps(c) for c in option.choices) + "]"
    if option.keyword in ("out", "prior_map"):
        return "_Path | None"
    return option.type.__name__


def field(option):
    """One keyword as a TypedDict field, with --help's text and the default as its docstring."""
    default = literal(option.default) if option.default is not None else None
    doc = option.help.replace('"""', "'''") + (f" (default {default})" if default is not None else "")
    lines = textwrap.wrap(f'"""{doc}"""', width=WIDTH, initial_indent="    ", subsequent_indent="    ",
                          break_on_hyphens=False, break_long_words=False)
    return f"    {option.keyword}: {type_text(option)}\n" + "\n".join(lines)


def typed_dict(name, base, doc, options):
    return "\n".join([f"class {name}({base}, total=False):", f'    """{doc}"""', *(field(o) for o in options)])


def exports():
    return "__all__ = [\n" + textwrap.fill(", ".join(json.dumps(n) for n in arbor.__all__) + ",", width=WIDTH,
                                           initial_indent="    ", subsequent_indent="    ") + "\n]"


def run_options():
    filter_keywords = set(_options.FILTER_KEYWORDS)
    return "\n\n\n".join([
        typed_dict("_FilterOptions", "TypedDict",
                   "arbor.Filter's keywords: `arbor run`'s options, with \"_\" for \"-\" (known_gate=0.999 is "
                   "--known-gate=0.999).\n    One left out takes the command line's default.",
                   _options.FILTER_KEYWORDS),
        typed_dict("_RunOptions", "_FilterOptions", "arbor.run's keywords: arbor.Filter's, and out=.",
                   [o for o in _options.RUN_KEYWORDS if o not in filter_keywords]),
    ])


BLOCKS = {"exports": exports, "run options": run_options}


def render(text):
    """`text` (the stub) with each generated block rewritten."""
    for name, make in BLOCKS.items():
        pattern = re.compile(rf"^(# generated: {name}\n).*?^(# end generated: {name}\n)", re.M | re.S)
        if not pattern.search(text):
            raise SystemExit(f"{STUB}: no block '# generated: {name}' ... '# end generated: {name}'")
        text = pattern.sub(lambda m: m.group(1) + make() + "\n" + m.group(2), text)
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a generated block is not current")
    args = parser.parse_args()
    with open(STUB) as f:
        committed = f.read()
    text = render(committed)
    if args.check:
        if committed != text:
            print(f"{STUB} is stale: run scripts/generate_python_stub.py", file=sys.stderr)
            return 1
        return 0
    with open(STUB, "w") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
