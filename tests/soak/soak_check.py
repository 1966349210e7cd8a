#!/usr/bin/python3
"""The realtime soak: runs a scene on the realtime clock for --duration s (haptic thread pinned,
SCHED_FIFO asked for) and prints a table of what report.json says; exits 1 when a check fails,
2 when the run fails.

Checks (docs/TESTING.md, "The realtime soak"):
- no tick over budget after the first second: no tick whose own CPU time (thread CPU clock)
  exceeded the 1 ms period, i.e. no deadline miss caused by the engine's work. In a virtual
  machine the thread's CPU clock also runs while the host has taken the virtual CPU away (steal
  time, /proc/stat): when the haptic CPU's steal grew during the run, ticks over budget cannot be
  told from the host's and are printed, not asserted. Where it did not grow (or is not reported)
  and ticks went over budget, the run is made again: the engine's work at a tick repeats, a
  stall does not, so only ticks over budget in both runs are the engine's. The first second
  (cold caches, the first whole hierarchy build: about 2 ms at tick 1 of the liver demo) is
  printed, not asserted. Misses while the thread was off its CPU
  (a VM's stalls, preemption, late wake-ups) are counted and printed, not asserted: on a shared
  VM they come from the host, and a test that asserted them would fail on the host's load.
- where SCHED_FIFO was granted: the spin path ran (most waits ended by spinning to the deadline);
  and the misses are at most --max-stall-misses (default: not asserted).
- flat resident memory, where memory was locked: RSS at the end within --rss-growth-kb (default
  256 kB) of RSS 10 s into the run. With mlockall every page is resident once mapped, so growth
  is new allocation; 256 kB over the 50 s between is a leak of 5 bytes per tick.
Usage: soak_check.py --tacta BIN --scene SCENE --out DIR [--duration S] [--cpu N] [--set KEY=VALUE ...]
"""
import argparse
import json
import os
import subprocess
import sys


def steal_jiffies(cpu):
    """Steal time of one CPU, in USER_HZ ticks (/proc/stat, 8th value); None where not reported."""
    try:
        with open("/proc/stat") as f:
            for line in f:
                fields = line.split()
                if fields[0] == f"cpu{cpu}" and len(fields) > 8:
                    return int(fields[8])
    except OSError:
        pass
    return None


def realtime_run(command, out, cpu):
    """Runs `command` writing to `out`; returns (report.json, steal jiffies on cpu meanwhile or
    None where not reported), or (None, None) with the output printed when the run failed."""
    command = command + ["--out", out]
    steal_before = steal_jiffies(cpu)
    run = subprocess.run(command, capture_output=True, text=True)
    steal_after = steal_jiffies(cpu)
    stolen = None if steal_before is None or steal_after is None else steal_after - steal_before
    path = os.path.join(out, "report.json")
    if run.returncode != 0 or not os.path.exists(path):
        print(" ".join(command), run.stdout, run.stderr, sep="\n")
        return None, None
    return json.load(open(path)), stolen


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tacta", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--duration", type=float, default=60)
    p.add_argument("--cpu", type=int, default=min(1, (os.cpu_count() or 1) - 1))
    p.add_argument("--rss-growth-kb", type=int, default=256)
    p.add_argument("--max-stall-misses", type=int, default=-1, help="-1: not asserted")
    p.add_argument("--set", action="append", default=[], help="a scene override, as tacta run")
    a = p.parse_args()
    command = [a.tacta, "run", a.scene, "--realtime", "--duration", str(a.duration),
               "--haptic-cpu", str(a.cpu), "--quiet",
               "--set", "output.frames=false", "--set", "output.vtk=false", "--set", "output.plots=[]"]
    for s in a.set:
        command += ["--set", s]
    r, stolen = realtime_run(command, a.out, a.cpu)
    if r is None:
        return 2
    # Ticks over budget where steal did not grow: the engine's work at tick k is the same in every
    # run, a stall of the host's is not. So a second run tells them apart: a tick over budget in
    # both is the engine's; one over budget in one run only was a stall that landed on the
    # thread's CPU clock (a kernel without steal accounting, or a stall shorter than its jiffy).
    engine_ticks, again, compared = r["over_budget_ticks"], None, False
    listed = r["over_budget_tick_indices"]
    if not stolen and 0 < r["over_budget_ticks"] == len(listed):
        again, stolen_again = realtime_run(command, a.out + "_again", a.cpu)
        if again is None:
            return 2
        # A tick over budget in both runs is asserted whatever the second run's steal: two stalls
        # landing on the same tick by chance is not what a test should be built around.
        if again["over_budget_ticks"] == len(again["over_budget_tick_indices"]):
            engine_ticks = len(set(listed) & set(again["over_budget_tick_indices"]))
            compared = True
    rt, mem = r["realtime"], r["memory_kb"]
    fifo = rt["scheduler"] == "SCHED_FIFO" and rt["demoted_at_tick"] == -1
    pinned = rt["haptic_cpu"] == a.cpu
    waits = rt["spun_waits"] + rt["late_wakeups"]
    samples = mem["rss_every_10s"]
    rss_10 = samples[0] if samples else mem["rss_after_1s"]
    growth = mem["rss_end"] - rss_10
    stall_misses = r["deadline_misses"] - r["over_budget_ticks"]
    checks = [
        ("ticks", f"{r['ticks']} of {round(a.duration * r['haptic_rate_hz'])}",
         r["ticks"] == round(a.duration * r["haptic_rate_hz"])),
        ("scheduler", f"{rt['scheduler']} {rt['priority']}, CPU {rt['haptic_cpu']}, memory locked "
         f"{rt['memory_locked']} {rt['scheduler_note'] or ''}".strip(), None),
        ("ticks over budget after 1 s (engine's misses)",
         f"{r['over_budget_ticks']} (max tick CPU {r['max_tick_cpu_ms']:.3f} ms; host steal on "
         f"CPU {a.cpu} during the run: {'not reported' if stolen is None else f'{stolen} jiffies'})"
         + ("" if again is None else
            f"; run again: {again['over_budget_ticks']} (max {again['max_tick_cpu_ms']:.3f} ms), "
            f"over budget at the same tick in both: "
            f"{engine_ticks if compared else 'not known (more than report.json lists)'}"),
         engine_ticks == 0 if compared or not stolen else (None if engine_ticks else True)),
        ("ticks over budget in the first second (start-up)", str(r["warm_up_over_budget_ticks"]),
         None),
        ("deadline misses, all", f"{r['deadline_misses']} ({stall_misses} off the CPU); "
         f"max start jitter {r['max_start_jitter_ms']:.3f} ms",
         None if a.max_stall_misses < 0 or not (fifo and pinned) else stall_misses <= a.max_stall_misses),
        ("tick p50 / p99 / p999 / max (ms)",
         f"{r['tick_ms']['p50']:.3f} / {r['tick_ms']['p99']:.3f} / {r['tick_ms']['p999']:.3f} / "
         f"{r['tick_ms']['max']:.3f}", None),
        ("waits spun (spin_us " f"{rt['spin_us']:g})", f"{rt['spun_waits']} of {waits}, "
         f"{rt['late_wakeups']} woke past the deadline",
         (rt["spun_waits"] >= waits // 2) if fifo else None),
        ("RSS kB at 1 s, 10 s, end", f"{mem['rss_after_1s']}, {rss_10}, {mem['rss_end']} "
         f"(every 10 s: {', '.join(map(str, samples))})", None),
        ("RSS growth 10 s -> end", f"{growth} kB (bound {a.rss_growth_kb} kB)",
         growth <= a.rss_growth_kb if rt["memory_locked"] else None),
        ("faults", str(len(r["faults"])), not r["faults"]),
    ]
    print(f"| realtime soak, {a.duration:g} s, {os.path.basename(a.scene)} | measured | check |")
    print("|---|---|---|")
    for name, value, ok in checks:
        print(f"| {name} | {value} | {'-' if ok is None else 'pass' if ok else 'FAIL'} |")
    return 1 if any(ok is False for _, _, ok in checks) else 0


if __name__ == "__main__":
    sys.exit(main())
