#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Runs a command once and prints "WALL_S CPU_S MAXRSS_KB": its wall time
from fork to exit, its user + system time and its peak resident set, from
wait4's rusage (microsecond resolution, where /usr/bin/time -v prints
10 ms). The command's stdout goes to /dev/null, its stderr to FILE.

usage: proctime.py STDERR_FILE CMD [ARGS...]
"""
import os
import subprocess
import sys
import time

with open(sys.argv[1], "w") as err:
    t0 = time.perf_counter()
    p = subprocess.Popen(sys.argv[2:], stdout=subprocess.DEVNULL, stderr=err)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
if os.waitstatus_to_exitcode(status) != 0:
    sys.exit(f"proctime: {sys.argv[2]} failed ({os.waitstatus_to_exitcode(status)})")
print("%.6f %.6f %d" % (wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss))
