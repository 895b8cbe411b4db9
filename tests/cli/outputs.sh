# Output files are never clobbered when they are not ours, and interrupts leave nothing behind.
# Sourced by tests/cli_test.sh: uses expect_ok, expect_error, $RTLAB, $tmp, fail.
out_dir=$tmp/outputs
mkdir -p "$out_dir"
expect_ok "outputs: scene" gen flake --size 1 -o "$out_dir/s.json"

# -o a FIFO: the data goes into it and it stays a FIFO.
mkfifo "$out_dir/fifo"
timeout 120 cat "$out_dir/fifo" >"$out_dir/fifo.received" &
reader=$!
expect_ok "outputs: rays into a FIFO" rays --scene "$out_dir/s.json" --count 100 -o "$out_dir/fifo"
wait $reader
[[ -p $out_dir/fifo ]] || { echo "FAIL (outputs fifo): $out_dir/fifo is no longer a FIFO"; fail=1; }
[[ $(stat -c %s "$out_dir/fifo.received") -eq 3200 ]] ||
    { echo "FAIL (outputs fifo): reader got $(stat -c %s "$out_dir/fifo.received") bytes, not 3200"; fail=1; }

# Only new files and rtlab's own outputs are replaced (rtlab runs as root on shared machines).
# Its own: a second run over the first's output replaces it, and every output carries the mark.
mkdir -p "$out_dir/real"
expect_ok "outputs: rays" rays --scene "$out_dir/s.json" --count 10 -o "$out_dir/real/target.rays"
chmod 600 "$out_dir/real/target.rays"
expect_ok "outputs: rays over rtlab's own output" rays --scene "$out_dir/s.json" --count 20 \
    -o "$out_dir/real/target.rays"
[[ $(stat -c %s:%a "$out_dir/real/target.rays") == 640:600 ]] ||
    { echo "FAIL (outputs own): not replaced, or mode lost: $(stat -c %s:%a "$out_dir/real/target.rays")"; fail=1; }
python3 -c 'import os, sys; os.getxattr(sys.argv[1], "user.rtlab.output")' "$out_dir/real/target.rays" ||
    { echo "FAIL (outputs own): no user.rtlab.output mark"; fail=1; }
# A regular file rtlab did not write is refused and left as it was.
echo notes >"$out_dir/real/notes.rays"
expect_error "outputs: rays over a file that is not rtlab's" rays --scene "$out_dir/s.json" \
    --count 10 -o "$out_dir/real/notes.rays"
grep -q "notes.rays: exists and was not written by rtlab" "$tmp/err" ||
    { echo "FAIL (outputs foreign): $(cat "$tmp/err")"; fail=1; }
[[ $(cat "$out_dir/real/notes.rays") == notes ]] || { echo "FAIL (outputs foreign): file changed"; fail=1; }
# A symbolic link to a regular file (even rtlab's own) or to nothing is refused: link and
# target stay as they were, nothing is created.
ln -s real/target.rays "$out_dir/link.rays"
expect_error "outputs: rays through a symlink" rays --scene "$out_dir/s.json" --count 10 \
    -o "$out_dir/link.rays"
grep -q "link.rays: is a symbolic link" "$tmp/err" || { echo "FAIL (outputs symlink): $(cat "$tmp/err")"; fail=1; }
[[ -L $out_dir/link.rays && $(stat -c %s "$out_dir/real/target.rays") -eq 640 ]] ||
    { echo "FAIL (outputs symlink): link or target changed"; fail=1; }
ln -s real/new.hits "$out_dir/dangling.hits"
expect_error "outputs: trace --hits through a dangling symlink" trace --scene "$out_dir/s.json" \
    --rays "$out_dir/real/target.rays" --hits "$out_dir/dangling.hits"
[[ -L $out_dir/dangling.hits && ! -e $out_dir/real/new.hits ]] ||
    { echo "FAIL (outputs dangling symlink): link or new target wrong"; fail=1; }
# A link to a device is written into (nothing is replaced).
ln -s /dev/null "$out_dir/null.hits"
expect_ok "outputs: trace --hits through a link to /dev/null" trace --scene "$out_dir/s.json" \
    --rays "$out_dir/real/target.rays" --hits "$out_dir/null.hits"
[[ -L $out_dir/null.hits ]] || { echo "FAIL (outputs link to device): link replaced"; fail=1; }

# Character devices are written into, never replaced (CI runs as root, where a rename would
# succeed and turn /dev/null into a regular file).
expect_ok "outputs: rays -o /dev/null" rays --scene "$out_dir/s.json" --count 10 -o /dev/null
expect_ok "outputs: trace --hits /dev/null" trace --scene "$out_dir/s.json" \
    --rays "$out_dir/real/target.rays" --hits /dev/null
expect_ok "outputs: render --stats-json /dev/null" render "$out_dir/s.json" -o "$out_dir/r.png" \
    --width 8 --height 8 --stats-json /dev/null
[[ -c /dev/null ]] || { echo "FAIL (outputs /dev/null): /dev/null is no longer a character device"; fail=1; }

# Unwritable outputs fail before the work (the folder does not exist), naming the output.
expect_error "outputs: stats-json folder missing" render "$out_dir/s.json" -o "$out_dir/r2.png" \
    --width 8 --height 8 --stats-json "$out_dir/none/stats.json"
grep -q "none/stats.json" "$tmp/err" || { echo "FAIL (outputs early check): $(cat "$tmp/err")"; fail=1; }
[[ ! -e $out_dir/r2.png ]] || { echo "FAIL (outputs early check): image written"; fail=1; }
expect_error "outputs: stability --markdown folder missing" stability --case grazing --rays 10 \
    --markdown "$out_dir/none/s.md"
grep -q "rtlab stability: \[" "$tmp/err" && { echo "FAIL (outputs early check): stability ran"; fail=1; }
expect_error "outputs: stability --json is a folder" stability --case grazing --rays 10 \
    --json "$out_dir"
expect_error "outputs: rays -o folder missing" rays --scene "$out_dir/s.json" -o "$out_dir/none/x.rays"
expect_error "outputs: trace --hits folder missing" trace --scene "$out_dir/s.json" \
    --rays "$out_dir/real/target.rays" --hits "$out_dir/none/x.hits"
expect_error "outputs: gen -o folder missing" gen flake --size 1 -o "$out_dir/none/x.json"
leftovers=$(find "$out_dir" -name '*rtlab-tmp*')
[[ -z $leftovers ]] || { echo "FAIL (outputs): temporaries left: $leftovers"; fail=1; }

# SIGINT / SIGTERM: exit 130 / 143, one line on stderr, no file left in the output folder.
# interrupt_run SIGNAL EXPECTED_RC WAIT_FOR_TEMP ARGS...: starts rtlab ARGS with its output in an
# empty folder; with WAIT_FOR_TEMP=1 signals it once the temporary output exists (the write
# phase), else after 1 s (the work phase).
interrupt_run() {
    local sig=$1 want=$2 wait_tmp=$3; shift 3
    local dir=$tmp/interrupt
    rm -rf "$dir"; mkdir -p "$dir"
    "$RTLAB" "$@" >"$tmp/int.out" 2>"$tmp/int.err" &
    local pid=$! seen=0
    # Background jobs start with SIGINT ignored; wait until rtlab has installed its handler.
    for _ in $(seq 1 600); do
        local caught
        caught=$(awk '/^SigCgt:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
        [[ -n $caught && $(( 0x$caught & 2 )) -ne 0 ]] && break
        sleep 0.05
    done
    for _ in $(seq 1 3000); do
        if [[ $wait_tmp -eq 1 ]]; then
            [[ -n $(ls -A "$dir") ]] && { seen=1; break; }
            sleep 0.02
        else
            sleep 1; seen=1; break
        fi
        kill -0 $pid 2>/dev/null || break
    done
    kill -s "$sig" $pid 2>/dev/null
    wait $pid
    local rc=$?
    if [[ $seen -eq 0 || $rc -eq 0 ]]; then
        echo "FAIL (interrupt $sig $*): finished (rc $rc) before it could be interrupted"; fail=1
    elif [[ $rc -ne $want ]]; then
        echo "FAIL (interrupt $sig $*): exit $rc, expected $want"; cat "$tmp/int.err"; fail=1
    elif [[ -n $(ls -A "$dir") ]]; then
        echo "FAIL (interrupt $sig $*): left $(ls -A "$dir")"; fail=1
    elif [[ $(grep -c . "$tmp/int.err") -ne 1 ]] || ! grep -q "interrupted by SIGINT\|terminated by SIGTERM" "$tmp/int.err"; then
        echo "FAIL (interrupt $sig $*): stderr is not one interrupt line:"; cat "$tmp/int.err"; fail=1
    fi
}
# A large ray file, interrupted while its temporary grows.
interrupt_run INT 130 1 rays --scene "$out_dir/s.json" --kind random --count 4000000 \
    -o "$tmp/interrupt/big.rays"
interrupt_run TERM 143 1 rays --scene "$out_dir/s.json" --kind random --count 4000000 \
    -o "$tmp/interrupt/big.rays"
# A large render, interrupted while rendering.
interrupt_run INT 130 0 render "$out_dir/s.json" --width 4096 --height 4096 --spp 16 \
    -o "$tmp/interrupt/big.png" --stats-json "$tmp/interrupt/big.json"
