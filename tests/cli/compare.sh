# rtlab compare contracts (sourced by tests/cli_test.sh: uses expect_ok, $RTLAB, $tmp, fail).
# Hit records: float t, uint32 prim (0xFFFFFFFF = miss), float u, v.
write_hits() {  # write_hits FILE "t prim" ...
    python3 - "$@" <<'PY'
import struct, sys
with open(sys.argv[1], "wb") as f:
    for rec in sys.argv[2:]:
        t, prim = rec.split()
        f.write(struct.pack("<fIff", float(t), int(prim), 0.0, 0.0))
PY
}
write_hits "$tmp/cmp-a.hits" "1.5 3" "inf 4294967295" "2.0 7"
write_hits "$tmp/cmp-b.hits" "1.5 3" "inf 4294967295" "2.0 7"
write_hits "$tmp/cmp-nan.hits" "1.5 3" "inf 4294967295" "nan 7"
expect_ok "compare equal hits" compare "$tmp/cmp-a.hits" "$tmp/cmp-b.hits"
grep -q '"agree":true' "$tmp/out" || { echo "FAIL (compare equal): $(cat "$tmp/out")"; fail=1; }
# A NaN t is a disagreement in either order, never agreement.
for order in "$tmp/cmp-a.hits $tmp/cmp-nan.hits" "$tmp/cmp-nan.hits $tmp/cmp-a.hits"; do
    # shellcheck disable=SC2086
    "$RTLAB" compare $order >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [[ $rc -ne 1 ]] || ! grep -q '"agree":false' "$tmp/out" ||
        ! grep -q '"nan_t":1' "$tmp/out"; then
        echo "FAIL (compare NaN t, $order): exit $rc, $(cat "$tmp/out" "$tmp/err")"; fail=1
    fi
done
