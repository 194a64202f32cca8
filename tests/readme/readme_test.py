#!/usr/bin/python3
"""Runs the README's quick start as a new user would and checks that every block prints what the README shows
after it, so that the README cannot go stale: a changed default, option or figure fails here.

Usage: readme_test.py --source REPO --build BUILD_DIR   (ctest runs it as Readme.QuickStart)

Each ```sh or ```python block of the "Quick start" section runs in a scratch copy of the repository's layout
(its top-level entries linked, `build` linked to BUILD_DIR, `out/` empty), in order, so that later blocks see
the files earlier ones wrote. A ```text block right after a code block is what that block prints
(stdout and stderr together): every line it shows must be printed, in the same order, though it may leave
printed lines out; `…` in a shown line stands for any text (a time, a path that varies). It also checks that
the README's first block holds the two commands, and that .ci/run runs the second of them."""

import argparse
import os
import re
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^```(\w*)\n(.*?)^```[ \t]*$", re.M | re.S)
WILDCARD = "…"


def fenced_blocks(text):
    return [(m.group(1), m.group(2)) for m in FENCE.finditer(text)]


def section(text, title):
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


def line_pattern(shown):
    return re.compile("".join(".*" if part == WILDCARD else re.escape(part)
                              for part in re.split(f"({WILDCARD})", shown.rstrip())) + r"\s*$")


def first_unmatched(shown_lines, printed_lines):
    """The first shown line not printed after the previous one's match, or None when all are."""
    at = 0
    for shown in shown_lines:
        pattern = line_pattern(shown)
        while at < len(printed_lines) and not pattern.fullmatch(printed_lines[at]):
            at += 1
        if at == len(printed_lines):
            return shown
        at += 1
    return None


def stale_copy(shown_lines):
    """The shown lines with their first digit changed: what a README left behind by the code would show."""
    for i, line in enumerate(shown_lines):
        m = re.search(r"\d", line)
        if m:
            digit = str((int(m.group()) + 1) % 10)
            return shown_lines[:i] + [line[:m.start()] + digit + line[m.end():]] + shown_lines[i + 1:]
    return None


def check_the_two_commands(readme, source):
    lang, body = fenced_blocks(readme)[0]
    commands = [line.split("#")[0].strip() for line in body.splitlines() if line.split("#")[0].strip()]
    errors = []
    if lang != "sh" or commands != ["scripts/main.sh", "scripts/test.sh"]:
        errors.append(f"the README's first block should be the two commands, not {lang}: {commands}")
    for command in commands:
        if not os.access(os.path.join(source, command), os.X_OK):
            errors.append(f"{command}, a command of the README, is not an executable file")
    with open(os.path.join(source, ".ci", "run"), encoding="utf-8") as f:
        ci = f.read()
    if len(commands) == 2 and not re.search(rf"^exec {re.escape(commands[1])}\s*$", ci, re.M):
        errors.append(f".ci/run does not run the README's test command ({commands[1]})")
    return errors


def scratch_checkout(source, build, work):
    source = os.path.abspath(source)
    for entry in os.listdir(source):
        if entry not in ("build", "out", ".git"):
            os.symlink(os.path.join(source, entry), os.path.join(work, entry))
    os.symlink(os.path.abspath(build), os.path.join(work, "build"))


def run_block(lang, body, work):
    env = dict(os.environ, PYTHONPATH=os.path.join(work, "build", "python"))
    command = ["bash", "-euo", "pipefail", "-c", body] if lang == "sh" else [sys.executable, "-c", body]
    done = subprocess.run(command, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=240)
    return done.returncode, done.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--build", required=True)
    args = parser.parse_args()
    with open(os.path.join(args.source, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    errors = check_the_two_commands(readme, args.source)
    blocks = fenced_blocks(section(readme, "Quick start"))
    ran = 0
    with tempfile.TemporaryDirectory(prefix="arbor_readme_") as work:
        scratch_checkout(args.source, args.build, work)
        for i, (lang, body) in enumerate(blocks):
            if lang not in ("sh", "python"):
                continue
            rc, printed = run_block(lang, body, work)
            ran += 1
            print(f"--- {lang} block {ran} (exit {rc}):\n{body}{printed}")
            if rc != 0:
                errors.append(f"{lang} block {ran} exited {rc}")
                continue
            if i + 1 >= len(blocks) or blocks[i + 1][0] != "text":
                continue
            shown = [line for line in blocks[i + 1][1].splitlines() if line.strip()]
            printed_lines = printed.splitlines()
            missing = first_unmatched(shown, printed_lines)
            if missing is not None:
                errors.append(f"{lang} block {ran}: the README shows\n    {missing}\n  which it did not print")
            stale = stale_copy(shown)
            if stale is not None and first_unmatched(stale, printed_lines) is None:
                errors.append(f"{lang} block {ran}: a shown line with a changed figure still matched; the check "
                              "would not notice a stale README")
    if ran == 0:
        errors.append("the README's quick start has no sh or python block")
    for e in errors:
        print(f"FAIL: {e}")
    print(f"{ran} quick-start blocks run; " + ("the README is stale" if errors else "every shown line printed"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
