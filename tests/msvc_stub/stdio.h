/* Declarations only, for the MSVC syntax check. */
#ifndef HF_STUB_STDIO_H
#define HF_STUB_STDIO_H
#include <stdarg.h>
#include <stddef.h>
int vsnprintf(char *, size_t, const char *, va_list);
int snprintf(char *, size_t, const char *, ...);
int printf(const char *, ...);
#endif
