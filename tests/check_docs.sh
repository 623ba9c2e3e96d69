#!/bin/sh
# tests/check_docs.sh: do README.md and docs/*.md agree with the code?
#
# Run from the repository root:   sh tests/check_docs.sh
# (make doc-check; part of make check and make test). CC names the
# compiler (default gcc); BUILD the folder for the generated file (build).
#
# Checks, each printing one line per drift:
#   (a) names: every hf_, hf__ and HF_ word of README.md and docs/*.md
#       occurs in hairfur.h (a word ending in "_", as in `hf_color3d_*`,
#       begins one), but for the few listed in OTHER_NAMES below, which
#       must occur in the file named there. docs/performance-log.md is
#       left out: its dated runs name the code as it was then.
#   (b) struct listings: every "typedef struct hf_x {" or "typedef enum
#       hf_x {" in a ```c block has the header's fields, in its order
#       (comments and spacing aside).
#   (c) code: every other ```c block compiles against the header's
#       declarations (C99, strict warnings; unused names allowed), each as
#       the body of a function of its own, behind a #line directive so
#       messages name the markdown file. A block's free variables are
#       declared in an HTML comment right above it, which readers do not
#       see:  <!-- c: hf_fur *fur; hf_fur_info info; -->
#       GL calls compile against the stand-in declarations below. The
#       README's Quick start is left to make quickstart (a whole program).
#   (d) commands: in ```sh blocks and in `make ...` quotes, every make
#       target is one of the Makefile's, and every build/NAME a program
#       of examples/ or tests/.
#   (e) the stack: the per-call figures of docs/frame.md and the most the
#       Makefile's test stack comment names are the header's.
#   (f) links: every relative link names a file there, and a heading
#       there when it names one.
#   (g) the hair shader: docs/luts.md links examples/hair_shading.glsl,
#       the one text gl_marschner reads and the web page is built with.
# Exits 1 on any drift, 2 when a file is missing; 0 otherwise.
# POSIX sh and awk, and a C compiler.

HDR=hairfur.h
CC=${CC:-gcc}
BUILD=${BUILD:-build}
# names a document may use that hairfur.h does not define: name, and the
# file that defines it
OTHER_NAMES="HF_TEST_SIMD_LEVEL:tests/test_hairfur.c
HF_POINTS_COMPACT:examples/ribbon_expand.glsl"

DOCS="README.md $(ls docs/*.md | grep -v '^docs/performance-log\.md$')"
for f in $HDR $DOCS Makefile docs/frame.md; do
    [ -r "$f" ] || { echo "check_docs: cannot read $f (run from the repository root)" >&2; exit 2; }
done
mkdir -p "$BUILD" || exit 2
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
drift=0
say() { echo "check_docs: $*"; drift=$((drift + 1)); }

# ---- (a) names --------------------------------------------------------------
grep -ohE '\b(hf|HF)_[A-Za-z0-9_]*' $HDR | sort -u > "$tmp/hdr_names"
for f in $DOCS; do
    grep -noE '\b(hf|HF)_[A-Za-z0-9_]*' "$f" | sed "s|^|$f:|"
done > "$tmp/doc_names"
while IFS=: read -r file line name; do
    case $name in
    *_) grep -q "^$name" "$tmp/hdr_names" && continue ;;
    *) grep -qx "$name" "$tmp/hdr_names" && continue ;;
    esac
    other=$(printf '%s\n' "$OTHER_NAMES" | sed -n "s/^$name://p")
    if [ -n "$other" ]; then
        grep -qw "$name" "$other" && continue
        say "$file:$line: $name is not in $other"
        continue
    fi
    say "$file:$line: $name is not in $HDR"
done < "$tmp/doc_names"

# ---- the ```c blocks: listings into $tmp/listings, code into doc_blocks.c --
awk -v tmp="$tmp" '
function flush_listing() { }
FNR == 1 { state = 0; ctx = ""; inctx = 0; quick = 0; qdone = 0 }
# the README quick start: its first ```c block is checked elsewhere
FILENAME == "README.md" && /^## Quick start[ \t]*$/ { quick = 1 }
FILENAME == "README.md" && /^## / && !/^## Quick start/ { quick = 0 }
state == 0 && /^<!-- c:/ { inctx = 1; ctx = ""; ctxline = FNR }
state == 0 && inctx {
    l = $0; sub(/^<!-- c:/, "", l); e = sub(/-->[ \t]*$/, "", l)
    ctx = ctx l "\n"; if (e) inctx = 0; next
}
state == 0 && /^```c[ \t]*$/ {
    state = 1; start = FNR + 1; body = ""; nb++
    skip = quick && !qdone; if (quick) qdone = 1
    next
}
state == 0 && !/^[ \t]*$/ { ctx = "" }
state == 1 && /^```[ \t]*$/ {
    state = 0
    if (skip) { ctx = ""; next }
    if (body ~ /typedef (struct|enum) hf_[A-Za-z0-9_]+ *\{/) {
        printf "%s\t%d\n", FILENAME, start > (tmp "/listing_files")
        printf "@@ %s %d\n%s", FILENAME, start, body > (tmp "/listings")
    } else {
        n++
        printf "static void doc_block_%d(void)\n{\n", n > (tmp "/blocks.c")
        if (ctx != "")
            printf "#line %d \"%s\"\n%s", ctxline, FILENAME, ctx > (tmp "/blocks.c")
        printf "#line %d \"%s\"\n%s}\n\n", start, FILENAME, body > (tmp "/blocks.c")
    }
    ctx = ""
    next
}
state == 1 { body = body $0 "\n" }
END { printf "%d\n", n > (tmp "/nblocks") }
' $DOCS
: >> "$tmp/blocks.c"; : >> "$tmp/listings"

# ---- (b) struct listings against the header ------------------------------------
# Each typedef of a listing and of the header, comments and spacing
# removed, one per line: "NAME<TAB>text".
norm_typedefs='
{ text = text $0 "\n" }
END {
    gsub(/\/\*([^*]|\*+[^*\/])*\*+\//, " ", text)   # comments
    gsub(/[ \t\n]+/, " ", text)
    while (match(text, /typedef (struct|enum) hf_[A-Za-z0-9_]+ *\{[^}]*\} *hf_[A-Za-z0-9_]+ *;/)) {
        t = substr(text, RSTART, RLENGTH); text = substr(text, RSTART + RLENGTH)
        name = t; sub(/;$/, "", name); sub(/.*\} */, "", name); sub(/ +$/, "", name)
        gsub(/ *([{};,=\[\]()*]) */, "&", t); gsub(/ *\{ */, "{", t)
        gsub(/ *\} */, "}", t); gsub(/ *; */, ";", t); gsub(/ *, */, ",", t)
        gsub(/ *= */, "=", t); gsub(/ *\* */, "*", t)
        print name "\t" t
    }
}'
sed -n '1,/^#endif \/\* HAIRFUR_H \*\//p' $HDR | awk "$norm_typedefs" > "$tmp/hdr_typedefs"
awk '/^@@ /{ if (out) close(out); out = FILENAME ".part" ++k; print $2 ":" $3 > (FILENAME ".where" k); next } { print > out }' \
    "$tmp/listings"
for part in "$tmp"/listings.part*; do
    [ -f "$part" ] || continue
    where=$(cat "$tmp/listings.where${part##*.part}")
    awk "$norm_typedefs" "$part" | while IFS='	' read -r name text; do
        h=$(awk -F'\t' -v n="$name" '$1 == n { print $2 }' "$tmp/hdr_typedefs")
        if [ -z "$h" ]; then echo "$where: $name: no such typedef in $HDR"
        elif [ "$h" != "$text" ]; then
            echo "$where: $name differs from $HDR (comments aside):"
            echo "      doc: $text"
            echo "      hdr: $h"
        fi
    done
done > "$tmp/listing_drift"
[ -s "$tmp/listing_drift" ] && { sed 's/^/check_docs: /' "$tmp/listing_drift"; drift=$((drift + 1)); }

# ---- (c) the code blocks, compiled ---------------------------------------------
out=$BUILD/doc_blocks.c
{
    echo '/* generated by tests/check_docs.sh from the C blocks of README.md'
    echo '   and docs: each block the body of a function */'
    echo '#include "hairfur.h"'
    echo '#include <stdint.h>'
    echo '#include <stdlib.h>'
    echo '#include <string.h>'
    echo '/* GL stand-ins: the calls the blocks make, typed as GL types them */'
    echo 'typedef unsigned GLenum, GLuint, GLbitfield; typedef int GLint, GLsizei;'
    echo 'typedef float GLfloat; typedef long GLintptr, GLsizeiptr;'
    echo 'typedef unsigned char GLboolean; typedef char GLchar;'
    echo 'enum { GL_ARRAY_BUFFER = 1, GL_COPY_READ_BUFFER, GL_TEXTURE_BUFFER,'
    echo '       GL_ELEMENT_ARRAY_BUFFER, GL_TEXTURE_2D, GL_RGBA32F, GL_RGBA16I,'
    echo '       GL_RGBA, GL_FLOAT, GL_SHORT, GL_UNSIGNED_SHORT, GL_BYTE,'
    echo '       GL_UNSIGNED_INT, GL_TRIANGLES, GL_STREAM_DRAW, GL_STATIC_DRAW,'
    echo '       GL_DYNAMIC_COPY, GL_MAP_WRITE_BIT, GL_MAP_INVALIDATE_BUFFER_BIT,'
    echo '       GL_TRUE = 1 };'
    echo 'void glBindBuffer(GLenum, GLuint);'
    echo 'void glBufferData(GLenum, GLsizeiptr, const void *, GLenum);'
    echo 'void glBufferSubData(GLenum, GLintptr, GLsizeiptr, const void *);'
    echo 'void *glMapBufferRange(GLenum, GLintptr, GLsizeiptr, GLbitfield);'
    echo 'GLboolean glUnmapBuffer(GLenum);'
    echo 'void glCopyBufferSubData(GLenum, GLenum, GLintptr, GLintptr, GLsizeiptr);'
    echo 'void glBindTexture(GLenum, GLuint);'
    echo 'void glTexBuffer(GLenum, GLenum, GLuint);'
    echo 'void glTexImage2D(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum,'
    echo '                  GLenum, const void *);'
    echo 'void glBindVertexArray(GLuint);'
    echo 'void glVertexAttribPointer(GLuint, GLint, GLenum, GLboolean, GLsizei,'
    echo '                           const void *);'
    echo 'void glDrawElements(GLenum, GLsizei, GLenum, const void *);'
    echo 'GLint glGetUniformLocation(GLuint, const GLchar *);'
    echo 'void glUniform1f(GLint, GLfloat);'
    echo 'void glUniform3fv(GLint, GLsizei, const GLfloat *);'
    echo
    cat "$tmp/blocks.c"
} > "$out.tmp"
if cmp -s "$out.tmp" "$out"; then rm -f "$out.tmp"; else mv "$out.tmp" "$out"; fi
if ! $CC -std=c99 -fsyntax-only -Wall -Wextra -Wpedantic -Werror -Wno-unused \
        -Wno-unused-parameter -I. "$out" > "$tmp/cc.log" 2>&1; then
    say "a code block does not compile ($CC, C99; the blocks are in $out):"
    sed -n '1,40s/^/    /p' "$tmp/cc.log"
fi

# ---- (d) make targets and programs named -----------------------------------------
targets=$(grep -oE '^[a-z][a-z0-9_-]*:' Makefile | tr -d :)
for f in $DOCS; do
    awk '
    /^```/ { insh = !insh && /^```sh[ \t]*$/; next }
    {
        l = $0
        if (!insh) {   # only quoted commands outside ```sh blocks
            q = ""
            while (match(l, /`make [^`]*`/)) {
                q = q " " substr(l, RSTART + 1, RLENGTH - 2); l = substr(l, RSTART + RLENGTH)
            }
            l = q
        }
        while (match(l, /(^|[ \t;&(])make( +[A-Za-z0-9_\/.=$(){}"-]+)+/)) {
            m = substr(l, RSTART, RLENGTH); l = substr(l, RSTART + RLENGTH)
            n = split(m, w, / +/)
            for (i = 1; i <= n; i++) {
                if (w[i] ~ /make$/ || w[i] == "" || w[i] ~ /^-/ || w[i] ~ /=/) continue
                if (w[i] !~ /^[a-z][a-z0-9_\/-]*$/) break
                print FNR "\t" w[i]
            }
        }
        l = $0
        while (insh && match(l, /(^|[ \t])build\/[a-z0-9_]+/)) {
            m = substr(l, RSTART, RLENGTH); l = substr(l, RSTART + RLENGTH)
            sub(/^[ \t]/, "", m); print FNR "\t" m
        }
    }' "$f" | while IFS='	' read -r line word; do
        case $word in
        build/*)
            prog=${word#build/}
            [ -f "examples/$prog.c" ] || [ -f "tests/$prog.c" ] ||
                grep -q "(BUILD)/$prog\b" Makefile ||
                echo "$f:$line: $word: no such program in examples/ or tests/" ;;
        *)
            printf '%s\n' "$targets" | grep -qx -- "$word" ||
                echo "$f:$line: make $word: no such target in the Makefile" ;;
        esac
    done
done > "$tmp/cmd_drift"
[ -s "$tmp/cmd_drift" ] && { sed 's/^/check_docs: /' "$tmp/cmd_drift"; drift=$((drift + 1)); }

# ---- (e) the stack figures ---------------------------------------------------------
# The header's paragraph "Stack (gcc, x86-64, ..." against docs/frame.md's
# "Each call's stack is bounded" and the Makefile's "about N KiB at most".
hdr_stack=$(sed -n '/^       - Stack (gcc/,/make test runs its native builds/p' $HDR | tr '\n' ' ' | tr -s ' ')
doc_stack=$(sed -n "/^Each call's stack is bounded/,/its native builds on a/p" docs/frame.md | tr '\n' ' ' | tr -s ' ')
[ -n "$hdr_stack" ] || say "$HDR: no paragraph \"- Stack (gcc\" (its stack figures)"
[ -n "$doc_stack" ] || say "docs/frame.md: no paragraph \"Each call's stack is bounded\""
fig() { printf '%s\n' "$1" | sed -n "s/.*$2.*/\1/p"; }
if [ -n "$hdr_stack" ] && [ -n "$doc_stack" ]; then
    for pair in \
        "hf_fur_ribbons:hf_fur_ribbons about \([0-9]*\) KiB:\`hf_fur_ribbons\` needs about \([0-9]*\) KiB" \
        "hf_fur_simulate:hf_fur_simulate about \([0-9]*\) KiB:\`hf_fur_simulate\` about \([0-9]*\) KiB" \
        "hf_fur_simulate at -O0:hf_fur_simulate about [0-9]* KiB[^(]*(\([0-9]*\) at -O0:\`hf_fur_simulate\` about [0-9]* KiB[^(]*(\([0-9]*\) at \`-O0\`" \
        "hf_fur_interpolate_points:hf_fur_interpolate_points \([0-9]*\) KiB:\`hf_fur_interpolate_points\` \([0-9]*\)" \
        "hf_fur_interpolate_points at -O0:hf_fur_interpolate_points [0-9]* KiB (\([0-9]*\) at -O0:\`hf_fur_interpolate_points\` [0-9]* (\([0-9]*\) at \`-O0\`" \
        "compact points:(23 at -O0; \([0-9]* and [0-9]*\) for compact:\`-O0\`; \([0-9]* and [0-9]*\) with compact" \
        "the other calls:per-frame calls under \([0-9]*\) KiB:the rest under \([0-9]*\) KiB"
    do
        what=${pair%%:*}; rest=${pair#*:}
        h=$(fig "$hdr_stack" "${rest%%:*}"); d=$(fig "$doc_stack" "${rest#*:}")
        if [ -z "$h" ] || [ -z "$d" ]; then
            say "the stack of $what: not found in $HDR ('${h:-?}') or docs/frame.md ('${d:-?}')"
        elif [ "$h" != "$d" ]; then
            say "the stack of $what: $HDR says $h KiB, docs/frame.md $d"
        fi
    done
    most=$(printf '%s\n' "$hdr_stack" | grep -oE '[0-9]+ at -O0' | sort -n | tail -n 1 | cut -d' ' -f1)
    mk=$(sed -n 's/.*per-frame calls about \([0-9]*\) KiB at most.*/\1/p' Makefile)
    [ "$most" = "$mk" ] ||
        say "Makefile: its test stack comment says ${mk:-?} KiB at most, $HDR ${most:-?} (at -O0)"
fi

# ---- (f) links ---------------------------------------------------------------------
# Every relative link [text](path#anchor) of README.md and docs/*.md (the
# log too) names a file that exists and, in a markdown file, a heading
# whose anchor (GitHub's: lower case, punctuation dropped, spaces to
# hyphens) is the one given.
for f in README.md docs/*.md; do
    dir=$(dirname "$f")
    grep -noE '\]\([^)# ]*(#[^) ]*)?\)' "$f" | while IFS=: read -r line link; do
        target=${link#](}; target=${target%)}
        path=${target%%#*}; anchor=
        case $target in *'#'*) anchor=${target#*#} ;; esac
        case $path in http:*|https:*|mailto:*) continue ;; esac
        [ -n "$path" ] && file="$dir/$path" || file=$f
        if [ ! -e "$file" ]; then echo "$f:$line: link to $path: no such file"; continue; fi
        [ -n "$anchor" ] || continue
        case $file in *.md) ;; *) continue ;; esac
        awk -v a="$anchor" '
            /^```/ { code = !code; next }
            !code && /^#+ / {
                h = $0; sub(/^#+ +/, "", h); h = tolower(h)
                gsub(/[^a-z0-9 _-]/, "", h); gsub(/ /, "-", h)
                if (h == a) found = 1
            }
            END { exit !found }' "$file" ||
            echo "$f:$line: link to $target: no such heading in $file"
    done
done > "$tmp/link_drift"
[ -s "$tmp/link_drift" ] && { sed 's/^/check_docs: /' "$tmp/link_drift"; drift=$((drift + 1)); }

# ---- (g) the hair shader -----------------------------------------------------
# docs/luts.md shows no copy of the examples' hair shader but points to it:
# it links examples/hair_shading.glsl, which gl_marschner reads and the
# web page's build (the Makefile) turns into a C array.
SHADING=examples/hair_shading.glsl
grep -q "](../$SHADING)" docs/luts.md ||
    say "docs/luts.md: no link to $SHADING (the examples' hair shader)"
grep -q "\"$SHADING\"" examples/gl_marschner.c ||
    say "examples/gl_marschner.c does not read $SHADING"
grep -q "^\$(WEB_DIR)/hair_shading_glsl.h: $SHADING" Makefile ||
    say "Makefile: the web page is not built from $SHADING"

if [ $drift -ne 0 ]; then
    echo "check_docs: drift between the docs and the code"
    exit 1
fi
echo "check_docs: README.md and docs/*.md agree with the code" \
     "($(cat "$tmp/nblocks") code blocks compiled, $(grep -c . "$tmp/listing_files" 2>/dev/null || echo 0) struct listings)"
