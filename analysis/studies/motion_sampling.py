#!/usr/bin/python3
"""Per-scan vs per-control motion sampling (issue 11), from the result.json files that
experiments/scripts/motion_sampling_study.sh writes under OUT/sim/<run>/ and OUT/utias/<run>/.

Simulated worlds: for each odometer rate K (readings per scan) and particle count, the ATE and the share of
scans whose pose NEES lies in the two-sided 95 % chi-square(3) band, every run a dot, the mean a bar, the two
samplings paired by seed. UTIAS: per robot, FastSLAM's ATE (best particle, and SE(2)-aligned) beside the
smoother's on the same scenario.

Usage: /usr/bin/python3 analysis/studies/motion_sampling.py OUT
Writes OUT/motion_sampling.md, OUT/motion_sampling_sim.csv, OUT/motion_sampling_utias.csv and
OUT/motion_sampling.png.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis.results import markdown_table, mean_ci, read_study_runs  # noqa: E402

SAMPLINGS = ["per-scan", "per-control"]
COLORS = {"per-scan": "tab:blue", "per-control": "tab:orange"}


def cell(values):
    mean, ci = mean_ci(list(values))
    n = len(values)
    return f"{mean:.3f} ± {ci:.3f} (n = {n})" if n >= 3 else " / ".join(f"{v:.3f}" for v in values)


def study_runs(out, part, name_pattern, metrics):
    """The runs under OUT/PART/<run>/result.json whose names match name_pattern, as a frame (also written to
    OUT/motion_sampling_PART.csv when there are any)."""
    df = read_study_runs(os.path.join(out, part, "*", "result.json"), name_pattern, metrics)
    if not df.empty:
        df.to_csv(os.path.join(out, f"motion_sampling_{part}.csv"), index=False)
    return df


def sim_section(out):
    df = study_runs(out, "sim", r"k(?P<k>\d+)-p(?P<particles>\d+)-s(?P<seed>\d+)-(?P<sampling>per-scan|per-control)",
                    ["ate_rmse_m", "ate_aligned_rmse_m", "nees_in_band_fraction", "nees_median", "wall_time_s"])
    if df.empty:
        return df, ["No simulated runs found."]
    rows = []
    for (k, m), g in df.groupby(["k", "particles"]):
        row = {"readings per scan K": k, "particles": m}
        for s in SAMPLINGS:
            gs = g[g.sampling == s].sort_values("seed")
            row[f"ATE {s} [m]"] = cell(gs.ate_rmse_m)
            row[f"SE(2)-aligned ATE {s} [m]"] = cell(gs.ate_aligned_rmse_m)
            row[f"NEES in band {s}"] = cell(gs.nees_in_band_fraction)
        paired = g.pivot(index="seed", columns="sampling", values="ate_rmse_m").dropna()
        row["seeds where per-scan ATE is lower"] = f"{int((paired['per-scan'] < paired['per-control']).sum())} of {len(paired)}"
        aligned = g.pivot(index="seed", columns="sampling", values="ate_aligned_rmse_m").dropna()
        row["... aligned ATE lower"] = f"{int((aligned['per-scan'] < aligned['per-control']).sum())} of {len(aligned)}"
        rows.append(row)
    lines = ["## Simulated worlds (uniform, 200 landmarks, 150 scans, known association, FastSLAM 2.0)", "",
             "Mean ± 95 % CI over seeds (individual values where fewer than 3). With K = 1 the two samplings are",
             "the same algorithm. The unaligned ATE is dominated by a rigid offset of the whole solution (the",
             "map's frame is fixed by the first scans and is a posterior sample); the aligned ATE is the shape.", "",
             markdown_table(pd.DataFrame(rows))]
    return df, lines


def utias_section(out):
    df = study_runs(out, "utias",
                    r"r(?P<robot>\d)-(?P<method>fastslam1|fastslam2|smoother)(?:-s(?P<seed>\d+)-(?P<sampling>per-scan|per-control))?",
                    ["ate_rmse_m", "ate_aligned_rmse_m", "nees_in_band_fraction", "rejected_measurements", "wall_time_s"])
    if df.empty:
        return df, []
    rows = []
    for robot, g in df.groupby("robot"):
        sm = g[g.method == "smoother"]
        row = {"robot": robot,
               "smoother ATE [m] (aligned)": f"{sm.ate_rmse_m.iloc[0]:.3f} ({sm.ate_aligned_rmse_m.iloc[0]:.3f})" if len(sm) else "–"}
        for method in ["fastslam2", "fastslam1"]:
            for s in SAMPLINGS:
                gs = g[(g.method == method) & (g.sampling == s)].sort_values("seed")
                if len(gs):
                    row[f"{method} {s} ATE [m]"] = " / ".join(f"{v:.2f}" for v in gs.ate_rmse_m)
                    row[f"{method} {s} aligned [m]"] = " / ".join(f"{v:.2f}" for v in gs.ate_aligned_rmse_m)
        g2 = g[(g.method == "fastslam2") & (g.sampling == "per-scan")]
        row["fastslam2 per-scan NEES in band"] = " / ".join(f"{v:.2f}" for v in g2.nees_in_band_fraction)
        rows.append(row)
    lines = ["", "## UTIAS MRCLAM Dataset 6, known association, 100 particles (seeds 1 / 2 / 3)", "",
             "The smoother: Ceres, Cauchy loss, one pose per scan. \"aligned\": after an SE(2) alignment to Vicon.", "",
             markdown_table(pd.DataFrame(rows))]
    return df, lines


def victoria_park_section(out):
    df = study_runs(out, "victoria_park", r"(?P<assoc>jcbb|nn)-p(?P<particles>\d+)-s(?P<seed>\d+)-(?P<sampling>per-scan|per-control)",
                    ["ate_rmse_m", "landmarks", "wall_time_s"])
    if df.empty:
        return []
    rows = []
    for (m, s), g in df.groupby(["particles", "sampling"]):
        g = g.sort_values("seed")
        rows.append({"particles": m, "motion sampling": s, "seeds": len(g),
                     "GPS RMSE [m] per seed": " / ".join(f"{v:.2f}" for v in g.ate_rmse_m),
                     "landmarks": " / ".join(str(int(v)) for v in g.landmarks),
                     "wall time [s] (2 threads)": " / ".join(f"{v:.1f}" for v in g.wall_time_s)})
    return ["", "## Victoria Park, FastSLAM 2.0 + JCBB (GPS RMSE after SE(2) alignment, jumps removed)", "",
            markdown_table(pd.DataFrame(rows))]


def plot(sim, utias, out):
    panels = 3 + (not utias.empty)
    fig, axes = plt.subplots(1, panels, figsize=(5.0 * panels, 4.2), layout="constrained")
    if not sim.empty:
        sub = sim[sim.particles == sim.particles.max()]
        ks = sorted(sub.k.unique())
        for ax, metric, ylabel in [(axes[0], "ate_rmse_m", "ATE [m]"),
                                   (axes[1], "ate_aligned_rmse_m", "SE(2)-aligned ATE [m]"),
                                   (axes[2], "nees_in_band_fraction", "share of scans with NEES in the 95 % band")]:
            for j, s in enumerate(SAMPLINGS):
                for i, k in enumerate(ks):
                    v = sub[(sub.k == k) & (sub.sampling == s)][metric]
                    x = i + (j - 0.5) * 0.35
                    ax.bar(x, v.mean(), width=0.33, color=COLORS[s], alpha=0.35, label=s if i == 0 else None)
                    ax.scatter([x] * len(v), v, color=COLORS[s], s=14, zorder=3)
            ax.set_xticks(range(len(ks)), [f"K = {k}" for k in ks])
            ax.set_xlabel(f"odometer readings per scan (particles = {sub.particles.max()})")
            ax.set_ylabel(ylabel)
            ax.set_ylim(bottom=0)
            ax.grid(True, axis="y", alpha=0.3)
        axes[2].axhline(0.95, color="grey", lw=0.8, ls="--")
        axes[0].legend(title="motion sampling")
        axes[0].set_title("simulated, known association")
    if not utias.empty:
        ax = axes[-1]
        robots = sorted(utias.robot.unique())
        for i, r in enumerate(robots):
            g = utias[utias.robot == r]
            sm = g[g.method == "smoother"]
            if len(sm):
                ax.scatter([i - 0.3], sm.ate_rmse_m, marker="s", color="black", s=24, label="smoother" if i == 0 else None)
            for j, s in enumerate(SAMPLINGS):
                v = g[(g.method == "fastslam2") & (g.sampling == s)].ate_rmse_m
                ax.scatter([i + j * 0.3] * len(v), v, color=COLORS[s], s=14, label=f"FastSLAM 2.0 {s}" if i == 0 else None)
        ax.set_xticks(range(len(robots)), [f"robot {r}" for r in robots])
        ax.set_ylabel("ATE [m]")
        ax.set_ylim(bottom=0)
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend()
        ax.set_title("UTIAS MRCLAM 6, known association")
    fig.savefig(os.path.join(out, "motion_sampling.png"), dpi=120)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    sim, lines = sim_section(out)
    utias, more = utias_section(out)
    more += victoria_park_section(out)
    with open(os.path.join(out, "motion_sampling.md"), "w", encoding="utf-8") as f:
        f.write("# Motion sampling: per-scan vs per-control\n\n" + "\n".join(lines + more) + "\n")
    plot(sim, utias, out)
    print(f"wrote {out}/motion_sampling.md and motion_sampling.png")


if __name__ == "__main__":
    main()
