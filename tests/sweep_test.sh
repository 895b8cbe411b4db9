#!/usr/bin/env bash
# rtlab sweep run end to end on tests/sweeps/small.json (2 scenes x 3 specs x 2 methods x 2 ray
# kinds): the run completes with the deliberately failing cases (segura_feito closest hit on
# triangles) recorded as failed and the rest done, each row naming the methods that ran; two runs' merged tables agree case for case
# (all but timings and provenance); a run interrupted with SIGINT leaves only complete shard files
# and a second run finishes it without redoing finished cases. Run by CTest with RTLAB set.
set -uo pipefail
: "${RTLAB:?set RTLAB to the rtlab executable}"
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
small=$here/sweeps/small.json

# A full run: exit 1 (some cases failed), 24 done and 6 failed.
"$RTLAB" sweep run "$small" -o "$tmp/a" 2>"$tmp/a.err"
rc=$?
[[ $rc -eq 1 ]] || { cat "$tmp/a.err"; fail "sweep run exited $rc, expected 1 (failed cases)"; }
"$RTLAB" sweep status "$tmp/a" >"$tmp/a.status" || fail "sweep status"
grep -q "30 cases: 24 done, 6 failed, 0 missing" "$tmp/a.status" || { cat "$tmp/a.status"; fail "status"; }
"$RTLAB" sweep merge "$tmp/a" -o "$tmp/a/merged" >/dev/null || fail "sweep merge"
head -n 1 "$tmp/a/merged.csv" | grep -q "p_max_leaf" || fail "merged.csv has no p_max_leaf column"
[[ $(wc -l <"$tmp/a/merged.csv") -eq 31 ]] || fail "merged.csv is not 30 rows and a header"
# Every row says what ran: the listed method in its family's set, the defaults in the others.
python3 - "$tmp/a/merged.json" <<'PY' || fail "a row's sets do not match its methods"
import json, sys
for c in json.load(open(sys.argv[1]))["cases"]:
    if c["type"] == "crosscheck" or c["status"] != "done":
        continue
    sets = c["sets"].split()
    if c["methods"] == "segura_feito":
        assert "triangle=segura_feito" in sets, c
    if c["scene"] == "terrain3":
        assert sorted(s.split("=")[0] for s in sets) == ["sphere", "triangle"], c
PY

# The report: a table per scene and the max_leaf line plot.
if python3 -c "import matplotlib" 2>/dev/null; then
    python3 "$here/../bench/report.py" --sweep "$tmp/a/merged.json" --out "$tmp/a/report.md" \
        --plots "$tmp/a/plots" 2>/dev/null || fail "bench/report.py --sweep"
    [[ -s $tmp/a/plots/sweep-bvh_binned-max_leaf.png ]] || fail "no max_leaf plot"
    grep -q "^### terrain3" "$tmp/a/report.md" || fail "no terrain3 table in the report"
fi

# Re-running a finished sweep measures nothing again.
"$RTLAB" sweep run "$small" -o "$tmp/a" --jobs 2 2>"$tmp/a2.err"
grep -q "24 already done" "$tmp/a2.err" || { cat "$tmp/a2.err"; fail "re-run did not skip the done cases"; }

# A shard log that is a symbolic link (planted in the folder) is never written through: the run
# stops with a one-line error naming the log, and the link's target is unchanged.
mkdir -p "$tmp/linklog/logs"
echo precious >"$tmp/victim"
ln -s "$tmp/victim" "$tmp/linklog/logs/shard-0000.log"
"$RTLAB" sweep run "$small" -o "$tmp/linklog" 2>"$tmp/linklog.err" && fail "sweep run wrote through a log link"
grep -q "shard-0000.log (Too many levels of symbolic links)" "$tmp/linklog.err" ||
    { cat "$tmp/linklog.err"; fail "no one-line error naming the log link"; }
[[ $(cat "$tmp/victim") == precious ]] || fail "the log link's target was written"

# A second folder, two shards at a time and 4 shards: the same table but timings.
"$RTLAB" sweep run "$small" -o "$tmp/b" --jobs 2 --shards 4 2>/dev/null
"$RTLAB" sweep merge "$tmp/b" -o "$tmp/b/merged" >/dev/null || fail "merge b"
python3 "$here/sweep_compare.py" "$tmp/a/merged.json" "$tmp/b/merged.json" --failed 6 --total 30 ||
    fail "runs a and b disagree"

# Interrupt: more rays so the run is still going when SIGINT arrives.
sed 's/"count": 400/"count": 10000/; s/"repeat": 1/"repeat": 2/' "$small" >"$tmp/big.json"
"$RTLAB" sweep run "$tmp/big.json" -o "$tmp/c" --shards 4 2>"$tmp/c.err" &
pid=$!
for _ in $(seq 1 600); do
    n=$(cat "$tmp"/c/results/*.jsonl 2>/dev/null | wc -l)
    [[ $n -ge 2 ]] && break
    sleep 0.1
done
kill -INT "$pid"
wait "$pid"
rc=$?
n=$(cat "$tmp"/c/results/*.jsonl 2>/dev/null | wc -l)
[[ $rc -eq 130 ]] || { cat "$tmp/c.err"; fail "interrupted run exited $rc, expected 130 ($n results)"; }
[[ $n -lt 30 ]] || fail "the run finished before the interrupt; nothing tested"
# Every shard file is complete: every line parses (status would fail otherwise).
"$RTLAB" sweep status "$tmp/c" --json >"$tmp/c.status" || fail "status after the interrupt"
python3 - "$tmp/c" >"$tmp/c.before" <<'PY' || fail "reading shard files"
import glob, json, sys
for f in sorted(glob.glob(sys.argv[1] + "/results/*.jsonl")):
    for line in open(f):
        j = json.loads(line)
        if j["status"] == "done":
            print(j["case"], j["provenance"]["start"], j["provenance"]["end_unix"])
PY
"$RTLAB" sweep run "$tmp/big.json" -o "$tmp/c" 2>"$tmp/c2.err"
"$RTLAB" sweep merge "$tmp/c" -o "$tmp/c/merged" >/dev/null || fail "merge after resume"
# The cases done before the interrupt kept their results (same end time: not redone).
while read -r id start end; do
    grep -q "\"case\":\"$id\".*\"end_unix\":$end" "$tmp"/c/results/*.jsonl ||
        fail "case $id was redone after the interrupt"
done <"$tmp/c.before"
python3 - "$tmp/c/merged.json" <<'PY' || fail "resumed sweep incomplete"
import json, sys
t = json.load(open(sys.argv[1]))
bad = sum(1 for c in t["cases"] if c["status"] != "done")
assert not t["missing"] and len(t["cases"]) == 30 and bad == 6, (len(t["cases"]), bad, t["missing"])
PY
ls "$tmp"/c/results | grep -v '\.jsonl$' | grep -qv '\.tmp-rtlab$' && fail "stray files in results/"
echo "sweep: local runs, resume and interrupt OK ($(wc -l <"$tmp/c.before") cases kept over the interrupt)"
