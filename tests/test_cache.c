/*
 * test_cache.c - pre-combined cel ranges (cs_cache_build,
 * cs_frame_begin_cached) against the direct render of the same frame.
 *
 * A busy stack of sixteen overlapping cels is rendered once directly and
 * once with a range of its cels pre-combined into (E, T) runs: the two
 * must agree within 1e-5 in linear light, with the cache at the back, in
 * the middle (live cels in front and behind), over a light box, and while
 * the cels in front move. The cache's size is reported exactly (the needed
 * size fits, one byte less is refused, at an odd address too); a cache made
 * at other options, an empty range or one past the end is refused.
 *
 * On tests/testlib.h; the last line is `test_cache: N passed, M failed`.
 */
#include "beta_common.h"

static void test_cache(void)
{
    build_busy_scene(&g_scene);
    cs_render_opts o = opts_n(96, 64, 5);
    cs_cache cache;
    cs_error e;
    const size_t n = (size_t)3 * 96 * 64;
    /* Too small: reported with the size it needs, and refused by the frame. */
    cs_status st = cs_cache_build(&cache, cache_buf + 1, 100, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.status != CS_OK && cache.bytes_needed > 100,
          "small cache: %s, needed %zu", cs_status_str(st), cache.bytes_needed);
    cs_renderer r;
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o, &cache, &e) == CS_ERR_STATE,
          "unusable cache refused");
    size_t needed = cache.bytes_needed;
    /* Exactly the reported size fits (odd address: alignment is handled). */
    st = cs_cache_build(&cache, cache_buf + 1, needed, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_OK && cache.bytes_used == needed, "cache of the needed size: %s, %zu vs %zu",
          cs_status_str(st), cache.bytes_used, needed);
    st = cs_cache_build(&cache, cache_buf + 1, needed - 1, &g_ws, &g_scene, &o, 3, 13, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.bytes_needed == needed, "one byte short: %s",
          cs_status_str(st));
    st = cs_cache_build(&cache, cache_buf + 1, needed, &g_ws, &g_scene, &o, 3, 13, &e);
    printf("  cache of cels 3..15 at 96x64: %u runs, %zu bytes\n", cache.run_count,
           cache.bytes_used);
    /* Cels 0-2 live in front, the cached background behind. */
    CHECK(render(&g_scene, &o, NULL, img_a) == CS_OK, "direct");
    CHECK(render(&g_scene, &o, &cache, img_b) == CS_OK, "cached");
    double d = max_diff(img_a, img_b, n);
    CHECK(d <= 1.0 / 255.0 && d < 1e-5, "cache vs direct: %.2e", d);
    /* Animate the front: move cel 0; the cache stays valid. */
    for (int t = 0; t < 3; t++) {
        g_scene.cels[0].transform.e = 5.0f * (float)t;
        g_scene.cels[1].transform.f = -3.0f * (float)t;
        render(&g_scene, &o, NULL, img_a);
        render(&g_scene, &o, &cache, img_b);
        d = max_diff(img_a, img_b, n);
        CHECK(d < 1e-5, "animated front, frame %d: cache vs direct %.2e", t, d);
    }
    /* A cached range in the middle: live cels in front and behind. */
    st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 1, 5, &e);
    CHECK(st == CS_OK, "middle cache: %s", cs_status_str(st));
    render(&g_scene, &o, NULL, img_a);
    render(&g_scene, &o, &cache, img_b);
    d = max_diff(img_a, img_b, n);
    CHECK(d < 1e-5, "middle cache vs direct: %.2e", d);
    /* Without the background card, with a light box behind. */
    g_scene.has_background = false;
    float fs[3] = {1, 1, 1}, bs[3] = {0.6f, 0.5f, 0.9f};
    cs_scene_set_lights(&g_scene, fs, bs);
    g_scene.cel_count -= 1; /* drop the opaque back wall so the light shows */
    st = cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 2, 10, &e);
    CHECK(st == CS_OK, "light box cache: %s", cs_status_str(st));
    render(&g_scene, &o, NULL, img_a);
    render(&g_scene, &o, &cache, img_b);
    d = max_diff(img_a, img_b, n);
    CHECK(d < 1e-5, "light box cache vs direct: %.2e", d);
    /* Pre-combined and reused at other options is refused. */
    cs_render_opts o2 = opts_n(96, 64, 4);
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o2, &cache, &e) == CS_ERR_STATE,
          "cache at other AA refused");
    o2 = opts_n(80, 64, 5);
    CHECK(cs_frame_begin_cached(&r, &g_ws, &g_scene, &o2, &cache, &e) == CS_ERR_STATE,
          "cache at other size refused");
    /* Bad ranges. */
    CHECK(cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 5, 0, &e) ==
              CS_ERR_ARG,
          "empty range");
    CHECK(cs_cache_build(&cache, cache_buf, sizeof cache_buf, &g_ws, &g_scene, &o, 10, 100,
                         &e) == CS_ERR_ARG,
          "range past the end");
    /* Size query: no buffer at all. */
    st = cs_cache_build(&cache, NULL, 0, &g_ws, &g_scene, &o, 0, 3, &e);
    CHECK(st == CS_ERR_CAP_CACHE && cache.bytes_needed > 0, "size query");
}


int main(void)
{
    TL_RUN(test_cache);
    return tl_summary("test_cache");
}
