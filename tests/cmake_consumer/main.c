/* A program that uses hairfur.h as a user's project does: found by the
   build system (CMake's hairfur::hairfur or pkg-config's hairfur), so the
   header is included as <hairfur.h>. Prints the version and the ropes'
   default gravity, damping and sub-step. */
#define HAIRFUR_IMPLEMENTATION /* in exactly one .c or .cpp file */
#include <hairfur.h>
#include <stdio.h>
#include <string.h>

int main(void)
{
    hf_rope_params params;
    hf_rope_params_init(&params);
    printf("cmake_consumer: hairfur %s (%d), gravity %g, damping %g, "
           "substep %g s\n",
           hf_version_string(), hf_version(), (double)params.gravity[1],
           (double)params.damping, (double)params.substep);
    /* the implementation compiled here is the header's */
    if (strcmp(hf_version_string(), HAIRFUR_VERSION_STRING) != 0 ||
        hf_version() != HAIRFUR_VERSION_NUMBER || params.gravity[1] >= 0.0f)
        return 1;
    return 0;
}
