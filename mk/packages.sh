#!/bin/sh
# mk/packages.sh [GROUP...] - print the Debian packages of mk/packages.txt
# on one line, separated by spaces, each once, in file order: those of the
# groups named, or of every group when none is named. Fails on a group the
# file does not have. POSIX sh and awk only (runs before build-essential is
# installed).
list="$(dirname "$0")/packages.txt"
exec awk -v want=" $* " '
    { sub(/#.*/, ""); gsub(/^[ \t]+|[ \t]+$/, "") }
    $0 == "" { next }
    /^\[.*\]$/ {
        group = substr($0, 2, length($0) - 2)
        groups = groups " " group " "
        next
    }
    (want ~ /^ *$/ || index(want, " " group " ")) && !seen[$0]++ {
        out = out (out == "" ? "" : " ") $0
    }
    END {
        n = split(want, w, " ")
        for (i = 1; i <= n; ++i)
            if (!index(groups, " " w[i] " ")) {
                printf "mk/packages.sh: no group [%s] in %s\n", w[i], FILENAME > "/dev/stderr"
                exit 1
            }
        print out
    }' "$list"
