/* The host C test of the C API: checks.c against the host build of ppoe-ffi's staticlib,
 * compiled as strict C99 (examples/c-firmware/build.sh). Exit status 0 if all passed. */
#include <stdarg.h>
#include <stdio.h>

#include "checks.h"

void report(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
}

int main(void) {
    int failures = check_cases() + check_errors();
    printf("RESULT: %s\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}
