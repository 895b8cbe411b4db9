# rtlab gen contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
expect_ok "gen list" gen --list
expect_ok "gen help" gen --help
expect_ok "gen flake json" gen flake --size 2 -o "$tmp/f.json"
[[ -s $tmp/f.json ]] || { echo "FAIL (gen flake json): $tmp/f.json missing"; fail=1; }
expect_ok "gen flake mesh" gen flake --size 2 --as mesh --tess uv:16x8 -o "$tmp/f.ply"
[[ -s $tmp/f.ply ]] || { echo "FAIL (gen flake mesh): $tmp/f.ply missing"; fail=1; }
expect_ok "gen mesh scene" gen terrain --size 3 -o "$tmp/t.json"
ls "$tmp"/t.mesh*.ply >/dev/null 2>&1 || { echo "FAIL (gen mesh scene): no mesh beside t.json"; fail=1; }
expect_ok "gen cube tess obj" gen nested --size 0 --tess cube:3 -o "$tmp/n.obj"
expect_error "gen size too big" gen flake --size 13 -o "$tmp/bad1.json"
expect_error "gen negative size" gen flake --size -1 -o "$tmp/bad2.json"
expect_error "gen memory guard" gen flake --size 12 -o "$tmp/bad3.json"
expect_error "gen bad tess" gen flake --size 1 --as mesh --tess uv:2x1 -o "$tmp/bad4.ply"
expect_error "gen garbled tess" gen flake --tess cube:lots -o "$tmp/bad5.json"
expect_error "gen unknown generator" gen frobnicate -o "$tmp/bad6.json"
expect_error "gen no output" gen flake
expect_error "gen bad extension" gen flake -o "$tmp/bad7.txt"
expect_error "gen bad --as" gen flake --as blobs -o "$tmp/bad8.json"
# NFF out and in: the SPD databases as the SPD writes them, read back by every scene command.
expect_ok "gen nff" gen tetra --size 2 -o "$tmp/t.nff"
head -1 "$tmp/t.nff" | grep -q '^b 0.078 0.361 0.753$' || { echo "FAIL (gen nff): bad first line"; fail=1; }
expect_ok "gen nff of a generic scene" gen nested --size 0 -o "$tmp/n.nff"
expect_ok "info nff" info "$tmp/t.nff"
expect_ok "render nff" render "$tmp/t.nff" --width 16 --height 16 -o "$tmp/t.png"
printf 'b 0 0 0\nv\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\nresolution 8 8\ns 0 0 zero 1\n' >"$tmp/bad.nff"
expect_error "bad nff" info "$tmp/bad.nff"
grep -q "bad.nff:9:" "$tmp/err" || { echo "FAIL (bad nff): error does not name file:line: $(cat "$tmp/err")"; fail=1; }
for f in bad1.json bad2.json bad3.json bad4.ply bad5.json bad6.json bad7.txt bad8.json; do
    [[ -e $tmp/$f ]] && { echo "FAIL (gen error cases): $tmp/$f was written"; fail=1; }
done
