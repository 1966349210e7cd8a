#!/usr/bin/env python3
"""Energy (kinetic, elastic, total) or largest displacement against time, one line per body, from
a Tacta energy.csv (columns time_s,body,kinetic_J,elastic_J,total_J,max_displacement_m).

Usage: energy.py ENERGY.csv OUT.png [--quantity energy|displacement] [--title T]"""

import argparse

from plotlib import PlotInputError, column, fail, pyplot, read_table, save


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("energy")
    parser.add_argument("output")
    parser.add_argument("--quantity", choices=["energy", "displacement"], default="energy")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    try:
        names = ["time_s", "body", "kinetic_J", "elastic_J", "total_J", "max_displacement_m"]
        _, rows = read_table(args.energy, names)
        bodies = [row["body"] for row in rows]
        time = column(args.energy, rows, "time_s")
        plt = pyplot()
        figure, axis = plt.subplots(figsize=(8, 4.5))
        for body in dict.fromkeys(bodies):
            pick = [i for i, b in enumerate(bodies) if b == body]
            t = [time[i] for i in pick]
            if args.quantity == "energy":
                for key, label in (("kinetic_J", "kinetic"), ("elastic_J", "elastic"), ("total_J", "total")):
                    values = column(args.energy, rows, key)
                    axis.plot(t, [values[i] for i in pick], label=f"{body}: {label}")
                axis.set_ylabel("energy (J)")
            else:
                values = column(args.energy, rows, "max_displacement_m")
                axis.plot(t, [values[i] for i in pick], label=body)
                axis.set_ylabel("largest displacement (m)")
        axis.set_xlabel("time (s)")
        axis.grid(True, alpha=0.3)
        axis.legend()
        if args.title:
            axis.set_title(args.title)
        save(figure, args.output)
    except PlotInputError as error:
        fail(str(error))


if __name__ == "__main__":
    main()
