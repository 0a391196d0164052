/*
 * semihost.h - the two services the bare-metal self test needs from its host:
 * write a string, exit with a code.
 *
 * On the MCU (semihost.c) they are ARM semihosting calls (BKPT 0xAB), which
 * QEMU answers with -semihosting-config enable=on: SYS_WRITE0 and
 * SYS_EXIT_EXTENDED, whose code becomes QEMU's exit status. The host variant
 * of the same program (host_port.c) writes to stdout and calls exit().
 */
#ifndef MCU_SEMIHOST_H
#define MCU_SEMIHOST_H

/* Write a NUL-terminated string. */
void sh_write0(const char *s);

/* End the program; code is the exit status (0..255). Does not return. */
void sh_exit(int code);

#endif /* MCU_SEMIHOST_H */
