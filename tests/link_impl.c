/* link_impl.c - the implementation compiled as C; link_main.cpp calls it
   from C++. Proves the extern "C" declarations link. */
#define HAIRFUR_IMPLEMENTATION
#include "../hairfur.h"
