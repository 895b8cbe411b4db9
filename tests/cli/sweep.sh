# rtlab sweep contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
sweeps=$(cd "$(dirname "${BASH_SOURCE[0]}")/../sweeps" && pwd)
expect_ok "sweep help" sweep --help
expect_ok "sweep plan" sweep plan "$sweeps/small.json"
cp "$tmp/out" "$tmp/plan1"
expect_ok "sweep plan again" sweep plan "$sweeps/small.json"
cmp -s "$tmp/plan1" "$tmp/out" || { echo "FAIL (sweep plan): two plans of one file differ"; fail=1; }
grep -q "30 cases" "$tmp/plan1" || { echo "FAIL (sweep plan): not 30 cases"; fail=1; }
expect_ok "sweep plan shards" sweep plan "$sweeps/small.json" --shards 5 --json
# Validation errors name the file and the place, before anything runs or is written.
bad() {  # bad NAME SED-EXPRESSION: a broken copy of small.json must fail plan, run and submit
    sed "$2" "$sweeps/small.json" >"$tmp/$1.json"
    expect_error "sweep plan $1" sweep plan "$tmp/$1.json"
    expect_error "sweep run $1" sweep run "$tmp/$1.json" -o "$tmp/$1.dir"
    expect_error "sweep submit $1" sweep submit "$tmp/$1.json" --slurm --dry-run -o "$tmp/$1.dir"
    [[ -e $tmp/$1.dir ]] && { echo "FAIL (sweep $1): $tmp/$1.dir was created"; fail=1; }
    grep -q "$tmp/$1.json: " "$tmp/err" || { echo "FAIL (sweep $1): error does not name the file: $(cat "$tmp/err")"; fail=1; }
}
bad unknown-generator 's/"generator": "terrain"/"generator": "frobnicate"/'
bad unknown-key 's/"max_leaf"/"max_leafs"/'
bad out-of-range 's/\[1, 4\]/[1, 0]/'
bad unknown-method 's/"segura_feito"/"segura"/'
bad unknown-kind 's/"shadow"/"umbra"/'
bad unknown-field 's/"repeat"/"repeats"/'
bad not-json 's/"name": "small",/"name": "small"/'
bad render-scene 's/"scenes": \["terrain3"\]/"scenes": ["terrain9"]/'
bad render-aov 's/"color", "depth"\]/"color", "albedo"]/'
bad render-key 's/"width": 32/"widht": 32/'
bad crosscheck-prim 's/"prim": "sphere"/"prim": "torus"/'
bad crosscheck-method 's/"geometric", "stable"\]/"geometric", "stabel"]/'
# A case whose methods its scene would not use is refused as `rtlab trace --method` is: a sphere
# method on the triangle-only scene (trace: nothing used, an error), two methods of one family.
bad method-unused 's/"segura_feito"/"geometric"/'
grep -qxF "rtlab: $tmp/method-unused.json: scenes[0] x methods[1]: method 'geometric' matches no primitive of scene 'flake1-mesh' (triangle)" "$tmp/err" ||
    { echo "FAIL (sweep method-unused): $(cat "$tmp/err")"; fail=1; }
bad method-twice 's/"segura_feito"/"segura_feito,watertight"/'
grep -q "methods\[1\]: 'segura_feito,watertight' names two methods of the triangle family" "$tmp/err" ||
    { echo "FAIL (sweep method-twice): $(cat "$tmp/err")"; fail=1; }
expect_error "sweep status of no sweep" sweep status "$tmp"
expect_error "sweep merge of no sweep" sweep merge "$tmp"
expect_error "sweep submit without --slurm" sweep submit "$sweeps/small.json" --dry-run
expect_ok "sweep submit dry run" sweep submit "$sweeps/small.json" --slurm --dry-run \
    --max-parallel 2 -o "$tmp/dry"
grep -q -- "--array=0-2%2" "$tmp/out" || { echo "FAIL (sweep submit dry run): no --array=0-2%2"; fail=1; }
grep -q -- "afterany" "$tmp/out" || { echo "FAIL (sweep submit dry run): no afterany"; fail=1; }
[[ -e $tmp/dry ]] && { echo "FAIL (sweep submit dry run): wrote $tmp/dry"; fail=1; }
