/*
 * semihost.h - ARM semihosting: services of the debugger (here QEMU, with
 * -semihosting-config enable=on) reached through BKPT 0xAB. The QEMU ports
 * use it for what the emulated chips lack: a console for fault reports, an
 * exit status, and a host file standing in for the flash page that keeps
 * the non-volatile data (nv_file.c). On a board without a debugger attached
 * BKPT faults: a port for real hardware does not link this file.
 */
#ifndef XGO_PORT_SEMIHOST_H
#define XGO_PORT_SEMIHOST_H

#include <stddef.h>

/* Writes a NUL-terminated string (QEMU: to its stderr). */
void xgo_sh_write0(const char *s);

/* Ends the program with an exit status (QEMU exits with it). */
void xgo_sh_exit(int code);

/* The command line (QEMU: -semihosting-config arg=... words joined by
 * spaces) into buf; returns 1, or 0 when there is none or it does not fit. */
int xgo_sh_cmdline(char *buf, size_t size);

/* Files on the host: open returns a handle or -1; mode "rb" or "wb". */
int xgo_sh_open(const char *path, const char *mode);
/* Both return the number of bytes transferred. */
size_t xgo_sh_read(int handle, void *buf, size_t n);
size_t xgo_sh_write(int handle, const void *buf, size_t n);
/* Returns 0 when the file was closed cleanly. */
int xgo_sh_close(int handle);

#endif /* XGO_PORT_SEMIHOST_H */
