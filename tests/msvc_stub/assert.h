/* Declarations only, for the MSVC syntax check. */
#ifndef HF_STUB_ASSERT_H
#define HF_STUB_ASSERT_H
#define assert(x) ((void)(x))
#endif
