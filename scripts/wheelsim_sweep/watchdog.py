"""Children die with the driver: process sessions, the death signal and the watchdog.

Every child of wheel-sweep (wheel-rig, scripts/wheel-cosim, mpirun for a bed) starts in a session
of its own (session id = its pid) with PR_SET_PDEATHSIG = SIGKILL, so the kernel kills it when
the driver thread that started it dies, also on SIGKILL. Its descendants stay in its session
(mpirun gives each rank a process group of its own, but not a session), so "every process of
the session" is the whole tree of a point. The watchdog is a separate process (its own session,
started first) that reads "+SID" / "-SID" lines from a pipe whose only writer is the driver; when
the pipe closes — the driver exited or was killed — it sends SIGKILL to every process of every
session still registered, and exits.

Run as a script, this file is the watchdog: /usr/bin/python3 watchdog.py.
"""

import os
import signal
import sys
import time


def _stat_fields(pid):
    """(ppid, session) of a process from /proc/PID/stat, or None if it is gone."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            text = f.read()
    except OSError:
        return None
    rest = text[text.rindex(b")") + 2:].split()  # after "pid (comm) "
    return int(rest[1]), int(rest[3])  # state ppid pgrp session ...


def session_members(sid):
    """PIDs of the live processes of session `sid` (not this process)."""
    out = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) != os.getpid():
            f = _stat_fields(name)
            if f is not None and f[1] == sid:
                out.append(int(name))
    return out


def kill_session(sid, sig=signal.SIGKILL):
    """Sends `sig` to every process of session `sid`; returns how many were signalled."""
    n = 0
    for pid in session_members(sid):
        try:
            os.kill(pid, sig)
            n += 1
        except (ProcessLookupError, PermissionError):
            pass
    return n


def kill_sessions_until_empty(sids, timeout=2.0):
    """SIGKILL to every process of `sids`, repeated until none is left (a process may fork
    while it is being killed) or `timeout` seconds passed."""
    deadline = time.monotonic() + timeout
    while True:
        if sum(kill_session(s) for s in sids) == 0 or time.monotonic() > deadline:
            return
        time.sleep(0.05)


def child_preexec(driver_pid):
    """A preexec_fn for a child: a session of its own, and SIGKILL when its parent (the driver
    thread that starts it) dies (wheelsim_post.mpi_launch.die_with_parent)."""
    from wheelsim_post.mpi_launch import die_with_parent  # not needed by the watchdog process
    return die_with_parent(driver_pid, new_session=True, who="wheel-sweep")


def main():
    """The watchdog: registers sessions from stdin lines; at EOF kills them all."""
    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGPIPE):
        signal.signal(s, signal.SIG_IGN)  # a Ctrl-C or a hang-up must not stop the cleanup
    sids = set()
    for line in sys.stdin.buffer:
        line = line.strip()
        if line[:1] == b"+":
            sids.add(int(line[1:]))
        elif line[:1] == b"-":
            sids.discard(int(line[1:]))
    kill_sessions_until_empty(sids)
    return 0


if __name__ == "__main__":
    sys.exit(main())
