#!/bin/sh
# viewer_check.sh - gl_marschner, the viewer for any mesh, as a user meets
# it: --help, clear errors for bad input, an animated skinned character
# from assimp-testmodels (stretch at most 1e-4, no NaN, every guide root on
# the skinned mesh, frames written with hair in them), and the same picture
# for a mesh in metres and the same mesh in centimetres.
# Needs build/gl_marschner, build/make_hairstyle, build/png_diff and headless GL (the Makefile's
# viewer-check target checks those); skips, saying why, without the models.
# Every check prints ok or FAILED; the exit status is the number failed.
set -u
B=${BUILD:-build}
O=${OUT:-out}/viewer_check
V="env -u DISPLAY -u WAYLAND_DISPLAY $B/gl_marschner"
M=/usr/share/assimp/models
fails=0
mkdir -p "$O"

ok() { echo "viewer_check: ok: $1"; }
bad() { echo "viewer_check: FAILED: $1"; fails=$((fails + 1)); }

# expect_error WHAT PATTERN ARGS...: exits non-zero, stderr names it
expect_error() {
    what=$1; pat=$2; shift 2
    if $V "$@" >"$O/stdout" 2>"$O/stderr"; then
        bad "$what: exit 0"
    elif grep -q -- "$pat" "$O/stderr"; then
        ok "$what: $(grep -m1 -- "$pat" "$O/stderr")"
    else
        bad "$what: stderr lacks '$pat': $(head -c 300 "$O/stderr")"
    fi
}

if [ ! -f "$M/X/Testwuson.X" ] || [ ! -f "$M/OBJ/WusonOBJ.obj" ]; then
    echo "viewer_check: skipped: no $M (install assimp-testmodels: make deps)"
    exit 0
fi

# --help: every option the mesh path adds, and the keys
if $V --help >"$O/help" 2>&1; then
    miss=""
    for o in --mesh --anim --grow-on --unit --density --length --color \
             --no-shadows --shadows --headless --frames --out --save-every --comb \
             --hair-length --settle --rest-from-gravity --volume --friction \
             --grid --stiffness Keys; do
        grep -q -- "$o" "$O/help" || miss="$miss $o"
    done
    # every key the viewer answers, with what it does
    keys=$(sed -n '/^Keys/,$p' "$O/help")
    for k in "K Kajiya" "G GPU" "C 3D" "V collid" "O shadow" "S specular" \
             "H body" "space orbit" "+/- or scroll" "arrows orbit" "Esc quits"; do
        printf '%s\n' "$keys" | grep -qF -- "$k" || miss="$miss key:'$k'"
    done
    if [ -z "$miss" ]; then ok "--help lists the mesh options and the keys"
    else bad "--help lacks:$miss"; fi
else
    bad "--help exits non-zero"
fi

# bad input: a clear message, no crash
expect_error "missing mesh file" "nope.obj" --headless --mesh "$O/nope.obj"
expect_error "unknown animation" "Wuson_Walk" --headless \
    --mesh "$M/X/Testwuson.X" --anim Dance
expect_error "unknown mesh to grow on" "Wuson" --headless \
    --mesh "$M/X/Testwuson.X" --grow-on Tail
expect_error "bad strand count" "expected a whole number" --headless \
    --strands 5k
expect_error "bad shadow mode" "deep or single" --headless --shadows soft
expect_error "bad unit" "unit" --headless --mesh "$M/OBJ/WusonOBJ.obj" \
    --unit furlong
expect_error "--save-every without %d" "%d" --headless --save-every 5 \
    --out "$O/x.png"
expect_error "--save-every with %s" "%d" --headless --save-every 5 \
    --out "$O/x_%s.png"
expect_error "--save-every with two %d" "%d" --headless --save-every 5 \
    --out "$O/x_%d_%d.png"

# the walking Wuson: skinned, capsules on the bones, frames written
# is_small VALUE LIMIT: VALUE is a plain number (not nan or inf) below LIMIT
is_small() {
    printf '%s\n' "$1" | grep -Eq '^[0-9]+(\.[0-9]+)?(e[-+][0-9]+)?$' &&
        awk -v w="$1" -v l="$2" 'BEGIN { exit !(w + 0 < l + 0) }'
}
WALK="--headless --mesh $M/X/Testwuson.X --anim Wuson_Walk --strands 4000 --hair-length 0.08 --frames 30"
# shellcheck disable=SC2086
if $V $WALK --save-every 15 --out "$O/wuson_%03d.png" >"$O/walk" 2>&1; then
    worst=$(sed -n 's/.*stretch.*worst \([^,]*\),.*/\1/p' "$O/walk")
    cols=$(sed -n 's/.*guides, \([0-9]*\) colliders$/\1/p' "$O/walk")
    nf=$(sed -n 's/.*non-finite coordinates: \([0-9]*\) in the guides.*, \([0-9]*\) in the.*/\1 \2/p' "$O/walk")
    miss=$(sed -n 's/.*roots: \([0-9]*\) of [0-9]* guide roots missing.*/\1/p' "$O/walk")
    rdist=$(sed -n 's/.*roots: .* m (\([^ ]*\) of the mesh size).*/\1/p' "$O/walk")
    if [ -f "$O/wuson_015.png" ] && [ -f "$O/wuson_030.png" ]; then
        ok "walk: wrote wuson_015.png and wuson_030.png"
    else bad "walk: frames missing"; fi
    if is_small "$worst" 1e-4; then
        ok "walk: worst stretch $worst < 1e-4"
    else bad "walk: worst stretch '$worst' (want a number below 1e-4)"; fi
    if [ "$nf" = "0 0" ]; then
        ok "walk: no NaN or infinity in the guides (every frame) or the strands"
    else bad "walk: non-finite coordinates (guides, strands): '$nf'"; fi
    if [ "$miss" = "0" ] && is_small "$rdist" 1e-5; then
        ok "walk: no root missing; roots within $rdist of the mesh size of the skinned mesh"
    else bad "walk: roots missing '$miss', off the skinned mesh by '$rdist' of its size"; fi
    # a picture with hair in it: not empty, and hair where the body alone
    # (--no-hair, the same frame) shows none
    # shellcheck disable=SC2086
    if d=$($B/png_diff --stats "$O/wuson_030.png"); then ok "walk: picture: $d"
    else bad "walk: empty picture: $d"; fi
    # shellcheck disable=SC2086
    if $V $WALK --no-hair --out "$O/wuson_bare.png" >"$O/bare" 2>&1; then
        if d=$($B/png_diff "$O/wuson_030.png" "$O/wuson_bare.png" 12 0.02); then
            bad "walk: no hair in the picture (against the body alone): $d"
        else ok "walk: hair in the picture, against the body alone: $d"; fi
    else bad "walk --no-hair: exit non-zero: $(tail -3 "$O/bare")"; fi
    if [ -n "$cols" ] && [ "$cols" -gt 10 ]; then
        ok "walk: $cols bone capsules"
    else bad "walk: colliders '$cols'"; fi
else
    bad "walk: exit non-zero: $(tail -3 "$O/walk")"
fi

# an authored hairstyle: make_hairstyle's curves read back as the guides
H=$M/X/BCN_Epileptic.X
if $B/make_hairstyle --mesh "$H" --part Head --plane 0,1,-0.53,0.717 \
       --curves 100 --out "$O/style.hair" >"$O/style" 2>&1 &&
   $V --headless --mesh "$H" --grow-on Head --guides "$O/style.hair" \
       --strands 3000 --frames 10 --out "$O/styled.png" >"$O/styled" 2>&1; then
    worst=$(sed -n 's/.*stretch.*worst \([^,]*\),.*/\1/p' "$O/styled")
    hair=$(sed -n 's/.*guides, hair \([0-9.]*\) m,.*/\1/p' "$O/styled")
    if awk -v w="$worst" -v h="$hair" \
         'BEGIN { exit !(w ~ /^[0-9.e+-]+$/ && w + 0 < 1e-4 && h + 0 > 0.25) }'; then
        ok "--guides style.hair: hair $hair m (the curves' length), stretch $worst"
    else bad "--guides: hair '$hair', stretch '$worst'"; fi
else
    bad "--guides style.hair: $(tail -n 2 "$O/style" "$O/styled")"
fi
# the same curves as a groom: its own strands, a quarter simulated
if $V --headless --mesh "$H" --grow-on Head --groom "$O/style.hair" \
       --guide-fraction 0.25 --frames 10 --out "$O/groom.png" >"$O/groom" 2>&1 &&
   grep -q "100 strands of 16 points, 25 guides" "$O/groom"; then
    ok "--groom style.hair: 100 strands, 25 guides"
else
    bad "--groom: $(grep -m1 -E 'strands|gl_marschner:' "$O/groom")"
fi
printf 'HAIR' >"$O/bad.hair"
expect_error "--guides with a bad .hair" "shorter than its 128-byte header" \
    --headless --guides "$O/bad.hair"

# metres and centimetres: the same picture (the unit is found from the
# size); read as metres, the centimetre mesh gives another one
awk '/^v /{ printf "v %.9g %.9g %.9g\n", $2 * 100, $3 * 100, $4 * 100; next }
     { print }' "$M/OBJ/WusonOBJ.obj" >"$O/wuson_cm.obj"
set -- --headless --still --frames 20 --strands 4000 --hair-length 0.1
if $V "$@" --mesh "$M/OBJ/WusonOBJ.obj" --out "$O/m.png" >/dev/null 2>&1 &&
   $V "$@" --mesh "$O/wuson_cm.obj" --out "$O/cm.png" >/dev/null 2>&1 &&
   $V "$@" --mesh "$O/wuson_cm.obj" --unit 0.001 --out "$O/mm.png" \
      >/dev/null 2>&1; then
    if d=$($B/png_diff "$O/m.png" "$O/cm.png"); then ok "m vs cm: $d"
    else bad "m vs cm differ: $d"; fi
    # the controls ask for 1 % of the pixels off by 12: seen from its
    # unlit side the fur is dark (light reaches it only through the fur)
    if d=$($B/png_diff "$O/m.png" "$O/mm.png" 12 0.01); then
        bad "the control (cm read at 1 mm a unit) looks the same: $d"
    else ok "control, cm read at 1 mm a unit, differs: $d"; fi
else
    bad "m / cm renders: exit non-zero"
fi

# compact GPU points (8 bytes) draw what the float ones draw, on a
# skinned character whose box follows its head; a control: far fewer
# strands (LOD 0.05) differ
set -- --headless --still --frames 20 --strands 4000 --hair-length 0.1 \
    --mesh "$M/OBJ/WusonOBJ.obj"
if $V "$@" --gpu-expand --out "$O/gpu.png" >/dev/null 2>&1 &&
   $V "$@" --gpu-expand --compact --out "$O/gpu8.png" >"$O/gpu8.txt" 2>&1 &&
   $V "$@" --gpu-expand --lod 0.05 --out "$O/gpu_lod.png" >/dev/null 2>&1; then
    if d=$($B/png_diff "$O/gpu.png" "$O/gpu8.png"); then
        ok "compact GPU points vs float: $d"
    else bad "compact GPU points differ from float: $d"; fi
    if d=$($B/png_diff "$O/gpu.png" "$O/gpu_lod.png" 12 0.01); then
        bad "the control (LOD 0.05) looks the same: $d"
    else ok "control, LOD 0.05, differs: $d"; fi
    if grep -q "ropes: .* colliders" "$O/gpu8.txt"; then
        ok "$(grep -m1 "ropes: " "$O/gpu8.txt")"
    else bad "no ropes time with the collider count"; fi
else
    bad "GPU point renders: exit non-zero"
fi

[ "$fails" -eq 0 ] && echo "viewer_check: all passed" ||
    echo "viewer_check: $fails FAILED"
exit "$fails"
