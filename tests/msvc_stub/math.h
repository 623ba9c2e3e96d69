/* Declarations only, for the MSVC syntax check (tests/msvc_check.sh):
   what hairfur.h uses from <math.h>, as MSVC's CRT declares it. */
#ifndef HF_STUB_MATH_H
#define HF_STUB_MATH_H
double sqrt(double); float sqrtf(float); double floor(double); float floorf(float);
double ceil(double); double exp(double); double log(double); double pow(double, double);
double sin(double); double cos(double); double tan(double); double acos(double);
double asin(double); double atan(double); double atan2(double, double);
double fabs(double); float fabsf(float); double fmod(double, double);
float sinf(float); float cosf(float); float powf(float, float); float expf(float);
double cbrt(double);
#define HUGE_VAL (1e300 * 1e300)
#define INFINITY ((float)HUGE_VAL)
#define NAN ((float)(INFINITY * 0.0F))
#endif
