/* The C firmware: the C API of ppoe (ppoe-ffi's staticlib) on a Cortex-M4F in QEMU
 * (mps2-an386), linked with newlib. Runs the checks of checks.c (the Rust firmware's cases:
 * f64 within 1e-12 and f32 within 1e-5 of the host, every status code), then measures one
 * PPOE call (SysTick under -icount, stack high-water) in the Rust firmware's output format,
 * and exits QEMU through semihosting: status 0 if everything passed, 1 otherwise. */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "checks.h"
#include "expected.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define CPACR (*(volatile uint32_t *)0xE000ED88u)

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, __heap_limit;
int main(void);
void Reset_Handler(void);
void Default_Handler(void);

/* A semihosting call (bkpt 0xab): r0 = operation, r1 = argument. */
static uint32_t semihost(uint32_t op, const void *arg) {
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static void fw_exit(int ok) {
    /* SYS_EXIT with ADP_Stopped_ApplicationExit (QEMU: status 0) or RunTimeErrorUnknown (1). */
    semihost(0x18, (const void *)(uintptr_t)(ok ? 0x20026u : 0x20023u));
    for (;;) {
    }
}

void report(const char *fmt, ...) {
    char buf[256];
    va_list ap;
    size_t n;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf - 1, fmt, ap);
    va_end(ap);
    n = strlen(buf);
    buf[n] = '\n';
    buf[n + 1] = '\0';
    semihost(0x04, buf); /* SYS_WRITE0 */
}

void Default_Handler(void) {
    report("fault");
    fw_exit(0);
}

void Reset_Handler(void) {
    uint32_t *src = &_sidata, *dst;
    for (dst = &_sdata; dst < &_edata;) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss;) {
        *dst++ = 0;
    }
    CPACR |= 0xFu << 20; /* CP10, CP11: the FPU */
    __asm__ volatile("dsb\n isb" ::: "memory");
    fw_exit(main() == 0);
}

/* SysTick ticks (core clock, 24 bits) for `reps` PPOE calls in f32 or f64. */
static uint32_t ticks(int f64, uint32_t reps) {
    static float th32[6], covs32[6 * 36], pose32[16], cov32[36];
    static double pose[16], cov[36];
    uint32_t s0, s1, i;
    for (i = 0; i < 6 * 36; i++) {
        covs32[i] = (float)CASES[0].covs[i];
        th32[i % 6] = (float)CASES[0].thetas[i % 6];
    }
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 5u; /* enable, core clock */
    s0 = SYST_CVR;
    for (i = 0; i < reps; i++) {
        if (f64) {
            ppoe_seed_f64(CASES[0].thetas, CASES[0].covs, pose, cov);
        } else {
            ppoe_seed_f32(th32, covs32, pose32, cov32);
        }
    }
    s1 = SYST_CVR;
    SYST_CSR = 0;
    return (s0 - s1) & 0x00FFFFFFu;
}

#define PAINT 0x5AFEC0DEu

/* Stack bytes of one PPOE call (high-water below the caller): paint, call, scan. */
static __attribute__((noinline)) uint32_t stack_used(int f64) {
    static float th32[6], covs32[6 * 36], pose32[16], cov32[36];
    static double pose[16], cov[36];
    uint32_t sp, p;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (p = (uint32_t)(uintptr_t)&__heap_limit; p < sp - 256; p += 4) {
        *(volatile uint32_t *)(uintptr_t)p = PAINT;
    }
    if (f64) {
        ppoe_seed_f64(CASES[0].thetas, CASES[0].covs, pose, cov);
    } else {
        ppoe_seed_f32(th32, covs32, pose32, cov32);
    }
    for (p = (uint32_t)(uintptr_t)&__heap_limit;
         p < sp - 256 && *(volatile uint32_t *)(uintptr_t)p == PAINT; p += 4) {
    }
    return sp - p;
}

int main(void) {
    int failures;
    report("ppoe C firmware (C API, ppoe-ffi): seed robot, %d cases, f64 and f32", N_CASES);
    failures = check_cases() + check_errors();
    report("systick ticks per PPOE call: f32 %lu f64 %lu (x40 = instructions under qemu -icount "
           "shift=0 on mps2 boards; meaningless otherwise)",
           (unsigned long)(ticks(0, 16) / 16), (unsigned long)(ticks(1, 4) / 4));
    report("stack per PPOE call (high-water below the caller, inputs excluded): f32 %lu B, "
           "f64 %lu B",
           (unsigned long)stack_used(0), (unsigned long)stack_used(1));
    report("RESULT: %s", failures ? "FAIL" : "PASS");
    return failures;
}
