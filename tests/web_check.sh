#!/bin/sh
# web_check.sh - the web page (make web: build/web/index.html, .js, .wasm)
# in a real browser: served on 127.0.0.1 (tests/web_serve.py), loaded in
# headless Chromium (WebGL2 through ANGLE on SwiftShader, no GPU needed)
# with ?frames=60&seed=7&test=1: the page runs 60 steps of 1/60 s, draws
# the last one, checks its own picture and writes PASS or FAIL into the
# page (#status, the title). Chromium's virtual time lets it finish, then
# --dump-dom gives the page and --screenshot the canvas (the test layout
# shows it alone, 640 x 480). It fails on:
#   - the page's own verdict: an error in the console (console.error or
#     console.warn, anything on stderr, an uncaught error, an abort), a
#     shader that does not compile, a GL error, a blank picture;
#   - any console message in Chromium's log (a good run writes none; the
#     browser's own WebGL warnings land there), but the performance notice
#     a busy machine gives on the page's readPixels;
#   - a blank screenshot (png_diff --stats: under 5 % of the pixels off
#     the background);
#   - a screenshot that differs from gl_marschner's headless render of the
#     same scene (gl_marschner --headless --frames 60 --shadows single
#     --no-oit --min-width 0 --root-fade 0: the built-in head, seed 7, with the one
#     shadow map the page draws, not the viewer's default deep opacity
#     maps, and the hair blended in draw order at its built width as the
#     page draws it, not with the viewer's default order-independent
#     transparency and 1-pixel strands, so the two are like for like) in more than 1 % of its pixels by more than 12 of 255 in a
#     channel (measured: 0.4 %); and, as a control that this tolerance
#     sees a change, the same scene one step earlier (--frames 59) must
#     fail that comparison (measured: 7 %).
# The native render needs build/gl_marschner and headless GL; without
# them that comparison is skipped, saying why, and the rest still runs.
#
#   sh tests/web_check.sh          the check (make web-check)
#   sh tests/web_check.sh bench N [QUERY]
#                                  N real-time frames (after 5) in headless
#                                  Chromium (QUERY: more of the page's
#                                  query, e.g. simd=1), the page's figures
#                                  printed and a screenshot of the page
#                                  (make web-bench)
# Needs chromium and python3 (the Makefile's targets check them and build
# the page). Every check prints ok or FAILED; the exit status is the number
# failed.
set -u
B=${BUILD:-build}
W=$B/web
D=$B/web-check
CHROMIUM=${CHROMIUM:-chromium}
TOL_THR=12     # png_diff: a channel off by more than this counts
TOL_LIMIT=0.01 # ... in at most this fraction of the pixels
fails=0
mkdir -p "$D"

ok() { echo "web_check: ok: $1"; }
bad() { echo "web_check: FAILED: $1"; fails=$((fails + 1)); }

# headless Chromium drawing WebGL2 in software (SwiftShader through ANGLE);
# --no-sandbox: CI runs as root
chromium_run() {
    "$CHROMIUM" --headless=new --use-angle=swiftshader \
        --enable-unsafe-swiftshader --no-sandbox --disable-gpu-sandbox \
        --no-first-run --disable-extensions --force-device-scale-factor=1 \
        --hide-scrollbars --enable-logging=stderr --v=0 "$@"
}

# the server, on a free port; stopped on exit
rm -f "$D/report.txt" "$D/url.txt"
python3 tests/web_serve.py "$W" 0 "$D/report.txt" >"$D/url.txt" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT HUP INT PIPE TERM
i=0
while [ ! -s "$D/url.txt" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
url=$(head -n 1 "$D/url.txt")
case $url in
http://127.0.0.1:*) ;;
*) echo "web_check: FAILED: the server did not start: $(cat "$D/url.txt")"
   exit 1 ;;
esac

if [ "${1:-}" = bench ]; then
    # real time: no virtual time, so the page's clock is the wall clock;
    # the page posts its figures, and its load (which the screenshot
    # waits for) waits for them
    n=${2:-20}
    chromium_run --window-size=1000,640 --screenshot="$D/page.png" \
        "$url?bench=$n&report=1${3:+&$3}" >/dev/null 2>"$D/bench.log"
    if [ -s "$D/report.txt" ]; then
        cat "$D/report.txt"
        echo "web_check: bench: the page's picture in $D/page.png"
        head -n 1 "$D/report.txt" | grep -q '^PASS: ' && exit 0
        echo "web_check: FAILED: the page reports a failure"
        exit 1
    fi
    echo "web_check: FAILED: no report from the page (log: $D/bench.log)"
    exit 1
fi

# the test run
rm -f "$D/web.png" "$D/dom.html"
if ! chromium_run --window-size=640,480 --virtual-time-budget=60000 \
        --screenshot="$D/web.png" --dump-dom \
        "$url?frames=60&seed=7&test=1" >"$D/dom.html" 2>"$D/chromium.log"; then
    bad "chromium exited non-zero (log: $D/chromium.log)"
fi
# the page's verdict: #status (its lines), and the title
status=$(awk '/<pre id="status">/ { f = 1 } f { print } f && /<\/pre>/ { exit }' \
    "$D/dom.html" | sed 's/.*<pre id="status">//; s/<\/pre>.*//')
title=$(sed -n 's/.*<title>\([^<]*\)<\/title>.*/\1/p' "$D/dom.html" | head -n 1)
if [ "$title" = "hairfur web: done" ] && [ "${status#PASS: }" != "$status" ]; then
    ok "the page: $status"
elif [ -n "$title" ]; then
    bad "the page ($title): ${status:-no status}"
else
    bad "no page in Chromium's output (log: $D/chromium.log)"
fi
# Chromium's performance notice on the page's own readPixels ("GPU stall
# due to ReadPixels", written when the machine is busy) is not a fault
msgs=$(grep ':CONSOLE' "$D/chromium.log" | grep -v 'GPU stall due to ReadPixels')
if [ -n "$msgs" ]; then
    bad "console messages: $(printf '%s\n' "$msgs" | head -n 10)"
else
    ok "no console message"
fi
if [ ! -s "$D/web.png" ]; then
    bad "no screenshot"
elif d=$($B/png_diff --stats "$D/web.png" 24 0.05); then
    ok "screenshot $D/web.png: $d"
else
    bad "screenshot $D/web.png is blank: $d"
fi

# the native render of the same scene
# --shadows single: the page's self-shadowing (one depth map, exp(-k d));
# --no-oit --min-width 0 --root-fade 0: the page's blending, in draw order, of ribbons
# as built
G="env -u DISPLAY -u WAYLAND_DISPLAY $B/gl_marschner --headless --shadows single --no-oit --min-width 0 --root-fade 0"
if [ ! -x $B/gl_marschner ] || [ ! -x $B/gl_check ]; then
    echo "web_check: comparison with the native render skipped: no" \
         "$B/gl_marschner (its packages: make deps)"
elif ! why=$(env -u DISPLAY -u WAYLAND_DISPLAY $B/gl_check); then
    echo "web_check: comparison with the native render skipped: $why"
elif [ -s "$D/web.png" ]; then
    if $G --frames 60 --out "$D/native.png" >"$D/native.log" 2>&1 &&
       $G --frames 59 --out "$D/native59.png" >>"$D/native.log" 2>&1; then
        if d=$($B/png_diff "$D/web.png" "$D/native.png" $TOL_THR $TOL_LIMIT); then
            ok "the page against gl_marschner --headless --frames 60 --shadows single --no-oit --min-width 0 --root-fade 0: $d"
        else
            bad "the page differs from gl_marschner's render ($D/web.png, $D/native.png): $d"
        fi
        if d=$($B/png_diff "$D/web.png" "$D/native59.png" $TOL_THR $TOL_LIMIT); then
            bad "the control (one step earlier) passes: $d"
        else
            ok "control, one step earlier, differs: $d"
        fi
    else
        bad "gl_marschner --headless failed (log: $D/native.log)"
    fi
fi

[ "$fails" -eq 0 ] && echo "web_check: all passed" ||
    echo "web_check: $fails FAILED"
exit "$fails"
