/*
 * qemu_board.h - what the QEMU ports (stm32f1, nrf51) share beyond the CPU:
 * non-volatile data in a host file (nv_file.h) and servo outputs kept for a
 * debugger (the emulated boards have no servo bus). A port embeds an
 * xgo_qemu_board_t in its struct xgo_port_s and returns it from
 * xgo_port_qemu_board(); qemu_board.c implements xgo_port_nv_load,
 * xgo_port_nv_save and xgo_port_servo_write on it.
 */
#ifndef XGO_PORT_QEMU_BOARD_H
#define XGO_PORT_QEMU_BOARD_H

#include "nv_file.h"
#include "xgo/port.h"

typedef struct xgo_qemu_board_s {
    xgo_nv_file_t nv;
    int32_t servo_raw_mdeg[XGO_SERVO_COUNT]; /* the last servo outputs */
    uint16_t servo_limp;
} xgo_qemu_board_t;

/* Implemented by the port: its embedded xgo_qemu_board_t. */
xgo_qemu_board_t *xgo_port_qemu_board(xgo_port_t *port);

#endif /* XGO_PORT_QEMU_BOARD_H */
