#!/usr/bin/python3
"""landmarks.csv from the runs of straight_edges.sh: per run, the confirmed landmarks, the true landmarks
observed and the spurious ones (result.json). Usage: landmarks.py OUT > landmarks.csv"""
import json
import pathlib
import sys

print("strategy,world,clutter,world_seed,filter_seed,landmarks,observed_true_landmarks,spurious_landmarks")
for result in sorted(pathlib.Path(sys.argv[1], "runs").glob("*/result.json")):
    strategy, world, clutter, seed, filter_seed = result.parent.name.rsplit("-", 4)
    r = json.loads(result.read_text())
    print(f"{strategy},{world},{clutter[1:]},{seed[1:]},{filter_seed[1:]},{r['landmarks']},"
          f"{r['observed_true_landmarks']},{r['spurious_landmarks']}")
