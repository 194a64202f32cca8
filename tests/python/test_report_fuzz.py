"""Seeded fuzzing of the report's input (issue 45): a sweep's results.jsonl and results.csv, mutated byte by
byte, cut, or spliced with hostile tokens, are either read or refused with a ValueError that names the file;
no other exception reaches the report (which turns a ValueError into exit 2 and a message)."""
import os
import random
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import results as ar  # noqa: E402

FIXTURE = os.path.join(ROOT, "tests", "data", "results_fixture")
TOKENS = [b"\n", b"\r\n", b"{", b"}", b"[", b'"', b",", b":", b"\xff", b"\xc3", b"\x00", b"1e999", b"NaN", b"-Infinity",
          b'"key"', b'"status": "ok"', b"null", b"```", b"![a](/etc/hostname)", b"<script>", b"\\u0000", b"\\ud800"]


def mutations(data, rng, count):
    """count mutants of data: flipped bytes, a cut, spliced tokens or a line repeated."""
    for _ in range(count):
        b = bytearray(data)
        kind = rng.randrange(4)
        if kind == 0:
            for _ in range(rng.randint(1, 8)):
                b[rng.randrange(len(b))] = rng.randrange(256)
        elif kind == 1:
            del b[rng.randrange(len(b)):]
        elif kind == 2:
            for _ in range(rng.randint(1, 4)):
                i = rng.randrange(len(b) + 1)
                b[i:i] = rng.choice(TOKENS)
        else:
            lines = bytes(b).split(b"\n")
            i = rng.randrange(len(lines))
            lines.insert(rng.randrange(len(lines) + 1), lines[i])
            b = bytearray(b"\n".join(lines))
        yield bytes(b)


def read_or_refuse(path):
    try:
        df = ar.load_results(str(path))
    except ValueError as e:  # the report's exit 2; the message must say where
        assert os.path.basename(str(path)) in str(e), str(e)[:300]
        return "refused"
    for column in df.columns:  # every cell the report prints goes through md_text
        for value in df[column].head(20):
            ar.md_text(value)
    return "read"


def fuzz(tmp_path, name, seed):
    with open(os.path.join(FIXTURE, name), "rb") as f:
        data = f.read()
    outcomes = {"read": 0, "refused": 0}
    for i, mutant in enumerate(mutations(data, random.Random(seed), 250)):
        path = tmp_path / name
        path.write_bytes(mutant)
        outcomes[read_or_refuse(path)] += 1
    assert outcomes["read"] > 0 and outcomes["refused"] > 0, outcomes  # both paths were walked


def test_mutated_jsonl_rows_are_read_or_refused_naming_the_file(tmp_path):
    fuzz(tmp_path, "results.jsonl", seed=45)


def test_mutated_csv_rows_are_read_or_refused_naming_the_file(tmp_path):
    fuzz(tmp_path, "results.csv", seed=46)
