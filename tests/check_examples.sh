#!/bin/sh
# tests/check_examples.sh: is every function of examples/ short enough to
# read in one go (at most MAX_LINES lines, signature to closing brace)?
#
# Run from the repository root:   sh tests/check_examples.sh
# (make examples-check; part of make test).
#
# A function is found the way the code is laid out (.clang-format): its
# body opens with "{" alone at column 0 and closes with "}" at column 0;
# its signature is the run of lines above the "{" back to one starting at
# column 0. The exceptions, each "file:function", are listed below, in
# one place; one that has come within the limit fails the check until it
# is taken off the list, so the list stays the true one.
# Exits 1 on a function over the limit or a stale exception; 0 otherwise.
# POSIX sh and awk only.

MAX_LINES=150
EXCEPTIONS=""

files=$(find examples -name '*.c' -o -name '*.h' | sort)
[ -n "$files" ] || { echo "check_examples: no examples/ here (run from the repository root)" >&2; exit 2; }

awk -v max="$MAX_LINES" -v exceptions="$EXCEPTIONS" '
BEGIN {
    ne = split(exceptions, e, "\n")
    for (i = 1; i <= ne; i++) allowed[e[i]] = 1
}
FNR == 1 { sig = 0; start = 0 }
# a signature starts at column 0 with a word; comments, preprocessor
# lines, braces and blank lines end it
/^[A-Za-z_]/ && !start { if (!sig) { sig = FNR; text = "" } text = text " " $0; next }
/^\{/ && sig && !start { start = sig; name = text; next }
/^\}/ && start {
    sub(/\(.*/, "", name); k = split(name, w, /[^A-Za-z0-9_]+/)
    fn = w[k]; if (fn == "" && k > 1) fn = w[k - 1]
    len = FNR - start + 1
    key = FILENAME ":" fn
    if (key in allowed) { seen[key] = len }
    else if (len > max) { print "check_examples: " FILENAME ":" start ": " fn " is " len " lines (at most " max ")"; bad = 1 }
    nfn++; start = 0; sig = 0; next
}
!start && (/^[ \t]*$/ || /^#/ || /^\/[*\/]/ || /^[ \t]*\*/ || /^\}/ || /^\{/) { sig = 0 }
!start && /^[ \t]/ && sig { text = text " " $0 }
END {
    for (i = 1; i <= ne; i++) {
        k = e[i]
        if (!(k in seen)) { print "check_examples: exception " k ": no such function (take it off the list)"; bad = 1 }
        else if (seen[k] <= max) { print "check_examples: exception " k " is " seen[k] " lines now: take it off the list"; bad = 1 }
        else listed = listed " " k " (" seen[k] ")"
    }
    if (bad) exit 1
    print "check_examples: " nfn " functions of examples/ within " max " lines; listed exceptions:" (listed == "" ? " none" : listed)
}' $files
