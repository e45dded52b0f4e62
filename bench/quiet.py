#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Waits until the machine is idle: until the CPUs were busy less than
BUSY (default 0.15) of a 0.3 s window (/proc/stat), for at most
MAX_SECONDS (default 30). A timing taken right after is less disturbed by
other work on a shared machine. Exits 0 either way; says on stderr when
it gave up.

usage: quiet.py [MAX_SECONDS] [BUSY]
"""
import sys
import time


def cpu():
    with open("/proc/stat") as fp:
        v = [int(x) for x in fp.readline().split()[1:]]
    idle = v[3] + v[4]  # idle + iowait
    return sum(v), idle


limit = float(sys.argv[1]) if len(sys.argv) > 1 else 30.0
busy_max = float(sys.argv[2]) if len(sys.argv) > 2 else 0.15
t_end = time.monotonic() + limit
while True:
    t0, i0 = cpu()
    time.sleep(0.3)
    t1, i1 = cpu()
    busy = 1.0 - (i1 - i0) / max(t1 - t0, 1)
    if busy < busy_max:
        break
    if time.monotonic() > t_end:
        print("quiet.py: the machine stayed busy (%.0f %%) for %g s" % (100 * busy, limit),
              file=sys.stderr)
        break
