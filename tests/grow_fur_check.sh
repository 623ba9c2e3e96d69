#!/bin/sh
# tests/grow_fur_check.sh - command-line checks of examples/grow_fur.c:
# --help, exit code 2 with a message for bad counts, counts written 5k /
# 2e4, and --guides landing within a factor 2 of its target on the
# built-in head. Skips (exit 0, with the reason) where build/grow_fur
# cannot be built (assimp or stb missing). Run from the repository root.
BIN=build/grow_fur
if ! make --no-print-directory "$BIN" >/dev/null 2>&1; then
    echo "grow_fur_check: SKIP: cannot build $BIN (needs libassimp-dev and libstb-dev: make deps)"
    exit 0
fi
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "grow_fur_check: FAIL: $*"; fail=1; }

# --help: exit 0, one line per option, the map orientation
"$BIN" --help >"$tmp/help" 2>&1; rc=$?
[ $rc -eq 0 ] || bad "--help exited $rc"
for opt in --mesh --density --strands --guides --tess-factor --collider --eye --out; do
    grep -q -- "^  $opt " "$tmp/help" || bad "--help has no line for $opt"
done
grep -q "PNG top row = v 1" "$tmp/help" || bad "--help does not say which way maps are read"

# bad values: exit 2 and a message naming the option and the value
for v in 5x abc "" -3 0 2.5 1e99 k " 7"; do
    "$BIN" --strands "$v" --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 2 ] || bad "--strands '$v' exited $rc, not 2"
    grep -q -- "--strands '$v'" "$tmp/out" || bad "--strands '$v': no message naming it"
done
for args in "--lod 2" "--lod x" "--eye 1,2" "--collider 1,2,3" "--collider 0,0,0,-1" \
            "--frames" "--nonsense 1" "--out f.png" "--guides 10 --tess-factor 5"; do
    # shellcheck disable=SC2086
    "$BIN" $args >/dev/null 2>&1; rc=$?
    [ $rc -eq 2 ] || bad "'$args' exited $rc, not 2"
done

# good counts: 5k and 2e4 grow 5000 and 20000 strands
for pair in 5k:5000 2e4:20000 300:300; do
    v=${pair%%:*}; want=${pair#*:}
    "$BIN" --strands "$v" --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 0 ] || bad "--strands $v exited $rc"
    grep -q " $want strands of " "$tmp/out" || bad "--strands $v did not grow $want strands"
done

# --guides within a factor 2 of the target on the built-in head
for g in 1000 2000 5000; do
    "$BIN" --guides "$g" --strands 5k --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 0 ] || bad "--guides $g exited $rc"
    n=$(sed -n 's/.*; \([0-9][0-9]*\) guides (.*/\1/p' "$tmp/out" | head -n 1)
    if [ -z "$n" ] || [ "$n" -lt $((g / 2)) ] || [ "$n" -gt $((g * 2)) ]; then
        bad "--guides $g made '${n:-?}' guides (not within 2x)"
    else
        echo "grow_fur_check: --guides $g -> $n guides"
    fi
done

# --collider none and an explicit sphere run; --eye runs
"$BIN" --collider none --eye 0,0,1 --frames 2 --strands 1k --out "$tmp/f.ply" >"$tmp/out" 2>&1 \
    || bad "--collider none --eye 0,0,1 failed"
grep -q "collider: none" "$tmp/out" || bad "--collider none not reported"
"$BIN" --collider 0,0,0,0.2 --frames 2 --strands 1k --out "$tmp/f.obj" >"$tmp/out" 2>&1 \
    || bad "--collider 0,0,0,0.2 failed"
grep -q "guide roots inside it" "$tmp/out" || bad "roots_inside not reported"
grep -q "sit inside the collider" "$tmp/out" || bad "a collider larger than the head: no roots-inside warning"

# curves out and back in: .hair (with colours) and OBJ polylines; read back
# as guide curves, every guide takes their shape (strands keep the length)
"$BIN" --frames 5 --strands 1k --out "$tmp/c.hair" >"$tmp/out" 2>&1 \
    || bad "--out c.hair failed: $(tail -n 1 "$tmp/out")"
grep -q "wrote .*c.hair: 1000 curves of 16 points" "$tmp/out" || bad "--out .hair: no curves written"
"$BIN" --frames 5 --strands 1k --out "$tmp/c.obj" --curves >"$tmp/out" 2>&1 \
    || bad "--out c.obj --curves failed"
[ "$(grep -c '^l ' "$tmp/c.obj")" -eq 1000 ] || bad "--curves: not 1000 'l' lines"
for g in c.hair c.obj; do
    "$BIN" --guides "$tmp/$g" --frames 2 --strands 1k --out "$tmp/f.obj" >"$tmp/out" 2>&1 \
        || bad "--guides $g failed: $(tail -n 1 "$tmp/out")"
    grep -q "guides: 1000 curves, 16000 points" "$tmp/out" || bad "--guides $g: not read"
done
"$BIN" --out "$tmp/c.hair" --curves >"$tmp/out" 2>&1 && bad "--curves with .hair accepted"
# a groom: its own 1000 strands, half of them simulated
"$BIN" --groom "$tmp/c.hair" --guide-fraction 0.5 --frames 5 --out "$tmp/g.hair" >"$tmp/out" 2>&1 \
    || bad "--groom failed: $(tail -n 1 "$tmp/out")"
grep -q "1000 strands of 16 points, 500 of them simulated guides" "$tmp/out" \
    || bad "--groom: $(grep -m1 groom "$tmp/out")"
"$BIN" --groom "$tmp/c.hair" --guides "$tmp/c.hair" >"$tmp/out" 2>&1 && bad "--groom with --guides accepted"
"$BIN" --groom "$tmp/c.hair" --guide-fraction 0 >"$tmp/out" 2>&1 && bad "--guide-fraction 0 accepted"
# a truncated .hair and a file of the wrong kind: refused, named
head -c 300 "$tmp/c.hair" >"$tmp/cut.hair"
"$BIN" --guides "$tmp/cut.hair" --frames 1 >"$tmp/out" 2>&1 && bad "a truncated .hair was accepted"
grep -q "truncated" "$tmp/out" || bad "a truncated .hair: no 'truncated' in: $(cat "$tmp/out")"
"$BIN" --guides "$tmp/f.obj" --frames 1 >"$tmp/out" 2>&1 && bad "an OBJ without polylines was accepted"
grep -q "no polylines" "$tmp/out" || bad "OBJ without polylines: $(cat "$tmp/out")"

if [ $fail -ne 0 ]; then echo "grow_fur_check: FAILED"; exit 1; fi
echo "grow_fur_check: all passed"
