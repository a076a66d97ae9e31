/*
 * hub75_model.c - decodes recorded HUB75 wire changes into what the panel shows.
 */
#include <stdlib.h>
#include <string.h>

#include "hub75_model.h"

static int wire(const hub75_model *m, uint64_t w, int f)
{
    return m->pin[f] >= 0 ? (int)((w >> m->pin[f]) & 1u) : 0;
}

void hub75_model_init(hub75_model *m, const hub75_config *c, uint64_t initial_wires)
{
    memset(m, 0, sizeof *m);
    m->width = c->panel_w * c->chain;
    m->height = c->panel_h;
    m->scan = hub75_scan(c);
    m->abits = hub75_addr_bits(c);
    for (int f = 0; f < HUB75_NFUNC; f++)
        m->pin[f] = c->pins.pin[f];
    for (int a = m->abits; a < 5; a++)
        m->pin[HUB75_A + a] = -1;
    m->shift = calloc((size_t)m->width, 1);
    m->latch = calloc((size_t)m->width, 1);
    m->on_time = calloc((size_t)m->width * (size_t)m->height * 3u, sizeof(uint64_t));
    m->row_lit = calloc((size_t)m->scan, sizeof(uint64_t));
    m->wires_last = initial_wires;
    m->lit = !wire(m, initial_wires, HUB75_OE);
    m->addr = 0;
}

void hub75_model_free(hub75_model *m)
{
    free(m->shift);
    free(m->latch);
    free(m->on_time);
    free(m->row_lit);
    free(m->pulses);
}

static void integrate(hub75_model *m, uint64_t t)
{
    if (!m->lit || t <= m->t_last)
        return;
    uint64_t dt = t - m->t_last;
    int r = m->addr;
    if (r >= m->scan)
        return; /* an address beyond the panel lights nothing */
    m->row_lit[r] += dt;
    for (int x = 0; x < m->width; x++) {
        uint8_t v = m->latch[x];
        for (int c = 0; c < 3; c++) {
            if ((v >> c) & 1u)
                m->on_time[((size_t)r * (size_t)m->width + (size_t)x) * 3u + (size_t)c] += dt;
            if ((v >> (3 + c)) & 1u)
                m->on_time[((size_t)(r + m->scan) * (size_t)m->width + (size_t)x) * 3u + (size_t)c] += dt;
        }
    }
}

void hub75_model_feed(hub75_model *m, const fake_gpio_event *ev)
{
    uint64_t prev = m->wires_last, now = ev->wires;
    integrate(m, ev->t_ns);
    m->t_last = ev->t_ns;

    uint8_t data = 0, data_prev = 0;
    for (int c = 0; c < 6; c++) {
        data |= (uint8_t)(wire(m, now, HUB75_R1 + c) << c);
        data_prev |= (uint8_t)(wire(m, prev, HUB75_R1 + c) << c);
    }
    int clk0 = wire(m, prev, HUB75_CLK), clk1 = wire(m, now, HUB75_CLK);
    int lat1 = wire(m, now, HUB75_LAT);
    if (!clk0 && clk1) {
        m->clock_edges++;
        if (data != data_prev)
            m->setup_violations++;
        if (lat1)
            m->clock_while_latched++;
        memmove(m->shift + 1, m->shift, (size_t)m->width - 1u);
        m->shift[0] = data;
    }
    if (lat1) {
        if (!wire(m, prev, HUB75_LAT))
            m->latches++;
        memcpy(m->latch, m->shift, (size_t)m->width);
    }
    int addr = 0;
    for (int a = 0; a < m->abits; a++)
        addr |= wire(m, now, HUB75_A + a) << a;
    int lit = !wire(m, now, HUB75_OE);
    if (addr != m->addr && (m->lit || lit))
        m->ghost_changes++;
    m->addr = addr;
    if (lit && !m->lit) {
        if (m->npulses == m->cappulses) {
            m->cappulses = m->cappulses ? 2 * m->cappulses : 1024;
            m->pulses = realloc(m->pulses, m->cappulses * sizeof *m->pulses);
        }
        m->pulses[m->npulses++] = (hub75_pulse){addr, ev->t_ns, 0};
    } else if (!lit && m->lit && m->npulses) {
        hub75_pulse *p = &m->pulses[m->npulses - 1];
        p->duration = ev->t_ns - p->t_on;
    }
    m->lit = lit;
    m->wires_last = now;
}

int hub75_model_image(const hub75_model *m, int planes, uint16_t *levels)
{
    uint64_t max = (1u << planes) - 1u;
    int dark = 0;
    for (int r = 0; r < m->scan; r++)
        if (!m->row_lit[r])
            dark++;
    for (int y = 0; y < m->height; y++) {
        uint64_t total = m->row_lit[y % m->scan];
        for (int i = 0; i < m->width * 3; i++) {
            uint64_t on = m->on_time[(size_t)y * (size_t)m->width * 3u + (size_t)i];
            levels[(size_t)y * (size_t)m->width * 3u + (size_t)i] =
                total ? (uint16_t)((on * max + total / 2u) / total) : 0;
        }
    }
    return dark;
}
