# Sourced by cli_test.sh: structure specs on the command line. Parameters reach the builder
# (max_leaf=1 and max_leaf=8 give different nodes/ray and bytes/prim, both with brute force's hit
# file), the JSON names the canonical spec, and bad keys or values (or keys without effect) are
# one-line errors.
"$RTLAB" gen soup --size 1 --seed 5 -o "$tmp/spec_soup.ply" 2>/dev/null
"$RTLAB" rays --scene "$tmp/spec_soup.ply" --kind primary --count 2000 --seed 2 \
    -o "$tmp/spec.rays" 2>/dev/null
"$RTLAB" trace --repeat 1 --no-warmup --scene "$tmp/spec_soup.ply" --rays "$tmp/spec.rays" \
    --accel brute \
    --hits "$tmp/spec_ref.hits" >/dev/null
for leaf in 1 8; do
    expect_ok "spec max_leaf=$leaf" trace --repeat 1 --no-warmup --scene "$tmp/spec_soup.ply" \
        --rays "$tmp/spec.rays" --accel "bvh:binned,max_leaf=$leaf" --stats --hits "$tmp/spec_$leaf.hits"
    cp "$tmp/out" "$tmp/spec_$leaf.json"
    grep -q "\"accel\":\"bvh:binned,max_leaf=$leaf,bins=16,ct=4,ci=1,block=1,threads=0\"" "$tmp/spec_$leaf.json" ||
        { echo "FAIL (spec): JSON does not name the canonical spec: $(cat "$tmp/spec_$leaf.json")"; fail=1; }
    "$RTLAB" compare "$tmp/spec_ref.hits" "$tmp/spec_$leaf.hits" >/dev/null ||
        { echo "FAIL (spec): bvh:binned,max_leaf=$leaf differs from brute force"; fail=1; }
done
field() {  # field FILE KEY: a number from rtlab trace's one-line JSON
    sed -E "s/.*\"$2\":([0-9.eE+-]+).*/\1/" "$1"
}
for key in nodes_per_ray bytes_per_prim; do
    if [[ $(field "$tmp/spec_1.json" $key) == "$(field "$tmp/spec_8.json" $key)" ]]; then
        echo "FAIL (spec): max_leaf=1 and max_leaf=8 report the same $key"; fail=1
    fi
done
# --stats adds the one cost model's prediction and the measured cost, and EPO for BVHs only.
for key in cost_model measured_cost epo; do
    grep -q "\"$key\":[0-9]" "$tmp/spec_8.json" ||
        { echo "FAIL (stats): bvh:binned --stats lacks $key: $(cat "$tmp/spec_8.json")"; fail=1; }
done
expect_ok "stats grid:two_level" trace --repeat 1 --no-warmup --scene "$tmp/spec_soup.ply" \
    --rays "$tmp/spec.rays" --accel grid:two_level --stats --hits "$tmp/spec_g2.hits"
grep -q '"cost_model":[0-9]' "$tmp/out" && ! grep -q '"epo"' "$tmp/out" ||
    { echo "FAIL (stats): grid:two_level --stats: $(cat "$tmp/out")"; fail=1; }
"$RTLAB" compare "$tmp/spec_ref.hits" "$tmp/spec_g2.hits" >/dev/null ||
    { echo "FAIL (spec): grid:two_level differs from brute force"; fail=1; }
# Timing defaults: one untimed warm-up run, then the median of 5 timed runs.
expect_ok "trace timing defaults" trace --scene "$tmp/spec_soup.ply" --rays "$tmp/spec.rays" \
    --accel bvh:pair
grep -q '"repeat":5' "$tmp/out" && grep -q '"warmup":true' "$tmp/out" ||
    { echo "FAIL (trace): default timing is not warm-up + 5 repeats: $(cat "$tmp/out")"; fail=1; }
expect_error "spec unknown key" trace --scene "$tmp/spec_soup.ply" --rays "$tmp/spec.rays" \
    --accel 'bvh:binned,leaf=8'
grep -q "unknown parameter 'leaf'" "$tmp/err" || { echo "FAIL (spec): $(cat "$tmp/err")"; fail=1; }
expect_error "spec out of range" trace --scene "$tmp/spec_soup.ply" --rays "$tmp/spec.rays" \
    --accel 'bvh:binned,max_leaf=0'
grep -q "max_leaf=0 is outside" "$tmp/err" || { echo "FAIL (spec): $(cat "$tmp/err")"; fail=1; }
expect_error "spec unknown structure" render --accel 'bvh:nope' scenes/glass.json -o "$tmp/x.png"
expect_ok "list json" list --json
grep -q '"default_spec": "grid:uniform,density=4,max_res=512,threads=0"' "$tmp/out" ||
    { echo "FAIL (spec): rtlab list --json lacks the grid's default spec"; fail=1; }
# A key without effect for the other settings is refused; rtlab list says where each key applies.
expect_error "spec key without effect" trace --scene "$tmp/spec_soup.ply" --rays "$tmp/spec.rays" \
    --accel 'bvh8,from=lbvh,ct=1'
grep -q "'ct' has no effect with from=lbvh" "$tmp/err" || { echo "FAIL (spec): $(cat "$tmp/err")"; fail=1; }
expect_ok "list json needs" list --json
grep -q '"default_spec": "bvh8,from=pbinned,leaves=soa,leaf_align=4,' "$tmp/out" &&
    ! grep -q '"default_spec": "bvh8,.*morton_bits' "$tmp/out" &&
    grep -q '"build_only": true' "$tmp/out" && grep -q '"values": \[' "$tmp/out" ||
    { echo "FAIL (spec): rtlab list --json lacks the keys' dependencies"; fail=1; }
expect_ok "list text needs" list
grep -q 'morton_bits.*\[only with from=lbvh\]' "$tmp/out" ||
    { echo "FAIL (spec): rtlab list does not say where morton_bits applies"; fail=1; }
