#!/bin/sh
# mk/quickstart.sh - the README quick start check (used by make quickstart).
#
#   sh mk/quickstart.sh extract README.md build/quickstart.c
#       Writes the first ```c fenced block under the line "## Quick start"
#       (before the next "## " heading) to the .c file, after a #line
#       directive, so compiler messages name README.md and its lines.
#       Leaves the .c file untouched when its text would not change.
#       Fails, naming the markdown file, when there is no such block.
#
#   sh mk/quickstart.sh run PROGRAM...
#       Runs each program and checks that it exits 0 and that its standard
#       output has a line
#           quickstart: <V> vertices, <I> indices, mean ribbon width <W>
#       with V > 0, I > 0 and W > 0 (a number, in metres).
set -u

case "${1-}" in
extract)
    md=$2 out=$3
    awk -v md="$md" '
        state == 0 { if ($0 ~ /^## Quick start[ \t]*$/) state = 1; next }
        state == 1 {
            if ($0 ~ /^## /) exit
            if ($0 ~ /^```c[ \t]*$/) {
                state = 2
                printf "#line %d \"%s\"\n", NR + 1, md
            }
            next
        }
        state == 2 && /^```[ \t]*$/ { state = 3; exit }
        state == 2 { print }
        END { exit state == 3 ? 0 : 10 + state }
    ' "$md" > "$out.tmp"
    rc=$?
    case $rc in
    0)  # unchanged: keep the file and its time, so nothing rebuilds
        if cmp -s "$out.tmp" "$out"; then rm -f "$out.tmp"
        else mv "$out.tmp" "$out"; fi
        exit 0 ;;
    10) echo "$md: no line '## Quick start': nothing to extract into $out" ;;
    11) echo "$md: no \`\`\`c block under '## Quick start' (before the next '## ' heading): nothing to extract into $out" ;;
    12) echo "$md: the \`\`\`c block under '## Quick start' has no closing \`\`\`" ;;
    *)  echo "$md: could not read it (awk exit $rc)" ;;
    esac >&2
    rm -f "$out.tmp"
    exit 1
    ;;
run)
    shift
    fail=0
    for prog in "$@"; do
        printf '%-28s ' "$(basename "$prog"):"
        "$prog" >"$prog.out" 2>"$prog.err"
        rc=$?
        if line=$(awk '
                /^quickstart: / { last = $0; v = $2; i = $4; w = $9
                    ok = NF == 9 && $3 == "vertices," && $5 == "indices," &&
                         $6 == "mean" && $7 == "ribbon" && $8 == "width" &&
                         v ~ /^[0-9]+$/ && i ~ /^[0-9]+$/ &&
                         w ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ &&
                         v + 0 > 0 && i + 0 > 0 && w + 0 > 0 }
                END { print last; exit !ok }' "$prog.out") && [ $rc -eq 0 ]
        then
            echo "$line"
        else
            fail=1
            echo "FAILED (exit $rc)"
            echo "  expected one line 'quickstart: <V> vertices, <I> indices, mean ribbon width <W>'"
            echo "  with V, I and W > 0 and exit 0; standard output was:"
            sed -n '1,20s/^/    /p' "$prog.out"
            if [ -s "$prog.err" ]; then
                echo "  standard error:"
                sed -n '1,20s/^/    /p' "$prog.err"
            fi
        fi
    done
    exit $fail
    ;;
*)
    echo "usage: sh mk/quickstart.sh extract README.md OUT.c | run PROGRAM..." >&2
    exit 2
    ;;
esac
