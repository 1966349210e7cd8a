#!/usr/bin/python3
"""Force against time from a Tacta trace (trace.csv): magnitude and x, y, z components.

Usage: force_vs_time.py TRACE.csv OUT.png [--peak-force N] [--title TEXT]
The trace needs columns time_s, force_x_N, force_y_N, force_z_N, force_N (others are ignored).
--peak-force draws the device's declared maximum force as a dashed line."""

import argparse
import sys

from plotlib import PlotInputError, column, fail, pyplot, read_table, save


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trace")
    parser.add_argument("output")
    parser.add_argument("--peak-force", type=float, help="device maximum force, N")
    parser.add_argument("--title", default="Force rendered to the device")
    args = parser.parse_args(argv)
    try:
        names = ["time_s", "force_x_N", "force_y_N", "force_z_N", "force_N"]
        _, rows = read_table(args.trace, names)
        data = {name: column(args.trace, rows, name) for name in names}
        plt = pyplot()
        figure, axes = plt.subplots(figsize=(8, 4.5))
        axes.plot(data["time_s"], data["force_N"], color="black", linewidth=1.6, label="|F|")
        for name, colour, label in (("force_x_N", "tab:red", "Fx"), ("force_y_N", "tab:green", "Fy"),
                                    ("force_z_N", "tab:blue", "Fz")):
            axes.plot(data["time_s"], data[name], color=colour, linewidth=0.9, label=label)
        if args.peak_force is not None:
            axes.axhline(args.peak_force, color="tab:orange", linestyle="--",
                         label=f"device peak {args.peak_force:g} N")
        axes.set_xlabel("time (s)")
        axes.set_ylabel("force (N)")
        axes.set_title(args.title)
        axes.grid(True, alpha=0.3)
        axes.legend(loc="best")
        figure.tight_layout()
        save(figure, args.output)
    except PlotInputError as error:
        fail(str(error))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
