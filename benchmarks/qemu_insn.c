/* benchmarks/qemu_insn.c — a QEMU TCG plugin (user mode, QEMU 7.x plugin API version 1)
 * that counts executed guest instructions: the total, and per translation block (TB)
 * start address, so benchmarks/arm-count.sh can attribute the counts to the functions
 * of a static guest binary with `nm -n`.
 *
 *   qemu-arm -plugin ./qemu_insn.so,out=FILE ./prog args
 *   qemu-system-arm -M mps2-an385 ... -plugin ./qemu_insn.so,out=FILE   (one vCPU: make mcu)
 *
 * FILE (default: stderr) gets one line `total N` and then one line per distinct
 * (start address, instruction count) translation, `ADDR NINSN EXECS` (hex address,
 * decimal counts), sorted by address.  N = sum of NINSN * EXECS.
 *
 * How: at translation time every TB gets an inline "add 1" on its entry's execution
 * counter (QEMU_PLUGIN_INLINE_ADD_U64: no helper call, so deterministic and cheap).
 * A TB executes whole unless the guest faults inside it (this harness does not), so
 * entries * instructions is the executed count.  QEMU may translate the same address
 * again (the code cache is flushed, or a TB is cut short); entries are keyed by
 * (address, length), so a re-translation of the same block shares its counter and a
 * differently cut one gets its own.  Inline adds are not atomic: single-threaded
 * guests only.
 *
 * QEMU does not install its plugin header (qemu-plugin.h) here, so the few types and
 * functions used are declared below from the documented 7.x API; QEMU resolves the
 * function symbols from its own executable when it loads the plugin. */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the QEMU plugin API subset (declared by hand; API version 1, QEMU 4.2 .. 8.1) ---- */
#define QI_EXPORT __attribute__((visibility("default")))
typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t {
    const char *target_name;
    struct { int min, cur; } version;
    bool system_emulation;
    union { struct { int smp_vcpus, max_vcpus; } system; } u;
} qemu_info_t;
struct qemu_plugin_tb;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb *tb, enum qemu_plugin_op op,
                                              void *ptr, uint64_t imm);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb *tb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
void qemu_plugin_outs(const char *string);

QI_EXPORT extern int qemu_plugin_version;
QI_EXPORT int qemu_plugin_version = 1;
QI_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv);
/* ---- end of the API subset ---- */

typedef struct qi_tb {
    uint64_t addr, ninsn;
    uint64_t execs;             /* the inline counter */
    struct qi_tb *next;         /* hash chain */
} qi_tb;

#define QI_HASH (1u << 16)
static qi_tb *qi_table[QI_HASH];
static size_t qi_count;
static const char *qi_out;

static unsigned qi_hash(uint64_t addr, uint64_t n)
{
    uint64_t h = (addr ^ (n << 40)) * 0x9E3779B97F4A7C15ull;
    return (unsigned)(h >> 48) & (QI_HASH - 1);
}

static void qi_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    uint64_t addr = qemu_plugin_tb_vaddr(tb), n = qemu_plugin_tb_n_insns(tb);
    unsigned h = qi_hash(addr, n);
    qi_tb *e;
    (void)id;
    for (e = qi_table[h]; e; e = e->next)
        if (e->addr == addr && e->ninsn == n) break;
    if (!e) {   /* entries are never freed or moved: QEMU keeps &e->execs in generated code */
        e = (qi_tb *)calloc(1, sizeof *e);
        if (!e) { qemu_plugin_outs("qemu_insn: out of memory\n"); abort(); }
        e->addr = addr; e->ninsn = n; e->next = qi_table[h]; qi_table[h] = e;
        qi_count++;
    }
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &e->execs, 1);
}

static int qi_cmp(const void *a, const void *b)
{
    const qi_tb *x = *(qi_tb *const *)a, *y = *(qi_tb *const *)b;
    if (x->addr != y->addr) return x->addr < y->addr ? -1 : 1;
    return x->ninsn < y->ninsn ? -1 : x->ninsn > y->ninsn;
}

static void qi_exit(qemu_plugin_id_t id, void *userdata)
{
    qi_tb **all = (qi_tb **)malloc(sizeof *all * (qi_count + 1));
    uint64_t total = 0;
    size_t i, k = 0;
    unsigned h;
    FILE *f = qi_out ? fopen(qi_out, "w") : stderr;
    (void)id; (void)userdata;
    if (!all || !f) { qemu_plugin_outs("qemu_insn: cannot write the counts\n"); return; }
    for (h = 0; h < QI_HASH; h++)
        for (qi_tb *e = qi_table[h]; e; e = e->next) { all[k++] = e; total += e->ninsn * e->execs; }
    qsort(all, k, sizeof *all, qi_cmp);
    fprintf(f, "total %" PRIu64 "\n", total);
    for (i = 0; i < k; i++)
        if (all[i]->execs)
            fprintf(f, "%" PRIx64 " %" PRIu64 " %" PRIu64 "\n", all[i]->addr, all[i]->ninsn, all[i]->execs);
    if (f != stderr) fclose(f);
    free(all);
}

QI_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    int i;
    if (info->system_emulation && info->u.system.smp_vcpus != 1) {
        qemu_plugin_outs("qemu_insn: user mode or one vCPU only (counts are not per vCPU)\n");
        return -1;
    }
    for (i = 0; i < argc; i++) {
        if (!strncmp(argv[i], "out=", 4)) qi_out = argv[i] + 4;
        else {
            qemu_plugin_outs("qemu_insn: unknown argument (only out=FILE)\n");
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, qi_trans);
    qemu_plugin_register_atexit_cb(id, qi_exit, NULL);
    return 0;
}
