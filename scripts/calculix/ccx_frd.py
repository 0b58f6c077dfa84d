#!/usr/bin/env python3
"""Reads the nodes and the nodal result blocks of a CalculiX .frd file (ASCII).

    nodes, blocks = read_frd("job.frd")
    nodes[17]                          # (x, y, z)
    blocks["SDV"]                      # [(time, {node: [values]}), ...] in the file's order
    python3 scripts/calculix/ccx_frd.py job.frd

The format, as CalculiX writes it: a node block ("    2C" then one " -1" line per node: the
number in columns 4-13, then the coordinates, 12 columns each), element blocks ("    3C", skipped)
and result blocks ("  100C" with the time in columns 13-24, " -4  NAME  COMPONENTS", one " -5"
line per component (ALL, a magnitude, has no values), then per node a " -1" line with the number and up to six values and " -2"
lines with six more each; " -3" ends a block). Element values (SDV, stresses) appear at the
nodes, extrapolated from the integration points and averaged over the elements around a node.
Values have six significant digits (e12.5).
"""
import sys


def _values(line, start):
    return [float(line[i:i + 12]) for i in range(start, len(line.rstrip()), 12)]


def read_frd(path):
    nodes, blocks = {}, {}
    with open(path) as f:
        lines = iter(f.read().splitlines())
    for line in lines:
        if line.startswith("    2C"):
            for row in lines:
                if row.startswith(" -3"):
                    break
                nodes[int(row[3:13])] = tuple(_values(row, 13))
        elif line.startswith("  100C"):
            time = float(line[12:24])
            header = next(lines)
            name = header[5:13].strip()
            count = 0  # the components, less the pseudo-component ALL (a magnitude CalculiX does not write)
            values, current = {}, None
            for row in lines:
                if row.startswith(" -3"):
                    break
                if row.startswith(" -5"):
                    count += row[5:13].strip() != "ALL"
                    continue
                if row.startswith(" -1"):
                    current = int(row[3:13])
                    values[current] = _values(row, 13)
                elif row.startswith(" -2"):
                    values[current] += _values(row, 13)
            for node, v in values.items():
                if len(v) != count:
                    raise ValueError(f"{path}: {name} at time {time}: node {node} has {len(v)} of {count} values")
            blocks.setdefault(name, []).append((time, values))
    return nodes, blocks


def main(argv):
    if len(argv) != 2:
        print("usage: ccx_frd.py JOB.frd", file=sys.stderr)
        return 2
    nodes, blocks = read_frd(argv[1])
    print(f"{len(nodes)} nodes")
    for name, series in blocks.items():
        print(f"{name}: {len(series)} times, the last {series[-1][0]:g}, {len(series[-1][1])} nodes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
