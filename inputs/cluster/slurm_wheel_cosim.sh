#!/usr/bin/env bash
# One coupled DEM wheel test (LIGGGHTS over the job's nodes + the rig on the first node), or one
# wheel-sweep, as a Slurm batch job. Docs: docs/dem-performance.md ("Clusters").
#
#   sbatch --export=ALL,WHEELSIM_RIG=inputs/rigs/ci_small_wheel.toml,WHEELSIM_BED=/path/bed.restart \
#          inputs/cluster/slurm_wheel_cosim.sh
#   sbatch -N 4 --ntasks-per-node=32 -t 12:00:00 --export=ALL,WHEELSIM_RIG=...,WHEELSIM_BED=... \
#          inputs/cluster/slurm_wheel_cosim.sh              # 128 LIGGGHTS ranks on 4 nodes
#   sbatch -N 1 --ntasks-per-node=32 --export=ALL,WHEELSIM_SWEEP=my_sweep.toml \
#          inputs/cluster/slurm_wheel_cosim.sh              # a whole sweep on one node
#
# Submit from the wheelsim checkout (or set WHEELSIM_ROOT); relative paths are relative to the
# submit directory. The #SBATCH lines below are defaults; sbatch's command line overrides them.
#
# Variables (environment; sbatch exports the submitting shell's environment by default):
#   WHEELSIM_ROOT          checkout or installed share/wheelsim holding scripts/wheel-cosim
#                          (default: the submit directory)
#   WHEELSIM_BUILD_DIR     build with bin/liggghts-wheel, bin/wheel-rig, meshes/ (default
#                          WHEELSIM_ROOT/build; read by wheel-cosim and wheel-sweep)
#   WHEELSIM_MPI_BIN       directory put first in PATH: the mpirun of the MPI liggghts-wheel was
#                          linked with (Debian: /usr/bin, OpenMPI 4.1, built with Slurm support)
# A coupled run (scripts/wheel-cosim, docs/coupled-runs.md):
#   WHEELSIM_RIG           rig config (TOML, terrain.type = "dem")                     [required]
#   WHEELSIM_BED           soil bin restart from inputs/in.soilbin (.vars beside it)   [required]
#   WHEELSIM_DECK          LIGGGHTS deck (default inputs/examples/in.wheel_coupled)
#   WHEELSIM_MESH          wheel mesh, STL (default: wheel-cosim's, build/meshes/test_small.stl)
#   WHEELSIM_NP            LIGGGHTS ranks (default: the job's tasks, SLURM_NTASKS)
#   WHEELSIM_WORK          logs and the ipc socket (default runs/cluster/JOBID); must be on a file
#                          system every node sees, and WORK/rig.sock at most 107 characters
#   WHEELSIM_OUT           run file (default WORK/run.h5)
#   WHEELSIM_LIGGGHTS_ARGS further LIGGGHTS arguments, split at spaces (e.g. "-var x0 0.5")
# A sweep instead (scripts/wheel-sweep, docs/sweeps.md), when WHEELSIM_SWEEP is set:
#   WHEELSIM_SWEEP         sweep config (TOML); dem.np sets each point's ranks
#   WHEELSIM_SWEEP_OUT     output directory (default: wheel-sweep's, runs/sweeps/<config name>)
#   WHEELSIM_SWEEP_ARGS    further wheel-sweep options, split at spaces (e.g. "--yes --jobs 2")
#
#SBATCH --job-name=wheel-cosim
#SBATCH --nodes=1
#SBATCH --ntasks=8
#SBATCH --cpus-per-task=1
#SBATCH --time=02:00:00
#SBATCH --output=wheel-cosim-%j.out

set -euo pipefail

die() { echo "slurm_wheel_cosim: error: $*" >&2; exit 2; }

submit_dir=${SLURM_SUBMIT_DIR:-$PWD}
cd "$submit_dir"
root=${WHEELSIM_ROOT:-$submit_dir}
[[ -x $root/scripts/wheel-cosim ]] ||
  die "no scripts/wheel-cosim under WHEELSIM_ROOT='$root' (submit from the checkout or set WHEELSIM_ROOT)"
if [[ -n ${WHEELSIM_MPI_BIN:-} ]]; then
  PATH=$WHEELSIM_MPI_BIN:$PATH
  export PATH
fi
command -v mpirun > /dev/null || die "no mpirun in PATH (set WHEELSIM_MPI_BIN)"
# Print OpenMPI's rank-to-node map into the LIGGGHTS screen log (check rank 0's node there).
export OMPI_MCA_rmaps_base_display_map=${OMPI_MCA_rmaps_base_display_map:-1}

job=${SLURM_JOB_ID:-local}
here=$(hostname -s)
first=$here
if [[ -n ${SLURM_JOB_NODELIST:-} ]] && command -v scontrol > /dev/null; then
  first=$(scontrol show hostnames "$SLURM_JOB_NODELIST" | head -n 1)
fi
echo "slurm_wheel_cosim: job $job on ${SLURM_JOB_NUM_NODES:-1} node(s)" \
     "(${SLURM_JOB_NODELIST:-$here}), ${SLURM_NTASKS:-?} task(s); this script and the rig on $here"
# OpenMPI maps ranks by slot from the allocation's first node, where Slurm runs the batch script:
# rank 0 (the only rank that talks to the rig) shares the node with the rig, as the ipc endpoint
# requires. Stop early if this is not so.
[[ $first == "$here" ]] ||
  die "this script runs on $here but the allocation's first node is $first: rank 0 would not be on the rig's node"

if [[ -n ${WHEELSIM_SWEEP:-} ]]; then
  if [[ ${SLURM_JOB_NUM_NODES:-1} -gt 1 ]]; then
    echo "slurm_wheel_cosim: warning: wheel-sweep starts every point's mpirun here, and each" \
         "maps its ranks from the first node: run points at once only within one node, or one" \
         "point per job (docs/dem-performance.md)" >&2
  fi
  sweep_cmd=("$root/scripts/wheel-sweep" "$WHEELSIM_SWEEP")
  [[ -n ${WHEELSIM_SWEEP_OUT:-} ]] && sweep_cmd+=(--out-dir "$WHEELSIM_SWEEP_OUT")
  read -r -a sweep_args <<< "${WHEELSIM_SWEEP_ARGS:-}"
  sweep_cmd+=(${sweep_args[@]+"${sweep_args[@]}"})
  echo "slurm_wheel_cosim: ${sweep_cmd[*]}"
  exec "${sweep_cmd[@]}"
fi

[[ -n ${WHEELSIM_RIG:-} ]] || die "set WHEELSIM_RIG (rig config) and WHEELSIM_BED (bed restart), or WHEELSIM_SWEEP"
[[ -n ${WHEELSIM_BED:-} ]] || die "set WHEELSIM_BED (a soil bin restart from inputs/in.soilbin)"
np=${WHEELSIM_NP:-${SLURM_NTASKS:-1}}
[[ $np =~ ^[1-9][0-9]*$ ]] || die "WHEELSIM_NP: expected a positive integer, got '$np'"
# wheel-cosim passes --oversubscribe (for small machines): on a cluster, more ranks than tasks
# would share cores silently. It also passes --bind-to none (two small jobs on one machine would
# otherwise share core 0, docs/coupled-runs.md "MPI launch"); a node of its own wants binding:
export WHEELSIM_MPI_BIND=${WHEELSIM_MPI_BIND:-core}
if [[ -n ${SLURM_NTASKS:-} && $np -gt $SLURM_NTASKS ]]; then
  die "WHEELSIM_NP=$np exceeds the job's $SLURM_NTASKS task(s): ask sbatch for more (--ntasks or -N/--ntasks-per-node)"
fi
work=${WHEELSIM_WORK:-$root/runs/cluster/$job}
mkdir -p "$work"
work=$(cd "$work" && pwd)
sock="$work/rig.sock"
((${#sock} <= 107)) ||
  die "the ipc socket path '$sock' is ${#sock} characters (ZeroMQ/Unix limit 107): set a shorter WHEELSIM_WORK"
out=${WHEELSIM_OUT:-$work/run.h5}
deck=${WHEELSIM_DECK:-$root/inputs/examples/in.wheel_coupled}

cmd=("$root/scripts/wheel-cosim" --rig "$WHEELSIM_RIG" --bed "$WHEELSIM_BED" --deck "$deck"
     --np "$np" --work "$work" --out "$out"
     --parameter "cluster/job_id=$job" --parameter "cluster/nodes=${SLURM_JOB_NUM_NODES:-1}")
[[ -n ${WHEELSIM_MESH:-} ]] && cmd+=(--mesh "$WHEELSIM_MESH")
read -r -a lmp_args <<< "${WHEELSIM_LIGGGHTS_ARGS:-}"
((${#lmp_args[@]} > 0)) && cmd+=(-- "${lmp_args[@]}")
echo "slurm_wheel_cosim: ${cmd[*]}"
exec "${cmd[@]}"
