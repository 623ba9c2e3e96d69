#!/bin/sh
# tests/grow_fur_check.sh - command-line checks of examples/grow_fur.c:
# --help, exit code 2 with a message for bad counts, counts written 5k /
# 2e4, --guides landing within a factor 2 of its target on the built-in
# head, the --collider forms, and the map convention (a density PNG white
# in its top half grows strands only on the top half of a UV-mapped quad).
# Skips (exit 0, with the reason) where build/grow_fur cannot be built
# (assimp or stb missing). Run from the repository root. GROW_FUR=path
# checks another build of grow_fur instead.
BIN=${GROW_FUR:-build/grow_fur}
if [ -z "${GROW_FUR:-}" ] && ! make --no-print-directory "$BIN" >/dev/null 2>&1; then
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
for opt in --mesh --density --estimator --strands --guides --tess-factor --collider --eye --out \
           --stiffness --volume --friction --grid --rest-from-gravity --keep-length; do
    grep -q -- "^  $opt " "$tmp/help" || bad "--help has no line for $opt"
done
grep -q "PNG top row = v 1" "$tmp/help" || bad "--help does not say which way maps are read"

# hair-hair interaction and draping: bad strengths refused (exit 2, the
# option named); long hair draped with the grid runs and says so
for pair in "--volume -1" "--volume 101" "--friction 1.5" "--grid 3" "--grid 129" \
            "--rest-from-gravity -1" "--stiffness 2" "--keep-length 2"; do
    set -- $pair
    "$BIN" "$1" "$2" --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 2 ] || bad "$1 $2: exit $rc, expected 2"
    grep -q -- "$1" "$tmp/out" || bad "$1 $2: no message naming it"
done
"$BIN" --strands 2000 --length-max 0.25 --rest-from-gravity 0.5 --frames 2 \
    --out "$tmp/h.hair" >"$tmp/out" 2>&1 || bad "--rest-from-gravity 0.5: $(tail -n 2 "$tmp/out")"
grep -q "rest from gravity: 0.5 s of draping" "$tmp/out" || bad "--rest-from-gravity: not reported"
grep -q "grid [0-9.]* (32^3 nodes)" "$tmp/out" || bad "the grid's time not reported"
"$BIN" --strands 2000 --volume 0 --friction 0 --frames 2 --out "$tmp/h.hair" \
    >"$tmp/out" 2>&1 || bad "--volume 0 --friction 0 failed"
grep -q "grid 0.000 (0^3 nodes)" "$tmp/out" || bad "--volume 0 --friction 0: a grid made"

# bad values: exit 2 and a message naming the option and the value
for v in 5x abc "" -3 0 2.5 1e99 k " 7"; do
    "$BIN" --strands "$v" --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 2 ] || bad "--strands '$v' exited $rc, not 2"
    grep -q -- "--strands '$v'" "$tmp/out" || bad "--strands '$v': no message naming it"
done
for args in "--lod 2" "--lod x" "--eye 1,2" "--collider 1,2,3" "--collider 0,0,0,-1" \
            "--estimator middle" \
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
grep -q "guide roots inside it" "$tmp/out" || bad "--collider none: roots inside not reported"
# sphere: and capsule: forms, repeatable, each reported as read
"$BIN" --collider sphere:0,0,0,0.09 --collider capsule:0,-0.05,0,0,0.05,0,0.06 \
    --collider auto --frames 2 --strands 1k --out "$tmp/f.obj" >"$tmp/out" 2>&1 \
    || bad "--collider sphere: + capsule: + auto failed: $(tail -n 1 "$tmp/out")"
grep -q "collider: given sphere, centre (0, 0, 0), radius 0.09" "$tmp/out" \
    || bad "--collider sphere: not reported"
grep -q "collider: given capsule, (0, -0.05, 0) - (0, 0.05, 0), radius 0.06" "$tmp/out" \
    || bad "--collider capsule: not reported"
grep -q "collider: auto sphere" "$tmp/out" || bad "--collider auto beside others not reported"
# bad ones: exit 2, the message names the bad value
for pair in "sphere:0,0,x,1|'x' is not a number" "capsule:0,0,0,1,1,1|6 numbers given, 7 expected" \
            "sphere:1,2,3,4,5|more than 4 numbers" "sphere:0,0,0,0|must be positive" \
            "sphere:0,,0,1|field 2 is empty" "box:0,0,0,1|unknown collider" \
            "sphere:1e9,0,0,1|'1e9' is beyond" "capsule:0,0,0,0,0,1,nan|'nan' is not a number"; do
    c=${pair%%|*}; msg=${pair#*|}
    "$BIN" --collider "$c" --frames 1 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
    [ $rc -eq 2 ] || bad "--collider '$c' exited $rc, not 2"
    grep -q -- "--collider '$c': .*$msg" "$tmp/out" || bad "--collider '$c': no message '$msg': $(cat "$tmp/out")"
done
"$BIN" --collider none --collider auto --frames 1 >"$tmp/out" 2>&1; rc=$?
[ $rc -eq 2 ] || bad "--collider none with another exited $rc, not 2"
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

# the map convention: a quad with v = y (v up, as assimp reads OBJ), and a
# density PNG white in its top rows, black below. The quad is split at
# y = 0.5 so that no triangle straddles the line (a straddling triangle's
# strands land on both sides whatever the map says).
if command -v python3 >/dev/null 2>&1; then
    cat >"$tmp/quad.obj" <<'EOF'
v 0 0 0
v 1 0 0
v 1 0.5 0
v 0 0.5 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 0.5
vt 0 0.5
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
f 4/4/1 3/3/1 5/5/1
f 4/4/1 5/5/1 6/6/1
EOF
    # an 8-bit grey PNG, 64 x 64: file rows 0..31 (the top) white
    python3 - "$tmp/top.png" <<'EOF'
import struct, sys, zlib
W = H = 64
rows = b"".join(b"\0" + bytes([255 if y < H // 2 else 0]) * W for y in range(H))
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n"
    + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 0, 0, 0, 0))
    + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
EOF
    # one frame, no collider: the head motion turns about y and slides
    # along x, so a root's y is where it grew
    if "$BIN" --mesh "$tmp/quad.obj" --density "$tmp/top.png" --collider none \
          --strands 2000 --frames 1 --out "$tmp/quad_c.obj" --curves >"$tmp/out" 2>&1; then
        # each 'l' line's first index is a strand's root
        # shellcheck disable=SC2046
        set -- $(awk '/^v / { n++; y[n] = $3 }
            /^l / { r = y[$2]; c++; if (r > 0.5) top++; if (r > 0.75) q++
                    if (min == "" || r < min) min = r }
            END { printf "%d %d %d %s\n", c, top, q, min }' "$tmp/quad_c.obj")
        if [ "$1" -eq 2000 ] && [ "$2" -eq "$1" ] && [ "$3" -gt 500 ]; then
            echo "grow_fur_check: map convention: $2 of $1 roots on the top half (lowest y $4, $3 above 0.75)"
        else
            bad "map convention: of $1 roots $2 on the top half, $3 above 0.75, lowest y $4 (want all 2000 above 0.5)"
        fi
    else
        bad "map convention: grow_fur failed: $(tail -n 2 "$tmp/out")"
    fi
else
    echo "grow_fur_check: map convention: SKIP (no python3 to write the PNG)"
fi

# the file's node transforms: a glTF quad of 2 x 2 units whose node
# scales it by 0.5 and moves it to x = 10 grows where the file puts it
if command -v python3 >/dev/null 2>&1; then
    python3 - "$tmp/node.gltf" <<'EOF'
import base64, json, struct, sys
pos = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
uv = [0, 0, 1, 0, 1, 1, 0, 1]
idx = [0, 1, 2, 0, 2, 3]
blob = struct.pack("<12f", *pos) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "scale": [0.5, 0.5, 0.5], "translation": [10, 0, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
    "buffers": [{"byteLength": len(blob), "uri": uri}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-1, -1, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]},
    open(sys.argv[1], "w"))
EOF
    if "$BIN" --mesh "$tmp/node.gltf" --collider none --strands 500 --frames 1 \
          --out "$tmp/node.obj" >"$tmp/out" 2>&1; then
        box=$(grep "^bounding box" "$tmp/out")
        case "$box" in
        *"(9.5, -0.5, 0) .. (10.5, 0.5, 0)"*)
            echo "grow_fur_check: node transforms: $box" ;;
        *) bad "node transforms not applied: $box (want (9.5, -0.5, 0) .. (10.5, 0.5, 0))" ;;
        esac
    else
        bad "node transforms: grow_fur failed: $(tail -n 2 "$tmp/out")"
    fi
fi

# a node tree with empty children (assimp's RAW importer makes one)
raw=/usr/share/assimp/models/RAW/WithColor.raw
if [ -f "$raw" ]; then
    "$BIN" --mesh "$raw" --strands 500 --frames 1 --out "$tmp/raw.hair" >"$tmp/out" 2>&1 ||
        bad "$raw: exit $?: $(tail -n 2 "$tmp/out")"
else
    echo "grow_fur_check: RAW node tree: SKIP ($raw missing: Debian's assimp-testmodels)"
fi

# --keep-length (the default): the .hair output's strands keep their
# segment lengths through the swing; the plain blend does not
if command -v python3 >/dev/null 2>&1; then
    for k in 1 0; do
        for n in 1 60; do
            "$BIN" --strands 3000 --points 24 --length-max 0.25 --keep-length $k \
                --frames $n --out "$tmp/k${k}_$n.hair" >"$tmp/out" 2>&1 ||
                bad "--keep-length $k --frames $n: $(tail -n 2 "$tmp/out")"
        done
    done
    cat >"$tmp/seg.py" <<'EOF'
import array, math, struct, sys
def segs(path):
    d = open(path, "rb").read()
    s, t, flags, dseg = struct.unpack_from("<4I", d, 4)
    off = 128 + (2 * s if flags & 1 else 0)
    xyz = array.array("f"); xyz.frombytes(d[off:off + 12 * t])
    return [math.dist(xyz[3 * i:3 * i + 3], xyz[3 * i + 3:3 * i + 6])
            for i in range(t - 1) if (i + 1) % (dseg + 1)]
a, b = segs(sys.argv[1]), segs(sys.argv[2])
print("%.3g" % max(abs(x - y) / max(x, 1e-9) for x, y in zip(a, b)))
EOF
    kept=$(python3 "$tmp/seg.py" "$tmp/k1_1.hair" "$tmp/k1_60.hair")
    plain=$(python3 "$tmp/seg.py" "$tmp/k0_1.hair" "$tmp/k0_60.hair")
    if python3 -c "import sys; sys.exit(not ($kept < 1e-4 and $plain > 1e-2))"; then
        echo "grow_fur_check: keep-length: segments change by at most $kept" \
             "over 60 frames ($plain without)"
    else
        bad "keep-length: segments change by $kept over 60 frames" \
            "(want < 1e-4), $plain without (want > 1e-2)"
    fi
fi

# refused before the run, saying why: an output that cannot be written,
# a name that is only an extension, no strand drawn
"$BIN" --out "$tmp/no/such/dir/f.hair" >"$tmp/out" 2>&1; rc=$?
{ [ $rc -eq 1 ] && grep -q "cannot write it" "$tmp/out"; } ||
    bad "an unwritable --out: exit $rc, $(cat "$tmp/out")"
! grep -q "frames at lod" "$tmp/out" || bad "an unwritable --out: the frames ran first"
echo keep >"$tmp/kept.hair"
"$BIN" --mesh "$tmp/no-such-mesh.obj" --out "$tmp/kept.hair" >"$tmp/out" 2>&1; rc=$?
{ [ $rc -eq 1 ] && [ "$(cat "$tmp/kept.hair")" = keep ]; } ||
    bad "an existing --out changed by a refused run (exit $rc)"
"$BIN" --out "$tmp/.hair" >"$tmp/out" 2>&1; rc=$?
{ [ $rc -eq 2 ] && grep -q "needs a stem" "$tmp/out"; } || bad "--out .hair: exit $rc"
"$BIN" --strands 268435456 --points 256 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
{ [ $rc -eq 2 ] && grep -q "need about" "$tmp/out"; } ||
    bad "7 TB of strands: exit $rc, $(cat "$tmp/out")"
"$BIN" --lod 0 --out "$tmp/f.obj" >"$tmp/out" 2>&1; rc=$?
{ [ $rc -eq 2 ] && grep -q -- "--lod" "$tmp/out"; } || bad "--lod 0: exit $rc"

if [ $fail -ne 0 ]; then echo "grow_fur_check: FAILED"; exit 1; fi
echo "grow_fur_check: all passed"
