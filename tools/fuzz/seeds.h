/*
 * seeds.h - the fuzz target's seed corpus, generated (no binary files in
 * git): one program (program.h) per mode, gait, preset action and input the
 * board knows, plus bad input of every kind, so the fuzzer starts from
 * everywhere in the core rather than from the parser alone.
 */
#ifndef XGO_FUZZ_SEEDS_H
#define XGO_FUZZ_SEEDS_H

#include <stddef.h>
#include <stdint.h>

/* Seed number i into buf (cap bytes); returns its length, 0 past the last. */
size_t fuzz_seed(unsigned i, uint8_t *buf, size_t cap);

/* A short name of seed i for its file ("action-07", ...). */
const char *fuzz_seed_name(unsigned i, char *buf, size_t cap);

#endif /* XGO_FUZZ_SEEDS_H */
