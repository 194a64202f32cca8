"""What the studies that read each run's own files (analysis/studies/own_pairings.py, lineage.py) share: the
run's scenario file and its steps (each scenario read once per sweep), the breakdown of a configuration's rows
by scenario kind, and the tables they write beside the sweep."""

import functools
import json
import os
import sys

from . import failures
from . import results as ar

# A sweep's configurations share their scenarios: each is read once.
scenario_steps = functools.lru_cache(maxsize=None)(ar.read_scenario_steps)


def main(doc, study):
    """Runs study(sweep, results with the failures marked) on the sweep folder the command line names; without
    one, prints the study's usage (doc) and returns 2."""
    if len(sys.argv) != 2:
        print(doc, file=sys.stderr)
        return 2
    return study(sys.argv[1], failures.mark_failures(ar.load_results(sys.argv[1])))


def scenario_path(sweep, run_dir, scenario):
    """A run's scenario file: a simulated world's copy inside the sweep, or the dataset file as the run read it
    (result.json's config.scenario, relative to where the sweep ran; the sweep's own column is relative to its
    spec)."""
    inside = os.path.join(sweep, scenario)
    if os.path.exists(inside):
        return inside
    with open(os.path.join(run_dir, "result.json"), encoding="utf-8") as f:
        recorded = json.load(f)["config"]["scenario"]
    if not os.path.exists(recorded):
        raise FileNotFoundError(f"{run_dir}: scenario {scenario} is neither in the sweep nor at {recorded} "
                                "(run the study from where the sweep ran)")
    return recorded


def scenario_groups(df):
    """(world kind, or the dataset file's name, rows) per scenario kind, then ("all", df)."""
    column = "world" if "world" in df and df["world"].notna().all() else "dataset"
    out = [(os.path.basename(str(kind)), rows) for kind, rows in df.groupby(column, sort=True)]
    return out + [("all", df)]


def filter_groups(df):
    """(configuration label, scenario kind, rows) for every filter configuration (the reference left out) and
    each of its scenario kinds, then all of them (scenario_groups)."""
    for label, rows in failures.configurations(df):
        if label == failures.REFERENCE:
            continue
        for kind, g in scenario_groups(rows):
            yield label, kind, g


def write_tables(sweep, stem, heading, intro, table, text):
    """SWEEP/STEM.csv (the table) and SWEEP/STEM.md (heading, intro, the markdown text); prints the text."""
    table.to_csv(os.path.join(sweep, stem + ".csv"), index=False)
    with open(os.path.join(sweep, stem + ".md"), "w", encoding="utf-8") as f:
        f.write(f"# {heading}\n\n{intro}\n\n{text}\n")
    print(text)
