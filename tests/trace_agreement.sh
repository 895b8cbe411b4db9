#!/usr/bin/env bash
# Every registered structure gives the same hit file as brute force through `rtlab trace`, on a
# tessellated sphere flake and on a random triangle soup, for closest-hit and any-hit rays, and
# hit files do not depend on the thread count.
# Run by CTest with RTLAB set to the executable.
set -euo pipefail
: "${RTLAB:?set RTLAB to the rtlab executable}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

accels=$("$RTLAB" list --names)
[[ -n $accels ]] || { echo "no structures listed"; exit 1; }

"$RTLAB" gen flake --size 1 --as mesh --tess uv:16x8 -o "$tmp/flake.ply" 2>/dev/null
"$RTLAB" gen soup --size 1 --seed 7 -o "$tmp/soup.ply" 2>/dev/null
for scene in flake.ply soup.ply; do
    for kind in primary shadow random; do
        "$RTLAB" rays --scene "$tmp/$scene" --kind $kind --count 3000 --seed 3 \
            -o "$tmp/$scene.$kind.rays" 2>/dev/null
        anyhit=()
        [[ $kind == shadow ]] && anyhit=(--any-hit)
        "$RTLAB" trace --repeat 1 --no-warmup --scene "$tmp/$scene" --rays "$tmp/$scene.$kind.rays" --accel brute \
            "${anyhit[@]}" --hits "$tmp/ref.hits" >/dev/null
        for accel in $accels; do
            "$RTLAB" trace --repeat 1 --no-warmup --scene "$tmp/$scene" --rays "$tmp/$scene.$kind.rays" \
                --accel "$accel" "${anyhit[@]}" --hits "$tmp/x.hits" >"$tmp/trace.json"
            if ! "$RTLAB" compare "$tmp/ref.hits" "$tmp/x.hits" "${anyhit[@]}" >"$tmp/cmp.json"; then
                echo "FAIL: $accel on $scene ($kind): $(cat "$tmp/cmp.json")"
                fail=1
            fi
        done
    done
done
# Results do not depend on the thread count: byte-identical hit files with 1 and 2 threads.
for accel in bvh:binned kdtree:sah grid:uniform; do
    for threads in 1 2; do
        "$RTLAB" trace --repeat 1 --no-warmup --scene "$tmp/flake.ply" --rays "$tmp/flake.ply.random.rays" --accel "$accel" \
            --threads $threads --hits "$tmp/t$threads.hits" >/dev/null
    done
    cmp -s "$tmp/t1.hits" "$tmp/t2.hits" || { echo "FAIL: $accel hits differ between 1 and 2 threads"; fail=1; }
done

[[ $fail -eq 0 ]] && echo "trace agreement: every structure matches brute force"
exit $fail
