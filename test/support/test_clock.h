/*
 * test_clock.h - monotonic time and sleeping for the programs that drive
 * xgo-emu in real time (test_pty_integration, test_host_state, bench_latency).
 *
 * Every wait in those programs is bounded by a deadline on this clock, so a
 * broken emulator makes them fail instead of hang.
 */
#ifndef XGO_TEST_CLOCK_H
#define XGO_TEST_CLOCK_H

/* CLOCK_MONOTONIC in whole milliseconds / whole microseconds (deadlines). */
long long xgo_test_now_ms(void);
long long xgo_test_now_us(void);

/* CLOCK_MONOTONIC in microseconds with the nanoseconds kept (latencies). */
double xgo_test_now_us_f(void);

/* Sleeps the whole time, resuming after a signal interrupts it. */
void xgo_test_sleep_ms(long ms);
void xgo_test_sleep_us(long us);

#endif /* XGO_TEST_CLOCK_H */
