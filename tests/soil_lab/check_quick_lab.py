#!/usr/bin/python3
"""The whole soil lab on the ci soil with the quick preset (CI smoke; docs/soil-lab.md):

  soil-lab run ci --preset quick --speed-check --plate-hold 0.05 --plate-hold-stages 2
                 --bed-hold 0.05
                                  -> SIGKILLed in its first shear box once it has consolidated
                                     and has two checkpoints; --archive A --park keeps the
                                     newest; the box's checkpoints, CSV and start record
                                     removed (a new machine); the same command with --archive A
                                     takes them back and resumes that box
                                     from its newest complete checkpoint (done.json:
                                     resumed_at_step; the CSV's rows evenly spaced to the end, no
                                     gap, no repeat, one change from consolidation to shear, at
                                     the step the first attempt began shearing; no checkpoint
                                     left)
                                  -> every test's output, results.toml/csv and the PNGs; the
                                     fitted values finite and in physically plausible ranges; the
                                     half-speed comparisons (quasi-static check) reported; the
                                     plates stood still at two depths (stress relaxation), each
                                     hold measured and the relaxed Bekker fit written; the
                                     larger plate again as LIGGGHTS' own mesh wall
                                     (soil_lab/trials/in.plate_wall_gran, the reference): its
                                     holds' mean relaxation within 0.1, its mean loading
                                     pressure within 15 %
  soil-lab run ... again          -> every bed and run skipped (resume), in seconds
  ... --shear-replicates 2        -> the finished lab grows a second shear bed (its own seed: another
                                     packing), its three boxes and its middle box at half
                                     speed, nothing else re-runs; the report's replicate table (2
                                     boxes per stress, each bed's fit), the speed check's
                                     replicate differences and its pairing over the two beds
  ... --tests plate --dt-check    -> the larger plate again at half the soil's time step on the
                                     same bed (nothing else re-runs): its record's and the deck's
                                     step, results.toml [time_step], the report's line, the SCM
                                     file's [source]
  soil-lab scm DIR --out F.toml   -> an SCM soil file that wheel-rig --check loads unchanged
  ... --plate-replicates 2        -> the finished lab grows a second plate bed (its own seed), its two
                                     plates and its larger plate at half speed and at half the
                                     step: each bed's Bekker fit, the checks paired over the two
                                     beds, the SCM file's [source] saying so
  bad input                       -> exit 2 naming the unknown soil / test / option

Exit 0 pass, 1 fail, 77 skip (liggghts-wheel not built).
"""
import argparse
import json
import os
import re
import signal
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "soil_lab"))
from soil_lab_py import analysis, plan  # noqa: E402
LAB = ROOT / "soil_lab" / "soil-lab"
HOLD_S, HOLD_STAGES = 0.05, 2  # the quick lab's plate holds (--plate-hold, --plate-hold-stages)
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def lab(*args, **kw):
    return subprocess.run([str(LAB), *args], capture_output=True, text=True, **kw)


def wall_gran_reference(out, build, lab_holds):
    """The lab's larger plate (fix wheel/cosim) against the same test with the plate as LIGGGHTS'
    own mesh wall, on the same bed: a relaxation at rest or a pressure that only our contact code
    produced would show here. Two codes on a chaotic packing of ~2000 grains: the comparison is of
    aggregates, with tolerances above their scatter (2026-11-29, three realizations: relaxation
    54.5/56.3, 55.3/51.6 and, wall/gran, 54.3/51.9 %; mean loading pressure 3013, 3019 and 3145
    Pa; single moving pressures at the 8 mm stop scatter more, 7.15 / 8.13 / 9.21 kPa, and are
    not compared)."""
    soil = tomllib.loads((out / "soil.toml").read_text())
    info = plan.SoilInfo(**{k: soil[k] for k in plan.SoilInfo.__dataclass_fields__})
    run, = [r for r in plan.make_plan(info, ("plate",), "quick", plate_hold=HOLD_S,
                                      plate_hold_stages=HOLD_STAGES).runs
            if r.name == "plate_b0.032"]
    # the schedule's length as the lab computes it for its parking messages (progress.run_progress)
    # against the deck's: the last CSV row of the held plate ends its reload
    t_last = float((out / run.name / "plate.csv").read_text().splitlines()[-1].split()[0])
    t_plan = plan.plate_test_time_s(run.variables)
    check(abs(t_last - t_plan) < 0.01 * t_plan,
          f"plan.plate_test_time_s {t_plan:.4f} s is the deck's schedule (last CSV row {t_last:.4f} s)")
    work = out / "wall_gran"
    work.mkdir(exist_ok=True)
    b, _, t = run.meshes["plate_mesh"][1:4]
    mesh = subprocess.run([str(build / "bin" / "wheel-mesh"), "tool", "plate-rect", b, b, t,
                           "--out", str(work / "plate"), "--formats", "stl"],
                          capture_output=True, text=True)
    bed = json.loads((out / "beds" / "plate" / "done.json").read_text())["result"]["restart"]
    cmd = [str(build / "bin" / "liggghts-wheel"), "-in",
           str(ROOT / "soil_lab" / "trials" / "in.plate_wall_gran"), "-log", "none",
           "-var", "inputs_dir", str(ROOT / "inputs"), "-var", "lab_decks",
           str(ROOT / "soil_lab" / "decks"), "-var", "restart_file", bed,
           "-var", "plate_mesh", str(work / "plate.stl"), "-var", "out_csv", str(work / "plate.csv")]
    for k, v in run.variables.items():
        cmd += ["-var", k, v]
    (work / "plate.csv").unlink(missing_ok=True)
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=work)
    check(mesh.returncode == 0 and r.returncode == 0,
          f"in.plate_wall_gran ran (exit {r.returncode}"
          + ("" if r.returncode == 0 and mesh.returncode == 0
             else f": {r.stdout[-400:]} {mesh.stderr}") + ")")
    if r.returncode != 0:
        return
    ref_plate = analysis.read_plate(work, {"meta": {"b_m": float(b)}})
    lab_plate = analysis.read_plate(out / "plate_b0.032", {"meta": {"b_m": float(b)}})
    ref = analysis.plate_holds(ref_plate)
    pairs = list(zip(lab_holds, ref))
    loading = [float(analysis.loading_branch(pl)[1].mean()) for pl in (lab_plate, ref_plate)]
    relax = [sum(h["relaxation"] for h in hs) / max(len(hs), 1) for hs in (lab_holds, ref)]
    check(len(ref) == 2 and len(pairs) == 2 and abs(loading[0] / loading[1] - 1) < 0.15 and
          abs(relax[0] - relax[1]) < 0.1,
          f"the plate as LIGGGHTS' own mesh wall: mean loading pressure {loading[0]:.0f} against "
          f"{loading[1]:.0f} Pa; mean relaxation of the holds {100 * relax[0]:.1f} against "
          f"{100 * relax[1]:.1f} %: "
          + "; ".join(f"z {1e3 * h['z_m']:.3g} mm {100 * a['relaxation']:.1f} % against "
                      f"{100 * h['relaxation']:.1f} %" for a, h in pairs))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build-dir", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--np", default="1")
    a = ap.parse_args()
    build = Path(a.build_dir)
    if not (build / "bin" / "liggghts-wheel").is_file():
        print("SKIP: liggghts-wheel not built")
        return 77
    out = Path(a.work) / "ci_quick"
    shutil.rmtree(out, ignore_errors=True)  # a fresh lab: the first run must do everything
    env = {**os.environ, "WHEELSIM_BUILD_DIR": str(build)}
    t0 = time.monotonic()
    hold = ["--plate-hold", f"{HOLD_S:g}", "--plate-hold-stages", str(HOLD_STAGES)]
    # the beds' hold checks last 0.05 s, not 0.2 s (CI time; soil_lab.bed_hold checks the hold)
    command = ["run", "ci", "--preset", "quick", "--speed-check", *hold, "--bed-hold", "0.05",
               "--out", str(out), "--np", a.np]
    box = out / "shear_s3000"
    Path(a.work).mkdir(parents=True, exist_ok=True)
    # --estimate before anything ran: no pace of its own, so the beds and runs are priced at
    # this machine's rate (here wheel-sweep's defaults: no rate cache), the beds' spheres
    # estimated from their recipes (checked against the prepared beds below)
    r = lab(*command, "--estimate",
            env={**env, "WHEELSIM_RATE_CACHE": str(Path(a.work) / "no_rate_cache.toml")})
    estimated = {b: int(n.replace(" ", "")) for b, n in
                 re.findall(r"bed '(\w+)': to prepare here, ~([\d ]+) spheres", r.stdout)}
    check(r.returncode == 0 and sorted(estimated) == ["plate", "repose", "shear"]
          and "pace unknown" not in r.stdout and "DEFAULT" in r.stdout
          and "h of wall time at the measured paces and this machine's rate" in r.stdout,
          f"--estimate of a lab not started prices its beds and runs at the machine's rate "
          f"({r.stdout[-600:]} {r.stderr[-300:]})")
    with open(Path(a.work) / "killed_lab.log", "w") as log:
        p = subprocess.Popen([str(LAB), *command], stdout=log, stderr=subprocess.STDOUT, env=env)
        deadline = time.monotonic() + 600
        while p.poll() is None and time.monotonic() < deadline:
            # killed while shearing, after the box consolidated: the resumed attempt must shear
            # on from the step the first one began at (runner.SHEAR_START_FILE), not consolidate
            if (box / "shear_start_step.txt").is_file() and \
                    len(list((box / "checkpoints").glob("lab-*.restart"))) >= 2:
                break
            time.sleep(0.05)
        killed = p.poll() is None
        p.send_signal(signal.SIGKILL)
        p.wait()
    start_file = box / "shear_start_step.txt"
    shear_start = int(start_file.read_text().split()[0]) if start_file.is_file() else None
    check(killed and not (box / "done.json").exists() and shear_start is not None,
          f"lab SIGKILLed in its first shear box after it consolidated (shear from step "
          f"{shear_start}) and two checkpoints "
          f"({time.monotonic() - t0:.0f} s; log {Path(a.work) / 'killed_lab.log'})")
    time.sleep(1.0)  # mpirun and the rank die with the lab (soil_lab.kill_kill)
    # parked (--park), and the box's checkpoint, CSV and start record then lost as on a new
    # machine: the resumed lab takes them back from the archive
    arch = Path(a.work) / "archive"
    shutil.rmtree(arch, ignore_errors=True)
    r = lab(*command, "--archive", str(arch), "--park", env=env)
    parked = arch / "shear_s3000" / "parked" / "parked.json"
    record = json.loads(parked.read_text()) if parked.is_file() else {}
    names = sorted(f["path"] for f in record.get("files", []))
    check(re.search(r"shear_s3000: parked at step \d+ \(\d+ steps into the run, (shear j "
                    r"[\d.]+ of [\d.]+ mm, \d+ %|consolidating under its lid);", r.stdout)
          is not None, f"--park says how far the box had come ({r.stdout[-300:]})")
    check(r.returncode == 0 and "shear_s3000: parked at step" in r.stdout and len(names) == 4
          and {"checkpoints/state.json", "shear.csv", "shear_start_step.txt"} < set(names),
          f"--park kept the killed box's newest checkpoint, state, CSV and start record ({names}; "
          f"{r.stdout[-500:]} {r.stderr[-500:]})")
    for f in names:
        (box / f).unlink()
    # the box's bed lost too: --park kept its record (done.json, hold record, .vars), so the box
    # resumes without it and the bed is poured only for the boxes that must start from it
    check(sorted(f.name for f in (arch / "beds" / "shear").iterdir())
          == ["done.json", "hold.json", "restart.vars"], "--park kept the shear bed's record")
    shutil.rmtree(out / "beds" / "shear")
    r = lab(*command, "--archive", str(arch), env=env)
    print(r.stdout[-4000:], r.stderr[-2000:])
    check(r.returncode == 0, f"soil-lab run exit 0 (got {r.returncode}, {time.monotonic() - t0:.0f} s)")
    resumed = r.stdout.find("shear_s3000: resuming from its checkpoint")
    poured = r.stdout.find("bed 'shear': preparing")
    check("bed 'shear': its record restored from the archive" in r.stdout and
          0 <= resumed < poured, "the killed box resumed before its lost bed was poured again "
          f"(for the next box; at {resumed} and {poured} in the log)")
    for f in ("soil.toml", "results.toml", "results.csv", "plate.png", "plate_holds.png",
              "shear_curves.png",
              "mohr_coulomb.png", "beds/plate/done.json", "plate_b0.02/plate.csv",
              "plate_b0.032/plate.csv", "shear_s3000/shear.csv", "shear_s6000/shear.csv",
              "shear_s9000/shear.csv", "repose/repose.dump"):
        check((out / f).is_file(), f"{f} written")
    check(f"shear_s3000: its checkpoint at step {record.get('step')} (parked" in r.stdout and
          "shear_s3000: resuming from its checkpoint at step" in r.stdout,
          "the killed box resumed from its parked checkpoint")
    check(not (arch / "shear_s3000" / "parked").exists() and
          (arch / "shear_s3000" / "done.json").is_file(),
          "the finished box's archive folder holds its results, not its parked checkpoint")
    eta = re.search(r"~([0-9.]+) min left\] shear_s3000: resuming", r.stdout)
    check(eta is not None and float(eta.group(1)) > 0,
          f"the resumed lab's ETA counts the runs skipped as done at their own wall time "
          f"({eta.group(0) if eta else 'no ETA'})")
    done = json.loads((box / "done.json").read_text()) if (box / "done.json").is_file() else {}
    rows = [[float(x) for x in line.split()] for line in
            (box / "shear.csv").read_text().splitlines() if line and not line.startswith("#")] \
        if (box / "shear.csv").is_file() else []
    gaps = [b[0] - a_[0] for a_, b in zip(rows, rows[1:])]
    phases = [int(r_[6]) for r_ in rows]
    turns = [k for k in range(1, len(phases)) if phases[k] != phases[k - 1]]
    log = (box / "liggghts.log").read_text(errors="replace") if (box / "liggghts.log").is_file() else ""
    check(phases[:1] == [1] and phases[-1:] == [2] and len(turns) == 1 and
          f"consolidation ended in an attempt before this one; shearing from step {shear_start}" in log,
          f"the resumed box sheared on from step {shear_start} (consolidation, then shear: "
          f"{len(turns)} phase change(s) in the CSV)")
    check(done.get("resumed_at_step", 0) > 0 and done.get("wall_s_before_resume", 0) > 0 and
          not (box / "checkpoints").exists(),
          f"done.json: resumed at step {done.get('resumed_at_step')}, wall before "
          f"{done.get('wall_s_before_resume')} s; checkpoints removed")
    check(len(gaps) > 100 and max(gaps) - min(gaps) < 1e-9 * max(gaps) + 1e-12 and
          rows[-1][1] > 0.99 * done.get("meta", {}).get("box_m", 1) * 0.12,
          f"resumed CSV: {len(rows)} rows evenly spaced (row interval {min(gaps, default=0):.6g}.."
          f"{max(gaps, default=0):.6g} s), displacement at the end {rows[-1][1] if rows else None} m")
    res = tomllib.loads((out / "results.toml").read_text()) if (out / "results.toml").is_file() else {}
    bulk, plate, shear = res.get("bulk", {}), res.get("plate", {}), res.get("shear", {})
    check(1000 < bulk.get("bulk_density_kg_m3", 0) < 2500 and 0.2 < bulk.get("porosity", 0) < 0.6,
          f"bulk density {bulk.get('bulk_density_kg_m3')} kg/m^3, porosity {bulk.get('porosity')}")
    check(0 < plate.get("n", 0) <= 2 and plate.get("kphi_N_m_n2", 0) > 0,
          f"Bekker n {plate.get('n')}, kphi {plate.get('kphi_N_m_n2')}")
    # The holds: in.lab_plate stood the plate still (phase 4, one sinkage per hold) at 1/2 and
    # all of the loading depth, for 0.05 s each, on both plates.
    holds = plate.get("holds", {})
    check(sorted(holds) == ["b0.02", "b0.032"] and all(
        len(hs) == 2 and all(abs(h["hold_s"] - 0.05) < 0.002 and h["p_end_Pa"] > 0 for h in hs)
        and abs(hs[1]["z_m"] - 2 * hs[0]["z_m"]) < 1e-3 * hs[1]["z_m"] for hs in holds.values()),
        f"two 0.05 s holds per plate at half and all of the loading depth ({holds})")
    plate_b = (analysis.read_plate(out / "plate_b0.032", {"meta": {"b_m": 0.032}})
               if (out / "plate_b0.032" / "plate.csv").is_file() else
               {"z": [], "phase": []})
    held = [z for z, ph in zip(plate_b["z"], plate_b["phase"]) if ph == analysis.PLATE_HOLD]
    plate_phases = [int(ph) for ph in plate_b["phase"]]
    order = [ph for k, ph in enumerate(plate_phases) if k == 0 or ph != plate_phases[k - 1]]
    check(order == [1, 4, 1, 4, 2, 3] and len({round(z, 12) for z in held}) == 2,
          f"plate_b0.032's phases load, hold, load, hold, unload, reload ({order}); the plate "
          f"still while held ({len({round(z, 12) for z in held})} sinkage values in the holds)")
    relaxed = plate.get("relaxed", {})
    check(0 < relaxed.get("n", 0) <= 2 and relaxed.get("points") == 4,
          f"the relaxed Bekker fit on the 4 hold ends ({relaxed})")
    wall_gran_reference(out, build, holds.get("b0.032", []))
    # ci: sliding friction 0.5 and rolling friction 0.1 between glass-like spheres: a loose
    # granular packing's internal friction angle lies well inside 15..45 deg.
    check(15 < shear.get("friction_deg", 0) < 45, f"friction angle {shear.get('friction_deg')} deg")
    lost = [s.get("particles_lost_at_end") for s in shear.get("stresses", [])]
    check(len(lost) == 3 and all(x == 0.0 for x in lost),
          f"no grain leaves the shear boxes (lost fractions {lost})")
    check(len(res.get("cost", {})) == 8, f"cost of 8 runs recorded ({len(res.get('cost', {}))})")
    total = res.get("cost_total", {})
    check(len(total.get("beds", {})) == 6 and total.get("lab_wall_s", 0) > total.get("runs_wall_s", 0) > 0,
          f"lab wall time = beds (3, each with its bed-hold check) + runs ({total})")
    spheres = {b: int(float(json.loads((out / "beds" / b / "done.json").read_text())
                            ["result"]["spheres"])) for b in estimated
               if (out / "beds" / b / "done.json").is_file()}
    check(len(spheres) == 3 and all(abs(estimated[b] - n) <= 0.05 * n + 50
                                    for b, n in spheres.items()),
          f"the estimate's spheres per bed within 5 % of the prepared beds' ({estimated} against "
          f"{spheres})")
    holds_bed = res.get("bed_hold", {})
    check(sorted(holds_bed) == ["plate", "repose", "shear"] and
          all(0 <= h["settlement"] < 0.01 for h in holds_bed.values()),
          f"each ci bed holds under its test settings, settling < 1 % in 0.2 s ({holds_bed})")
    inv = res.get("soil", {}).get("invocations", [])
    check(len(inv) == 2 and all(len(i.get("git_commit", "")) == 40 and "--preset quick" in
                                i.get("command", "") and i.get("host") for i in inv),
          f"provenance of both invocations (killed, resumed): command, git commit, host ({inv})")
    qs = res.get("quasi_static", {})
    check(set(qs) >= {"plate_b0.032", "shear_s6000"} and
          all(abs(q["difference"]) < (1 if q["relative"] else 15) and q["half_speed"] > 0
              for q in qs.values()),
          f"quasi-static comparisons of the plate and the shear box ({sorted(qs)})")

    t0 = time.monotonic()
    r = lab(*command, env=env)
    skipped = len(re.findall(r"done before, skipped", r.stdout))
    check(r.returncode == 0 and skipped == 11,
          f"re-run skips 3 beds and 8 runs ({skipped} skipped, {time.monotonic() - t0:.1f} s)")

    # Replicates grow on the finished lab (docs/soil-lab.md "Replicate boxes"): the first bed's
    # runs keep their records, a second shear bed is poured with its own seed.
    t0 = time.monotonic()
    r = lab(*command, "--shear-replicates", "2", env=env)
    skipped = len(re.findall(r"done before, skipped", r.stdout))
    ran = sorted(set(re.findall(r"(shear_s\d+_r2(?:_half)?): running", r.stdout)))
    check(r.returncode == 0 and skipped == 11 and ran == ["shear_s3000_r2", "shear_s6000_r2",
                                                          "shear_s6000_r2_half",
                                                          "shear_s9000_r2"],
          f"--shear-replicates 2 on the finished lab: {skipped} of 11 kept, ran {ran} "
          f"({time.monotonic() - t0:.1f} s; {r.stderr.strip()[-300:]})")
    res = tomllib.loads((out / "results.toml").read_text()) if r.returncode == 0 else {}
    rep = res.get("shear", {}).get("replicates", {})
    rho = [json.loads((out / "beds" / b / "done.json").read_text())["result"]["bulk_density"]
           for b in ("shear", "shear_r2") if (out / "beds" / b / "done.json").is_file()]
    check(len(rho) == 2 and rho[0] != rho[1],
          f"the replicate bed is another packing of the same soil (bulk density {rho} kg/m3)")
    check(rep.get("fitted_replicates") == [1, 2] and
          [b.get("boxes") for b in rep.get("by_stress", [])] == [2, 2, 2] and
          all(15 < phi < 45 for phi in rep.get("friction_deg", [])) and
          len(res.get("shear", {}).get("stresses", [])) == 6 and
          len(res.get("quasi_static", {}).get("shear_s6000", {}).get("replicate_differences",
                                                                       [])) == 1,
          f"replicate table: each bed's phi {rep.get('friction_deg')} deg, peaks' spread "
          f"{[round(b.get('tau_peak_spread', -1), 3) for b in rep.get('by_stress', [])]}, "
          "six Mohr-Coulomb points, the speed check's replicate difference")
    paired = res.get("quasi_static_paired", {}).get("shear_s6000", {})
    check(paired.get("runs") == ["shear_s6000", "shear_s6000_r2"] and
          paired.get("verdict") in ("quasi-static", "rate effect", "cannot tell") and
          paired.get("interval_low", 1) <= paired.get("mean_difference", 0) <=
          paired.get("interval_high", -1),
          f"the speed check paired over the two beds: {paired.get('differences')}, mean "
          f"{paired.get('mean_difference')}, 95 % interval {paired.get('interval_low')} .. "
          f"{paired.get('interval_high')}: {paired.get('verdict')}")

    # The time-step check grows on the finished lab too: the larger plate again at half the
    # soil's step on the same bed (--dt-check; --tests plate: the plates' runs, the half-speed
    # one among them, are the lab's own)
    t0 = time.monotonic()
    r = lab(*command, "--tests", "plate", "--dt-check", env=env)
    skipped = len(re.findall(r"done before, skipped", r.stdout))
    ran = sorted(set(re.findall(r"(\S+): running", r.stdout)))
    check(r.returncode == 0 and skipped == 4 and ran == ["plate_b0.032_halfdt"],
          f"--dt-check on the finished lab: the bed, both plates and the half-speed plate kept "
          f"({skipped} of 4), ran {ran} "
          f"({time.monotonic() - t0:.1f} s; {r.stderr.strip()[-300:]})")
    dts = [json.loads((out / n / "done.json").read_text()).get("dt_s")
           for n in ("plate_b0.032", "plate_b0.032_halfdt") if (out / n / "done.json").is_file()]
    log = out / "plate_b0.032_halfdt" / "liggghts.log"
    text = log.read_text() if log.is_file() else ""
    ran_dt = [float(x) for x in re.findall(r"soil-lab: plate: .*, dt (\S+) s,", text)]
    check(len(dts) == 2 and dts[1] == 0.5 * dts[0] and len(ran_dt) == 1 and
          abs(ran_dt[0] / dts[1] - 1) < 1e-9 and "soil_at_step.in" in text,
          f"the half-step plate ran at half the soil's step on the same bed (records {dts} s, "
          f"the deck's {ran_dt} s, from its soil_at_step.in)")
    res = tomllib.loads((out / "results.toml").read_text()) if r.returncode == 0 else {}
    step_check = res.get("time_step", {}).get("plate_b0.032", {})
    check(step_check.get("quantity") == "pressure at the end of loading" and
          -0.5 < step_check.get("difference", 9) < 0.5 and
          len(step_check.get("profile_difference", [])) == analysis.PLATE_PROFILE_BANDS and
          "time step: plate_b0.032: pressure at the end of loading at half the step" in r.stdout,
          f"results.toml [time_step.plate_b0.032] and the report's line "
          f"({ {k: step_check.get(k) for k in ('difference', 'passed')} })")

    scm = out / "ci_fitted.toml"
    scm.unlink(missing_ok=True)
    r = lab("scm", str(out), "--out", str(scm))
    # the SCM file states its plates' speed check; a failed one is refused without
    # --rate-dependent (the quick plates' check reads -3 %, tolerance 5 %, on this build: either
    # outcome is checked for what it must do)
    plate_check = res.get("quasi_static", {}).get("plate_b0.032", {})
    if plate_check.get("passed") is False:
        check(r.returncode == 2 and "speed check failed" in r.stderr and not scm.is_file(),
              f"soil-lab scm refuses plates that failed their speed check ({r.stderr.strip()})")
        r = lab("scm", str(out), "--out", str(scm), "--rate-dependent")
    check(r.returncode == 0 and scm.is_file(), f"soil-lab scm wrote {scm} ({r.stderr.strip()})")
    if scm.is_file():
        check(("NOT quasi-static" if plate_check.get("passed") is False else ": quasi-static")
              in tomllib.loads(scm.read_text())["source"]["bekker"]["n"],
              f"the Bekker [source] states the plates' speed check ({plate_check})")
        check("time-step check: plate_b0.032 at half the step" in
              tomllib.loads(scm.read_text())["source"]["bekker"]["n"],
              "the Bekker [source] states the plates' time-step check")
    if scm.is_file():
        text = (ROOT / "wheel_dynamics" / "examples" / "rig_scm.toml").read_text()
        text = re.sub(r'(?m)^mesh = "[^"]*"', f'mesh = "{build / "meshes" / "test_small.obj"}"', text)
        text = re.sub(r'(?m)^soil = "[^"]*"', f'soil = "{scm}"', text)
        cfg = out / "rig_check.toml"
        cfg.write_text(text)
        r = subprocess.run([str(build / "bin" / "wheel-rig"), "--config", str(cfg), "--check"],
                           capture_output=True, text=True)
        check(r.returncode == 0, f"wheel-rig --check loads the fitted soil ({r.stderr.strip()})")
        check("fitted from the DEM soil 'ci'" in scm.read_text(), "[source] names the DEM soil")

    # Replicate plates grow on the finished lab too (docs/soil-lab.md "Replicate plates"): a
    # second plate bed with its own seed, its two plates, its larger plate at half speed and at
    # half the step; both checks then paired over the two beds, and the SCM file says so
    t0 = time.monotonic()
    r = lab(*command, "--tests", "plate", "--dt-check", "--plate-replicates", "2", env=env)
    skipped = len(re.findall(r"done before, skipped", r.stdout))
    ran = sorted(set(re.findall(r"(\S+): running", r.stdout)))
    check(r.returncode == 0 and skipped == 5 and
          ran == ["plate_b0.02_r2", "plate_b0.032_r2", "plate_b0.032_r2_half",
                  "plate_b0.032_r2_halfdt"],
          f"--plate-replicates 2 on the finished lab: the first bed and its 4 plates kept "
          f"({skipped} of 5), ran {ran} ({time.monotonic() - t0:.1f} s; "
          f"{r.stderr.strip()[-300:]})")
    res = tomllib.loads((out / "results.toml").read_text()) if r.returncode == 0 else {}
    rep = res.get("plate", {}).get("replicates", {})
    rho = rep.get("bed_bulk_density_kg_m3", {})
    check(rep.get("fitted_replicates") == [1, 2] and
          [b.get("plates") for b in rep.get("by_width", [])] == [2, 2] and
          all(0.1 < n < 2 for n in rep.get("n", [])) and len(rho) == 2 and
          rho.get("bed1") != rho.get("bed2") and
          len(res.get("plate", {}).get("elastic_K_Pa_m", {})) +
          len(res.get("plate", {}).get("elastic_K_errors", {})) == 2,   # the first bed's
          f"plate replicate table: each bed's n {rep.get('n')}, kphi {rep.get('kphi_N_m_n2')}, "
          f"beds {rho} kg/m3, the end pressures' spread "
          f"{[round(b.get('p_end_spread', -1), 3) for b in rep.get('by_width', [])]}")
    pairs = {name: res.get(name, {}).get("plate_b0.032", {})
             for name in ("quasi_static_paired", "time_step_paired")}
    check(all(c.get("runs") == ["plate_b0.032", "plate_b0.032_r2"] and c.get("beds") == 2 and
              c.get("interval_low", 1) <= c.get("mean_difference", 0) <= c.get("interval_high", -1)
              for c in pairs.values()) and
          "time step over 2 beds at plate b 0.032 m" in r.stdout,
          "the plate's speed and step checks paired over the two beds: "
          + "; ".join(f"{k}: {c.get('differences')} -> {c.get('verdict')}"
                      for k, c in pairs.items()))
    scm.unlink(missing_ok=True)
    rate = pairs["quasi_static_paired"].get("verdict") == "rate effect"
    r = lab("scm", str(out), "--out", str(scm), *(["--rate-dependent"] if rate else []))
    source = tomllib.loads(scm.read_text())["source"]["bekker"]["n"] if scm.is_file() else ""
    check(r.returncode == 0 and "over 2 beds (plate b 0.032 m, each paired on its bed)" in source
          and "; time-step check over 2 beds" in source,
          f"the Bekker [source] states both checks over the two beds ({r.stderr.strip()})")

    for args, message in ((("run", "nosuch"), "unknown soil 'nosuch'"),
                          (("run", "ci", "--tests", "plate,sheer"), "did you mean 'shear'?"),
                          (("run", "ci", "--tets", "plate"), "did you mean '--tests'?"),
                          (("run", "ci", "--checkpoints", "-1"), "--checkpoints: expected a number >= 0"),
                          (("run", "ci", "--plate-hold", "-1"), "--plate-hold -1 s is outside (0, 60]"),
                          (("scm", str(out / "nothing"), "--out", "x.toml"), "not a soil-lab directory")):
        r = lab(*args, env=env)
        check(r.returncode == 2 and message in r.stderr,
              f"soil-lab {' '.join(args)}: exit 2 with \"{message}\" (exit {r.returncode}: {r.stderr.strip()})")
    print(f"{len(failures)} failed" if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
