# Every file of tests/malformed/ (truncated, wrong magic, wrong and huge counts, bad UTF-8, deeply
# nested JSON, NaN/Inf/1e39 numbers, out-of-range indices, ...) through every command that reads
# it: exit 1 (bad input), exactly one line on stderr naming the file and the place and problem
# listed in tests/malformed/MANIFEST, and no output file left. Sourced by tests/cli_test.sh.
malformed=$(dirname "${BASH_SOURCE[0]}")/../malformed
bad_out=$tmp/malformed-out
mkdir -p "$bad_out"
expect_ok "malformed: good scene" gen flake --size 1 -o "$tmp/good.json"
expect_ok "malformed: good rays" rays --scene "$tmp/good.json" --count 16 -o "$tmp/good.rays"
expect_ok "malformed: good hits" trace --scene "$tmp/good.json" --rays "$tmp/good.rays" \
    --hits "$tmp/good.hits"

# check_rejected FILE PLACE ARGS...: rtlab ARGS must exit 1 with one stderr line naming FILE
# and containing PLACE, and leave $bad_out empty.
check_rejected() {
    local file=$1 place=$2; shift 2
    "$RTLAB" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    local what="malformed $(basename "$file"): rtlab $1"
    if [[ $rc -ne 1 ]]; then
        echo "FAIL ($what): exit $rc, expected 1"; cat "$tmp/err"; fail=1
    elif [[ $(wc -l <"$tmp/err") -ne 1 ]]; then
        echo "FAIL ($what): $(wc -l <"$tmp/err") lines on stderr:"; cat "$tmp/err"; fail=1
    elif ! grep -qF -- "$file" "$tmp/err" || ! grep -qF -- "$place" "$tmp/err"; then
        echo "FAIL ($what): message does not name the file and '$place':"; cat "$tmp/err"; fail=1
    fi
    if [[ -n $(ls -A "$bad_out") ]]; then
        echo "FAIL ($what): left $(ls -A "$bad_out")"; fail=1
        rm -rf "${bad_out:?}"/* "$bad_out"/.[!.]*
    fi
}

count=0
while IFS='|' read -r name place; do
    name=${name%% }; place=${place# }
    [[ -z $name || $name == \#* ]] && continue
    f=$malformed/$name
    [[ -f $f ]] || { echo "FAIL (malformed): $f listed in MANIFEST is missing"; fail=1; continue; }
    count=$((count + 1))
    case $name in
    *.rays)
        check_rejected "$f" "$place" trace --scene "$tmp/good.json" --rays "$f" \
            --hits "$bad_out/x.hits" ;;
    *.hits)
        check_rejected "$f" "$place" compare "$f" "$tmp/good.hits" ;;
    *)
        check_rejected "$f" "$place" rays --scene "$f" --count 8 -o "$bad_out/x.rays"
        check_rejected "$f" "$place" render "$f" -o "$bad_out/x.png" --width 4 --height 4 \
            --stats-json "$bad_out/x.json"
        check_rejected "$f" "$place" info "$f" ;;
    esac
done <"$malformed/MANIFEST"
[[ $count -ge 40 ]] || { echo "FAIL (malformed): only $count files in the MANIFEST"; fail=1; }
[[ $(ls "$malformed" | grep -vc MANIFEST) -eq $count ]] ||
    { echo "FAIL (malformed): files in tests/malformed/ not listed in MANIFEST"; fail=1; }

# A folder where a ray file is expected is named as a folder.
expect_error "trace --rays DIR" trace --scene "$tmp/good.json" --rays "$tmp"
grep -q "is a folder" "$tmp/err" || { echo "FAIL (trace --rays DIR): $(cat "$tmp/err")"; fail=1; }
