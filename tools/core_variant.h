/*
 * core_variant.h - which build of the core a host program renders with.
 *
 * On x86-64 hosts the core is built twice: for the baseline x86-64 every
 * such machine runs, and at -O3 for x86-64-v3 (AVX2, FMA, BMI2; Haswell
 * and later, Zen), which the same sources turn into ~7 % fewer
 * instructions a frame with the same bytes (-ffp-contract=off holds in
 * both, so no multiply-add is fused). The core cannot choose for itself
 * (target_clones needs libgcc's __cpu_model, and the core is
 * freestanding), so celsim, celfw and bench link libcelscan_host.a, in
 * which the frame's entry points (cs_frame_begin, cs_render_line_runs,
 * cs_line_pixels, ...) are forwarders to one of the two builds, chosen
 * before main from the CPU, or from the environment:
 *
 *   CELSCAN_CORE=auto|baseline|x86-64-v3
 *
 * and afterwards by core_variant_select (celsim --core). Everything else
 * of the API is the baseline build's; the two builds share every type and
 * give the same bytes, so a frame begun by one may be rendered by the other.
 */
#ifndef CORE_VARIANT_H
#define CORE_VARIANT_H

/* Selects the build `name` ("auto": the fastest this CPU runs). Returns
 * NULL, or what is wrong (an unknown name, or a CPU without it); the
 * selection is then unchanged. Call it before rendering starts: the
 * threads of a frame read the choice without a lock. */
const char *core_variant_select(const char *name);

/* The build in use ("baseline" or "x86-64-v3"). */
const char *core_variant_name(void);

/* The names core_variant_select takes, for usage texts: "auto|baseline|...". */
const char *core_variant_choices(void);

#endif /* CORE_VARIANT_H */
