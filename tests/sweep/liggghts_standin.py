#!/usr/bin/python3
"""A stand-in for liggghts-wheel in the stall-guard tests (tests/sweep `bed_stall`, `bed_steady`;
tests/soil_lab check_stall_lab.py): linked as <fake build>/bin/liggghts-wheel, started by the
tools through mpirun like the real one, it runs no simulation. It prints its deck's name, then:

  deck named in $STANDIN_STALL_DECKS (comma-separated, e.g. "in.soilbin"): sleeps 300 s without
      printing another line (a hung run), in this process (no child left to outlive a kill);
  any other deck: prints a line every 0.25 s for $STANDIN_STEADY_S seconds (default 0: a healthy
      run that keeps printing), then finishes: for in.soilbin it writes `-var restart_file`'s file
      and its .vars, as in.soilbin does, and exits 0; other decks just exit 0.
"""

import os
import sys
import time


def var(name):
    """The value of `-var NAME VALUE` on the command line, or None."""
    args = sys.argv[1:]
    for i in range(len(args) - 2):
        if args[i] == "-var" and args[i + 1] == name:
            return args[i + 2]
    return None


def main():
    args = sys.argv[1:]
    deck = os.path.basename(args[args.index("-in") + 1]) if "-in" in args else "?"
    print(f"stand-in liggghts-wheel (pid {os.getpid()}): {deck}", flush=True)
    if deck in os.environ.get("STANDIN_STALL_DECKS", "").split(","):
        time.sleep(300)
        return 1
    end = time.monotonic() + float(os.environ.get("STANDIN_STEADY_S", "0"))
    step = 0
    while time.monotonic() < end:
        time.sleep(0.25)
        step += 100
        print(f"{step:8d} stand-in thermo line", flush=True)
    restart = var("restart_file")
    if deck == "in.soilbin" and restart is not None:
        with open(restart, "w") as f:
            f.write("not a restart: written by the stand-in liggghts-wheel\n")
        with open(f"{restart}.vars", "w") as f:
            f.write("variable bed_depth index 0.03\n")
    print(f"stand-in liggghts-wheel: {deck} done", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
