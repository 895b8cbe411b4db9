# rtlab stability contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB,
# $tmp). The watertightness check: `rtlab trace --method watertight --robust` loses no
# ray from inside a closed perturbed sphere, with every structure.
expect_ok "stability help" stability --help
expect_ok "stability list" stability --list
grep -q '^watertight ' "$tmp/out" || { echo "FAIL (stability list): no watertight case"; fail=1; }
expect_error "stability unknown case" stability --case nope
expect_error "stability zero rays" stability --rays 0
expect_ok "stability fixture" stability --fixture "$tmp/wt" --rays 3000 --seed 3
if [[ -s $tmp/wt/sphere.ply && -s $tmp/wt/inside.rays ]]; then
    accels=$("$RTLAB" list --names)
    [[ -n $accels ]] || { echo "FAIL (stability leaks): rtlab list named no structure"; fail=1; }
    for accel in $accels; do
        if "$RTLAB" trace --repeat 1 --no-warmup --scene "$tmp/wt/sphere.ply" --rays "$tmp/wt/inside.rays" \
            --accel "$accel" --method watertight --robust >"$tmp/trace.json" 2>"$tmp/err"; then
            hits=$(grep -o '"hits":[0-9]*' "$tmp/trace.json" | cut -d: -f2)
            [[ $hits == 3000 ]] ||
                { echo "FAIL (stability leaks): $accel: $hits of 3000 inside rays hit"; fail=1; }
        else
            echo "FAIL (stability leaks): rtlab trace --accel $accel failed: $(head -c 300 "$tmp/err")"
            fail=1
        fi
    done
else
    echo "FAIL (stability fixture): $tmp/wt/sphere.ply or inside.rays missing"; fail=1
fi
expect_ok "stability report files" stability --case degenerate --rays 100 \
    --markdown "$tmp/stab.md" --json "$tmp/stab.json"
grep -q '^## degenerate' "$tmp/stab.md" 2>/dev/null ||
    { echo "FAIL (stability report files): no degenerate section in $tmp/stab.md"; fail=1; }
grep -q '"cases":\[' "$tmp/stab.json" 2>/dev/null ||
    { echo "FAIL (stability report files): $tmp/stab.json has no cases"; fail=1; }
