/* gl_check.c - does headless EGL + OpenGL 3.3 core work here?
 * Exit 0 and print "OK: renderer | version | EGL path", or exit 1 and
 * print "SKIP: <what is missing>". The Makefile and tests use it to skip
 * GL checks with a reason. Needs no GLFW (built with GLC_NO_GLFW). */
#define GLC_NO_GLFW
#define GLC_IMPLEMENTATION
#include "gl_common.h"

#include <stdio.h>

int main(void)
{
    char info[1024];
    if (!glc_probe_headless(info, sizeof info)) {
        printf("SKIP: %s\n", info);
        return 1;
    }
    printf("OK: %s\n", info);
    return 0;
}
