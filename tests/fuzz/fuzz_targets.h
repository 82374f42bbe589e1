/* fuzz_targets: entry points fed arbitrary bytes, by libFuzzer and by the replay test. */
#ifndef FUZZ_TARGETS_H
#define FUZZ_TARGETS_H

#include <stddef.h>
#include <stdint.h>

/* Each parses data as one kind of input and frees everything; it must never crash. */
int fuzz_job(const uint8_t *data, size_t size);
int fuzz_scene(const uint8_t *data, size_t size);
int fuzz_image(const uint8_t *data, size_t size);
int fuzz_summary(const uint8_t *data, size_t size); /* worker verdict's summary.csv reader */

#endif
