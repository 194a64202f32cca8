"""Small multiples with direct labels (issue 44): a comparison figure draws one panel per association strategy
(or filter, or map back end), the same axes in every panel so that panels compare at a glance, and names each
line at its right end instead of in a legend box, whose colours a reader would have to match by eye. Lines
whose values are identical (known association ignores clutter; map back ends agree run for run) are drawn once,
under one label that says so, instead of hiding each other."""

import textwrap

import numpy as np

from . import results as ar

# Which column splits a figure into panels: the first of these that varies between its lines.
PANEL_ORDER = ("assoc", "filter", "map")
COLOURS = ar.plt.get_cmap("tab10").colors
WRAP = 30  # characters in a line of a direct label: a long label would squeeze the panels beside it


def panels_of(shown, groups):
    """Splits lines into panels: (panel column or None, [(panel value, [rows of each line])]). Real strategies
    come first and oracles after them, in the order the table lists them."""
    column = next((c for c in PANEL_ORDER if c in shown and len({g[c].iloc[0] for g in groups}) > 1), None)
    if column is None:
        return None, [(None, groups)]
    bounds = (ar.ORACLE_ASSOC, ar.REFERENCE_FILTER)
    values = sorted({g[column].iloc[0] for g in groups}, key=lambda v: (v in bounds, str(v)))
    return column, [(v, [g for g in groups if g[column].iloc[0] == v]) for v in values]


def panel_title(column, value):
    """The panel's value, and its role where it is an oracle or the reference: a panel of known association is
    a bound, not a strategy."""
    if column is None:
        return ""
    role = ar.role({column: value})
    return f"{value} ({role})" if role else str(value)


def same_values(g, columns):
    """What makes two lines identical: their runs' values, seed by seed. Not the scenario's file: a world with
    clutter is another file, and known association, which ignores clutter, gives the same values on both."""
    keys = [c for c in ["seed"] + list(columns) if c in g]
    return tuple(map(tuple, g.sort_values(keys)[keys].astype(str).to_numpy()))


def collapse_identical(groups, x, metrics):
    """Groups of lines whose runs agree in x and every metric, run for run: [[rows, rows, ...], ...], each
    inner list drawn once."""
    merged = {}
    for g in groups:
        merged.setdefault(same_values(g, [x] + list(metrics)), []).append(g)
    return list(merged.values())


def line_label(copies, columns):
    """The label of a line that stands for one or more identical lines: each column's value, or its values
    where the copies differ ("clutter = 0, 1 /scan"), then "(identical)" where there are several."""
    bare, named = [], []
    for c in columns:
        values = [v for v in dict.fromkeys(g[c].iloc[0] for g in copies) if not (isinstance(v, float) and v != v)]
        if not values:
            continue
        text = ", ".join(str(int(v)) if isinstance(v, float) and v.is_integer() else str(v) for v in values)
        if c in ar.METHOD:
            bare.append(text.replace(", ", " = "))
        else:
            name, unit = ar.DIMENSIONS.get(c, (c, ""))
            named.append(f"{name} = {text}{unit}")
    text = ", ".join((["/".join(bare)] if bare else []) + named) or "all runs"
    text = f"{text} (identical)" if len(copies) > 1 else text
    return "\n".join(textwrap.wrap(text, WRAP, break_long_words=False))


class Styles:
    """A line's colour from its method (filter, strategy) and its dash from the rest (clutter, world), the same
    in every panel: fastslam2 is one colour throughout, and the cluttered world dashed beside the clean one."""

    DASHES = ("-", "--", ":", "-.")

    def __init__(self):
        self.colours, self.dashes = {}, {}

    def __call__(self, copies, columns):
        first = copies[0].iloc[0]
        method = tuple(str(first[c]) for c in columns if c in ar.METHOD)
        context = tuple(str(first[c]) for c in columns if c not in ar.METHOD)
        colour = self.colours.setdefault(method, COLOURS[len(self.colours) % len(COLOURS)])
        if len(copies) > 1:  # one line for several contexts: drawn solid, its label says which
            return colour, "-"
        return colour, self.dashes.setdefault(context, self.DASHES[len(self.dashes) % len(self.DASHES)])


def grid(rows, columns, width=3.6, height=2.8, sharey="row"):
    """A rows x columns grid of panels sharing the x axis (and y per row, or everywhere with sharey=True)."""
    fig, axes = ar.plt.subplots(rows, columns, figsize=(0.6 + (width + 1.4) * columns, 0.6 + height * rows),
                                layout="constrained", squeeze=False, sharex=True, sharey=sharey)
    for ax in axes.flat:
        ax.grid(True, which="both", alpha=0.3)
    return fig, axes


def label_ends(ax, ends, fontsize=7):
    """Names each line at its right end: ends is [(x, y, text, colour)] in data coordinates. The labels go just
    right of the panel, moved apart vertically where they would overlap, with a thin stroke to their line's
    end. Call after every line is drawn: the axes' limits are fixed here so that the labels stay put."""
    ends = [(x, y, t, c) for x, y, t, c in ends if np.isfinite(x) and np.isfinite(y)]
    if not ends:
        return
    ax.set_xlim(ax.get_xlim())
    ax.set_ylim(ax.get_ylim())
    to_axes = ax.transData + ax.transAxes.inverted()
    placed = sorted(((to_axes.transform((x, y))[1], x, y, t, c) for x, y, t, c in ends), key=lambda e: e[0])
    height_pt = ax.get_window_extent().height * 72.0 / ax.figure.dpi
    # Each label's height in axes fractions: a wrapped label takes a line of text per line.
    heights = [1.3 * fontsize * (e[3].count("\n") + 1) / max(height_pt, 1.0) for e in placed]
    ys = [min(max(e[0], 0.0), 1.0) for e in placed]
    for i in range(1, len(ys)):  # push up past the label below
        ys[i] = max(ys[i], ys[i - 1] + (heights[i - 1] + heights[i]) / 2)
    overflow = ys[-1] - 1.0
    if overflow > 0:  # then the whole column down again, as far as the bottom allows
        ys = [y - min(overflow, ys[0]) for y in ys]
    for y_text, (_, x, y, text, colour) in zip(ys, placed):
        ax.annotate(text, xy=(x, y), xycoords="data", xytext=(1.03, y_text), textcoords="axes fraction",
                    fontsize=fontsize, color=colour, va="center", ha="left", annotation_clip=False,
                    arrowprops=dict(arrowstyle="-", color=colour, lw=0.5, alpha=0.5, shrinkA=0, shrinkB=2))
