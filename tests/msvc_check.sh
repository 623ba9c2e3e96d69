#!/bin/sh
# msvc_check.sh - the header's MSVC branches, checked without MSVC: clang
# as MSVC (--target=x86_64-pc-windows-msvc, -fms-extensions
# -fms-compatibility, __clang__ undefined so the header takes its _MSC_VER
# branch), syntax only, C99 and C++14, the implementation included. MSVC's
# CRT headers are not on this machine: tests/msvc_stub/ declares the few C
# library functions the header uses, and clang's own headers give stdint.h,
# stdarg.h and the SSE2 intrinsics. What it proves: the header's compiler
# words (HF__INLINE as __forceinline, HF__RESTRICT as __restrict,
# __declspec(noinline)), its SSE2 path (_M_X64) and its CPUID dispatch
# (__cpuid, __cpuidex, _xgetbv, the AVX kernels) parse as MSVC-flavoured
# C and C++, and no GNU-only word (__attribute__, __builtin_*, ...) reaches
# MSVC from the header. What it does not: MSVC's own front end, its CRT or
# its code generation (unverified).
set -u
CLANG=${CLANG:-clang}
if ! command -v "$CLANG" >/dev/null 2>&1; then
    echo "msvc_check: skipped: no clang (make deps)"; exit 0
fi
RES=$("$CLANG" -print-resource-dir)/include
src=${TMPDIR:-/tmp}/hf_msvc_check_$$.c
printf '#define HAIRFUR_IMPLEMENTATION\n#include "hairfur.h"\nint main(void) { return hf_version() > 0 ? 0 : 1; }\n' >"$src"
# clang's immintrin.h, in MSVC mode, declares the AVX types and intrinsics
# only for a target that has them (MSVC's always does): -mavx2 -mavx512f
# -mavx512bw let it parse the run-time dispatched kernels
AVX="-mavx2 -mavx512f -mavx512bw"
fail=0
for lang in "c -std=c99" "c++ -std=c++14"; do
    # shellcheck disable=SC2086
    if out=$("$CLANG" --target=x86_64-pc-windows-msvc -fms-extensions \
            -fms-compatibility -fsyntax-only -Wall -Wextra $AVX \
            -Wno-builtin-macro-redefined -Wno-unused-function -U__clang__ \
            -nostdlibinc -isystem tests/msvc_stub -isystem "$RES" -I. \
            -Werror -x $lang "$src" 2>&1); then
        echo "msvc_check: ${lang%% *}: the header parses as MSVC-flavoured ${lang%% *}"
    else
        echo "msvc_check: ${lang%% *}: FAILED"; echo "$out" | head -20; fail=1
    fi
done
# clang accepts GNU extensions in MSVC mode, so also look at what the
# header itself hands MSVC: its own preprocessed lines must hold no GNU-only
# word (__attribute__, __builtin_*, __inline__, typeof, statement
# expressions' "({"); va_start and _mm_shuffle_ps expand to __builtin_
# calls from the system's own macros, and are left out
gnu=$("$CLANG" --target=x86_64-pc-windows-msvc -fms-extensions \
        -fms-compatibility -Wno-builtin-macro-redefined -U__clang__ \
        -nostdlibinc -isystem tests/msvc_stub -isystem "$RES" -I. -E "$src" 2>/dev/null |
      awk '/^# [0-9]+ "/ { mine = ($3 == "\"./hairfur.h\"") ; next } mine' |
      grep -E '__attribute__|__builtin_|__inline__|typeof|\(\{' |
      grep -vE '__builtin_va_(start|end)|__builtin_ia32_' | head -5)
if [ -n "$gnu" ]; then
    echo "msvc_check: GNU-only words reach MSVC from hairfur.h:"; echo "$gnu"; fail=1
else
    echo "msvc_check: no GNU-only word in what hairfur.h gives MSVC"
fi
rm -f "$src"
exit $fail
