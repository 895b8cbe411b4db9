# rtlab render contracts (sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp).
expect_ok "render help" render --help
expect_ok "render gen scene" gen flake --size 1 -o "$tmp/r.json"
expect_ok "render png" render "$tmp/r.json" -o "$tmp/r.png" --width 16 --height 12
[[ -s $tmp/r.png ]] || { echo "FAIL (render png): $tmp/r.png missing"; fail=1; }
expect_ok "render exr heatmap" render "$tmp/r.json" -o "$tmp/r.exr" --width 8 --height 8 \
    --aov heatmap --accel kdtree:sah --stats-json "$tmp/r-stats.json"
[[ -s $tmp/r.exr ]] || { echo "FAIL (render exr): $tmp/r.exr missing"; fail=1; }
grep -q '"heatmap"' "$tmp/r-stats.json" 2>/dev/null ||
    { echo "FAIL (render stats json): no heatmap figures in $tmp/r-stats.json"; fail=1; }
expect_ok "render explain only" render "$tmp/r.json" --explain
grep -q "refraction *disabled" "$tmp/out" ||
    { echo "FAIL (render explain): refraction not reported disabled"; cat "$tmp/out"; fail=1; }
expect_ok "render mesh scene" gen flake --size 1 --as mesh -o "$tmp/rm.json"
expect_ok "render exact" render "$tmp/rm.json" -o "$tmp/exact.png" --width 8 --height 8 --exact \
    --stats-json "$tmp/exact.json"
grep -q '"triangle=exact"' "$tmp/exact.json" ||
    { echo "FAIL (render exact): sets not triangle=exact"; fail=1; }
expect_error "render exact spheres" render "$tmp/r.json" -o "$tmp/x.png" --width 8 --height 8 --exact
expect_error "render exact heatmap" render "$tmp/rm.json" -o "$tmp/x.exr" --width 8 --height 8 \
    --exact --aov heatmap
expect_ok "render spd" render "$tmp/r.json" -o "$tmp/spd.png" --spd --width 8 --height 8
mkdir -p "$tmp/blocker"
echo "not a directory" >"$tmp/plainfile"
expect_error "render bad extension" render "$tmp/r.json" -o "$tmp/bad1.jpg" --width 8 --height 8
expect_error "render missing dir" render "$tmp/r.json" -o "$tmp/nodir/bad2.png" --width 8 --height 8
expect_error "render parent is a file" render "$tmp/r.json" -o "$tmp/plainfile/bad3.png" \
    --width 8 --height 8
expect_error "render target is a directory" render "$tmp/r.json" -o "$tmp/blocker" --width 8
expect_error "render no output" render "$tmp/r.json"
expect_error "render unknown accel" render "$tmp/r.json" -o "$tmp/bad4.png" --accel octree
expect_error "render unknown method" render "$tmp/r.json" -o "$tmp/bad5.png" --method nope
expect_error "render bad aov" render "$tmp/r.json" -o "$tmp/bad6.png" --aov albedo
expect_error "render bad fresnel" render "$tmp/r.json" -o "$tmp/bad7.png" --fresnel fast
expect_error "render bad offset" render "$tmp/r.json" -o "$tmp/bad8.png" --offset big
expect_error "render zero spp" render "$tmp/r.json" -o "$tmp/bad9.png" --spp 0
expect_error "render missing scene" render "$tmp/none.json" -o "$tmp/bad10.png"
for f in bad1.jpg nodir/bad2.png bad4.png bad5.png bad6.png bad7.png bad8.png bad9.png bad10.png; do
    [[ -e $tmp/$f ]] && { echo "FAIL (render error cases): $tmp/$f was written"; fail=1; }
done
ls "$tmp"/*.tmp-rtlab >/dev/null 2>&1 && { echo "FAIL (render): temporary files left"; fail=1; }
