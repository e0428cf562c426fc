/* The checks of the C API shared by the C firmware (main.c) and the host C test (host.c). */
#ifndef PPOE_C_CHECKS_H
#define PPOE_C_CHECKS_H

#include "ppoe.h"

/* One line of output (printf format, no trailing newline): provided by the platform. */
void report(const char *fmt, ...);

/* The seed robot's PPOE (right convention) through the C API, as symbols of their own
 * (instruction counts and code size are measured from them). */
ppoe_status ppoe_seed_f64(const double *thetas, const double *covs, double *pose, double *cov);
ppoe_status ppoe_seed_f32(const float *thetas, const float *covs, float *pose, float *cov);

/* Every test case in f64 (<= 1e-12 relative) and f32 (<= 1e-5), unchecked and checked,
 * and forward kinematics against the PPOE's pose; returns the number of failures. */
int check_cases(void);

/* Every status code the API can return, each provoked once; returns the number of
 * failures. */
int check_errors(void);

#endif
