# rtlab gen contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
expect_ok "gen list" gen --list
expect_ok "gen help" gen --help
expect_ok "gen flake json" gen flake --size 2 -o "$tmp/f.json"
[[ -s $tmp/f.json ]] || { echo "FAIL (gen flake json): $tmp/f.json missing"; fail=1; }
expect_ok "gen flake mesh" gen flake --size 2 --as mesh --tess uv:16x8 -o "$tmp/f.ply"
[[ -s $tmp/f.ply ]] || { echo "FAIL (gen flake mesh): $tmp/f.ply missing"; fail=1; }
expect_ok "gen mesh scene" gen tetra --size 3 -o "$tmp/t.json"
ls "$tmp"/t.mesh*.ply >/dev/null 2>&1 || { echo "FAIL (gen mesh scene): no mesh beside t.json"; fail=1; }
expect_ok "gen cube tess obj" gen nested --size 0 --tess cube:3 -o "$tmp/n.obj"
expect_error "gen size too big" gen flake --size 13 -o "$tmp/bad1.json"
expect_error "gen negative size" gen flake --size -1 -o "$tmp/bad2.json"
expect_error "gen memory guard" gen flake --size 12 -o "$tmp/bad3.json"
expect_error "gen bad tess" gen flake --size 1 --as mesh --tess uv:2x1 -o "$tmp/bad4.ply"
expect_error "gen garbled tess" gen flake --tess cube:lots -o "$tmp/bad5.json"
expect_error "gen unknown generator" gen teapot -o "$tmp/bad6.json"
expect_error "gen no output" gen flake
expect_error "gen bad extension" gen flake -o "$tmp/bad7.txt"
expect_error "gen bad --as" gen flake --as blobs -o "$tmp/bad8.json"
for f in bad1.json bad2.json bad3.json bad4.ply bad5.json bad6.json bad7.txt bad8.json; do
    [[ -e $tmp/$f ]] && { echo "FAIL (gen error cases): $tmp/$f was written"; fail=1; }
done
