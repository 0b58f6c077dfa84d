"""Reading an ecm-mpm output folder: history.csv, particles_final.csv and summary.json."""
import json
import os
from dataclasses import dataclass, field

import numpy as np


def _read_csv(path):
    """A CSV file of ecm (one header line, then numbers in shortest round-trip form) as a dict of
    column -> array. The numbers parse back to the doubles the run had."""
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
        data = np.loadtxt(f, delimiter=",", ndmin=2)
    if data.size == 0:
        data = np.zeros((0, len(header)))
    return {name: data[:, i].copy() for i, name in enumerate(header)}


@dataclass
class MpmOutput:
    """An ecm-mpm output folder: history (column -> array), particles (the final particles,
    column -> array; empty if the run wrote none) and summary (summary.json)."""
    history: dict = field(default_factory=dict)
    particles: dict = field(default_factory=dict)
    summary: dict = field(default_factory=dict)


def read_mpm_output(folder):
    """Reads an ecm-mpm output folder (a path) into an MpmOutput: history (history.csv: time in s,
    displacements in mm, loads in N, energies in N mm), particles (particles_final.csv: positions
    in mm, stresses in MPa, openings in mm; {} if the run wrote none) and summary (summary.json).
    Column names and units are those of the files' headers (mpm/README.md). Raises
    FileNotFoundError if the folder has no summary.json."""
    folder = os.fspath(folder)
    summary_path = os.path.join(folder, "summary.json")
    if not os.path.exists(summary_path):
        raise FileNotFoundError(f"{summary_path}: not an ecm-mpm output folder (no summary.json)")
    with open(summary_path, encoding="utf-8") as f:
        summary = json.load(f)
    history = _read_csv(os.path.join(folder, "history.csv"))
    particles_path = os.path.join(folder, "particles_final.csv")
    particles = _read_csv(particles_path) if os.path.exists(particles_path) else {}
    return MpmOutput(history, particles, summary)
