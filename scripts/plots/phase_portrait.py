#!/usr/bin/python3
"""Phase portraits of chosen nodes, like the paper's figures 8 and 9: x against vx and y
against vy, one row of two plots per node.

Usage: phase_portrait.py TRAJECTORY.csv OUT.png --nodes 3,7 [--labels "corner,centre"] [--title T]
The trajectory needs columns time_s,node,x,y,z,vx,vy,vz (m, m/s); rows of other nodes are ignored."""

import argparse
import sys

from plotlib import PlotInputError, column, fail, pyplot, read_table, save


def parse_nodes(text):
    try:
        nodes = [int(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise PlotInputError(f"--nodes: expected comma-separated node indices, found '{text}'") from None
    if not nodes:
        raise PlotInputError("--nodes: expected at least one node index")
    return nodes


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trajectory")
    parser.add_argument("output")
    parser.add_argument("--nodes", required=True, help="comma-separated node indices")
    parser.add_argument("--labels", help="comma-separated labels, one per node")
    parser.add_argument("--title", default="Phase portraits")
    args = parser.parse_args(argv)
    try:
        nodes = parse_nodes(args.nodes)
        labels = [s.strip() for s in args.labels.split(",")] if args.labels else [f"node {n}" for n in nodes]
        if len(labels) != len(nodes):
            raise PlotInputError(f"--labels: {len(labels)} labels for {len(nodes)} nodes")
        names = ["time_s", "node", "x", "y", "z", "vx", "vy", "vz"]
        _, rows = read_table(args.trajectory, names)
        node_of_row = column(args.trajectory, rows, "node")
        values = {name: column(args.trajectory, rows, name) for name in ("x", "y", "vx", "vy")}
        plt = pyplot()
        figure, grid = plt.subplots(len(nodes), 2, figsize=(9, 3.2 * len(nodes)), squeeze=False)
        for row, (node, label) in enumerate(zip(nodes, labels)):
            picked = [i for i, n in enumerate(node_of_row) if int(n) == node]
            if not picked:
                raise PlotInputError(f"{args.trajectory}: no rows for node {node}")
            for col, (pos, vel) in enumerate((("x", "vx"), ("y", "vy"))):
                axes = grid[row][col]
                axes.plot([values[pos][i] for i in picked], [values[vel][i] for i in picked],
                          linewidth=1.0)
                axes.plot(values[pos][picked[0]], values[vel][picked[0]], "o", color="tab:green",
                          markersize=4, label="start")
                axes.set_xlabel(f"{pos} (m)")
                axes.set_ylabel(f"{vel} (m/s)")
                axes.set_title(f"{label}: {pos} against {vel}")
                axes.grid(True, alpha=0.3)
        grid[0][0].legend(loc="best")
        figure.suptitle(args.title)
        figure.tight_layout()
        save(figure, args.output)
    except PlotInputError as error:
        fail(str(error))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
