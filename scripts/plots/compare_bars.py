#!/usr/bin/python3
"""Bar charts of `tacta compare` results: one panel per metric, one bar per model.

Usage: compare_bars.py COMPARE.csv OUT.png [--metrics tick_p50_ms,tick_p99_ms,...]
The CSV needs a `model` column and the metric columns (default: tick_p50_ms, tick_p99_ms,
max_displacement_m, energy_drift). Empty or non-finite values are drawn as missing."""

import argparse
import math
import sys

from plotlib import PlotInputError, fail, pyplot, read_table, save

DEFAULT_METRICS = ["tick_p50_ms", "tick_p99_ms", "max_displacement_m", "energy_drift"]
UNITS = {"_ms": "ms", "_m": "m", "_N": "N", "_s": "s"}


def unit_of(metric):
    for suffix, unit in UNITS.items():
        if metric.endswith(suffix):
            return unit
    return ""


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("compare")
    parser.add_argument("output")
    parser.add_argument("--metrics", help="comma-separated metric columns")
    args = parser.parse_args(argv)
    try:
        metrics = [m.strip() for m in args.metrics.split(",")] if args.metrics else DEFAULT_METRICS
        _, rows = read_table(args.compare, ["model"] + metrics)
        models = [row["model"].strip() for row in rows]
        plt = pyplot()
        figure, panels = plt.subplots(1, len(metrics), figsize=(3.4 * len(metrics), 4), squeeze=False)
        for axes, metric in zip(panels[0], metrics):
            heights = []
            for index, row in enumerate(rows):
                text = (row.get(metric) or "").strip()
                try:
                    value = float(text) if text else math.nan
                except ValueError:
                    raise PlotInputError(
                        f"{args.compare}:{index + 2}: column {metric}: expected a number, found '{text}'"
                    ) from None
                heights.append(value)
            shown = [h if math.isfinite(h) else 0.0 for h in heights]
            bars = axes.bar(range(len(models)), shown, color="tab:blue")
            for bar, value in zip(bars, heights):
                axes.annotate("n/a" if not math.isfinite(value) else f"{value:.3g}",
                              (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                              ha="center", va="bottom", fontsize=8)
            axes.set_xticks(range(len(models)))
            axes.set_xticklabels(models, rotation=30, ha="right", fontsize=8)
            unit = unit_of(metric)
            axes.set_title(metric)
            axes.set_ylabel(unit)
            axes.grid(True, axis="y", alpha=0.3)
        figure.tight_layout()
        save(figure, args.output)
    except PlotInputError as error:
        fail(str(error))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
