# rtlab info contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\n' >"$tmp/info.obj"
expect_ok "info obj" info "$tmp/info.obj"
grep -q "open" "$tmp/out" || { echo "FAIL (info obj): no 'open' in output"; fail=1; }
expect_ok "info obj json" info --json "$tmp/info.obj"
grep -q '"boundary_edges":5' "$tmp/out" || { echo "FAIL (info obj json): boundary_edges"; fail=1; }
printf '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1},\n' >"$tmp/info.json"
printf '  {"type": "mesh", "file": "info.obj"}]}\n' >>"$tmp/info.json"
expect_ok "info json scene" info "$tmp/info.json"
grep -q "sphere" "$tmp/out" || { echo "FAIL (info json scene): no sphere"; fail=1; }
expect_ok "info help" info --help
expect_error "info missing file" info "$tmp/does-not-exist.obj"
printf '\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR' >"$tmp/garbage.ply"
expect_error "info garbage ply" info "$tmp/garbage.ply"
printf 'hello, world\n' >"$tmp/garbage.obj"
expect_error "info garbage obj" info "$tmp/garbage.obj"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 9\nproperty float x\nproperty float y\nproperty float z\nend_header\n\x01\x02' >"$tmp/cut.ply"
expect_error "info truncated ply" info "$tmp/cut.ply"
printf '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}\n' >"$tmp/bad.json"
expect_error "info bad radius" info "$tmp/bad.json"
grep -q 'objects\[0\].radius: must be > 0' "$tmp/err" || { echo "FAIL (info bad radius): $(cat "$tmp/err")"; fail=1; }
expect_error "info unknown extension" info "$tmp/info.txt"
expect_error "info no file" info
