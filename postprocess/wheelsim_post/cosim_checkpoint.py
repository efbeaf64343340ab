"""The checkpoints of a coupled run (scripts/wheel-cosim --work DIR: DIR/checkpoints), and which
step a resume continues from: the one place that pairs the two halves.

A checkpoint at step s has two halves, written by two processes:
- the rig's `rig-<s>.ckpt` (its state and the inputs hash, line `t inputs_hash H`);
- LIGGGHTS' `liggghts-<s>.restart` with `.restart.wheel` (fix wheel/cosim's state) and
  `.restart.info` (`step`, `time`, `inputs_hash`, `ranks` lines), the .info written last.
A step is complete when both halves are whole. Each side keeps its newest two, so a kill while
checkpointing can leave a later half without its partner; the newest complete step is taken.

Callers: scripts/wheel-cosim --resume (`python3 -m wheelsim_post.cosim_checkpoint resume DIR
HASH`, which prints the step, or nothing without a checkpoint) and wheel-sweep --park
(scripts/wheelsim_sweep/archive.py).
"""
import re
import sys
from pathlib import Path

RIG = "rig-{s}.ckpt"
LIGGGHTS = ("liggghts-{s}.restart", "liggghts-{s}.restart.wheel", "liggghts-{s}.restart.info")


class CheckpointError(Exception):
    """The checkpoints cannot be resumed: the message says why and what to do."""


def halves(ckpt_dir):
    """(rig steps, LIGGGHTS steps) of the whole halves in ckpt_dir, as sets; empty without it."""
    d = Path(ckpt_dir)
    names = {f.name for f in d.iterdir()} if d.is_dir() else set()

    def steps(pattern):
        return {int(m.group(1)) for n in names if (m := re.fullmatch(pattern, n))}

    lmp = {s for s in steps(r"liggghts-(\d+)\.restart")
           if all(h.format(s=s) in names for h in LIGGGHTS)}
    return steps(r"rig-(\d+)\.ckpt"), lmp


def newest(ckpt_dir):
    """The step of the newest complete checkpoint in ckpt_dir, None without one."""
    rig, lmp = halves(ckpt_dir)
    return max(rig & lmp, default=None)


def info(ckpt_dir, step):
    """{key: value} of LIGGGHTS' liggghts-<step>.restart.info (step, time, inputs_hash, ranks)."""
    text = (Path(ckpt_dir) / LIGGGHTS[2].format(s=step)).read_text()
    return {k: v.strip() for k, v in (line.split(None, 1) for line in text.splitlines() if " " in line)}


def rig_inputs_hash(ckpt_dir, step):
    """The inputs hash the rig's half of `step` records ("missing" without one)."""
    m = re.search(r"(?m)^t inputs_hash (\S+)$", (Path(ckpt_dir) / RIG.format(s=step)).read_text())
    return m.group(1) if m else "missing"


def rig_progress(ckpt_dir, step):
    """(phase name, rig time [s], test start [s] or None) of the rig's half of `step`: its lines
    `t sim/phase_name P`, `n sim/time 1 T`, `n sim/test_start 1 T0` (nan before the test phase;
    wheel_dynamics' RigSimulation::save_checkpoint). KeyError names a missing line."""
    text = (Path(ckpt_dir) / RIG.format(s=step)).read_text()

    def line(kind, key):
        words = _rig_line(text, kind, key)
        if words is None:
            raise KeyError(f"{RIG.format(s=step)}: no '{kind} {key}' line")
        return words

    start = float(line("n", "sim/test_start")[1])
    return (line("t", "sim/phase_name")[0], float(line("n", "sim/time")[1]),
            None if start != start else start)


def rig_steps(text):
    """The rig steps a rig checkpoint's text records (`i sim/steps N`: the point's own steps from
    its start), None without the line."""
    words = _rig_line(text, "i", "sim/steps")
    return int(words[0]) if words else None


def _rig_line(text, kind, key):
    """The words after `KIND KEY` on a rig checkpoint's line (n numbers, i integers, t texts:
    RigSimulation::save_checkpoint), None without that line."""
    m = re.search(rf"(?m)^{kind} {re.escape(key)} (.*)$", text)
    return m.group(1).split() if m else None


def resume_step(ckpt_dir, inputs_hash, warn=lambda msg: print(msg, file=sys.stderr)):
    """The step a resume with `inputs_hash` continues from: None when ckpt_dir holds no half at
    all; CheckpointError when no step is complete, or the step's halves disagree with each other
    or with this run's inputs. A later unpaired half is named through `warn`."""
    d = Path(ckpt_dir)
    rig, lmp = halves(d)
    if not rig and not lmp:
        return None
    both = rig & lmp
    if not both:
        raise CheckpointError(
            f"no complete checkpoint in {d}: rig halves at steps {sorted(rig) or 'none'}, LIGGGHTS "
            f"halves (restart + .wheel + .info) at steps {sorted(lmp) or 'none'}: no step has both "
            f"(remove the directory to start from scratch)")
    s = max(both)
    for other, side in ((max(rig), "rig"), (max(lmp), "LIGGGHTS")):
        if other > s:
            warn(f"wheel-cosim: the {side} half at step {other} has no partner (a kill while "
                 f"checkpointing); using step {s}")
    lmp_info = info(d, s)
    if lmp_info.get("step") != str(s):
        raise CheckpointError(f"checkpoint step {s}: {d / LIGGGHTS[2].format(s=s)} says step "
                              f"{lmp_info.get('step')}")
    rig_hash, lmp_hash = rig_inputs_hash(d, s), lmp_info.get("inputs_hash", "missing")
    if rig_hash != lmp_hash:
        raise CheckpointError(f"checkpoint step {s}: the halves differ in their inputs hash: rig "
                              f"{rig_hash}, LIGGGHTS {lmp_hash}")
    if rig_hash != inputs_hash:
        raise CheckpointError(
            f"checkpoint step {s}: written with inputs hash {rig_hash}, this run's is {inputs_hash}: "
            f"an input changed (rig config, deck, bed, soil file, mesh, dt or arguments); resume "
            f"with the same inputs, or remove {d} to start from scratch")
    return s


def main(argv):
    if len(argv) != 3 or argv[0] != "resume":
        sys.exit("usage: python3 -m wheelsim_post.cosim_checkpoint resume CHECKPOINT_DIR INPUTS_HASH")
    try:
        s = resume_step(argv[1], argv[2])
    except CheckpointError as e:
        sys.exit(str(e))
    print("" if s is None else s)


if __name__ == "__main__":
    main(sys.argv[1:])
