#!/usr/bin/python3
"""Complexity figure of the map back ends (DESIGN.md §3): log-log step time, set time and bytes per particle
vs N, with least-squares slopes over N = 1e3..1e6 printed on the plot and to stdout.

Input: a results/maps/<commit>_<host>_<compiler>/ folder holding map_benchmark.json and step_benchmark.json
(written by bench/run_map_benchmarks.sh). Output in the same folder: map_complexity.png, summary.csv.
Usage: /usr/bin/python3 analysis/studies/plot_map_complexity.py results/maps/<folder>
"""
import json
import re
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

NAME = re.compile(r"^(?P<bench>BM_\w+)/backend:(?P<backend>\w+)/n:(?P<n>\d+)")
FIT_MIN_N = 1000
COLORS = {"naive": "tab:red", "tree": "tab:blue", "trie": "tab:green", "ekf": "tab:purple"}  # ekf: EKF-SLAM, no back end


def load(path):
    """{(bench, backend, n): benchmark entry}; the median aggregate where repetitions were run."""
    rows = {}
    for b in json.loads(Path(path).read_text())["benchmarks"]:
        m = NAME.match(b.get("run_name", b["name"]))
        if not m:
            continue
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        rows[(m["bench"], m["backend"], int(m["n"]))] = b
    return rows


def to_seconds(b, key):
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return b[key] * scale


def series(rows, bench, value):
    out = {}
    for (name, backend, n), b in sorted(rows.items()):
        if name == bench:
            out.setdefault(backend, []).append((n, value(b)))
    return out


def owned(b):
    """Bytes a particle owns; EKF-SLAM's one estimate (backend "ekf") owns all it holds."""
    return b.get("owned_bytes_per_particle", b["bytes_per_particle"])


def slope(points):
    pts = [(n, v) for n, v in points if n >= FIT_MIN_N and v > 0]
    if len(pts) < 2:
        return float("nan")
    x, y = np.log10([p[0] for p in pts]), np.log10([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def panel(ax, data, title, ylabel, what, dashed=None, dashed_what=None):
    """dashed: a second series per backend (same colours), e.g. the median beside the mean."""
    for backend, pts in data.items():
        s = slope(pts)
        print(f"{what:32s} {backend:6s} slope {s:6.3f}  (N >= {FIT_MIN_N}, {len([p for p in pts if p[0] >= FIT_MIN_N])} points)")
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color=COLORS.get(backend), label=f"{backend}: slope {s:.2f}")
        if dashed and backend in dashed:
            d = dashed[backend]
            sd = slope(d)
            print(f"{dashed_what:32s} {backend:6s} slope {sd:6.3f}")
            ax.loglog([p[0] for p in d], [p[1] for p in d], "s--", color=COLORS.get(backend), alpha=0.6,
                      label=f"{backend} {dashed_what.split()[-1]}: slope {sd:.2f}")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("landmarks N")
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = Path(sys.argv[1])
    step = load(folder / "step_benchmark.json")
    micro = load(folder / "map_benchmark.json")

    # Mean CPU time per step (the benchmark's manual time): resampling, whose copies are what the naive back
    # end pays O(M N) for, happens at its natural rate. The median (dashed) shows a step without resampling.
    step_time = series(step, "BM_FastSlam_Step", lambda b: to_seconds(b, "real_time"))
    step_median = series(step, "BM_FastSlam_Step", lambda b: b["step_median_s"])
    bytes_pp = series(step, "BM_FastSlam_Step", lambda b: b["bytes_per_particle"])
    owned_pp = series(step, "BM_FastSlam_Step", owned)
    set_time = series(micro, "BM_Map_Set", lambda b: to_seconds(b, "cpu_time"))
    copy_time = series(micro, "BM_Map_Copy", lambda b: to_seconds(b, "cpu_time"))

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    panel(axes[0][0], step_time, "one step, 1 thread: FastSLAM M=100 per back end, ekf = EKF-SLAM\n(CPU time; solid: mean, dashed: median)",
          "seconds per step", "step time mean", step_median, "step time median")
    panel(axes[0][1], bytes_pp, "map bytes per particle after the run (ekf: its joint Gaussian)\n(solid: all distinct bytes / M; dashed: owned)", "bytes",
          "bytes per particle", owned_pp, "bytes per particle owned")
    panel(axes[1][0], set_time, "one set on a map shared with its parent", "seconds", "set time")
    panel(axes[1][1], copy_time, "particle copy (map)", "seconds", "copy time")
    fig.suptitle(f"Map back ends vs N at constant density — {folder.name}", fontsize=10)
    fig.tight_layout()
    fig.savefig(folder / "map_complexity.png", dpi=120)

    # One table row per (backend, N) with every figure the report quotes.
    keys = sorted({(k[1], k[2]) for k in list(step) + list(micro)})
    def get(rows, bench, backend, n, f):
        b = rows.get((bench, backend, n))
        return "" if b is None else f"{f(b):.6g}"
    lines = ["backend,n,step_mean_s,step_median_s,set_s,copy_s,visit_near_s,alloc_bytes_per_set,bytes_per_particle,"
             "owned_bytes_per_particle,bytes_per_landmark"]
    for backend, n in keys:
        lines.append(",".join([backend, str(n),
            get(step, "BM_FastSlam_Step", backend, n, lambda b: to_seconds(b, "real_time")),
            get(step, "BM_FastSlam_Step", backend, n, lambda b: b["step_median_s"]),
            get(micro, "BM_Map_Set", backend, n, lambda b: to_seconds(b, "cpu_time")),
            get(micro, "BM_Map_Copy", backend, n, lambda b: to_seconds(b, "cpu_time")),
            get(micro, "BM_Map_VisitNear", backend, n, lambda b: to_seconds(b, "cpu_time")),
            get(micro, "BM_Map_Set", backend, n, lambda b: b.get("alloc_bytes_per_set", float("nan"))),
            get(step, "BM_FastSlam_Step", backend, n, lambda b: b["bytes_per_particle"]),
            get(step, "BM_FastSlam_Step", backend, n, owned),
            get(micro, "BM_Map_Particles", backend, n, lambda b: b["bytes_per_landmark"])]))
    (folder / "summary.csv").write_text("\n".join(lines) + "\n")
    print(f"wrote {folder / 'map_complexity.png'} and {folder / 'summary.csv'}")


if __name__ == "__main__":
    main()
