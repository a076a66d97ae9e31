/*
 * insncount.c - a QEMU TCG plugin that counts executed guest instructions
 * and snapshots the count whenever the guest enters one of a few marker
 * functions.
 *
 * Usage:
 *   qemu-system-arm ... -plugin libinsncount.so,mark=0xADDR,mark=0xADDR,...,out=FILE
 * Each time the guest starts executing the translation block at a mark's
 * address (a function entry: a call always starts a new block), the plugin
 * records "MARK-INDEX COUNT" (the marks numbered from 0 in the order
 * given), and at exit writes them, then "total COUNT", to FILE. The
 * firmware's fw_mark_* functions are such markers; tools/qemu-insn/
 * measure.sh turns the log into instructions per frame and per line.
 *
 * The count is exact and repeatable: an inline add of the block's
 * instruction count runs at the start of every block, and the firmware
 * enables no interrupt, so nothing depends on host timing. (A block that
 * is left early by an exception would be over-counted; the measured code
 * takes none.)
 *
 * Debian's QEMU (7.2) has plugin support built in but ships neither
 * plugins nor the qemu-plugin.h header, so the few declarations needed are
 * written out below from QEMU's documented plugin API, version 1
 * (include/qemu/qemu-plugin.h of QEMU 7.x, docs/devel/tcg-plugins.rst):
 * the plugin exports qemu_plugin_version and qemu_plugin_install, and
 * calls functions QEMU exports to it. Version 2 (QEMU 9) replaced the
 * inline call used here by a per-vCPU scoreboard variant.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- QEMU plugin API, version 1 (declarations as documented) ---- */
#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))
typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t {
    const char *target_name;
    struct {
        int min;
        int cur;
    } version;
    bool system_emulation;
    union {
        struct {
            int smp_vcpus;
            int max_vcpus;
        } system;
    };
} qemu_info_t;
struct qemu_plugin_tb;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_CB_R_REGS, QEMU_PLUGIN_CB_RW_REGS };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb, qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb *tb, enum qemu_plugin_op op,
                                              void *ptr, uint64_t imm);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb *tb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb,
                                    void *userdata);
void qemu_plugin_outs(const char *string);
QEMU_PLUGIN_EXPORT extern int qemu_plugin_version;
QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv);
/* ---- end of the API declarations ---- */

QEMU_PLUGIN_EXPORT int qemu_plugin_version = 1;

#define MAX_MARKS 16

static uint64_t insns;          /* executed instructions so far (one vCPU) */
static uint64_t marks[MAX_MARKS];
static int mark_count;
static const char *out_path;
static struct hit {
    uint32_t mark;
    uint64_t count;
} *hits;
static size_t hit_count, hit_cap;

static void on_mark(unsigned int vcpu, void *userdata)
{
    (void)vcpu;
    if (hit_count == hit_cap) {
        size_t cap = hit_cap ? 2 * hit_cap : 4096;
        struct hit *h = realloc(hits, cap * sizeof *h);
        if (!h)
            return; /* out of memory: lose the hit, keep the run going */
        hits = h;
        hit_cap = cap;
    }
    hits[hit_count].mark = (uint32_t)(uintptr_t)userdata;
    hits[hit_count].count = insns;
    hit_count++;
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &insns,
                                             qemu_plugin_tb_n_insns(tb));
    uint64_t pc = qemu_plugin_tb_vaddr(tb);
    for (int i = 0; i < mark_count; i++)
        if (pc == marks[i])
            qemu_plugin_register_vcpu_tb_exec_cb(tb, on_mark, QEMU_PLUGIN_CB_NO_REGS,
                                                 (void *)(uintptr_t)i);
}

static void write_log(qemu_plugin_id_t id, void *userdata)
{
    (void)id;
    (void)userdata;
    FILE *f = out_path ? fopen(out_path, "w") : NULL;
    if (!f) {
        qemu_plugin_outs("insncount: cannot write the log (out=FILE)\n");
        return;
    }
    for (size_t i = 0; i < hit_count; i++)
        fprintf(f, "%u %llu\n", hits[i].mark, (unsigned long long)hits[i].count);
    fprintf(f, "total %llu\n", (unsigned long long)insns);
    fclose(f);
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    if (info->system_emulation && info->system.smp_vcpus != 1) {
        qemu_plugin_outs("insncount: counts one vCPU only\n");
        return -1;
    }
    for (int i = 0; i < argc; i++) {
        if (!strncmp(argv[i], "mark=", 5) && mark_count < MAX_MARKS) {
            /* Thumb function symbols carry bit 0; instruction addresses do not. */
            marks[mark_count++] = strtoull(argv[i] + 5, NULL, 0) & ~(uint64_t)1;
        } else if (!strncmp(argv[i], "out=", 4)) {
            out_path = argv[i] + 4; /* argv lives as long as the plugin */
        } else {
            qemu_plugin_outs("insncount: arguments are mark=ADDR (up to 16) and out=FILE\n");
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, write_log, NULL);
    return 0;
}
