# rtlab cone contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
expect_ok "crosscheck cone" crosscheck --prim cone --rays 160 --by-set
grep -q "^cone *quadric" "$tmp/out" || { echo "FAIL (crosscheck cone): no quadric row"; fail=1; }
expect_ok "crosscheck cone json" crosscheck --prim cone --method stable --rays 80 --json
expect_error "crosscheck cone unknown method" crosscheck --prim cone --method geometric --rays 10
cat >"$tmp/cones.json" <<'JSON'
{"camera": {"from": [0, 1, 6], "at": [0, 0.5, 0], "width": 24, "height": 16},
 "lights": [{"type": "point", "position": [3, 4, 5]}],
 "objects": [{"type": "cone", "base": [-1, 0, 0], "base_radius": 0.5, "apex": [-1, 1, 0],
              "apex_radius": 0, "caps": "base"},
             {"type": "cone", "base": [1, 0, 0], "apex": [1, 1, 0], "radius": 0.4}]}
JSON
expect_ok "render cones" render "$tmp/cones.json" -o "$tmp/cones.png"
expect_ok "render cones quadric" render "$tmp/cones.json" -o "$tmp/cones-q.png" --method quadric
expect_ok "info cones" info "$tmp/cones.json"
expect_ok "rays cones" rays --scene "$tmp/cones.json" --kind primary --count 500 -o "$tmp/c.rays"
expect_ok "trace cones" trace --scene "$tmp/cones.json" --rays "$tmp/c.rays" --method quadric \
    --accel kdtree:sah
grep -q 'quadric' "$tmp/out" || { echo "FAIL (trace cones): method not reported"; fail=1; }
sed 's/"radius": 0.4/"radius": -0.4/' "$tmp/cones.json" >"$tmp/badcone.json"
expect_error "render bad cone" render "$tmp/badcone.json" -o "$tmp/badcone.png"
grep -q "objects\[1\]" "$tmp/err" || { echo "FAIL (bad cone): path not named"; fail=1; }
[[ -e $tmp/badcone.png ]] && { echo "FAIL (bad cone): image written"; fail=1; }
