/*
 * ssd1963_model.c - the SSD1963 controller model (see ssd1963_model.h).
 *
 * Commands are taken as the datasheet's command table has them: a command
 * word, then exactly its number of parameters, each on D[7:0]. A command is
 * applied when its last parameter arrives; a new command word ends the
 * previous one (and a memory write). Soft reset returns the configuration
 * to its defaults but keeps the PLL settings, as the datasheet says.
 */
#include "ssd1963_model.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    NOP = 0x00, SOFT_RESET = 0x01, DISPLAY_OFF = 0x28, DISPLAY_ON = 0x29, SET_COLUMN = 0x2A,
    SET_PAGE = 0x2B, WRITE_MEMORY_START = 0x2C, ADDRESS_MODE = 0x36, WRITE_MEMORY_CONTINUE = 0x3C,
    SET_LCD_MODE = 0xB0, SET_HORI_PERIOD = 0xB4, SET_VERT_PERIOD = 0xB6, SET_PLL = 0xE0,
    SET_PLL_MN = 0xE2, SET_LSHIFT_FREQ = 0xE6, SET_PIXEL_INTERFACE = 0xF0,
};

/* Parameters of the commands the model knows; -1: not a command it knows. */
static int param_count(uint8_t c)
{
    switch (c) {
    case NOP: case SOFT_RESET: case DISPLAY_OFF: case DISPLAY_ON: case WRITE_MEMORY_START:
    case WRITE_MEMORY_CONTINUE: return 0;
    case ADDRESS_MODE: case SET_PLL: case SET_PIXEL_INTERFACE: return 1;
    case SET_PLL_MN: case SET_LSHIFT_FREQ: return 3;
    case SET_COLUMN: case SET_PAGE: return 4;
    case SET_LCD_MODE: case SET_VERT_PERIOD: return 7;
    case SET_HORI_PERIOD: return 8;
    }
    return -1;
}

__attribute__((format(printf, 2, 3))) static void fault(ssd_model *m, const char *fmt, ...)
{
    if (m->fault[0])
        return;
    int n = snprintf(m->fault, sizeof m->fault, "command 0x%02X (bus write %ld): ", m->cmd,
                     m->commands + m->pixels);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m->fault + n, sizeof m->fault - (size_t)n, fmt, ap);
    va_end(ap);
}

/* The configuration after power-on or soft reset (the PLL's is kept by a soft reset). */
static void defaults(ssd_model *m)
{
    m->mode_set = m->display_on = m->writing = false;
    m->hdp = m->vdp = -1;
    m->pixel_interface = -1;
    m->sc = m->sp = m->col = m->page = 0;
    m->ec = m->width - 1;
    m->ep = m->height - 1;
}

bool ssd_model_init(ssd_model *m, int width, int height, uint16_t fill)
{
    memset(m, 0, sizeof *m);
    m->width = width;
    m->height = height;
    m->frame = malloc((size_t)width * (size_t)height * sizeof *m->frame);
    if (!m->frame)
        return false;
    for (size_t i = 0; i < (size_t)width * (size_t)height; i++)
        m->frame[i] = fill;
    defaults(m);
    return true;
}

void ssd_model_free(ssd_model *m)
{
    free(m->frame);
    m->frame = NULL;
}

void ssd_model_attach(ssd_model *m, volatile uint16_t **cmd, volatile uint16_t **data)
{
    *cmd = &m->bus[0];
    *data = &m->bus[1];
}

void ssd_model_wait(ssd_model *m, uint32_t us)
{
    m->now_us += us;
}

/* A start/end address pair (high byte first) within 0..last; false (a fault) if not. */
static bool address_pair(ssd_model *m, int last, int *start, int *end)
{
    int s = m->args[0] << 8 | m->args[1], e = m->args[2] << 8 | m->args[3];
    if (s > e || e > last) {
        fault(m, "window %d..%d is reversed or beyond the glass's last address %d", s, e, last);
        return false;
    }
    *start = s;
    *end = e;
    return true;
}

static void apply(ssd_model *m)
{
    const uint8_t *a = m->args;
    switch (m->cmd) {
    case SET_COLUMN: address_pair(m, m->hdp, &m->sc, &m->ec); break;
    case SET_PAGE: address_pair(m, m->vdp, &m->sp, &m->ep); break;
    case ADDRESS_MODE:
        if (a[0] != 0)
            fault(m, "address mode 0x%02X (flips, rotation) is not modelled", a[0]);
        break;
    case SET_PLL:
        if (a[0] == 0x01) {
            m->pll_on = true;
            m->pll_on_us = m->now_us;
        } else if (a[0] == 0x03) {
            if (!m->pll_on || m->now_us - m->pll_on_us < 100)
                fault(m, "PLL used as the clock %llu us after it was started (100 us needed)",
                      (unsigned long long)(m->now_us - m->pll_on_us));
            m->pll_locked = true;
        } else {
            m->pll_on = m->pll_locked = false;
        }
        break;
    case SET_LCD_MODE:
        m->hdp = (a[2] & 0x07) << 8 | a[3];
        m->vdp = (a[4] & 0x07) << 8 | a[5];
        m->mode_set = true;
        if (m->hdp != m->width - 1 || m->vdp != m->height - 1)
            fault(m, "panel mode %dx%d for a %dx%d glass", m->hdp + 1, m->vdp + 1, m->width, m->height);
        break;
    case SET_PIXEL_INTERFACE: m->pixel_interface = a[0] & 0x07; break;
    default: break; /* timing and clock settings: taken, not modelled */
    }
}

static void command(ssd_model *m, uint16_t v)
{
    m->commands++;
    if (m->nargs != 0 && m->nargs < param_count(m->cmd))
        fault(m, "ended after %d of its %d parameters", m->nargs, param_count(m->cmd));
    m->cmd = (uint8_t)v;
    m->nargs = 0;
    m->writing = false;
    if (v > 0xFF || param_count(m->cmd) < 0) {
        fault(m, "not a command of the SSD1963 (word 0x%04X)", v);
        return;
    }
    if (m->reset_seen && m->now_us - m->reset_us < 5000)
        fault(m, "sent %llu us after a soft reset (5 ms needed)",
              (unsigned long long)(m->now_us - m->reset_us));
    switch (m->cmd) {
    case SOFT_RESET:
        defaults(m);
        m->reset_us = m->now_us;
        m->reset_seen = true;
        break;
    case DISPLAY_ON: m->display_on = true; break;
    case DISPLAY_OFF: m->display_on = false; break;
    case WRITE_MEMORY_START:
        m->col = m->sc;
        m->page = m->sp;
        m->writing = true;
        break;
    case WRITE_MEMORY_CONTINUE: m->writing = true; break;
    default: break;
    }
    if (m->writing && !(m->pll_locked && m->mode_set && m->pixel_interface == 3))
        fault(m, "memory written before the PLL is locked, the panel mode set and the 16-bit 565 "
                 "interface chosen");
}

static void pixel(ssd_model *m, uint16_t v)
{
    m->pixels++;
    if (m->page > m->ep) {
        fault(m, "pixel past the window's last page %d", m->ep);
        return;
    }
    m->frame[(size_t)m->page * (size_t)m->width + (size_t)m->col] = v;
    if (++m->col > m->ec) {
        m->col = m->sc;
        m->page++;
    }
}

static void data(ssd_model *m, uint16_t v)
{
    if (m->writing) {
        pixel(m, v);
        return;
    }
    m->commands++;
    if (m->nargs >= param_count(m->cmd)) {
        fault(m, "parameter %d of a command that takes %d", m->nargs + 1, param_count(m->cmd));
        return;
    }
    if (v > 0xFF)
        fault(m, "parameter %d is 0x%04X: parameters are 8 bits, on D[7:0]", m->nargs + 1, v);
    m->args[m->nargs++] = (uint8_t)v;
    if (m->nargs == param_count(m->cmd))
        apply(m);
}

void ssd_model_write(volatile uint16_t *reg, uint16_t v)
{
    uintptr_t a = (uintptr_t)reg;
    ssd_model *m = (ssd_model *)(a & ~(uintptr_t)3); /* bus[] is the model's first member */
    if (a & 2u)
        data(m, v);
    else
        command(m, v);
}
