/* Vector table of the C firmware (Cortex-M): initial stack pointer, reset, and every other
 * exception to Default_Handler (which exits QEMU with a failure). */
    .syntax unified
    .thumb
    .section .isr_vector, "a"
    .global vectors
vectors:
    .word _estack
    .word Reset_Handler
    .rept 14
    .word Default_Handler
    .endr
