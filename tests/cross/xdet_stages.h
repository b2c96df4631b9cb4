/* tests/cross/xdet_stages.h — the stages of the determinism probe beyond shading
 * (bitree mesh, raster frame), each printing "name hash". */
#ifndef XDET_STAGES_H
#define XDET_STAGES_H
#include <stddef.h>
#include <stdint.h>
#include "core/hf.h"
uint32_t xdet_fnv(uint32_t h, const void *p, size_t n);
uint32_t xdet_fnv_i32(uint32_t h, int32_t v);
void xdet_stages(const hf *f);
#endif
