#!/bin/sh
# tests/check_api_doc.sh: does docs/api.md agree with hairfur.h?
#
# Run from the repository root:   sh tests/check_api_doc.sh
# Other files (e.g. to try a broken copy):
#   HDR=/tmp/hairfur.h API_DOC=/tmp/api.md sh tests/check_api_doc.sh
#
# Reads only the declaration half of the header (up to the line
# "#endif /* HAIRFUR_H */") and checks:
#   (a) every public function (a line starting "HFDEF ") is in api.md, as
#       "name(" or "`name`";
#   (b) every "hf_name(" in api.md is a public function of the header, and
#       every other hf_ / HF_ word in api.md occurs in the declaration half;
#   (c) every code of HF_RESULT_TABLE(X) has a row "| HF_X | value | message |"
#       in api.md (backticks around the code or value allowed; the message
#       verbatim), and every such row names a code of the table;
#   (d) every public struct and enum typedef ("typedef struct hf_x {",
#       "typedef enum hf_x {", "typedef struct hf_x hf_x;") is named in
#       api.md.
# Prints one line per drift and exits 1 if there is any; exits 2 when a file
# is missing or the header cannot be parsed; exits 0 otherwise.
# POSIX sh and awk only.

HDR=${HDR:-hairfur.h}
API_DOC=${API_DOC:-docs/api.md}

for f in "$HDR" "$API_DOC"; do
    if [ ! -r "$f" ]; then
        echo "check_api_doc: cannot read $f (run from the repository root," \
             "or set HDR / API_DOC)" >&2
        exit 2
    fi
done

awk -v hdr="$HDR" -v doc="$API_DOC" '
function trim(s) { sub(/^[ \t]+/, "", s); sub(/[ \t]+$/, "", s); return s }
function unquote(s) { gsub(/`/, "", s); return trim(s) }
function drift(msg) { ndrift++; print doc ": " msg }

# ---- the header, declaration half only ---------------------------------
FNR == NR {
    sub(/\r$/, "")
    if (hdr_done) next
    if ($0 ~ /^#endif \/\* HAIRFUR_H \*\//) { hdr_done = 1; next }

    # every word of the declaration half (comments included)
    line = $0
    gsub(/[^A-Za-z0-9_]/, " ", line)
    n = split(line, w, " ")
    for (i = 1; i <= n; i++) hword[w[i]] = 1

    # public functions: "HFDEF <type> name(" (the name may follow on a
    # later line of the declaration)
    if ($0 ~ /^HFDEF /) { pending = "" ; in_decl = 1 }
    if (in_decl) {
        pending = pending " " $0
        if (index(pending, "(")) {
            head = substr(pending, 1, index(pending, "(") - 1)
            gsub(/[^A-Za-z0-9_]/, " ", head)
            n = split(head, w, " ")
            name = w[n]
            if (!(name in pubfn)) { pubfn[name] = 1; forder[++nfunc] = name }
            in_decl = 0
        }
    }

    # public types
    if ($0 ~ /^typedef (struct|enum) hf_[A-Za-z0-9_]+ *\{/ ||
        $0 ~ /^typedef struct hf_[A-Za-z0-9_]+ +hf_[A-Za-z0-9_]+ *;/) {
        t = $0
        sub(/^typedef (struct|enum) /, "", t)
        sub(/[^A-Za-z0-9_].*$/, "", t)
        if (!(t in type)) { type[t] = 1; torder[++ntype] = t }
    }

    # the result table: "#define HF_RESULT_TABLE(X)" and its continuation
    # lines, joined into one string
    if ($0 ~ /^#define HF_RESULT_TABLE\(X\)/) in_table = 1
    if (in_table) {
        l = $0
        more = (l ~ /\\$/)
        sub(/\\$/, "", l)
        table = table " " l
        if (!more) in_table = 0
    }
    next
}

# ---- api.md ---------------------------------------------------------------
{
    sub(/\r$/, "")
    docline[++ndoc] = $0

    # words, and the words directly followed by "("
    line = $0
    gsub(/[^A-Za-z0-9_(]/, " ", line)
    gsub(/\(/, "( ", line)
    n = split(line, w, " ")
    for (i = 1; i <= n; i++) {
        word = w[i]
        call = 0
        if (word ~ /\($/) { call = 1; sub(/\($/, "", word) }
        if (word == "") continue
        dword[word] = 1
        if (call) dcall[word] = 1
        if (call && word ~ /^hf_/ && !(word in dcall_line)) {
            dcall_line[word] = FNR; dcall_order[++ndcall] = word
        }
        if (word ~ /^(hf|HF)_/ && !(word in dword_line)) {
            dword_line[word] = FNR; dword_order[++ndword] = word
        }
    }

    # result table rows: first cell HF_OK or HF_ERROR_*
    if ($0 ~ /^[ \t]*\|/) {
        row = $0
        gsub(/\\\|/, "\001", row)          # an escaped | inside a cell
        sub(/^[ \t]*\|/, "", row)
        sub(/\|[ \t]*$/, "", row)
        n = split(row, c, "|")
        code = unquote(c[1])
        if (code ~ /^HF_(OK|ERROR_[A-Z0-9_]+)$/) {
            if (code in rvalue) {
                drift("result code " code " has two rows in the result table (lines " rline[code] " and " FNR ")")
                next
            }
            msg = ""
            for (i = 3; i <= n; i++) msg = msg (i > 3 ? "|" : "") c[i]
            gsub(/\001/, "|", msg)
            rvalue[code] = (n >= 2) ? unquote(c[2]) : ""
            rmsg[code] = trim(msg)
            rline[code] = FNR
            rorder[++nrow] = code
        }
    }
}

END {
    if (!hdr_done) {
        print "check_api_doc: " hdr ": no line \"#endif /* HAIRFUR_H */\"; cannot find the declaration half" > "/dev/stderr"
        exit 2
    }
    if (nfunc == 0) {
        print "check_api_doc: " hdr ": no \"HFDEF \" declarations found" > "/dev/stderr"
        exit 2
    }

    # parse the joined result table: X(NAME, VALUE, "msg" "msg" ...)
    s = table
    ncode = 0
    while (match(s, /X\([ \t]*HF_[A-Z0-9_]+[ \t]*,[ \t]*-?[0-9]+[ \t]*,[ \t]*("[^"]*"[ \t]*)+\)/)) {
        e = substr(s, RSTART + 2, RLENGTH - 3)
        s = substr(s, RSTART + RLENGTH)
        name = e; sub(/[ \t]*,.*$/, "", name); name = trim(name)
        rest = e; sub(/^[^,]*,/, "", rest)
        value = rest; sub(/,.*$/, "", value); value = trim(value)
        sub(/^[^,]*,/, "", rest)
        msg = ""
        while (match(rest, /"[^"]*"/)) {
            msg = msg substr(rest, RSTART + 1, RLENGTH - 2)
            rest = substr(rest, RSTART + RLENGTH)
        }
        hvalue[name] = value; hmsg[name] = msg; corder[++ncode] = name
    }
    if (ncode == 0) {
        print "check_api_doc: " hdr ": no entries found in HF_RESULT_TABLE(X)" > "/dev/stderr"
        exit 2
    }

    # (a) every public function is documented
    for (i = 1; i <= nfunc; i++) {
        f = forder[i]
        if (f in dcall) continue
        found = 0
        for (j = 1; j <= ndoc && !found; j++)
            if (index(docline[j], "`" f "`")) found = 1
        if (!found)
            drift(f " is declared in " hdr " but not documented (no \"" f "(\" or \"`" f "`\")")
    }

    # (b) every function api.md calls exists; every hf_/HF_ word exists
    for (i = 1; i <= ndcall; i++) {
        if (!((f = dcall_order[i]) in pubfn))
            drift("line " dcall_line[f] ": " f "() is not a public function of " hdr)
    }
    for (i = 1; i <= ndword; i++) {
        if (!((wd = dword_order[i]) in hword) && !(wd in rvalue) &&
            !((wd in dcall) && wd ~ /^hf_/))
            drift("line " dword_line[wd] ": " wd " does not occur in the declarations of " hdr)
    }

    # (c) the result table
    if (nrow == 0)
        drift("no result table found (rows like \"| HF_ERROR_BAD_FORMAT | -6 | message |\")")
    for (i = 1; i <= ncode; i++) {
        k = corder[i]
        if (!(k in rvalue)) {
            if (nrow) drift("result code " k " (" hvalue[k] ") is in " hdr " but missing from the result table")
            continue
        }
        if (rvalue[k] != hvalue[k])
            drift("line " rline[k] ": " k " has value " rvalue[k] " in the result table, " hdr " says " hvalue[k])
        if (rmsg[k] != hmsg[k])
            drift("line " rline[k] ": the message of " k " differs from " hdr "\n      " doc ": " rmsg[k] "\n      " hdr ": " hmsg[k])
    }
    for (i = 1; i <= nrow; i++)
        if (!(rorder[i] in hvalue))
            drift("line " rline[rorder[i]] ": result code " rorder[i] " is in the result table but not in HF_RESULT_TABLE of " hdr)

    # (d) every public type is named
    for (i = 1; i <= ntype; i++)
        if (!(torder[i] in dword))
            drift(torder[i] " is declared in " hdr " but not documented")

    if (ndrift) {
        print "check_api_doc: " ndrift " drift(s) between " doc " and " hdr
        exit 1
    }
    print "check_api_doc: " doc " agrees with " hdr " (" nfunc " functions, " ntype " types, " ncode " result codes)"
}
' "$HDR" "$API_DOC"
