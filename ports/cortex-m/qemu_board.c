/*
 * qemu_board.c - the port functions every QEMU port implements the same way
 * (see qemu_board.h).
 */
#include "qemu_board.h"

int xgo_port_nv_load(xgo_port_t *p, xgo_board_nv_t *nv)
{
    return xgo_nv_file_load(&xgo_port_qemu_board(p)->nv, nv);
}

int xgo_port_nv_save(xgo_port_t *p, const xgo_board_nv_t *nv)
{
    return xgo_nv_file_save(&xgo_port_qemu_board(p)->nv, nv);
}

void xgo_port_servo_write(xgo_port_t *p, const int32_t raw_mdeg[XGO_SERVO_COUNT], uint16_t limp)
{
    xgo_qemu_board_t *q = xgo_port_qemu_board(p);
    unsigned i;
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        q->servo_raw_mdeg[i] = raw_mdeg[i];
    }
    q->servo_limp = limp;
}
