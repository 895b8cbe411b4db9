# Options that would silently do nothing are errors, and misleading messages stay fixed. Sourced by
# tests/cli_test.sh.
noop=$tmp/noop
mkdir -p "$noop"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$noop/tri.obj"
echo '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]}' >"$noop/sphere.json"
expect_ok "noop: rays" rays --scene "$noop/sphere.json" --count 16 -o "$noop/s.rays"
expect_ok "noop: tri rays" rays --scene "$noop/tri.obj" --count 16 -o "$noop/t.rays"

expect_error "noop: watertight on a scene without triangles" trace --scene "$noop/sphere.json" \
    --rays "$noop/s.rays" --method watertight
grep -q "no triangle primitives" "$tmp/err" || { echo "FAIL (noop watertight): $(cat "$tmp/err")"; fail=1; }
expect_error "noop: two methods of one family" trace --scene "$noop/tri.obj" \
    --rays "$noop/t.rays" --method watertight,badouel
grep -q "two methods of the triangle family" "$tmp/err" ||
    { echo "FAIL (noop two methods): $(cat "$tmp/err")"; fail=1; }
# A list naming one method per family for many scenes: one line says what is used.
expect_ok "noop: list with an absent family" trace --scene "$noop/tri.obj" --rays "$noop/t.rays" \
    --method watertight,geometric
[[ $(wc -l <"$tmp/err") -eq 1 ]] && grep -q "ignored.*using triangle=watertight" "$tmp/err" ||
    { echo "FAIL (noop list): stderr:"; cat "$tmp/err"; fail=1; }
# Exact mode certifies triangles with one test: other primitives and --method are refused.
expect_error "exact: a scene of spheres" trace --scene "$noop/sphere.json" --rays "$noop/s.rays" \
    --exact
grep -q "certifies triangle hits only" "$tmp/err" ||
    { echo "FAIL (exact spheres): $(cat "$tmp/err")"; fail=1; }
expect_error "exact: with --method" trace --scene "$noop/tri.obj" --rays "$noop/t.rays" --exact \
    --method watertight
expect_ok "exact: triangles" trace --scene "$noop/tri.obj" --rays "$noop/t.rays" --exact --stats
grep -q '"method":"exact"' "$tmp/out" && grep -q '"exact_fallbacks"' "$tmp/out" ||
    { echo "FAIL (exact row): $(cat "$tmp/out")"; fail=1; }
expect_error "noop: render --epsilon without --offset epsilon" render "$noop/sphere.json" \
    -o "$noop/x.png" --width 4 --height 4 --epsilon 0.01
expect_error "noop: gen --tess without --as mesh" gen flake --size 1 --tess uv:8x4 -o "$noop/g.json"
expect_ok "noop: gen --tess with --as mesh" gen flake --size 1 --tess uv:8x4 --as mesh -o "$noop/g.json"

# Messages that used to mislead.
expect_error "unknown command with a suggestion" trcae
grep -q "unknown command 'trcae'; did you mean 'trace'?" "$tmp/err" ||
    { echo "FAIL (did you mean): $(cat "$tmp/err")"; fail=1; }
expect_error "unknown command without a suggestion" frobnicate --help
grep -q "unknown command 'frobnicate'" "$tmp/err" || { echo "FAIL (unknown command): $(cat "$tmp/err")"; fail=1; }
# Every `rtlab WORD` a help text mentions is a command.
commands=$("$RTLAB" --help | sed -n '/^SUBCOMMANDS:/,$p' | awk 'NR>1 && NF {print $1}')
for sub in $commands; do
    for word in $("$RTLAB" "$sub" --help | grep -o 'rtlab [a-z]*' | awk '{print $2}' | sort -u); do
        grep -qx "$word" <<<"$commands" ||
            { echo "FAIL (help of $sub): mentions 'rtlab $word', which is no command"; fail=1; }
    done
done
"$RTLAB" stability --help | grep -q "prints the markdown report on stdout" ||
    { echo "FAIL (stability help): does not say where the report goes"; fail=1; }

# Memory: sizes whose estimate is over the limit are refused before any work.
expect_error "memory: rays" rays --scene "$noop/sphere.json" --count 100000000 --max-memory 64 \
    -o "$noop/big.rays"
grep -q "needs about" "$tmp/err" || { echo "FAIL (memory rays): $(cat "$tmp/err")"; fail=1; }
expect_error "memory: render" render "$noop/sphere.json" -o "$noop/big.png" --width 16384 \
    --height 16384 --max-memory 1024
grep -q "needs about" "$tmp/err" || { echo "FAIL (memory render): $(cat "$tmp/err")"; fail=1; }
expect_error "memory: crosscheck" crosscheck --prim sphere --rays 100000000 --max-memory 64
grep -q "needs about" "$tmp/err" || { echo "FAIL (memory crosscheck): $(cat "$tmp/err")"; fail=1; }
expect_error "memory: stability" stability --rays 100000000 --max-memory 64
grep -q "needs about" "$tmp/err" || { echo "FAIL (memory stability): $(cat "$tmp/err")"; fail=1; }

# Values finite in the scene but not after float arithmetic: no NaN/Inf pixel is written.
echo '{"lights": [{"type": "point", "position": [0, 0, 5], "color": [3e38, 3e38, 3e38]}],
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}],
 "materials": {"default": {"color": [3e38, 3e38, 3e38]}}}' >"$noop/hot.json"
"$RTLAB" render "$noop/hot.json" -o "$noop/hot.exr" --width 8 --height 8 \
    --stats-json "$noop/hot-stats.json" >"$tmp/out" 2>"$tmp/err" ||
    { echo "FAIL (non-finite pixels): render failed: $(cat "$tmp/err")"; fail=1; }
grep -q "pixels were NaN or infinite" "$tmp/err" ||
    { echo "FAIL (non-finite pixels): not reported: $(cat "$tmp/err")"; fail=1; }
python3 - "$noop/hot-stats.json" <<'PY' || { echo "FAIL (non-finite pixels): stats"; fail=1; }
import json, sys
assert json.load(open(sys.argv[1]))["non_finite_pixels"] > 0
PY
