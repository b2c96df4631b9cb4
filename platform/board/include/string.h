/* platform/board/include/string.h — the board build's <string.h>: the four functions
 * platform/board/libc_min.c defines (core/ and raster/ use memcpy, memset and memmove),
 * so the build needs no C library's headers (mk/mcu.sh puts this folder first with
 * -isystem; GCC's own freestanding headers give stddef.h, stdint.h and limits.h). */
#ifndef BR_BOARD_STRING_H
#define BR_BOARD_STRING_H
#include <stddef.h>

void *memcpy(void *restrict d, const void *restrict s, size_t n);
void *memmove(void *d, const void *s, size_t n);
void *memset(void *d, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);

#endif
