/* setjmp.h stub for tests/msvc_check.sh: clang's intrin.h includes it. */
#ifndef HF_MSVC_STUB_SETJMP_H
#define HF_MSVC_STUB_SETJMP_H
typedef int jmp_buf[16];
#endif
