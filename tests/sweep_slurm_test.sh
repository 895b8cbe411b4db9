#!/usr/bin/env bash
# rtlab sweep submit --slurm on a one-node Slurm cluster this test starts and stops itself
# (scripts/slurm-local): the sweep of tests/sweeps/small.json run as a job array gives the same
# merged table as `rtlab sweep run` (all but timings and provenance), failed cases included; the
# merge job (afterany) reports missing cases after `scancel` of one array task, and re-submitting
# completes the sweep without redoing finished cases. Skipped (exit 77, one line) when a cluster
# cannot be started: not root, or slurm-wlm/munge not installed. Run by CTest with RTLAB set.
set -uo pipefail
: "${RTLAB:?set RTLAB to the rtlab executable}"
if [[ $(id -u) -ne 0 ]]; then
    echo "sweep_slurm: skipped: not root, so no Slurm cluster can be started here"
    exit 77
fi
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    echo "sweep_slurm: skipped: slurm-wlm or munge not installed (scripts/deps installs them)"
    exit 77
fi
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/.." && pwd)
RTLAB=$(cd "$(dirname "$RTLAB")" && pwd)/$(basename "$RTLAB")
tmp=$(mktemp -d)
chmod 0755 "$tmp"  # munged (user munge) must reach the cluster folder inside
cluster=$tmp/cluster
cleanup() {
    [[ -f $cluster/slurm.conf ]] && "$repo/scripts/slurm-local" down "$cluster"
    rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }
small=$here/sweeps/small.json

up=$("$repo/scripts/slurm-local" up "$cluster") || fail "scripts/slurm-local up"
eval "$up"

# Waits until none of the given jobs is queued or running (squeue; no accounting here).
wait_jobs() {
    local ids=$1
    for _ in $(seq 1 600); do
        [[ -z $(squeue -h -j "$ids" 2>/dev/null) ]] && return 0
        sleep 0.2
    done
    squeue
    fail "jobs $ids still queued after 120 s"
}
jobs_of() { python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j["array"], j["merge"], sep=",")' "$1/slurm/jobs.json"; }

# The reference: the same sweep run locally.
"$RTLAB" sweep run "$small" -o "$tmp/local" 2>/dev/null
"$RTLAB" sweep merge "$tmp/local" -o "$tmp/local/merged" >/dev/null || fail "local merge"

# The job array: 4 shards, two at a time, one core each; the merge job merges after them.
"$RTLAB" sweep submit "$small" --slurm -o "$tmp/slurm" --shards 4 --max-parallel 2 \
    --cpus-per-task 1 >"$tmp/submit.out" || { cat "$tmp/submit.out"; fail "sweep submit"; }
grep -q -- "--array=0-3%2" "$tmp/slurm/slurm/array.sbatch" || fail "array script has no --array=0-3%2"
wait_jobs "$(jobs_of "$tmp/slurm")"
[[ -f $tmp/slurm/merged.json ]] || { cat "$tmp"/slurm/slurm/*.out; fail "the merge job wrote no merged.json"; }
python3 "$here/sweep_compare.py" "$tmp/local/merged.json" "$tmp/slurm/merged.json" --failed 6 \
    --total 30 || fail "local and Slurm tables disagree"
grep -q '"slurm_job":"[0-9]' "$tmp"/slurm/results/shard-0000.jsonl || fail "no Slurm job in provenance"
if python3 -c "import matplotlib" 2>/dev/null; then
    [[ -s $tmp/slurm/report.md ]] || { cat "$tmp/slurm/slurm/merge.out"; fail "the merge job built no report"; }
fi

# scancel of one running array task: the merge job reports the missing cases; re-submitting
# finishes the sweep and keeps the cases done before.
sed 's/"count": 400/"count": 20000/; s/"repeat": 1/"repeat": 2/' "$small" >"$tmp/big.json"
"$RTLAB" sweep submit "$tmp/big.json" --slurm -o "$tmp/s2" --shards 4 --max-parallel 1 \
    --cpus-per-task 1 >/dev/null || fail "submit big"
array=$(jobs_of "$tmp/s2")
array=${array%%,*}
for _ in $(seq 1 600); do
    [[ -s $tmp/s2/results/shard-0000.jsonl ]] && break
    sleep 0.1
done
scancel "${array}_0"
wait_jobs "$(jobs_of "$tmp/s2")"
n0=$(wc -l <"$tmp/s2/results/shard-0000.jsonl")
planned0=$(python3 -c 'import json,sys; print(sum(1 for c in json.load(open(sys.argv[1]))["cases"] if c["shard"] == 0))' \
    <("$RTLAB" sweep plan "$tmp/big.json" --shards 4 --json))
if [[ $n0 -ge $planned0 ]]; then
    echo "sweep_slurm: note: task 0 finished before scancel; the cancel path was not exercised"
else
    grep -q "cases missing" "$tmp/s2/slurm/merge.out" || { cat "$tmp/s2/slurm/merge.out"; fail "merge job did not report missing cases"; }
fi
done_cases() {  # done_cases DIR: "id end_unix" of every done case (failed ones run again)
    python3 - "$1" <<'PY'
import glob, json, sys
for f in sorted(glob.glob(sys.argv[1] + "/results/*.jsonl")):
    for line in open(f):
        j = json.loads(line)
        if j["status"] == "done":
            print(j["case"], repr(j["provenance"]["end_unix"]))
PY
}
done_cases "$tmp/s2" >"$tmp/before"
"$RTLAB" sweep submit "$tmp/big.json" --slurm -o "$tmp/s2" --max-parallel 2 --cpus-per-task 1 \
    >"$tmp/resubmit.out" || fail "re-submit"
wait_jobs "$(jobs_of "$tmp/s2")"
"$RTLAB" sweep status "$tmp/s2" | grep -q "30 cases: 24 done, 6 failed, 0 missing" ||
    { "$RTLAB" sweep status "$tmp/s2"; fail "re-submitted sweep incomplete"; }
done_cases "$tmp/s2" >"$tmp/after"
[[ -z $(comm -23 <(sort "$tmp/before") <(sort "$tmp/after")) ]] ||
    fail "cases done before scancel were redone: $(comm -23 <(sort "$tmp/before") <(sort "$tmp/after") | head -n 3)"
echo "sweep_slurm: job array agrees with the local run; scancel + re-submit OK ($(wc -l <"$tmp/before") results kept; $(cat "$tmp/resubmit.out" | head -n 1))"
