/* device_port.c - the fuzz target's port (see device_port.h). */
#include "device_port.h"

#include <string.h>

#include "promises.h"


uint32_t xgo_port_millis(xgo_port_t *port)
{
    return port->now_ms;
}

size_t xgo_port_tx_room(xgo_port_t *port)
{
    return FUZZ_PORT_OUT_CAP - port->out_len;
}

void xgo_port_tx_write(xgo_port_t *port, const uint8_t *bytes, size_t n)
{
    fuzz_check(n <= FUZZ_PORT_OUT_CAP - port->out_len, "the device wrote past the room it was given");
    memcpy(port->out + port->out_len, bytes, n);
    port->out_len += n;
}

void xgo_port_rx_resume(xgo_port_t *port)
{
    (void)port;
}

int xgo_port_nv_load(xgo_port_t *port, xgo_board_nv_t *nv)
{
    unsigned i;
    (void)port;
    memset(nv, 0, sizeof *nv);
    memcpy(nv->bt_name, "FUZZ", 4);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        nv->zero_offset_mdeg[i] = (int32_t)i * 100 - 600;
    }
    return 1;
}

int xgo_port_nv_save(xgo_port_t *port, const xgo_board_nv_t *nv)
{
    (void)nv;
    return (port->saves++ & 1u) == 0; /* every second save fails */
}

void xgo_port_servo_write(xgo_port_t *port, const int32_t raw_mdeg[XGO_SERVO_COUNT],
                          uint16_t limp)
{
    fuzz_check(limp < (1u << XGO_SERVO_COUNT), "limp mask");
    memcpy(port->servo_raw_mdeg, raw_mdeg, sizeof port->servo_raw_mdeg);
    port->servo_limp = limp;
}

void fuzz_device_init(xgo_device_t *d, xgo_port_t *port, const xgo_board_config_t *cfg)
{
    memset(port, 0, sizeof *port);
    xgo_device_init(d, port, cfg);
}

void fuzz_device_receive(xgo_device_t *d, const uint8_t *bytes, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (!xgo_device_rx_accepting(d)) {
            xgo_device_run(d); /* the ring is full: the main loop drains it */
        }
        fuzz_check(xgo_device_rx_accepting(d), "the ring stays full with the port's room free");
        (void)xgo_device_rx_put(d, bytes[i]);
    }
    xgo_device_run(d);
}

void fuzz_device_tick(xgo_device_t *d)
{
    d->port->now_ms += 1000u / XGO_TICK_HZ;
    xgo_device_tick_due(d);
    xgo_device_run(d);
    (void)xgo_device_idle(d);
}

size_t fuzz_device_output(xgo_device_t *d, uint8_t *out, size_t cap)
{
    xgo_port_t *port = d->port;
    size_t n = port->out_len < cap ? port->out_len : cap;
    memcpy(out, port->out, n);
    memmove(port->out, port->out + n, port->out_len - n);
    port->out_len -= n;
    return n;
}
