# SPDX-License-Identifier: BSD-3-Clause
"""What the Python tests share: running the flexbond executable and reading
the CSV files it writes."""

import csv
import subprocess

import numpy


def run_cli(executable, *args):
    """Runs the flexbond executable with args; its stdout. AssertionError
    with its stderr when it fails."""
    done = subprocess.run([executable, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True, check=False)
    if done.returncode != 0:
        raise AssertionError("flexbond %s: exit %d: %s" % (" ".join(args), done.returncode,
                                                            done.stderr))
    return done.stdout


def read_csv(path):
    """A CSV file's header and its numbers as an array."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], numpy.array([[float(v) for v in row] for row in rows[1:]])
