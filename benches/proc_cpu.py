"""CPU time of processes and threads from /proc (Linux), for benchmarks on a
shared machine: the CPU seconds a process or thread used do not depend on
how many other programs compete for the cores, unlike wall-clock time.

    snap = cpu_snapshot(server_pid)   # before
    ...
    print(cpu_delta(cpu_snapshot(server_pid), snap))

A snapshot reads `utime + stime` of the whole process (which includes its
threads that have exited), of each live thread (by thread id, with its
name), and of every descendant process of this script whose name starts
with "chrom" (the browser's processes).
"""
import os

TICK = os.sysconf("SC_CLK_TCK")


def _stat(path):
    """(comm, ppid, cpu seconds) from a /proc stat file, or None if gone."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        return None
    comm = text[text.index("(") + 1:text.rindex(")")]
    fields = text[text.rindex(")") + 2:].split()
    # Fields 4 (ppid), 14 (utime) and 15 (stime) of proc(5), counted from
    # field 3 (state) here.
    return comm, int(fields[1]), (int(fields[11]) + int(fields[12])) / TICK


def _descendants(root):
    parent = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            s = _stat(f"/proc/{name}/stat")
            if s:
                parent[int(name)] = s[1]
    out = []
    for pid in parent:
        p = pid
        while p in parent and p != root:
            p = parent[p]
        if p == root and pid != root:
            out.append(pid)
    return out


def cpu_snapshot(server_pid):
    """CPU seconds so far: `process` (the server's total), `threads`
    (thread id: (name, seconds) of the server's live threads) and
    `chromium` (all of this script's chromium processes)."""
    s = _stat(f"/proc/{server_pid}/stat")
    threads = {}
    for tid in os.listdir(f"/proc/{server_pid}/task"):
        t = _stat(f"/proc/{server_pid}/task/{tid}/stat")
        if t:
            threads[tid] = (t[0], t[2])
    chromium = 0.0
    for pid in _descendants(os.getpid()):
        p = _stat(f"/proc/{pid}/stat")
        if p and p[0].startswith("chrom"):
            chromium += p[2]
    return {"process": s[2] if s else 0.0, "threads": threads, "chromium": chromium}


def cpu_delta(after, before):
    """What was used between two snapshots taken while no render runs:
    `chromium`, the server's `process` total, its `overhead` (the threads
    alive at both snapshots: the connection's worker, which sums passes and
    encodes frames, the async threads that send them, the main thread) and
    `rendering` (the rest: the render threads, which start and end with
    their render)."""
    per_thread = {}
    for tid, (name, seconds) in after["threads"].items():
        if tid in before["threads"]:
            used = seconds - before["threads"][tid][1]
            per_thread[name] = per_thread.get(name, 0.0) + used
    overhead = sum(per_thread.values())
    process = after["process"] - before["process"]
    return {
        "chromium": after["chromium"] - before["chromium"],
        "process": process,
        "overhead": overhead,
        "rendering": process - overhead,
        "per_thread": {n: v for n, v in per_thread.items() if v > 0},
    }
