// link_main.cpp - C++ caller of the C implementation in link_impl.c.
#include "../hairfur.h"
#include <cstdio>
#include <cstring>

int main()
{
    hf_rng r;
    hf_rng_seed(&r, 42u, 54u);
    if (hf_rng_u32(&r) != 0xa15c02b7u || hf_version() != HAIRFUR_VERSION_NUMBER ||
        std::strcmp(hf_result_string(HF_OK), "success") != 0) {
        std::printf("C++ -> C link check: wrong results\n");
        return 1;
    }
    std::printf("C++ -> C link check: ok\n");
    return 0;
}
