# The SPD's published image statistics for balls (SF 4; SPD 3.14 README, "Database Analysis": eye
# hit rays 263169, reflect rays 175095, shadow rays 954368) are reproduced by `rtlab render --spd`
# within 1% (measured: exact, +0.49%, +0.07%); the SPD says a classical ray tracer lands within
# about 10%. Sourced by tests/cli_test.sh (uses expect_ok, $RTLAB, $tmp, fail).
expect_ok "gen balls 4" gen balls --size 4 -o "$tmp/balls4.nff"
expect_ok "render balls --spd" render "$tmp/balls4.nff" --spd -o "$tmp/balls4.png" \
    --stats-json "$tmp/balls4.json"
python3 - "$tmp/balls4.json" <<'PY' || fail=1
import json, sys
s = json.load(open(sys.argv[1]))
published = {"reflected": (175095, s["rays"]["reflected"]), "shadow": (954368, s["rays"]["shadow"])}
bad = False
if s["rays"]["eye"] != 513 * 513:
    print(f"FAIL (balls --spd): {s['rays']['eye']} eye rays, want 513x513"); bad = True
for what, (want, got) in published.items():
    if abs(got - want) > 0.01 * want:
        print(f"FAIL (balls --spd): {got} {what} rays, SPD publishes {want}"); bad = True
if s["hits"] < 513 * 513:  # balls has no background: all 263169 eye rays hit (and more rays)
    print(f"FAIL (balls --spd): only {s['hits']} hits, every eye ray should hit"); bad = True
sys.exit(1 if bad else 0)
PY
